"""A short span between two supports that hold the deflection: the PD beams' moment and shear errors in it against
the exact beam, beside the estimate of their warning (pdverify/numerics/span_warnings.py; docs/trust.md):

    PYTHONPATH=. python benchmarks/short_spans.py [--points 101 201 401 801] [--models pd-eb pd-timoshenko]

A 1 m steel beam (20 x 50 mm). Spans of 0.02, 0.0212, 0.04, 0.0437 and 0.08 L (on and off the grids): a pinned or
clamped support or a stiff, stiff and (partly) rotational, medium or soft spring inside that far from a pinned, clamped,
guided or free end; and two supports inside at 0.5 L and 0.5 L + a (each pinned or clamped, or a softer spring beside
a pin or a clamp) on pinned-pinned,
clamped-free and free-clamped beams. Loads: a force at 0.3 or 0.5 L (0.3 or 0.8 L beside two supports inside), or a
uniform load.
Printed per model: c = (error in the span) / (s (h / a)^2 max_span |q| / max |q|) for q = V, M (max_span: in the span
and a horizon beyond its ends; s the share a spring softer than 10 EI / a³ leaves, span_warnings.spring_share), its
largest by the span's supports (spans over `shortest` spacings only; a span to a softer spring apart), the cases whose
error passes 1e-3 with no warning at all, and the cases where the line is the only warning and every error is below
1e-3.
About a minute.
"""

from __future__ import annotations

import argparse
import itertools
from collections import defaultdict

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import NEAR_TOLERANCE
from pdverify.numerics.loads import within
from pdverify.numerics.span_warnings import spans
from pdverify.registry import run

MODELS = ("pd-eb", "pd-timoshenko")
SHORTEST = {"pd-eb": (10, 4), "pd-timoshenko": (0, 0)}  # as the models pass it (pd-eb: its layer and straddle lines)
INSIDE_ONLY = {"pd-eb": True, "pd-timoshenko": False}  # as the models pass it
QUANTITIES = ("V", "M")


