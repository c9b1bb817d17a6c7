"""Runner overhead on 200 small cases: the wall time of `load_study` + `run_study` (validation, hashing,
reference evaluation, atomic case files, tables) against the wall time of solving the same cases in a
bare loop (`registry.run` on each case, nothing recorded), in one process (workers=1) so the comparison
is not blurred by parallelism. Both are the best of ``REPEAT`` runs. (Comparing with the sum of the
models' own total_s instead would flatter the runner: its background writer thread competes for the
GIL and inflates the models' timings.) The one-time start-up (importing the model registry: scipy,
scikit-fem, pandas) is measured apart as `startup_s`: it is paid once per process, whatever the number
of cases. Prints one JSON line; run with `python benchmarks/runner_overhead.py`.
"""

import json
import tempfile
import time
from pathlib import Path

from pdverify.study import load_study, run_study

ROOT = Path(__file__).resolve().parents[1]
REPEAT = 3

STUDY = """name = "overhead"
scenes = ["{root}/studies/paper_diyaroglu/clamped_clamped.toml", "{root}/studies/paper_diyaroglu/simply_supported.toml"]
reference = "exact-eb"
[[runs]]
model = "pd-eb"
variant = ["paper", "corrected"]
points = [401, 801, 1201, 1601, 2001]
horizon = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]
"""


def main():
    t0 = time.perf_counter()
    from pdverify.registry import models, run
    from pdverify.study.spec import code_digest

    models()
    code_digest()
    startup = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "s.toml"
        p.write_text(STUDY.format(root=ROOT))
        cases = load_study(p).cases
        bare, wall, solver = [], [], []
        for k in range(REPEAT):
            t0 = time.perf_counter()
            for c in cases:
                run(c.scene(), c.model, **c.given)
            bare.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            study = load_study(p)
            df = run_study(study, Path(d) / f"out{k}", workers=1, progress=False)
            wall.append(time.perf_counter() - t0)
            solver.append(float(df["total_s"].sum()))
    print(json.dumps({"cases": len(df), "startup_s": startup, "wall_s": min(wall), "bare_loop_s": min(bare),
                      "overhead_fraction": (min(wall) - min(bare)) / min(bare),
                      "models_total_s_in_study": min(solver)}))


if __name__ == "__main__":
    main()
