"""Does each PD model have a limit at a fixed horizon? Self-convergence in m (docs/nonlocal.md):

    PYTHONPATH=. python benchmarks/fixed_horizon_limits.py [--delta 0.2] [--models pd-bond-pair ...] [--json]

On the nonlocal study's members (studies/nonlocal/: every support pair of a 1 m beam, a clamped-clamped and a
clamped-free rod and shaft; sine and uniform loads), each model at delta held and m = delta / dx = 8, 16, ..., 128
(nested grids): the largest change of the measured field between successive m at the points
of the m = 8 grid, relative to the finest grid's largest value, and the order log2 of the ratio of successive
changes. A variant with a limit shows changes that fall (order p > 0: it converges at order p); changes that stay
the same (order 0) grow like ln m; changes that grow have no limit. Changes near 1e-13 are round-off (a polynomial
load the variant reproduces exactly). The model's own continuum hook (``continuum_limit``) is printed beside.
"""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path

import numpy as np

from pdverify.core.errors import PdverifyError
from pdverify.core.scene_file import load_scene
from pdverify.registry import get_model, run

ROOT = Path(__file__).resolve().parents[1] / "studies" / "nonlocal"
BEAM = ("pp", "cc", "cf", "cg", "cp", "pg")
CASES = [  # (model, options, members)
    ("pd-eb", {"variant": "paper"}, BEAM),
    ("pd-eb", {"variant": "corrected"}, BEAM),
    ("pd-bond-pair", {"ends": "mirror"}, BEAM),
    ("pd-bond-pair", {"ends": "taylor"}, BEAM),
    ("pd-bond-pair", {"variant": "paper", "ends": "mirror"}, BEAM),
    ("pd-timoshenko", {"variant": "corrected"}, BEAM),
    ("pd-rod", {"variant": "corrected"}, ("rod_cc", "rod_cf")),
    ("pd-rod", {"variant": "paper"}, ("rod_cc", "rod_cf")),
    ("pd-torsion", {"variant": "corrected"}, ("shaft_cc", "shaft_cf")),
    ("pd-torsion", {"variant": "paper"}, ("shaft_cc", "shaft_cf")),
    ("pd-higher-order", {}, BEAM),
    ("pd-higher-order", {"shear": "centred"}, BEAM),
    ("pd-higher-order", {"stretch": "path"}, BEAM),
    ("pd-higher-order", {"clamp": "face"}, ("cc", "cf")),
]
M = (8, 16, 32, 64, 128)


def changes(model: str, opts: dict, scene_path: Path, delta: float, ms=M) -> dict:
    """The changes between successive m at fixed ``delta`` (module docstring), their orders and the hook's word."""
    scene = load_scene(scene_path)
    measures = get_model(model).measures
    values = []
    for m in ms:
        r = run(scene, model, points=int(round(m * scene.length / delta)) + 1, horizon_length=delta, **opts)
        v = np.asarray(r.w if measures == "w" else r.fields[measures], float)
        values.append(v[:: m // ms[0]])
    top = float(np.abs(values[-1]).max())
    inc = [float(np.abs(b - a).max()) / top for a, b in zip(values, values[1:])]
    orders = [float(np.log2(a / b)) if a > 0 and b > 0 else float("nan") for a, b in zip(inc, inc[1:])]
    mdl = get_model(model)
    limit = mdl.continuum_limit(scene, mdl.resolve(scene, dict(opts, points=41, horizon_length=delta)))
    return {"changes": inc, "orders": orders, "error_bound": r.info.get("error_bound"), "no_limit": bool(limit)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--delta", type=float, default=0.2, help="the horizon length (the members are 1 m long)")
    ap.add_argument("--models", nargs="*", help="only these models")
    ap.add_argument("--json", action="store_true", help="one JSON object per line")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")  # the rows' own warnings (round-off, boundary layers): not this table's
    for model, opts, members in CASES:
        if args.models and model not in args.models:
            continue
        for member in members:
            for load in ("sine", "uniform"):
                row = {"model": model, "options": opts, "scene": f"{member}_{load}", "delta": args.delta}
                try:
                    row.update(changes(model, opts, ROOT / f"{member}_{load}.toml", args.delta))
                except PdverifyError as exc:
                    row["refused"] = " ".join(exc.lines)
                if args.json:
                    print(json.dumps(row), flush=True)
                    continue
                name = model + "".join(f" {k}={v}" for k, v in opts.items())
                if "refused" in row:
                    print(f"{name:36s} {row['scene']:16s} refused: {row['refused'][:90]}", flush=True)
                    continue
                inc = " ".join(f"{v:.2e}" for v in row["changes"])
                orders = " ".join(f"{v:5.2f}" for v in row["orders"])
                hook = "no limit declared" if row["no_limit"] else ""
                print(f"{name:36s} {row['scene']:16s} changes {inc}  orders {orders}  {hook}", flush=True)


if __name__ == "__main__":
    main()