# springs inside (EI = 4.17e4 N m²): stiff (k a³ / EI from 160 at a = 0.02 L: a support to the line), stiff with a
# stiff rotational stiffness (a clamp to it) or a partial one (kr a / EI 1.4 ... 5.8), medium (k a³ / EI 5.8 ... 369: a
# support to the line from 10), softer (0.19 ... 12 and 0.019 ... 1.2: a share of one below 10) and soft (at most 0.12)
SPRINGS = {
    "stiff spring": ({"type": "spring", "stiffness": 1e12}, False),
    "stiff spring kr": ({"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e12}, True),
    "stiff spring, partial kr": ({"type": "spring", "stiffness": 1e12, "rotational_stiffness": 3e6}, True),
    "medium spring": ({"type": "spring", "stiffness": 3e10}, False),  # k a³ / EI 5.8 ... 369
    "softer spring": ({"type": "spring", "stiffness": 1e9}, False),  # k a³ / EI 0.19 ... 12
    "softer spring 1e8": ({"type": "spring", "stiffness": 1e8}, False),  # k a³ / EI 0.019 ... 1.2
    "soft spring": ({"type": "spring", "stiffness": 1e7}, False),
}


def inner_support(kind: str, at: float) -> tuple[dict, bool]:
    """(the support inside at ``at``, whether it holds the rotation)."""
    if kind in SPRINGS:
        sup, held = SPRINGS[kind]
        return {**sup, "position": at}, held
    return {"type": kind, "position": at}, kind == "clamped"


def scenes(inside_only: bool):
    """(label, scene dictionary, span (lo, hi), holds the rotation) of every case (``inside_only``: only a support
    inside counts as holding it, as the model passes it)."""
    for end, inner, a, load in itertools.product(
        ("pinned", "clamped", "guided", "free"),
        ("pinned", "clamped", *SPRINGS),
        (0.02, 0.0212, 0.04, 0.0437, 0.08),
        ("F0.3", "F0.5", "q"),
    ):
        sup, held = inner_support(inner, 1.0 - a)
        yield (
            f"{inner} inside {a} from a {end} end, {load}",
            {"left": "pinned", "right": end},
            [sup],
            load,
            (1.0 - a, 1.0),
            held or (end == "clamped" and not inside_only),
        )
    for (t1, t2), (left, right), a, load in itertools.product(
        (
            ("clamped", "pinned"),
            ("pinned", "clamped"),
            ("clamped", "clamped"),
            ("pinned", "pinned"),
            ("clamped", "softer spring"),
            ("pinned", "softer spring"),
            ("clamped", "softer spring 1e8"),
        ),
        (("pinned", "pinned"), ("clamped", "free"), ("free", "clamped")),
        (0.02, 0.0212, 0.04, 0.0437, 0.08),
        ("F0.3", "F0.8", "q"),
    ):
        yield (
            f"{t1} and {t2} {a} apart inside a {left}-{right} beam, {load}",
            {"left": left, "right": right},
            [inner_support(t1, 0.5)[0], inner_support(t2, 0.5 + a)[0]],
            load,
            (0.5, 0.5 + a),
            inner_support(t1, 0.5)[1] or inner_support(t2, 0.5 + a)[1],
        )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[101, 201, 401, 801])
    ap.add_argument("--models", nargs="*", default=list(MODELS))
    args = ap.parse_args()
    for model in args.models:
        worst, silent, alone, rows = defaultdict(lambda: (0.0, "")), 0, 0, 0
        for label, ends, inner, load, (lo, hi), held in scenes(INSIDE_ONLY[model]):
            at = {"F0.3": 0.3, "F0.5": 0.5, "F0.8": 0.8}.get(load)
            ld = (
                {"type": "distributed", "value": -1e3}
                if at is None
                else {"type": "point_force", "position": at, "value": -1e3}
            )
            sc = parse_scene(
                {
                    "name": "short span",
                    "beam": {"length": 1.0},
                    "section": {"width": 0.02, "height": 0.05},
                    "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                    "supports": {**ends, "inner": inner},
                    "loads": [ld],
                }
            )
            exact = solve_straight(sc, model != "pd-eb")
            # the span as the models count it, and the share of a rigid support's error its springs leave
            shares = [s for p, q, s in spans(sc) if abs(p[0] - lo) < 1e-12 and abs(q[0] - hi) < 1e-12]
            bounded = bool(shares)
            for n in args.points:
                r = run(sc, model, points=n)
                ex, dx, a = exact.fields(r.x), r.x[1] - r.x[0], hi - lo
                span = (r.x >= lo - 1e-9) & (r.x <= hi + 1e-9)
                near = (r.x >= lo - 3 * dx * (1 + 1e-9)) & (r.x <= hi + 3 * dx * (1 + 1e-9))  # a horizon beyond
                errs, lines = {}, r.info.get("warnings", [])
                for q, name in (("w", "w"), ("rotation", "rotation"), ("V", "V"), ("M", "M")):
                    got = getattr(r, q) if q in ("w", "rotation") else np.asarray(r.fields[q])
                    d = np.abs(got - ex[name]) / np.abs(ex[name]).max()
                    errs[q] = float(d.max())
                    if q in QUANTITIES and bounded:
                        share = np.abs(got[near]).max() / np.abs(got).max()
                        if not within(a, SHORTEST[model][len(inner) > 1], dx) and share > 0:
                            key = (q, ("held" if held else "pinned") + (", softer spring" if shares[0] < 1 else ""))
                            c = float(d[span].max()) / ((dx / a) ** 2 * share * shares[0])
                            worst[key] = max(worst[key], (c, f"{label}, {n} points"))
                rows += 1
                if max(errs.values()) > NEAR_TOLERANCE and not lines:
                    silent += 1
                    print(f"{model} {label} {n} points: errors {errs}, no warning")
                if max(errs.values()) <= NEAR_TOLERANCE and lines and all(w.startswith("the span of") for w in lines):
                    alone += 1
        print(
            f"{model}: {rows} cases; {silent} over {NEAR_TOLERANCE:g} with no warning; {alone} with the span line "
            f"alone and every error below {NEAR_TOLERANCE:g}; largest c: "
            + "; ".join(f"{q} ({h}) {c:.3g} ({where})" for (q, h), (c, where) in sorted(worst.items()))
        )


if __name__ == "__main__":
    main()
