"""The study runner's own time on a study, with the accuracy of the same run (docs/performance.md).

    PYTHONPATH=. python benchmarks/study_overhead.py studies/speed_vs_error.toml --workers 1 2 --repeat 3

Each repetition runs the whole study into a fresh folder (in one process, as the CLI does) and prints
meta.json's timing (wall time of cases and tables, the models' time, the runner's overhead) beside the
run's errors: how many cases are ok, and their max error relative to the reference's max (``err_max``).
"""

from __future__ import annotations

import argparse
import json
import tempfile
from pathlib import Path

import numpy as np

from pdverify.study import load_study, run_study


def measure(study_file: Path, workers: int) -> dict:
    with tempfile.TemporaryDirectory() as d:
        df = run_study(load_study(study_file), Path(d) / "out", workers=workers, progress=False)
        t = json.loads((Path(d) / "out" / "meta.json").read_text())["timing"]
    ok = df[df["status"] == "ok"]
    rel = ok["err_max"].dropna().to_numpy()  # relative to max |reference| (metrics.errors)
    wall = t["cases_s"] + t["tables_s"]
    own = wall - t["solver_s"] / workers  # as derived.overhead computes it (meta.json's runner_overhead_s)
    return {
        "workers": workers,
        "cases": len(df),
        "ok": len(ok),
        "wall_s": wall,
        "solver_s": t["solver_s"],
        "store_s": t["store_s"],
        "tables_s": t["tables_s"],
        "overhead_s": own,
        "overhead": own / wall,
        "rel_err_min": float(rel.min()),
        "rel_err_median": float(np.median(rel)),
        "rel_err_max": float(rel.max()),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study", type=Path)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    for w in args.workers:
        for _ in range(args.repeat):
            m = measure(args.study, w)
            print(
                f"workers={m['workers']} cases={m['cases']} ok={m['ok']} wall={m['wall_s']:.3f}s "
                f"models={m['solver_s']:.3f}s store={m['store_s']:.3f}s tables={m['tables_s']:.3f}s "
                f"overhead={m['overhead_s']:.3f}s ({100 * m['overhead']:.1f} %) "
                f"max error min/median/max={m['rel_err_min']:.2e}/{m['rel_err_median']:.2e}/{m['rel_err_max']:.2e}"
            )


if __name__ == "__main__":
    main()
