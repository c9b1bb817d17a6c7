"""The rotation next to a jump of the shear: each PD beam's error against its exact beam divided by |J| h² / EI, the
largest jump J inside the span (a point force, a support's reaction) and h = max(spacing, horizon / 3); the constant
its warning uses (Model.jump_rotation, pdverify/registry/jump_rotation.py; docs/trust.md) must be above every ratio:

    PYTHONPATH=. python benchmarks/jump_rotation.py [--points 201 401] [--models pd-eb ...] [--horizons 3 5]

A 1 m steel beam, 20 x 50 mm, pinned at both ends, under one point force: alone (on and off a point, clamped or pinned
ends), or 0.5 to 12.4 spacings beside a pin inside on a point, a pin off the points, or a spring of 1e9 N/m.
Printed per model and horizon: the largest ratio, its case, and the cases over 1e-3 of max |rotation| unwarned.
"""

from __future__ import annotations

import argparse

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}


def scene(left: str, right: str, inner: dict | None, force_at: float):
    d = {
        "name": "jump",
        "beam": {"length": 1.0},
        "section": {"width": 0.02, "height": 0.05},
        "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
        "supports": {"left": left, "right": right, "inner": [inner] if inner else []},
        "loads": [{"type": "point_force", "position": force_at, "value": -700.0}],
    }
    return parse_scene(d)


def cases(dx: float):
    """(name, scene) of every case at spacing ``dx``."""
    for f in (0.0, 0.37):
        yield f"alone clamped-clamped +{f}", scene("clamped", "clamped", None, 0.5 + f * dx)
        yield f"alone pinned-pinned +{f}", scene("pinned", "pinned", None, 0.3 + f * dx)
    for k in (0.5, 1, 1.37, 3.5, 6, 12.37):
        yield f"{k} beside a pin", scene("pinned", "pinned", {"type": "pinned", "position": 0.5}, 0.5 + k * dx)
        at = 0.5 + 0.41 * dx
        yield (
            f"{k} beside a pin off the points",
            scene("pinned", "pinned", {"type": "pinned", "position": at}, at + k * dx),
        )
        spring = {"type": "spring", "position": 0.5, "stiffness": 1e9}
        yield f"{k} beside a spring", scene("pinned", "pinned", spring, 0.5 + k * dx)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=[201, 401])
    ap.add_argument("--models", nargs="+", default=list(MODELS))
    ap.add_argument("--horizons", type=float, nargs="+", default=[3.0, 5.0])
    args = ap.parse_args()
    for name in args.models:
        for m in args.horizons:
            worst, silent = (0.0, ""), []
            for n in args.points:
                dx = 1.0 / (n - 1)
                h = max(dx, m * dx / 3)
                for label, sc in cases(dx):
                    r, e = run(sc, name, points=n, horizon=m), run(sc, MODELS[name], points=n)
                    err = np.abs(r.rotation - e.rotation)
                    J = max([700.0] + [abs(v) for k, v in r.info["reactions"].items() if k.startswith("force_inner")])
                    ratio = err.max() * sc.EI / (J * h**2)
                    worst = max(worst, (ratio, f"{label}, {n} points"))
                    rel = err.max() / np.abs(e.rotation).max()
                    if rel > 1e-3 and not r.info.get("warnings"):
                        silent.append(f"{label}, {n} points: {rel:.2g}")
            c = get_model(name).jump_rotation
            print(f"{name} horizon {m:g}: largest ratio {worst[0]:.3f} ({worst[1]}); constant {c:g}")
            for line in silent:
                print(f"  unwarned over 1e-3: {line}")


if __name__ == "__main__":
    main()
