"""A distributed load's edge within the layer that an end's ghosts reach: pd-eb's (corrected) shear beside it against
the exact beam, beside the estimate of its warning (pdverify/numerics/load_warnings.py: edge_shear_warnings;
docs/trust.md):

    PYTHONPATH=. python benchmarks/load_edges.py [--points 101 401] [--horizons 1 2 3 4 5 3.5 4.7]

A 1 m steel beam (20 x 50 mm), its left end clamped, pinned, guided, free, a spring or a spring with a rotational
stiffness (the right end pinned, or clamped beside a guided or free one). One edge of a distributed load d spacings from
the left end (d = 0.3 ... 13.5, on and between points): a uniform or sine load from the edge to 0.5 L, a uniform one
from the end to the edge, and a short patch of 9 spacings from the edge. A horizon below 3 that is not whole is given
as a length (`horizon_length`, m = δ / spacing).
Printed: c = (the shear's largest error within the layer and 4 spacings beyond) / (|q| h) of the one-edge loads,
largest by the end's kind and by the edge's class (nearer than 2.5 spacings, farther within the layer of 2 m + 0.5
spacings, beyond it); the cases whose error (any quantity) passes 1e-3 with no warning; those whose shear error
passes 1e-3 and its line's estimate; and those where the line is the only warning and every error is below 1e-3.
About half a minute.
"""

from __future__ import annotations

import argparse
import itertools
from collections import defaultdict

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import EDGE_NEAR, NEAR_TOLERANCE
from pdverify.papers.diyaroglu.model import EDGE_SHEAR
from pdverify.registry import run

ENDS = {
    "clamped": ("clamped", "pinned"),
    "pinned": ("pinned", "pinned"),
    "guided": ("guided", "clamped"),
    "free": ("free", "clamped"),
    "spring": ({"type": "spring", "stiffness": 1e7}, "pinned"),
    "spring kr": ({"type": "spring", "stiffness": 1e7, "rotational_stiffness": 1e5}, "pinned"),
}
DISTANCES = (0.3, 0.5, 1.0, 1.5, 2.0, 2.6, 3.0, 4.5, 6.2, 8.0, 9.7, 11.5, 13.5)  # in spacings
FORMS = ("to the middle", "sine to the middle", "from the end", "patch of 9")


def load(form: str, a: float, dx: float) -> dict:
    """The distributed load of ``form`` with its edge at ``a``."""
    if form == "to the middle":
        return {"type": "distributed", "value": -1e3, "start": a, "end": 0.5}
    if form == "sine to the middle":
        return {"type": "distributed", "value": -1e3, "shape": "sine", "start": a, "end": 0.5}
    if form == "from the end":
        return {"type": "distributed", "value": -1e3, "start": 0.0, "end": a}
    return {"type": "distributed", "value": -1e3, "start": a, "end": a + 9 * dx}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[101, 401])
    ap.add_argument("--horizons", type=float, nargs="*", default=[1, 2, 3, 4, 5, 3.5, 4.7])
    args = ap.parse_args()
    worst = defaultdict(lambda: (0.0, ""))
    rows = silent = under = alone = zero = 0
    for (kind, (left, right)), n, m, d, form in itertools.product(
        ENDS.items(), args.points, args.horizons, DISTANCES, FORMS
    ):
        dx = 1.0 / (n - 1)
        sc = parse_scene(
            {
                "name": "load edge",
                "beam": {"length": 1.0},
                "section": {"width": 0.02, "height": 0.05},
                "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                "supports": {"left": left, "right": right},
                "loads": [load(form, d * dx, dx)],
            }
        )
        given = {"horizon": m} if float(m).is_integer() else {"horizon_length": m * dx}
        r = run(sc, "pd-eb", points=n, **given)
        ex = solve_straight(sc, False).fields(r.x)
        h = dx * max(1.0, m / 3)
        errs = {}
        for q in ("w", "rotation", "M", "V"):
            got = getattr(r, q) if q in ("w", "rotation") else np.asarray(r.fields[q])
            errs[q] = np.abs(got - ex[q]) / np.abs(ex[q]).max()
        near = r.x <= (2 * m + 4) * dx * (1 + 1e-9)
        V = np.asarray(r.fields["V"])
        if form in ("to the middle", "from the end"):  # one uniform load's edge inside: its c (a sine's jump near the
            # end is small beside its slope there, whose error is not the edge's)
            absolute = float(np.abs(V - ex["V"])[near].max())
            where = "near" if d < EDGE_NEAR else ("layer" if d < 2 * m + 0.5 else "beyond")
            key = (kind, where)
            worst[key] = max(
                worst[key],
                (
                    absolute / (1e3 * abs(float(sc.load_shape(sc.loads[0], d * dx))) * h),
                    f"{form}, d {d}, m {m}, {n} points",
                ),
            )
        rows += 1
        lines = r.info.get("warnings", [])
        mine = [w for w in lines if "that its ghosts reach: the shear" in w]
        fitted = [w for w in lines if w.startswith("loads[0] has an edge at")]  # the fitted ends' own line, quoted
        big = max(float(e.max()) for e in errs.values())
        label = f"{kind} end, {form}, d {d}, m {m}, {n} points"
        if big > NEAR_TOLERANCE and not lines:
            silent += 1
            print(f"silent: {label}: " + ", ".join(f"{q} {float(e.max()):.2g}" for q, e in errs.items()))
        if not np.abs(V).max() > 0:  # a load narrower than the grid, lumped on the held end: its own line
            zero += 1
            continue
        shear = float(errs["V"][near].max()) * np.abs(ex["V"]).max() / np.abs(V).max()  # relative to the model's
        est = float(mine[0].split("here ")[1].split(" ")[0]) if mine else 0.0
        if shear > NEAR_TOLERANCE and shear > est and not fitted:
            under += 1
            print(f"under: {label}: V {shear:.2g} near the end, estimate {est:g}; {len(lines)} lines")
        if big <= NEAR_TOLERANCE and mine and len(mine) == len(lines):
            alone += 1
    print(
        f"pd-eb (EDGE_SHEAR {EDGE_SHEAR}): {rows} cases; {silent} over {NEAR_TOLERANCE:g} with no warning; {under} "
        f"with the shear beside the end over {NEAR_TOLERANCE:g} and its line's estimate; {alone} with the line alone "
        f"and every error below {NEAR_TOLERANCE:g}; {zero} whose shear is zero (a load narrower than the grid)"
    )
    for (kind, where), (c, at) in sorted(worst.items()):
        print(f"  c {kind:10s} {where:7s} {c:.3g} ({at})")


if __name__ == "__main__":
    main()
