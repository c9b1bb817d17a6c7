"""Loads near an end that holds the deflection: each PD beam's deflection and moment errors against its exact beam (each
relative to its largest value, the larger of the two; and the rotation's apart) against the estimate of its warning, C
(h / d)², d the load's distance from the end (a distributed load's centroid), h = max(spacing, horizon / 3) and C the
model's constant for the end's kind (``Model.estimate_constants``; pdverify/registry/end_loads.py; docs/trust.md). Where
it warns the ratio error / estimate must be below 1:

    PYTHONPATH=. python benchmarks/end_loads.py [--points 101 201 401] [--models pd-eb ...] [--horizons 3 5] [-o k=v]

A 1 m steel beam, 20 x 50 mm, on fifteen end pairs (the left end clamped, pinned, a spring: soft, stiff, with a soft
or a stiff rotational stiffness, free or guided), under one load near the left end: a patch from the end or off it, or
a point force, its arm 2.5 to 40 spacings. Printed per model and horizon: the largest ratio of the end's part of the
error to the estimate where the warning estimates (the end's part: with the load the same number of spacings off at
twice the points it stays while the rest falls 4 times; cases an earlier warning names are left out: a point load in
the end's layer), the constant each end kind's cases need, and the cases over 1e-3 no warning names. ``-o key=value``:
a model option (pd-bond-pair's variant and ends).
"""

from __future__ import annotations

import numpy as np
from estimate_args import parse

from pdverify.core.result import quantity_of
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run
from pdverify.registry.end_loads import CLOSEST, NEAR

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}
ENDS = [("clamped", "free"), ("clamped", "pinned"), ("clamped", "clamped"), ("pinned", "pinned"), ("pinned", "clamped")]
# spring ends on the left (EI 4.17e4 N m²): soft (k L³ / EI 24), stiff, with a soft and a stiff rotational one
SPRINGS = {
    "soft spring": {"type": "spring", "stiffness": 1e6},
    "stiff spring": {"type": "spring", "stiffness": 1e12},
    "spring kr 1e4": {"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e4},
    "spring kr 1e12": {"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e12},
}
ENDS += [(name, right) for name in SPRINGS for right in ("pinned", "clamped")]
ENDS += [("free", "clamped"), ("guided", "clamped")]  # a load near a free or guided end (the ends' ghosts carry it)
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
            "supports": {"left": SPRINGS.get(left, left), "right": right},
            "loads": loads(kind, arm),
        }
    )


def error(sc, name: str, n: int, m: float, options: dict | None = None):
    """(the larger of w's and M's largest errors, each relative to its own largest value, the rotation's, the
    warnings)."""
    r, e = run(sc, name, points=n, horizon=m, **(options or {})), run(sc, MODELS[name], points=n)
    M, Me = (quantity_of(x.w, x.rotation, x.fields, "moment") for x in (r, e))
    errors = [np.abs(a - b).max() / np.abs(b).max() for a, b in ((r.w, e.w), (M, Me)) if b is not None and b.any()]
    turn = np.abs(r.rotation - e.rotation).max() / np.abs(e.rotation).max() if np.abs(e.rotation).any() else 0.0
    return max(errors), float(turn), r.info.get("warnings", [])


def main() -> None:
    args, options = parse(__doc__, [101, 201, 401], list(MODELS))
    for name in args.models:
        for m in args.horizons:
            worst, turned, silent, need = (0.0, ""), (0.0, ""), [], {}
            for left, right in ENDS:
                for n in args.points:
                    dx = 1.0 / (n - 1)
                    for kind in ("patch from the end", "patch off the end", "force"):
                        for k in ARMS:
                            if 2 * k * dx >= 1.0:  # a patch twice its arm long would not fit on a coarse grid
                                continue
                            err, turn, said = error(scene(left, right, kind, k * dx), name, n, m, options)
                            # the same load k spacings off at twice the points: the end's part stays, the rest falls
                            # 4 times
                            finer, turn_fine, _ = error(
                                scene(left, right, kind, k * dx / 2), name, 2 * n - 1, m, options
                            )
                            end = max((4 * finer - err) / 3, finer)
                            end_turn = max((4 * turn_fine - turn) / 3, turn_fine)
                            label = f"{kind} arm {k} spacings, {left}-{right}, {n} points"
                            h = max(dx, m * dx / 3)
                            if (
                                CLOSEST * h <= k * dx < NEAR
                            ):  # the constant this case needs where it is estimated: end's part / (h/d)²
                                need[left] = max(need.get(left, (0.0, "")), (end / (h / (k * dx)) ** 2, label))
                            mine = [w for w in said if "spacings from the left end" in w and "(h / d)" in w]
                            if mine:
                                est = float(mine[0].split(", here ")[1].split(",")[0])
                                worst = max(worst, (end / est, label))
                                turned = max(turned, (end_turn / est, label))
                            elif err > 1e-3 and not said:
                                silent.append(f"{label}: {err:.2g} (the end's part {end:.2g})")
            c = get_model(name).estimate_constants(scene("clamped", "free", "force", 0.1), options)[0]
            print(f"{name} horizon {m:g}, C = {c}: largest error / estimate {worst[0]:.3f} ({worst[1]})")
            print(f"  the rotation's: {turned[0]:.3f} ({turned[1]})")
            for kind, (c_need, label) in sorted(need.items()):
                print(f"  the {kind} end's cases need C >= {c_need:.3g} ({label})")
            for line in silent:
                print(f"  unwarned over 1e-3: {line}")


if __name__ == "__main__":
    main()
