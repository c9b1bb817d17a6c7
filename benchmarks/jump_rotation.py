"""The rotation next to a jump of the shear: each PD beam's rotation error against its exact beam (relative to max
|rotation|) divided by the estimate of its warning, max over the jumps J (point forces, the ends' forces, the
reactions of supports inside) of c |J| h² / (EI max |rotation|), h = max(spacing, horizon / 3) and c the model's
``jump_rotation`` inside the span or at an end (pdverify/registry/jump_rotation.py; docs/trust.md). Every ratio must
be below 1:

    PYTHONPATH=. python benchmarks/jump_rotation.py [--points 41 61 101 201 401] [--models pd-eb ...] [--horizons 3 5]

A 1 m steel beam, 20 x 50 mm: a uniform load on four end pairs, and on [0, 0.3], [0, 0.51], [0, 0.7] of them; one
point force 1 to 40 spacings from a clamped or a pinned end, alone (on and off a point, clamped or pinned ends), or 0.5
to 12.4 spacings beside a pin inside on a point, a pin off the points, or a spring of 1e9 N/m. Printed per model
and horizon: the largest ratio over the cases with no other warning and its case, the largest where another warning
names the cause (a force in an end's layer), and every case over 1e-3 of max |rotation| unwarned. ``-o key=value``:
a model option (pd-bond-pair's variant and ends).
"""

from __future__ import annotations

import numpy as np
from estimate_args import parse

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run
from pdverify.registry.jump_rotation import jump_estimates

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}
UNIFORM = {"type": "distributed", "value": -1000.0}


def scene(left: str, right: str, inner: dict | None, force_at: float | None, patch: float | None = None):
    """The beam on ``left``, ``right`` and ``inner`` supports under a point force at ``force_at`` (None: a uniform
    load, or one on [0, ``patch``])."""
    force = {"type": "point_force", "position": force_at, "value": -700.0}
    load = UNIFORM if patch is None else {**UNIFORM, "start": 0.0, "end": patch}
    d = {
        "name": "jump",
        "beam": {"length": 1.0},
        "section": {"width": 0.02, "height": 0.05},
        "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
        "supports": {"left": left, "right": right, "inner": [inner] if inner else []},
        "loads": [load if force_at is None else force],
    }
    return parse_scene(d)


def cases(dx: float):
    """(name, scene) of every case at spacing ``dx``."""
    for left, right in (("clamped", "clamped"), ("pinned", "pinned"), ("clamped", "free"), ("clamped", "pinned")):
        yield f"uniform {left}-{right}", scene(left, right, None, None)
        for a in (0.3, 0.51, 0.7):  # a load over one end and past the middle: the end's reaction and the load's edge
            yield f"patch [0, {a}] {left}-{right}", scene(left, right, None, None, a)
    for k in (1, 3.5, 6, 12.37, 40):
        yield f"{k} from a clamped end", scene("clamped", "pinned", None, k * dx)
        yield f"{k} from a pinned end", scene("pinned", "clamped", None, k * dx)
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
    args, options = parse(__doc__, [41, 61, 101, 201, 401], list(MODELS))
    for name in args.models:
        for m in args.horizons:
            worst, flagged, silent, used = (0.0, ""), (0.0, ""), [], set()
            for n in args.points:
                dx = 1.0 / (n - 1)
                for label, sc in cases(dx):
                    r, e = run(sc, name, points=n, horizon=m, **options), run(sc, MODELS[name], points=n)
                    err = np.abs(r.rotation - e.rotation)
                    c = get_model(name).estimate_constants(sc, options)[1]  # the options' (pd-bond-pair's ends)
                    used.add(c)
                    _, _, est = jump_estimates(c, sc, r.rotation, r.info)
                    if not len(est) or not est.max():  # nothing estimated (no rotation: the force on a support)
                        continue
                    ratio = err.max() / np.abs(e.rotation).max() / est.max()
                    others = [w for w in r.info.get("warnings", []) if not w.startswith("rotation beside")]
                    if others:  # the case's error has another cause its warnings name (a load in an end's layer)
                        flagged = max(flagged, (ratio, f"{label}, {n} points: {others[0][:60]}"))
                    else:
                        worst = max(worst, (ratio, f"{label}, {n} points"))
                    rel = err.max() / np.abs(e.rotation).max()
                    if rel > 1e-3 and not r.info.get("warnings"):
                        silent.append(f"{label}, {n} points: {rel:.2g}")
            c = " and ".join(map(str, sorted(used)))
            print(f"{name} horizon {m:g}, c = {c}: largest error / estimate {worst[0]:.3f} ({worst[1]})")
            print(f"  largest where another warning names the cause: {flagged[0]:.3f} ({flagged[1]})")
            for line in silent:
                print(f"  unwarned over 1e-3: {line}")


if __name__ == "__main__":
    main()
