"""Elastic supports, supports inside the span and the section forces of ``pd-higher-order`` (Yang, Oterkus & Oterkus
2020). Arrays in, arrays out; the model is in model.py.

**Supports as multipliers.** Each reaction the supports give beyond the ends' held DOFs is an unknown lam: the
force or counter-clockwise moment of a spring end or of a support inside the span. It enters the equations as the
load vector g of a unit load of its kind at its place (Eq. 16b: a force on w, a couple as -1 on theta; at an end
with ``loads = faces`` the end face's parabolic shear and linear traction, as the end loads) and holds the
displacement work-conjugate to it, g . u: a support inside the span holds the mid-line w (and, clamped, the rotation
-theta) at its position, split between the two nearest points as a point load is; a spring end holds what its
pinned or clamped end would (``pin = face``: the end face's mean w + h^2/20 w*). Rigid: g . u = 0; spring:
k g . u + lam = 0. The system stays symmetric (K u - lam g = F, g . u = 0); the reported reactions are these
multipliers and the ends' K u - F, two of them closed by statics (:func:`pdverify.numerics.statics.closed_reactions`),
so they balance the loads to round-off whatever the solve's residual.

**Section forces.** The local theory's generalised section forces N = b (K11 y' + K10 y) (the Euler-Lagrange
momenta of Eq. 9 per unit width b, y = (theta, theta*, w, w*), :mod:`pdverify.exact.higher_order`) from the
solution's y and its derivative by second-order differences that never straddle a point load or a support
(:func:`pdverify.numerics.recovery.derivative`): moment M = -N_theta (sagging); at the two end points, where the
layers of w* and theta* (about 0.1 h wide) sit on a grid that does not resolve them, M extrapolated from the next
three points (the resultant M is smooth through the layers), whose derivatives do not take the end points'
values. The shear V = dM/dx by the same differences (the theory's -N_w, a shear strain times G h, loses its
digits on a slender beam: w' + theta ~ V / (G A)).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError
from ...core.scene import PointForce, PointMoment, Scene, Spring
from ...numerics.recovery import derivative, jump_positions, kink_positions
from ...numerics.statics import statics_from_zero, statics_over
from ...theory.higher_order import NF, TH, point_work

D1 = np.zeros((5, 4))
D1[[0, 2, 3, 4], [0, 1, 2, 3]] = 1.0  # a = theta', c = theta*', g = w' + ..., e = w*' + ...
D0 = np.zeros((5, 4))
D0[[1, 3, 4], [3, 0, 1]] = 2.0, 1.0, 3.0  # s = 2 w*, g = ... + theta, e = ... + 3 theta*


def reaction_unknowns(scene: Scene) -> list[dict]:
    """One entry per reaction that is an unknown: ``key`` (its name in ``info["reactions"]``), ``kind`` ("force" or
    "moment"), ``at`` (position), ``stiffness`` (None: rigid), ``end`` (0, 1 or None)."""
    out = []
    for side, at, e in (("left", 0.0, 0), ("right", scene.length, 1)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            if sup.stiffness:
                out.append(dict(key=f"force_{side}", kind="force", at=at, stiffness=sup.stiffness, end=e))
            if sup.rotational_stiffness:
                k = sup.rotational_stiffness
                out.append(dict(key=f"moment_{side}", kind="moment", at=at, stiffness=k, end=e))
    for i, s in enumerate(scene.supports.inner):
        spring = s.type == "spring"
        if s.holds_deflection:
            k = s.stiffness if spring else None
            out.append(dict(key=f"force_inner_{i}", kind="force", at=s.position, stiffness=k, end=None))
        if s.holds_rotation:
            k = s.rotational_stiffness if spring else None
            out.append(dict(key=f"moment_inner_{i}", kind="moment", at=s.position, stiffness=k, end=None))
    return out


def unit_vector(r: dict, x: np.ndarray, h: float, faces: bool, pin: str) -> np.ndarray:
    """g (4n): the generalised force of a unit reaction ``r`` on the points x (module docstring), per unit area
    times the area (the caller divides)."""
    n, dx = len(x), x[1] - x[0]
    g = np.zeros((n, NF))
    load = (PointForce if r["kind"] == "force" else PointMoment)(
        type="point_force" if r["kind"] == "force" else "point_moment", position=r["at"], value=1.0
    )
    if r["end"] is not None:
        k = 0 if r["end"] == 0 else n - 1
        g[k] = point_work(load, h, faces and (r["kind"] == "moment" or pin == "face"), at_end=True)
        return g.ravel()
    pos = float(np.clip((r["at"] - x[0]) / dx, 0.0, n - 1))
    i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
    t = pos - i
    if abs(t) < 1e-9 or i == n - 1:
        t = 0.0
    # a force on the mid-line w; a couple as an end's would act (a linear traction over the section: -1 on theta,
    # -3 h^2/20 on theta*), so the support holds the section's mean rotation theta + 3 h^2/20 theta*
    work = point_work(load, h, r["kind"] == "moment", at_end=True)
    for node, wgt in ((i, 1.0 - t), (i + 1, t)):
        if wgt != 0.0:
            g[node] += wgt * work
    return g.ravel()


def augmented(B, b: np.ndarray, held, unknowns: list, x: np.ndarray, h: float, faces: bool, pin: str, area: float):
    """(matrix, rhs, scales): the band B (the ``held`` DOFs as unit rows) with a row and a column per reaction
    unknown: [[K, -g/s], [k A s g^T, 1]] (springs: k G.u + R = 0) or [[K, -g/s], [g^T, 0]] (rigid: G.u = 0), g the
    unit reaction's load vector G per unit area A (held DOFs zeroed), s its largest entry (lam = R s: entries of
    order one), each row scaled to its largest entry."""
    K = B.tocsr()
    diag = np.abs(K.diagonal())
    cols, rows, d, scales = [], [], [], []
    for r in unknowns:
        g = unit_vector(r, x, h, faces, pin) / area
        g[np.asarray(held, np.int64)] = 0.0
        kd = float(diag[g != 0].max()) if np.any(g != 0) else 1.0  # the stiffness of the DOFs it acts on
        s = (float(np.abs(g).max()) or 1.0) / kd  # lam = R s: the column's entries those of K there
        cols.append(-g / s)
        scales.append(s)
        k = r["stiffness"]
        row = g * (k * area * s if k is not None else 1.0)
        dd = 1.0 if k is not None else 0.0
        norm = max(float(np.abs(row).max()), dd) / kd  # the row's largest entry kd too
        rows.append(row / norm)
        d.append(dd / norm)
    A = sp.bmat(
        [[K, sp.csr_matrix(np.column_stack(cols))], [sp.csr_matrix(np.vstack(rows)), sp.diags(d)]], format="csr"
    )
    return A, np.r_[b, np.zeros(len(unknowns))], scales


def paper_supports_refusal(scene: Scene, params: dict) -> str:
    """The line refusing springs and supports inside the span in ``variant = paper`` ("" where the scene has none)."""
    if params["variant"] != "paper" or scene.supports.simple:
        return ""
    return (
        "variant = paper: Appendix B's fictitious layers hold a beam at its ends only; springs and supports "
        "inside the span need variant = corrected"
    )


def with_supports(scene: Scene, params: dict, B, b: np.ndarray, held, x: np.ndarray, faces: bool, pin: str):
    """(matrix, rhs, free, unknowns, scales): the band B as it is when the supports are the ends' alone, else the
    :func:`augmented` system; ``variant = paper`` refuses springs and supports inside the span in one line."""
    if why := paper_supports_refusal(scene, params):
        raise InputError(why)
    free = np.delete(np.arange(B.n), held)
    unknowns = reaction_unknowns(scene)
    if not unknowns:
        return B, b, free, [], []
    A, rhs, scales = augmented(B, b, held, unknowns, x, scene.section.depth, faces, pin, scene.section.A)
    return A, rhs, np.r_[free, B.n + np.arange(len(unknowns))], unknowns, scales


def section_forces(
    scene: Scene, x: np.ndarray, u: np.ndarray, C: np.ndarray, h: float, layer: int = 0, reactions=None
) -> tuple:
    """({"M", "V"} at the points from u (n x 4) (module docstring), the point loads inside the beam and the positions
    of the supports inside the span whose layers are left as recovered). By statics over the sections' layers
    (:data:`DEPTHS` depths, at least ``layer`` points): next to each end from the end's ``reactions`` (the solve's,
    named as exact-eb names them: :func:`from_ends`), then on each side of a point load and of a support inside the
    span from the points beside them (:func:`pdverify.numerics.statics.statics_over`), the supports' reactions acting
    as loads; a support whose reaction is not given keeps its layers as recovered."""
    jumps = np.r_[jump_positions(scene, "shear"), jump_positions(scene, "moment")]
    dx = x[1] - x[0]
    ends = [x[0] + dx / 2, x[-1] - dx / 2]  # no difference takes the end points' values, inside the ends' layers
    kinks = kink_positions(scene)
    dy = np.column_stack([derivative(x, u[:, k], np.r_[jumps, ends], kinks) for k in range(NF)])
    m = dy @ D1.T + u @ D0.T  # the measures per point
    M = -(scene.section.A / h) * ((m @ C) @ D1)[:, TH]  # -b (D1^T C m)_theta
    if len(x) >= 4:  # the end points: extrapolated past the ends' layers of w*, theta* (M itself is smooth there)
        M[0] = 3 * M[1] - 3 * M[2] + M[3]
        M[-1] = 3 * M[-2] - 3 * M[-3] + M[-4]
    V = derivative(x, M, jumps, kinks)
    n = len(x)
    loads = [ld for ld in scene.loads if isinstance(ld, (PointForce, PointMoment)) and 0.0 < ld.position < x[-1]]
    inner = [s.position for s in scene.supports.inner]
    if not layer or n < 4:
        return {"M": M, "V": V}, loads, inner
    held, unknown = reaction_loads(scene, reactions or {})
    loaded = scene.model_copy(update={"loads": list(scene.loads) + held})
    wide = max(layer, int(np.ceil(DEPTHS * h / dx - 1e-9)))  # the stretch each side: the layers reach about half a
    # depth (a whole number of spacings to rounding counts as whole: a scaled copy's 10.000000000000002 is 10)
    M, V, kl, kr = from_ends(loaded, x, M, V, reactions or {}, wide, unknown)
    at = [(p - x[0]) / dx for p in [ld.position for ld in loads] + inner]  # in spacings; the two points around each
    spans = [(np.floor(t + 1e-9) - wide, np.ceil(t - 1e-9) + wide + 1) for t in at]
    spans = [(max(a, kl), min(b, n - kr)) for a, b in spans]  # the ends' stretches hold already: anchors for the rest
    known = [p for p in inner if p not in unknown]
    M, V, kept = statics_over(loaded, x, M, V, spans, unknown, known)  # a support without its reaction: layers stay
    left = lambda at: any(a <= at <= b for a, b in kept)  # noqa: E731 - in a span statics left as recovered
    return {"M": M, "V": V}, [ld for ld in loads if left(ld.position)], [p for p in inner if left(p)]


DEPTHS = 2  # depths next to each end, point load and support inside the span over which M and V are taken by statics


def from_ends(scene: Scene, x, M, V, reactions: dict, wide: int, barriers=()) -> tuple:
    """(M, V, the points taken at the left end, at the right end) with the ``wide`` points next to each end taken by
    statics from the end itself: V(0) = force_left, M(0) = -moment_left, V(L) = -force_right, M(L) = moment_right
    (the model's ``reactions``, two of them closed by statics: docs/contract.md), the loads of ``scene`` (the supports
    inside the span with their reactions among them) acting on the way. A stretch stops at the beam's middle (a
    middle point both reach: the mean of the two) and before a support of ``barriers`` (positions: reactions not
    known). No reactions given: as they are."""
    if not {"force_left", "moment_left", "force_right", "moment_right"} <= set(reactions):
        return M, V, 0, 0
    n, dx = len(x), x[1] - x[0]
    at = [(p - x[0]) / dx for p in barriers]
    kl = min([wide, (n + 1) // 2, *(int(np.ceil(t - 1e-9)) for t in at)])
    kr = min([wide, (n + 1) // 2, *(n - 1 - int(np.floor(t + 1e-9)) for t in at)])
    Q, R = statics_from_zero(scene, x)
    vl, ml = reactions["force_left"], -reactions["moment_left"]
    vr = -reactions["force_right"] - Q[-1]  # V(0) and M(0) that give the right end's values
    mr = reactions["moment_right"] - vr * x[-1] - R[-1]
    M, V = np.array(M, float), np.array(V, float)
    both = kl + kr > n  # an odd grid whose middle point both stretches reach
    for v0, m0, part in ((vl, ml, slice(0, kl)), (vr, mr, slice(n - kr, n))):
        V[part], M[part] = v0 + Q[part], m0 + v0 * x[part] + R[part]
    if both:
        c = n // 2
        V[c], M[c] = (vl + vr) / 2 + Q[c], (ml + mr) / 2 + (vl + vr) / 2 * x[c] + R[c]
    return M, V, kl, kr


def reaction_loads(scene: Scene, reactions: dict) -> tuple[list, list[float]]:
    """(the supports inside the span's reactions as point loads, the positions of those whose reactions are not in
    ``reactions``): a force ``force_inner_i`` (up) and a couple ``moment_inner_i`` (counter-clockwise) each."""
    loads, unknown = [], []
    for i, s in enumerate(scene.supports.inner):
        keys = [("force", PointForce)] * s.holds_deflection + [("moment", PointMoment)] * s.holds_rotation
        if any(f"{kind}_inner_{i}" not in reactions for kind, _ in keys):
            unknown.append(s.position)
            continue
        for kind, cls in keys:
            loads.append(cls(type=f"point_{kind}", position=s.position, value=reactions[f"{kind}_inner_{i}"]))
    return loads, unknown


__all__ = ["reaction_unknowns", "unit_vector", "augmented", "with_supports", "section_forces"]
