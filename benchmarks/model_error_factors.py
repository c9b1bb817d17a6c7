"""How many times the first sine mode's model error g (pi delta / L)^2 each PD variant's continuum is off the local
beam theory on other support pairs and loads (docs/nonlocal.md, "In every result"):

    PYTHONPATH=. python benchmarks/model_error_factors.py [--deltas 0.05 0.1 0.2] [--m 32] [--continuum-m 128]
        [--out rows.jsonl]

A 1 m steel beam (10 x 10 mm), every support pair of clamped, pinned, guided and free ends that holds it (both
orientations), under a sine load, a uniform load, a uniform load on the left or right half or on [0.25, 0.5] L, a point
force at 0.5 or 0.75 L and a couple at 0.75 L; each variant's continuum at horizon delta (``continuum = true``:
extrapolated in m at fixed delta from m to continuum-m, pdverify.theory.continuum; from m / 4 where the variant is
singular to working precision there) against exact-eb (exact-timoshenko for pd-timoshenko):
ratio = max |w_continuum - w_local| / max |w_local| / (g (pi delta / L)^2). Prints, per variant and unordered support
pair, the largest ratio over loads and horizons; the models' ``model_error_ends`` tables hold these (rounded up).
A variant without a limit at fixed delta on a pair (``Model.continuum_limit``) is listed apart: its "continuum" is its
finest grid, and its warning says so instead.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np

from pdverify.core.errors import InputError, SolveError
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run

PAIRS = [
    ("clamped", "clamped"),
    ("clamped", "pinned"),
    ("pinned", "clamped"),
    ("clamped", "guided"),
    ("guided", "clamped"),
    ("clamped", "free"),
    ("free", "clamped"),
    ("pinned", "pinned"),
    ("pinned", "guided"),
    ("guided", "pinned"),
]
LOADS = {
    "sine": [{"type": "distributed", "value": -1000.0, "shape": "sine"}],
    "uniform": [{"type": "distributed", "value": -1000.0}],
    "half-left": [{"type": "distributed", "value": -1000.0, "start": 0.0, "end": 0.5}],
    "half-right": [{"type": "distributed", "value": -1000.0, "start": 0.5, "end": 1.0}],
    "quarter": [{"type": "distributed", "value": -1000.0, "start": 0.25, "end": 0.5}],
    "force-mid": [{"type": "point_force", "position": 0.5, "value": -100.0}],
    "force-3q": [{"type": "point_force", "position": 0.75, "value": -100.0}],
    "couple-3q": [{"type": "point_moment", "position": 0.75, "value": 30.0}],
}
VARIANTS = [
    ("pd-eb", {"variant": "corrected"}),
    ("pd-eb", {"variant": "paper"}),
    ("pd-bond-pair", {}),
    ("pd-bond-pair", {"ends": "mirror"}),
    ("pd-timoshenko", {"variant": "corrected"}),
    ("pd-timoshenko", {"variant": "energy"}),
]
M, CONTINUUM_M = 32, 128  # grids at delta = 32 dx; the continuum is extrapolated from them to m = 128


def scene(left: str, right: str, loads: list):
    return parse_scene(
        {
            "name": f"{left}-{right}",
            "beam": {"length": 1.0},
            "section": {"width": 0.01, "height": 0.01},
            "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3},
            "supports": {"left": left, "right": right},
            "loads": loads,
        }
    )


def set_grids(m: int, continuum_m: int):
    global M, CONTINUUM_M
    M, CONTINUUM_M = m, continuum_m


def rows(deltas):
    for left, right in PAIRS:
        for load, loads in LOADS.items():
            sc = scene(left, right, loads)
            for name, options in VARIANTS:
                model = get_model(name)
                ref = "exact-timoshenko" if model.theory == "timoshenko" else "exact-eb"
                g = model.gradient_coefficient(sc, {})
                for delta in deltas:
                    c = None
                    for m in (M, M // 4):  # pd-timoshenko corrected is singular to working precision at m = 128
                        points = int(round(m / delta)) + 1
                        given = dict(options, points=points, horizon_length=delta, continuum=True)
                        given["continuum_m"] = CONTINUUM_M * m // M
                        try:
                            limit = model.continuum_limit(sc, model.resolve(sc, given))
                            c = run(sc, name, **given)
                            break
                        except SolveError:
                            continue
                        except InputError:  # a horizon the variant refuses (pd-timoshenko's end zones past L / 6)
                            c = None
                            break
                    if c is None:
                        continue
                    e = run(sc, ref, points=points)
                    err = float(np.abs(np.asarray(c.w) - e.w).max() / np.abs(e.w).max())
                    yield {
                        "model": name,
                        "options": options,
                        "pair": f"{left}-{right}",
                        "load": load,
                        "delta": delta,
                        "ratio": err / (g * (math.pi * delta) ** 2),
                        "no_limit": limit is not None,
                        "m": m,
                    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--deltas", type=float, nargs="+", default=[0.05, 0.1, 0.2])
    ap.add_argument("--out", default=None)
    ap.add_argument("--m", type=int, default=M, help="m = delta / dx of the first grid")
    ap.add_argument("--continuum-m", type=int, default=CONTINUUM_M, help="the largest m of the extrapolation")
    args = ap.parse_args()
    set_grids(args.m, args.continuum_m)
    out = open(args.out, "w") if args.out else None
    table: dict = {}
    for r in rows(args.deltas):
        if out:
            out.write(json.dumps(r) + "\n")
        key = (r["model"] + " " + " ".join(f"{k}={v}" for k, v in r["options"].items()), r["no_limit"])
        pair = "-".join(sorted(r["pair"].split("-")))
        table.setdefault(key, {})[pair] = max(table.get(key, {}).get(pair, 0.0), r["ratio"])
    for (variant, no_limit), pairs in sorted(table.items()):
        what = " (no limit at fixed delta: its finest grid)" if no_limit else ""
        print(f"{variant}{what}: " + ", ".join(f"{p} {v:.3g}" for p, v in sorted(pairs.items())))


if __name__ == "__main__":
    main()
