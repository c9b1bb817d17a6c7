"""Runner overhead on 200 small cases: wall time of `load_study` + `run_study` (validation, hashing,
reference evaluation, atomic case files, tables) against the sum of the models' own total_s, in one
process (workers=1) so the comparison is not blurred by parallelism. The one-time start-up (importing
the model registry: scipy, scikit-fem, pandas) is measured apart as `startup_s`: it is paid once per
process, whatever the number of cases. Prints one JSON line; run with `python benchmarks/runner_overhead.py`.
"""

import json
import tempfile
import time
from pathlib import Path

from pdverify.study import load_study, run_study

ROOT = Path(__file__).resolve().parents[1]

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
    from pdverify.registry import models
    from pdverify.study.spec import code_digest

    models()
    code_digest()
    startup = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "s.toml"
        p.write_text(STUDY.format(root=ROOT))
        t0 = time.perf_counter()
        study = load_study(p)
        df = run_study(study, Path(d) / "out", workers=1, progress=False)
        wall = time.perf_counter() - t0
    solver = float(df["total_s"].sum())
    print(json.dumps({"cases": len(df), "startup_s": startup, "wall_s": wall, "solver_s": solver,
                      "overhead_fraction": (wall - solver) / solver}))


if __name__ == "__main__":
    main()
