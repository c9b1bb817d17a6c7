"""Golden results of every paper benchmark: regenerate with ``python -m pdverify.apps.golden --regenerate``.

A change to a golden file must be explained in the commit message (which model changed and why).
The tests (tests/regression/test_golden.py) compare every curve to rtol max(1e-10, cond * eps) of its largest value
(cond: the run's condition estimate; why, with the measurements, in the test's docstring).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from ..core.scene_file import load_scene
from ..registry import run

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "golden"

# (scene, model, options): the configurations the papers' benchmarks use
CASES = [
    *[
        (f"paper_diyaroglu/{s}.toml", "pd-eb", {"variant": v, "points": 101})
        for s in ("clamped_free", "clamped_clamped", "simply_supported")
        for v in ("paper", "corrected")
    ],
    *[
        (f"paper_diyaroglu/{s}.toml", "fem-eb", {"points": 101})
        for s in ("clamped_free", "clamped_clamped", "simply_supported")
    ],
    *[
        (f"paper_diyaroglu/{s}.toml", "pd-bond-pair", {"variant": v, "ends": e, "points": 201})
        for s in ("clamped_free", "clamped_clamped", "simply_supported")
        for v, e in (("paper", "mirror"), ("continuous-alpha", "mirror"), ("corrected", "taylor"))
    ],
    *[
        (f"paper_yang/{s}.toml", "fem-timoshenko", {"points": 101})
        for s in ("ss_uniform", "ss_centre_force", "cc_uniform", "cantilever_tip_force", "cantilever_tip_moment")
    ],
    ("paper_moyer/cantilever_table1.toml", "fem-timoshenko", {"points": 101}),
    *[
        (f"paper_yang/{s}.toml", "pd-higher-order", {"variant": v, "points": 1001})
        for s in ("ss_uniform", "ss_centre_force", "cc_uniform", "cantilever_tip_force", "cantilever_tip_moment")
        for v in ("paper", "corrected")
    ],
    *[
        (f"paper_yang/{s}.toml", "fem-plane-stress", {"element": "q4", "points": 101, "layers": 8})
        for s in ("ss_uniform", "cantilever_tip_force")
    ],
    *[
        ("paper_moyer/cantilever_table1.toml", "pd-timoshenko", {"variant": v, "horizon": m, "points": 101})
        for v in ("paper", "corrected")
        for m in (2, 3, 4)
    ],
    ("paper_moyer/rod_example1.toml", "pd-rod", {"points": 101, "horizon": 1}),
    *[
        ("paper_moyer/beam_example2.toml", "pd-timoshenko", {"variant": v, "points": 101, "horizon": 1})
        for v in ("corrected", "energy")
    ],
    *[
        (f"paper_curved/{s}.toml", "pd-curved", {"form": f, "degree": 4, "points": 401})
        for s in ("semicircle_tangential", "semicircle_normal", "straight_sine")
        for f in ("primal", "mixed")
    ],
    *[
        ("paper_curved/quintic_manufactured.toml", "pd-curved-mms", {"form": f, "degree": 4, "points": 401})
        for f in ("primal", "mixed")
    ],
]


def key(scene: str, model: str, options: dict) -> str:
    opts = "_".join(f"{k}-{v}" for k, v in sorted(options.items()))
    return f"{Path(scene).parent.name}__{Path(scene).stem}__{model}__{opts}"


def compute(scene: str, model: str, options: dict) -> dict:
    r = run(load_scene(ROOT / "studies" / scene), model, **options)
    out = {"scene": scene, "model": model, "options": options, "x": r.x.tolist(), "w": np.asarray(r.w).tolist()}
    if "u" in r.fields and not np.any(r.w):  # axial models: the axial displacement is the answer
        out["u"] = np.asarray(r.fields["u"]).tolist()
    if r.info.get("cond") is not None:  # for the record; the test takes its allowance from its own run
        out["cond"] = float(r.info["cond"])
    return out


def regenerate(only: str = "") -> list[Path]:
    GOLDEN.mkdir(parents=True, exist_ok=True)
    out = []
    for scene, model, options in CASES:
        if only not in key(scene, model, options):
            continue
        p = GOLDEN / f"{key(scene, model, options)}.json"
        p.write_text(json.dumps(compute(scene, model, options)))
        out.append(p)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--regenerate", action="store_true", help="rewrite tests/golden/*.json")
    ap.add_argument("--only", default="", help="only the cases whose file name contains this text")
    args = ap.parse_args()
    if args.regenerate:
        for p in regenerate(args.only):
            print(p.relative_to(ROOT))


if __name__ == "__main__":
    main()
