"""A sine load that ends inside the beam, where its slope jumps: pd-eb (corrected)'s shear beside such an edge against
the exact beam, beside the estimate of its warning (pdverify/numerics/load_warnings.py: slope_jump_warnings;
docs/trust.md):

    PYTHONPATH=. python benchmarks/slope_jumps.py [--points 401 1601] [--horizons 1 3 5]

A 1 m steel beam (20 x 50 mm), its left end clamped, pinned, guided or free (the right end clamped, or pinned beside a
clamped one), under a sine load q = q0 sin(πx / L) on a patch of 2, 3, 4, 6, 9, 20 or 60 spacings whose first edge
lies 5, 12, 40 or 150 spacings (plus f = 0, 0.3, 0.5 of one) from the left end: beyond the 2 J spacings within which
the model takes a load by its cell averages, so by its jumps. Printed: c = (the shear's largest error within 3
spacings of an edge) / (|q'| dx²) at that edge, largest by f, where no other line speaks and it passes 1e-4 of max
|V|; the cases whose error (any quantity) passes 1e-3 with no warning; those whose shear error passes the line's
estimate (both relative to the model's max |V|); those where the line is the only warning and every error is below
1e-3, with the estimate's ratio to the largest error there. About 10 seconds.
"""

from __future__ import annotations

import argparse
import itertools
import re
from collections import defaultdict

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import NEAR_TOLERANCE
from pdverify.registry import run

ENDS = {"clamped": "pinned", "pinned": "clamped", "guided": "clamped", "free": "clamped"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[401, 1601])
    ap.add_argument("--horizons", type=float, nargs="*", default=[1, 3, 5])
    args = ap.parse_args()
    worst, silent, under, alone, ratios, rows = defaultdict(float), 0, 0, 0, [], 0
    for (left, right), n, m, width, d, f in itertools.product(
        ENDS.items(), args.points, args.horizons, (2, 3, 4, 6, 9, 20, 60), (5, 12, 40, 150), (0.0, 0.3, 0.5)
    ):
        dx = 1.0 / (n - 1)
        a, b = (d + f) * dx, (d + f + width) * dx
        load = {"type": "distributed", "shape": "sine", "value": -1e3, "start": a, "end": b}
        sc = parse_scene(
            {
                "name": "a sine patch",
                "beam": {"length": 1.0},
                "section": {"width": 0.02, "height": 0.05},
                "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                "supports": {"left": left, "right": right},
                "loads": [load],
            }
        )
        r = run(sc, "pd-eb", variant="corrected", points=n, horizon=m)
        ex = solve_straight(sc, False).fields(r.x)
        errs = {}
        for q in ("w", "rotation", "M", "V"):
            got = getattr(r, q) if q in ("w", "rotation") else np.asarray(r.fields[q])
            errs[q] = float(np.abs(got - ex[q]).max() / np.abs(ex[q]).max())
        dV = np.abs(np.asarray(r.fields["V"]) - ex["V"])
        lines = r.info.get("warnings", [])
        said = [w for w in lines if "where its slope q' jumps" in w]
        top = float(np.abs(np.asarray(r.fields["V"])).max())
        for e in (a, b) if len(lines) == len(said) else ():  # no other line: the edges' own errors
            near = np.abs(r.x - e) <= 3 * dx * (1 + 1e-9)
            slope = abs(1e3 * np.pi * np.cos(np.pi * e)) * dx * dx
            if dV[near].max() > 0.1 * NEAR_TOLERANCE * top:  # (else the beam's own error, not the edge's)
                worst[f] = max(worst[f], float(dV[near].max()) / slope)
        shear = float(dV.max() / np.abs(np.asarray(r.fields["V"])).max())
        rows += 1
        if max(errs.values()) > NEAR_TOLERANCE and not lines:
            silent += 1
            print(f"silent: {left} end, {n} points, horizon {m:g}, patch {width} from {d + f}: {errs}")
        if said:
            est = float(re.search(r"here ([\d.e+-]+) of max \|V\|", said[0]).group(1))
            if shear > est:
                under += 1
                print(
                    f"under: {left} end, {n} points, horizon {m:g}, patch {width} from {d + f}: V {shear:.3g}, {est:g}"
                )
            if len(lines) == 1 and max(errs.values()) <= NEAR_TOLERANCE:
                alone += 1
                ratios.append(est / max(errs.values()))
    print(
        f"pd-eb (corrected): {rows} cases; {silent} over {NEAR_TOLERANCE:g} with no warning; {under} whose shear error "
        f"passes the line's estimate; {alone} with the line alone and every error below {NEAR_TOLERANCE:g}"
        + (f" (estimate / largest error: median {np.median(ratios):.3g}, largest {max(ratios):.3g})" if ratios else "")
    )
    print("largest c by the edge's place between points: " + ", ".join(f"f {k:g}: {v:.3g}" for k, v in worst.items()))


if __name__ == "__main__":
    main()
