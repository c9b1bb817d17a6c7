"""A distributed axial load or torque that ends inside a rod or a torsion bar: pd-rod's displacement and pd-torsion's
twist against the exact member, beside the estimate of their warning (pdverify/papers/moyer/load_edges.py;
docs/trust.md):

    PYTHONPATH=. python benchmarks/member_edges.py [--points 51 101 201 401] [--horizons 1 2 3 5]

A 1 m steel member (20 x 50 mm), clamped-pinned, clamped-free or pinned-clamped, under a uniform load of 1 kN/m on
[0.3, 0.7], [0.2, 0.35], [0.5, 1] or [0.1, 0.9] L, each edge moved f = 0, 0.25, 0.5, 0.8 of a spacing. Printed per
model: c = (the largest error of u or the twist relative to its largest value) / (Σ |p| h² / (S max)) over the cases
whose error passes 1e-4 (h = max(spacing, horizon / 3), p the load's jump at an edge, S = EA or GJ), the cases whose
error passes 1e-3 with no warning, those whose error passes the line's estimate, and those where the line is the only
warning and the error is below 1e-3. About 20 seconds.
"""

from __future__ import annotations

import argparse
import itertools
import re

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.numerics.load_warnings import NEAR_TOLERANCE
from pdverify.registry import run

MODELS = {"pd-rod": ("exact-rod", "axial", "u"), "pd-torsion": ("exact-torsion", "torque", "twist")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[51, 101, 201, 401])
    ap.add_argument("--horizons", type=int, nargs="*", default=[1, 2, 3, 5])
    args = ap.parse_args()
    for model, (ref, component, field) in MODELS.items():
        c, silent, under, alone, rows, over = 0.0, 0, 0, 0, 0, []
        for (left, right), n, m, (a, b), f in itertools.product(
            (("clamped", "pinned"), ("clamped", "free"), ("pinned", "clamped")),
            args.points,
            args.horizons,
            ((0.3, 0.7), (0.2, 0.35), (0.5, 1.0), (0.1, 0.9)),
            (0.0, 0.25, 0.5, 0.8),
        ):
            dx = 1.0 / (n - 1)
            start, end = a + f * dx, (b + f * dx if b < 1.0 else 1.0)
            load = {"type": "distributed", "value": 0.0, component: 1e3, "start": start, "end": end}
            sc = parse_scene(
                {
                    "name": "a patch on a member",
                    "beam": {"length": 1.0},
                    "section": {"width": 0.02, "height": 0.05},
                    "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                    "supports": {"left": left, "right": right},
                    "loads": [load],
                }
            )
            r, e = run(sc, model, points=n, horizon=m), run(sc, ref, points=n)
            got, want = np.asarray(r.fields[field]), np.asarray(e.fields[field])
            err = float(np.abs(got - want).max() / np.abs(want).max())
            stiff = 2e11 * 0.02 * 0.05 if component == "axial" else float(sc.material.G * sc.section.J)
            edges = [x for x in (start, end) if 0.0 < x < 1.0]
            h = max(dx, m * dx / 3)
            if err > 0.1 * NEAR_TOLERANCE:
                c = max(c, err / (len(edges) * 1e3 * h * h / stiff / np.abs(got).max()))
            lines = r.info.get("warnings", [])
            said = [w for w in lines if "ends inside the member" in w]
            rows += 1
            if err > NEAR_TOLERANCE and not lines:
                silent += 1
                print(f"silent: {model} {left}-{right} {n} points horizon {m} [{start:g}, {end:g}]: {err:.3g}")
            if said:
                est = float(re.search(r"here ([\d.e+-]+) of its largest", said[0]).group(1))
                if err > est:
                    under += 1
                    print(f"under: {model} {left}-{right} {n} points horizon {m}: {err:.3g} against {est:g}")
                if len(lines) == 1 and err <= NEAR_TOLERANCE:
                    alone += 1
                    over.append(est / max(err, 1e-300))
        ratio = f" (estimate / error: median {np.median(over):.3g}, largest {max(over):.3g})" if over else ""
        print(
            f"{model}: {rows} cases; largest c {c:.3g}; {silent} over {NEAR_TOLERANCE:g} with no warning; {under} "
            f"whose error passes the line's estimate; {alone} with the line alone and the error below "
            f"{NEAR_TOLERANCE:g}{ratio}"
        )


if __name__ == "__main__":
    main()
