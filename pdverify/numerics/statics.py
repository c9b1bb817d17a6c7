"""Support reactions of a straight beam closed by statics: a model gives a value for every reaction it can (its
multipliers, its end moments and shears); two of them are then taken from the two equilibrium equations, so the
reactions balance the loads to round-off whatever the model's discretisation error, and a statically determinate
beam's reactions are exact. Sign convention as exact-eb: force +z on the beam, moment counter-clockwise on the beam.
"""

from __future__ import annotations

import numpy as np

from ..core.reactions import load_resultants
from ..core.scene import HELD, Distributed, PointForce, PointMoment, Scene, Spring


def reaction_keys(scene: Scene, from_right: bool = False) -> list[tuple[str, float, float]]:
    """(key, force coefficient, moment coefficient about x = 0) of every reaction the supports give: rigid end and
    inner forces, then springs' forces, then rigid moments, then springs' moments (the order statics picks from),
    each kind from the left end on (``from_right``: from the right end on, the mirror image's order)."""
    L = scene.length
    rigid_f, spring_f, rigid_m, spring_m = [], [], [], []
    for side, at in (("left", 0.0), ("right", L)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            if sup.stiffness:
                spring_f.append((f"force_{side}", 1.0, at))
            if sup.rotational_stiffness:
                spring_m.append((f"moment_{side}", 0.0, 1.0))
            continue
        if HELD[sup][1]:
            rigid_f.append((f"force_{side}", 1.0, at))
        if HELD[sup][2]:
            rigid_m.append((f"moment_{side}", 0.0, 1.0))
    for i, s in enumerate(scene.supports.inner):
        spring = s.type == "spring"
        if s.holds_deflection:
            (spring_f if spring else rigid_f).append((f"force_inner_{i}", 1.0, s.position))
        if s.holds_rotation:
            (spring_m if spring else rigid_m).append((f"moment_inner_{i}", 0.0, 1.0))

    def at(key: str) -> float:
        side = key.split("_", 1)[1]
        return (
            {"left": 0.0, "right": L}.get(side)
            if side in ("left", "right")
            else scene.supports.inner[int(side[6:])].position
        )

    kinds = (rigid_f, spring_f, rigid_m, spring_m)
    return [k for kind in kinds for k in sorted(kind, key=lambda k: at(k[0]), reverse=from_right)]


def closed_reactions(scene: Scene, model: dict[str, float]) -> dict:
    """Every reaction of ``scene``'s supports (zero where the supports give none): the model's values ``model``
    (missing ones count as unknown), two of them replaced by statics (the first force, then the first reaction
    that makes the two equations independent), the mean of doing so from the left end on and from the right end on
    (each balances the loads, so their mean does, and a mirror image gives the mirrored reactions); ``method`` says
    which."""
    left, right = _closed(scene, model, reaction_keys(scene)), _closed(scene, model, reaction_keys(scene, True))
    out = {k: (v + right[k]) / 2 if isinstance(v, float) else v for k, v in left.items()}
    if left["method"] != right["method"]:
        out["method"] = f"the mean of {left['method']} and of {right['method']}"
    return out


def _closed(scene: Scene, model: dict[str, float], keys: list) -> dict:
    """:func:`closed_reactions` with statics picking from ``keys`` in their order."""
    P, Mo = load_resultants(scene)
    L = scene.length
    first = next(k for k in keys if k[1] != 0.0)
    # independent of the first force: another force 1e-9 L away from it (the determinant a length), or a moment (1)
    scale = lambda k: max(L, 1e-300) if k[1] else 1.0  # noqa: E731
    second = next(k for k in keys if k is not first and abs(first[1] * k[2] - first[2] * k[1]) > 1e-9 * scale(k))
    out = {f"{kind}_{side}": 0.0 for side in ("left", "right") for kind in ("force", "moment")}
    out.update({k: float(model.get(k, 0.0)) for k, _, _ in keys})
    rest_f = P + sum(out[k] * cf for k, cf, _ in keys if k not in (first[0], second[0]))
    rest_m = Mo + sum(out[k] * cm for k, _, cm in keys if k not in (first[0], second[0]))
    A = np.array([[first[1], second[1]], [first[2], second[2]]])
    a, b = np.linalg.solve(A, -np.array([rest_f, rest_m]))
    out[first[0]], out[second[0]] = float(a), float(b)
    given = [k for k, _, _ in keys if k not in (first[0], second[0])]
    out["method"] = f"statics for {first[0]} and {second[0]}" + (
        f"; the model's own values for {', '.join(given)}" if given else " (statically determinate)"
    )
    return out


_GX, _GW = np.polynomial.legendre.leggauss(24)
_GX8, _GW8 = np.polynomial.legendre.leggauss(8)  # the statics M / EI on a piece between loads and interfaces: a
# quadratic under uniform loads (exact), smooth under sine loads (degree 15 exact)


def jump_share(x: np.ndarray, at: float, dx: float) -> np.ndarray:
    """The share of a unit jump at ``at`` that each point's value carries: 1 past it, 0 before, 1/2 on a point within
    1e-9 spacings of it (the mean of its two sides: a mirror image carries the same, and the rounding of a scaled grid's
    positions decides no side); an end point on it carries its support's side (0 at x[0], 1 at x[-1]: the load acts on
    the beam), as the exact beams' end values, whose reactions are -M(0), M(L), V(0) and -V(L)."""
    on = np.abs(x - at) <= 1e-9 * dx
    share = np.where(on, 0.5, np.where(x > at, 1.0, 0.0))
    if on[0]:
        share[0] = 0.0
    if on[-1]:
        share[-1] = 1.0
    return share


def statics_from_zero(scene: Scene, x: np.ndarray, dx: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(Q, R) at the points ``x``: the shear and the moment that the transverse loads on [0, x] add, with V(0) = M(0) =
    0 (dV/dx = q, dM/dx = V; a force P makes V jump by P, a couple C makes M jump by -C). Distributed loads by
    Gauss-Legendre on each point's part of their span (their shapes are smooth on it). ``dx``: the grid's spacing,
    whose 1e-9 decides whether a position is on a load (default: that of ``x``, a grid)."""
    x = np.asarray(x, float)
    if dx is None:
        dx = float(x[1] - x[0]) if len(x) > 1 else scene.length
    Q, R = np.zeros(len(x)), np.zeros(len(x))
    for ld in scene.loads:
        if isinstance(ld, PointForce) and ld.value:
            Q += ld.value * jump_share(x, ld.position, dx)
            R += ld.value * np.maximum(x - ld.position, 0.0)
        elif isinstance(ld, PointMoment) and ld.value:
            R -= ld.value * jump_share(x, ld.position, dx)
        elif isinstance(ld, Distributed) and ld.value:
            a, b = scene.span(ld)
            hi = np.clip(x, a, b)[:, None]
            s = (a + hi) / 2 + (hi - a) / 2 * _GX  # each point's part of the span, one row each
            q = ld.value * scene.load_shape(ld, s) * (hi - a) / 2 * _GW
            Q += q.sum(axis=1)
            R += (q * (x[:, None] - s)).sum(axis=1)
    return Q, R


def merge_spans(spans, n: int) -> list[list[int]]:
    """The index spans [lo, hi) clipped to the n points, sorted, overlapping and touching ones merged (an anchor
    between two touching spans would be spoiled by both)."""
    merged = []
    for lo, hi in sorted((max(0, int(a)), min(n, int(b))) for a, b in spans):
        if merged and lo <= merged[-1][1] + 1:
            merged[-1][1] = max(merged[-1][1], hi)
        elif hi > lo:
            merged.append([lo, hi])
    return merged


def statics_over(scene: Scene, x: np.ndarray, M: np.ndarray, V: np.ndarray, spans, barriers=(), two_sided=()) -> tuple:
    """(M, V) with the points of each index span [lo, hi) re-derived by statics with the loads from the points next to
    it, where the model's M and V hold: between two such points the statics that meets the model's M at both (the
    shear from their moments: a model's M converges faster than its V), from one the continuation of its M and V. The
    resultants of any beam theory are in equilibrium with the loads, so they carry the anchors' error and none of the
    span's layers. Overlapping or touching spans are merged; a merged span with a position of ``barriers`` on it
    (supports inside the span, whose reactions the loads do not hold: give their own layers as spans too, so that no
    anchor lies in them), or with no point left to anchor it, is left as it is, and so is one with a position of
    ``two_sided`` on it and a point next to it on one side only (a support whose reaction is among the loads, beside
    an end's layers: a continuation from one point carries that point's V error across the whole stretch); the third
    value lists those spans' (first, last) positions."""
    n = len(x)
    M, V = np.array(M, float), np.array(V, float)
    merged = merge_spans(spans, n)
    Q, R = statics_from_zero(scene, x)
    M0, V0 = M.copy(), V.copy()  # the anchors' values, as the model gave them
    kept = []
    for lo, hi in merged:
        anchors = [k for k in (lo - 1, hi) if 0 <= k < n]  # both sides of an inner span: the mean is mirror-symmetric
        on = [any(x[lo] <= b <= x[hi - 1] for b in points) for points in (barriers, two_sided)]
        if not anchors or on[0] or (len(anchors) == 1 and on[1]):
            kept.append((float(x[lo]), float(x[hi - 1])))
            continue
        part, k = slice(lo, hi), anchors[0]
        if len(anchors) == 2:  # the moments at both anchors fix the shear between (a model's V converges slower)
            a, b = anchors
            shear0 = (M0[b] - M0[a] - (R[b] - R[a])) / (x[b] - x[a])
        else:
            shear0 = V0[k] - Q[k]  # the shear at x = 0+ that the anchor's V implies
        V[part], M[part] = shear0 + Q[part], M0[k] + shear0 * (x[part] - x[k]) + R[part] - R[k]
    return M, V, kept


def rotation_over(scene: Scene, x: np.ndarray, M: np.ndarray, rotation: np.ndarray, spans, kept=()) -> np.ndarray:
    """The Euler-Bernoulli rotation on the index spans that :func:`statics_over` re-derived (``spans`` as given to it,
    ``kept`` its third value): from the rotation at the points next to a span, where it holds, by the integral of the
    curvature M / EI (dθ/dx = M / EI), M the statics through the span's moments (M = A + B x + R(x), exact between
    the loads, a couple's jump included) on Gauss-Legendre points of the pieces between the grid points, the point
    loads, the distributed loads' ends and the interfaces. Between two anchors the integrals from both, weighted by
    the distance (mirror-symmetric). Differences of w across two loads a few spacings apart straddle the jumps and
    kinks of the curvature there."""
    n = len(x)
    out = np.array(rotation, float)
    dx = float(x[1] - x[0])
    _, R = statics_from_zero(scene, x)
    breaks = [g.start for g in scene.segments[1:]]
    for ld in scene.loads:
        breaks += list(scene.span(ld)) if isinstance(ld, Distributed) else [ld.position]
    for lo, hi in merge_spans(spans, n):
        anchors = [k for k in (lo - 1, hi) if 0 <= k < n]
        if not anchors or (float(x[lo]), float(x[hi - 1])) in kept:
            continue
        first, last = min(anchors[0], lo), max(anchors[-1], hi - 1)
        k = anchors[0]  # the statics through the anchor and the span's first point (statics_over's M meets both)
        B = ((M[lo] - R[lo]) - (M[k] - R[k])) / (x[lo] - x[k])
        A = M[k] - R[k] - B * x[k]
        cuts = np.unique(np.r_[x[first : last + 1], [c for c in breaks if x[first] < c < x[last]]])
        mid, half = (cuts[1:] + cuts[:-1]) / 2, (cuts[1:] - cuts[:-1]) / 2
        s = (mid[:, None] + half[:, None] * _GX8).ravel()
        curvature = (A + B * s + statics_from_zero(scene, s, dx)[1]) / scene.stiffness_at(s)["EI"]
        total = np.r_[0.0, np.cumsum((curvature.reshape(len(mid), -1) * _GW8).sum(axis=1) * half)]
        integral = total[np.searchsorted(cuts, x[first : last + 1])]  # ∫ from x[first] to each point
        part = slice(lo - first, hi - first)
        ends = [out[a] + integral - integral[a - first] for a in anchors]  # from each anchor
        if len(ends) == 1:
            out[lo:hi] = ends[0][part]
            continue
        t = (x[first : last + 1] - x[first]) / (x[last] - x[first])
        out[lo:hi] = ((1 - t) * ends[0] + t * ends[1])[part]
    return out
