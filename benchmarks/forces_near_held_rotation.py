"""A point force beside a clamp inside the span: the PD beams' errors of w and of the rotation against the exact beam
beside the estimate of their warning (pdverify/numerics/load_warnings.py: held_rotation_warnings; docs/trust.md):

    PYTHONPATH=. python benchmarks/forces_near_held_rotation.py [--points 201 801] [--models pd-eb pd-timoshenko]

A 1 m aluminium beam (50 x 100 mm) on seven end pairs, clamped inside at 0.05 ... 0.9 L, under one force 0.01, 0.02,
0.04 or 0.08 m to either side of the clamp. Printed: each case whose estimate is below its error, or whose error
passes 1e-3 with neither the estimate nor the line of rows that straddle the force (none expected), then the counts
and the largest error / estimate, per model. About 15 seconds.
"""

from __future__ import annotations

import argparse

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.load_warnings import NEAR_TOLERANCE
from pdverify.registry import run

MODELS = ("pd-eb", "pd-timoshenko")
ENDS = [("clamped", "free"), ("pinned", "free"), ("clamped", "guided"), ("pinned", "pinned"), ("clamped", "pinned")]
ENDS += [("free", "pinned"), ("clamped", "clamped")]
AT = (0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 0.85, 0.9)
OFFSETS = (-0.08, -0.04, -0.02, -0.01, 0.01, 0.02, 0.04, 0.08)


def case(left: str, right: str, at: float, force: float):
    """The scene: the clamp inside at ``at``, the force at ``force``."""
    return parse_scene(
        {
            "name": "force beside a clamp inside",
            "beam": {"length": 1.0},
            "section": {"width": 0.05, "height": 0.1},
            "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33},
            "supports": {"left": left, "right": right, "inner": [{"position": at, "type": "clamped"}]},
            "loads": [{"type": "point_force", "position": force, "value": -1e3}],
        }
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="*", default=[201, 801])
    ap.add_argument("--models", nargs="*", default=list(MODELS))
    args = ap.parse_args()
    for model in args.models:
        rows, worst, warned, findings, straddled = 0, [0.0, 0.0], 0, 0, 0
        for (left, right), at, off in ((e, a, o) for e in ENDS for a in AT for o in OFFSETS):
            if not 0.005 < at + off < 0.995:
                continue
            sc = case(left, right, at, at + off)
            exact = solve_straight(sc, model != "pd-eb")
            for n in args.points:
                r = run(sc, model, points=n)
                ex = exact.fields(r.x)
                err = [float(np.abs(getattr(r, q) - ex[q]).max() / np.abs(ex[q]).max()) for q in ("w", "rotation")]
                lines = r.info.get("warnings", [])
                said = [w for w in lines if "which holds the rotation" in w]
                est = float(said[0].split(" = ")[-1].split(";")[0]) if said else None
                rows += 1
                if est is not None:
                    warned += 1
                    worst = [max(worst[k], err[k] / est) for k in (0, 1)]
                elif any("straddle" in w for w in lines):
                    straddled += 1
                    continue
                if (est is None and max(err) > NEAR_TOLERANCE) or (est is not None and max(err) > est):
                    findings += 1
                    print(
                        f"{model} {left}-{right} clamp at {at} force at {at + off:.3g} {n} points: "
                        f"errors w {err[0]:.2e} rotation {err[1]:.2e}, estimate {est}"
                    )
        print(
            f"{model}: {rows} cases, {warned} warned with the estimate, {straddled} with the straddle line, {findings} "
            f"above their estimate or over {NEAR_TOLERANCE:g} unwarned; error / estimate at most {worst[0]:.2f} (w), "
            f"{worst[1]:.2f} (rotation)"
        )


if __name__ == "__main__":
    main()
