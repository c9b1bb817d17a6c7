"""Distributed loads beside a clamp inside the span: the PD beams' error against the exact beam beside the estimate of
their warning (pdverify/numerics/load_warnings.py: distributed_near_held_warnings; docs/trust.md):

    PYTHONPATH=. python benchmarks/loads_near_held_rotation.py [--slenderness 10 100] [--points 101 401] [--models ...]

A 1 m steel beam of square section on every listed end pair, clamped inside at 0.15, 0.3, 0.5, 0.71 or 0.9 L, under
one distributed load (partial loads on either side or across the clamp, a uniform and a sine load on the whole beam).
pd-eb and pd-timoshenko against exact Euler-Bernoulli and Timoshenko beams, pd-higher-order against exact-higher-order
(its own theory, with the model's loads and pin). Printed: each case whose estimate is below its error or whose error
passes 1e-3 unwarned (none expected), then the counts and the quantiles of estimate / error over the warned cases,
per model.
"""

from __future__ import annotations

import argparse

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import NEAR_TOLERANCE
from pdverify.registry import get_model, run

MODELS = ("pd-eb", "pd-timoshenko", "pd-higher-order")
ENDS = [("free", "pinned"), ("pinned", "pinned"), ("clamped", "free"), ("free", "guided"), ("pinned", "clamped")]
ENDS += [("clamped", "clamped"), ("guided", "free"), ("pinned", "free")]
AT = (0.15, 0.3, 0.5, 0.71, 0.9)
LOADS = [(0.02, 0.1), (0.1, 0.29), (0.0, 0.6), (-0.3, -0.02), (-0.1, 0.2), (-0.2, -0.11), (-1, 1), "sine"]


def case(left, right, at, load, slenderness):
    """The scene, or None where the load falls off the beam."""
    if load == "sine":
        ld = {"type": "distributed", "value": -1e3, "shape": "sine"}
    else:
        start, end = max(0.0, at + load[0]), min(1.0, at + load[1])
        if end <= start + 0.005:
            return None
        ld = {"type": "distributed", "value": -1e3, "start": start, "end": end}
    h = 1.0 / slenderness
    return parse_scene(
        {
            "name": "clamp inside",
            "beam": {"length": 1.0},
            "section": {"width": h, "height": h},
            "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33},
            "supports": {"left": left, "right": right, "inner": [{"position": at, "type": "clamped"}]},
            "loads": [ld],
        }
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slenderness", type=float, nargs="*", default=[10.0, 100.0])
    ap.add_argument("--points", type=int, nargs="*", default=[101, 401])
    ap.add_argument("--models", nargs="*", default=list(MODELS))
    args = ap.parse_args()
    for model in args.models:
        rows, ratios, findings, quiet_small = 0, [], 0, 0
        for (left, right), at, load, slenderness in (
            (e, a, ld, s) for e in ENDS for a in AT for ld in LOADS for s in args.slenderness
        ):
            sc = case(left, right, at, load, slenderness)
            if sc is None:
                continue
            exact = reference(sc, model)
            for n in args.points:
                r = run(sc, model, points=n)
                ex = exact(r.x)
                err = float(np.abs(r.w - ex).max() / np.abs(ex).max())
                said = [w for w in r.info.get("warnings", []) if w.startswith("distributed loads beside")]
                est = float(said[0].split(" = ")[1].split(" (")[0]) if said else None
                rows += 1
                if est is not None:
                    ratios.append(est / err)
                    quiet_small += err < NEAR_TOLERANCE
                if (est is None and err > NEAR_TOLERANCE) or (est is not None and err > est):
                    findings += 1
                    print(
                        f"{model} {left}-{right} clamp at {at} load {load} L/h {slenderness:g} {n} points: "
                        f"error {err:.2e}, estimate {est}"
                    )
        q = np.quantile(ratios, [0.0, 0.5, 1.0]) if ratios else [np.nan] * 3
        print(
            f"{model}: {rows} cases, {len(ratios)} warned ({quiet_small} with an error below {NEAR_TOLERANCE:g}), "
            f"{findings} below their estimate's promise; estimate / error: least {q[0]:.3g}, median {q[1]:.3g}, "
            f"largest {q[2]:.3g}"
        )


def reference(sc, model: str):
    """x -> the reference deflection at x: the exact beam of the model's theory."""
    if model == "pd-higher-order":
        opts = get_model(model).reference_options({})
        return lambda x: get_model("exact-higher-order").evaluate(sc, opts, x)["w"]
    exact = solve_straight(sc, model != "pd-eb")
    return lambda x: exact.fields(x)["w"]


if __name__ == "__main__":
    main()
