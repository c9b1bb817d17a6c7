"""A distributed load that pd-eb (corrected) takes by its cell averages, not by its jumps, because an edge lies within
the 2 J spacings of an end where the rows of its kinks would leave the grid: the shear beside each of its edges (the
far one too) against the exact beam, beside the estimate of its warning (pdverify/numerics/load_warnings.py:
cell_average_warnings; docs/trust.md):

    PYTHONPATH=. python benchmarks/load_edges.py [--points 101 401] [--horizons 1 2 3 4 5 3.5 4.7]

A 1 m steel beam (20 x 50 mm), its left end clamped, pinned, guided, free, a spring or a spring with a rotational
stiffness (the right end pinned, or clamped beside a guided or free one). A load with one edge d spacings from the left
end (d = 0.3 ... 13.5) and the other at 0.5 L + f spacings (f = 0, 0.02, 0.25, 0.5, 0.8: where it falls between points),
uniform or sine, or a patch of 9 spacings from d. A horizon that is not whole is given as a length (`horizon_length`,
m = δ / spacing).
Printed: c = (the shear's largest error within 2 J + 3 spacings of an edge) / (|q| dx + |q'| dx²), q and q' the load and
its slope at the edge (beyond 2 J + 4 spacings of the end, times its place between points, `cell_place`), largest by
the load's shape and the edge (near the end, far), for the loads taken by their cell averages and for those taken by
their jumps; the cases whose error (any quantity) passes 1e-3 with no warning; those whose shear error passes 1e-3
and the line's estimate (both relative to the model's max |V|; not where the fitted ends' line names the edge); and
those where the line is the only warning and every error is below 1e-3; the largest shear error beside the line's
estimate. About 40 seconds.
"""

from __future__ import annotations

import argparse
import itertools
from collections import defaultdict

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import CELL_REACH, NEAR_TOLERANCE, cell_place
from pdverify.numerics.loads import within
from pdverify.papers.diyaroglu.model import CELL_SHEAR
from pdverify.papers.diyaroglu.operator import curvature_weights
from pdverify.papers.diyaroglu.scenes import spreads
from pdverify.registry import run

ENDS = {
    "clamped": ("clamped", "pinned"),
    "pinned": ("pinned", "pinned"),
    "guided": ("guided", "clamped"),
    "free": ("free", "clamped"),
    "spring": ({"type": "spring", "stiffness": 1e7}, "pinned"),
    "spring kr": ({"type": "spring", "stiffness": 1e7, "rotational_stiffness": 1e5}, "pinned"),
}
DISTANCES = (0.3, 1.0, 2.4, 4.5, 6.2, 8.0, 9.7, 13.5)  # of the near edge, in spacings
FORMS = ("uniform", "sine", "patch of 9")
FAR = (0.0, 0.02, 0.25, 0.5, 0.8)  # the far edge at 0.5 L + FAR spacings


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[101, 401])
    ap.add_argument("--horizons", type=float, nargs="*", default=[1, 2, 3, 4, 5, 3.5, 4.7])
    args = ap.parse_args()
    worst = defaultdict(lambda: (0.0, ""))
    rows = silent = under = alone = lined = 0
    ratio = (0.0, "")
    for (kind, (left, right)), n, m, d, form, f in itertools.product(
        ENDS.items(), args.points, args.horizons, DISTANCES, FORMS, FAR
    ):
        if form == "patch of 9" and f:
            continue
        dx = 1.0 / (n - 1)
        a, b = d * dx, (d + 9) * dx if form == "patch of 9" else 0.5 + f * dx
        load = {"type": "distributed", "value": -1e3, "start": a, "end": b}
        if form == "sine":
            load["shape"] = "sine"
        sc = parse_scene(
            {
                "name": "load edge",
                "beam": {"length": 1.0},
                "section": {"width": 0.02, "height": 0.05},
                "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                "supports": {"left": left, "right": right},
                "loads": [load],
            }
        )
        given = {"horizon": m} if float(m).is_integer() else {"horizon_length": m * dx}
        r = run(sc, "pd-eb", points=n, **given)
        J = len(curvature_weights(r.info["horizon_factor"], dx, "corrected"))
        cells = not spreads(sc.loads[0], sc, n, dx, J)
        ex = solve_straight(sc, False).fields(r.x)
        errs = {}
        for q in ("w", "rotation", "M", "V"):
            got = getattr(r, q) if q in ("w", "rotation") else np.asarray(r.fields[q])
            errs[q] = float(np.abs(got - ex[q]).max() / np.abs(ex[q]).max())
        V = np.asarray(r.fields["V"])
        dV = np.abs(V - ex["V"])
        k = np.pi if form == "sine" else 0.0
        for which, e in (("near", a), ("far", b)):
            size = 1e3 * (abs(float(sc.load_shape(sc.loads[0], e))) * dx + k * abs(np.cos(k * e)) * dx * dx)
            if not within(min(e, 1.0 - e), 2 * J + CELL_REACH, dx):  # beyond the layer: by its place between points
                size *= cell_place(e / dx)
            if size > 0:
                key = ("cells" if cells else "jumps", "sine" if form == "sine" else "uniform", which)
                c = float(dV[np.abs(r.x - e) <= (2 * J + 3) * dx].max()) / size
                worst[key] = max(worst[key], (c, f"{kind} end, {form}, d {d}, far +{f}, m {m}, {n} points"))
        rows += 1
        lines = r.info.get("warnings", [])
        mine = [w for w in lines if "by its cell averages" in w]
        label = f"{kind} end, {form}, d {d}, far +{f}, m {m}, {n} points"
        if max(errs.values()) > NEAR_TOLERANCE and not lines:
            silent += 1
            print(f"silent: {label}: " + ", ".join(f"{q} {e:.2g}" for q, e in errs.items()))
        if not np.abs(V).max() > 0:  # a load narrower than the grid, lumped on the held end: its own line
            continue
        shear = float(dV.max() / np.abs(V).max())  # relative to the model's, as the line
        est = float(mine[0].split(" here ")[1].split(" ")[0]) if mine else 0.0
        fitted = any(w.startswith("loads[0] has an edge at") for w in lines)  # the fitted ends' line, quoted
        if shear > NEAR_TOLERANCE and shear > est and not fitted:
            under += 1
            print(f"under: {label}: V {shear:.2g}, estimate {est:g}; {len(lines)} lines")
        lined += bool(mine)
        if mine:
            ratio = max(ratio, (shear / est, label))
        if max(errs.values()) <= NEAR_TOLERANCE and mine and len(mine) == len(lines):
            alone += 1
    print(
        f"pd-eb (CELL_SHEAR {CELL_SHEAR}): {rows} cases; {silent} over {NEAR_TOLERANCE:g} with no warning; {under} "
        f"with the shear over {NEAR_TOLERANCE:g} and the line's estimate (where the fitted ends' line does not name "
        f"the edge); {alone} with the line alone and every error below {NEAR_TOLERANCE:g}; {lined} with the line, the "
        f"shear's error at most {ratio[0]:.3g} of its estimate ({ratio[1]})"
    )
    for key, (c, at) in sorted(worst.items()):
        print(f"  c {' '.join(key):22s} {c:.3g} ({at})")


if __name__ == "__main__":
    main()
