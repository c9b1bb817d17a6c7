"""Loads near an end that holds the deflection: each PD beam's deflection error against its exact beam (relative to
max |w|) against the estimate of its warning, C (h / d)², d the load's distance from the end (a distributed load's
centroid), h = max(spacing, horizon / 3) and C the model's ``end_load_error`` for the end's kind
(pdverify/registry/end_loads.py; docs/trust.md). Where it warns the ratio error / estimate must be below 1:

    PYTHONPATH=. python benchmarks/end_loads.py [--points 101 201 401] [--models pd-eb ...] [--horizons 3 5]

A 1 m steel beam, 20 x 50 mm, on five end pairs (the left end clamped or pinned), under one load near the left end: a
patch from the end or off it, or a point force, its arm 2.5 to 40 spacings. Printed per model and horizon: the largest
ratio of the end's part of the error to the estimate where the warning estimates (the end's part: with the load the
same number of spacings off at twice the points it stays while the rest falls 4 times; cases an earlier warning names
are left out: a point load in the end's layer), and the cases over 1e-3 of max |w| no warning names.
"""

from __future__ import annotations

import argparse

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}
ENDS = [("clamped", "free"), ("clamped", "pinned"), ("clamped", "clamped"), ("pinned", "pinned"), ("pinned", "clamped")]
ARMS = (2.5, 5, 10, 20, 40)  # spacings


def loads(kind: str, arm: float):
    """One load of ``kind`` whose arm about x = 0 is ``arm`` (in metres)."""
    if kind == "patch from the end":
        return [{"type": "distributed", "value": -5000.0, "start": 0.0, "end": 2 * arm}]
    if kind == "patch off the end":
        return [{"type": "distributed", "value": -5000.0, "start": arm / 2, "end": 1.5 * arm}]
    if kind == "force":
        return [{"type": "point_force", "position": arm, "value": -500.0}]
    return [{"type": "point_moment", "position": arm, "value": 50.0}]


def scene(left: str, right: str, kind: str, arm: float):
    return parse_scene(
        {
            "name": "end",
            "beam": {"length": 1.0},
            "section": {"width": 0.02, "height": 0.05},
            "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
            "supports": {"left": left, "right": right},
            "loads": loads(kind, arm),
        }
    )


def error(sc, name: str, n: int, m: float):
    r, e = run(sc, name, points=n, horizon=m), run(sc, MODELS[name], points=n)
    return np.abs(r.w - e.w).max() / np.abs(e.w).max(), r.info.get("warnings", [])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=[101, 201, 401])
    ap.add_argument("--models", nargs="+", default=list(MODELS))
    ap.add_argument("--horizons", type=float, nargs="+", default=[3.0, 5.0])
    args = ap.parse_args()
    for name in args.models:
        for m in args.horizons:
            worst, silent = (0.0, ""), []
            for left, right in ENDS:
                for n in args.points:
                    dx = 1.0 / (n - 1)
                    for kind in ("patch from the end", "patch off the end", "force"):
                        for k in ARMS:
                            err, said = error(scene(left, right, kind, k * dx), name, n, m)
                            # the same load k spacings off at twice the points: the end's part stays, the rest falls
                            # 4 times
                            finer, _ = error(scene(left, right, kind, k * dx / 2), name, 2 * n - 1, m)
                            end = max((4 * finer - err) / 3, finer)
                            label = f"{kind} arm {k} spacings, {left}-{right}, {n} points"
                            mine = [w for w in said if "spacings from the left end" in w and "(h / d)" in w]
                            if mine:
                                est = float(mine[0].split(", here ")[1].split(",")[0])
                                worst = max(worst, (end / est, label))
                            elif err > 1e-3 and not said:
                                silent.append(f"{label}: {err:.2g} (the end's part {end:.2g})")
            c = get_model(name).end_load_error
            print(f"{name} horizon {m:g}, C = {c}: largest error / estimate {worst[0]:.3f} ({worst[1]})")
            for line in silent:
                print(f"  unwarned over 1e-3: {line}")


if __name__ == "__main__":
    main()
