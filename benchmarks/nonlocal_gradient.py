"""Each PD model's gradient coefficient, measured (docs/nonlocal.md):

    PYTHONPATH=. python benchmarks/nonlocal_gradient.py [--deltas 0.05 0.08]

On the nonlocal study's sine-loaded members (studies/nonlocal/: a pinned-pinned beam, a clamped-clamped rod and
shaft, L = 1), the model's continuum at each horizon delta (its discrete solution extrapolated in m at fixed delta,
pdverify.theory.continuum, never the series of its symbol) against the local solution at the largest value:
g = (continuum / local - 1) / (k delta)^2, k = pi / L, beside the symbol's g (pdverify.theory.symbols.GRADIENT;
pd-higher-order's slender limit, higher_order_gradient, against its own theory, exact-higher-order with the loads and
pins the model is given) and the extrapolation's own estimate.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from pdverify.core.scene_file import load_scene
from pdverify.registry import get_model, run
from pdverify.theory import continuum as C
from pdverify.theory.symbols import GRADIENT, higher_order_gradient

CASES = [  # (model, options, scene, symbol, local reference)
    ("pd-eb", {}, "pp_sine", "curvature", "exact-eb"),
    ("pd-eb", {"variant": "paper"}, "pp_sine", "curvature", "exact-eb"),
    ("pd-bond-pair", {"ends": "mirror"}, "pp_sine", "bond-pair", "exact-eb"),
    ("pd-bond-pair", {"ends": "mirror", "variant": "paper"}, "pp_sine", "bond-pair", "exact-eb"),
    ("pd-bond-pair", {}, "pp_sine", "bond-pair", "exact-eb"),
    ("pd-rod", {}, "rod_cc_sine", "rod", "exact-rod"),
    ("pd-rod", {"variant": "paper"}, "rod_cc_sine", "rod", "exact-rod"),
    ("pd-torsion", {}, "shaft_cc_sine", "rod", "exact-torsion"),
    ("pd-torsion", {"variant": "paper"}, "shaft_cc_sine", "rod", "exact-torsion"),
    (
        "pd-higher-order",
        {"ends": "mirror", "pin": "mid", "loads": "mid"},
        "pp_sine",
        "higher-order",
        ("exact-higher-order", {"pin": "held", "loads": "mid"}),
    ),
]


def measure(model, opts, scene_name, ref, delta, top=64):
    scene = load_scene(f"studies/nonlocal/{scene_name}.toml")
    m = get_model(model)
    points = int(round(8 * scene.length / delta)) + 1
    base = m.resolve(scene, dict(opts, points=points, horizon_length=delta, continuum_m=top))
    base = {k: v for k, v in base.items() if k not in ("horizon", "continuum")}
    dx = scene.length / (points - 1)
    (x, w, _, fields), info = C._extrapolated(m, scene, base, delta, dx, m.continuum_limit(scene, base))
    value = w if m.measures == "w" else fields[m.measures]
    name, given = ref if isinstance(ref, tuple) else (ref, {})
    e = run(scene, name, points=points, **given)
    local = e.w if m.measures == "w" else e.fields[m.measures]
    i = int(np.argmax(np.abs(local)))
    k = math.pi / scene.length
    return (value[i] / local[i] - 1) / (k * delta) ** 2, info["error_bound"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--deltas", type=float, nargs="+", default=[0.05, 0.08])
    args = ap.parse_args()
    for model, opts, scene, symbol, ref in CASES:
        got = [measure(model, opts, scene, ref, d) for d in args.deltas]
        nu = load_scene(f"studies/nonlocal/{scene}.toml").material.poissons_ratio
        want = f"{higher_order_gradient(nu) if symbol == 'higher-order' else GRADIENT[symbol]:.5f}"
        text = "  ".join(f"delta={d:g}: g={g:.5f} (estimate {e:.1e})" for d, (g, e) in zip(args.deltas, got))
        name = model + "".join(f" {k}={v}" for k, v in opts.items())
        print(f"{name:40s} symbol g={want}  {text}", flush=True)


if __name__ == "__main__":
    main()
