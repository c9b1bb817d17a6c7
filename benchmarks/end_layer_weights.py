"""pd-higher-order's end-layer bond weights at a fixed horizon (docs/nonlocal.md, "A limit at fixed δ"):

    PYTHONPATH=. python benchmarks/end_layer_weights.py [--delta 0.2] [--m 16 64 256] [--stiffness]

The corrected variant's truncated ends calibrate the bonds of the 2J + 1 points at each end so that every point keeps
Σ_j w_kj ξ² = V_k and every nearest-neighbour segment carries the same total Σ w_kj ξ² / d = Δx
(``end_layer = patch``, :func:`pdverify.papers.yang.bonds.end_layer_weights`). The segment next to an end is covered
only by the bonds from or onto the end point, two per offset, where an interior segment has 2d bonds of offset d, so
holding its total makes those bonds' weights grow like m at a fixed δ. Printed: each listed bond's weight over the
interior weight of its offset, on a 1 m beam, for each m; the last column is the largest ratio in the layer and the most
negative one.
"""

from __future__ import annotations

import argparse

from pdverify.papers.yang.bonds import end_layer_ratios, end_layer_weights

BONDS = (  # (point, offset) as functions of m: the end point's nearest and longest bonds, the bonds onto it
    ("end point, offset +1", lambda m: (0, 1)),
    ("end point, offset +m", lambda m: (0, m)),
    ("point 1 onto the end", lambda m: (1, -1)),
    ("point m/2 onto the end", lambda m: (m // 2, -(m // 2))),
    ("point m onto the end", lambda m: (m, -m)),
    ("point m/2, offset +1", lambda m: (m // 2, 1)),
    ("point 2m, offset +1", lambda m: (2 * m, 1)),
)


def ratios(m: int, delta: float) -> tuple[list[float], float, float]:
    """The listed bonds' weights over the interior weights of their offsets, and the layer's largest and smallest."""
    dx = delta / m
    n = int(round(1.0 / dx)) + 1
    k, off, _ = end_layer_weights(n, float(m), dx, "partial")
    ratio = end_layer_ratios(n, float(m), dx, "partial")
    listed = []
    for _, bond in BONDS:
        p, o = bond(m)
        sel = (k == p) & (off == o)
        listed.append(float(ratio[sel][0]) if sel.any() else float("nan"))
    return listed, float(ratio.max()), float(ratio.min())


def least_eigenvalue(m: int, delta: float) -> float:
    """The smallest eigenvalue of pd-higher-order's assembled matrix (pinned-pinned sine load, 1 m, the default options
    at horizon_length = delta on m = delta / dx), diagonally scaled to a unit diagonal: negative if it is indefinite."""
    import numpy as np

    from pdverify.core.scene_file import load_scene
    from pdverify.registry import get_model

    scene = load_scene("studies/nonlocal/pp_sine.toml")
    model = get_model("pd-higher-order")
    params = model.resolve(scene, {"points": int(round(m / delta)) + 1, "horizon_length": delta})
    A = model.assemble(scene, params).matrix.toarray()
    d = np.sqrt(np.abs(np.diag(A)))
    B = A / d[:, None] / d[None, :]
    return float(np.linalg.eigvalsh((B + B.T) / 2)[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--delta", type=float, default=0.2, help="the horizon length (the beam is 1 m long)")
    ap.add_argument("--m", type=int, nargs="*", default=[4, 16, 64], help="delta / dx (256: about a minute)")
    ap.add_argument("--stiffness", action="store_true", help="also the assembled matrix's smallest scaled eigenvalue")
    args = ap.parse_args()
    rows = {m: ratios(m, args.delta) for m in args.m}
    print(f"{'bond (weight / interior weight)':28s}" + "".join(f"{'m = ' + str(m):>11s}" for m in args.m))
    for i, (name, _) in enumerate(BONDS):
        print(f"{name:28s}" + "".join(f"{rows[m][0][i]:11.3f}" for m in args.m))
    print(f"{'largest in the layer':28s}" + "".join(f"{rows[m][1]:11.3f}" for m in args.m))
    print(f"{'smallest in the layer':28s}" + "".join(f"{rows[m][2]:11.3f}" for m in args.m))
    if args.stiffness:
        least = [least_eigenvalue(m, args.delta) for m in args.m]
        print(f"{'least scaled eigenvalue':28s}" + "".join(f"{v:11.2e}" for v in least))


if __name__ == "__main__":
    main()
