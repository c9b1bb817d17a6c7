"""The loads, supports and reactions of ``fem-plane-stress`` on the strip mapped onto the beam axis
(:mod:`reference_fem.curved_mesh`); their meaning, the same in every model, is in
:mod:`reference_fem.plane_stress`'s docstring and docs/supports.md.

Loads (value along n, axial along t, or global (x, y) with ``frame = "global"``): a distributed load's normal part
is a traction on the loaded face, its tangential part a line load on the mid-line; an end force a parabolic shear
traction over the end face plus a uniform traction for its tangential part; an interior force acts at the loaded
face's node (normal part) and the mid-height node (tangential part); a moment, at an end or inside, a linear normal
traction on the section line through its station. Supports: fixed components (in the end frame, by a rotation of
the end faces' DOFs), face-mean constraints (``pin = face``) and the guided end's equal tangential displacements.
"""

from __future__ import annotations

import numpy as np

from pdverify.core.scene import Distributed, PointForce, Scene
from pdverify.numerics.factorcache import digest
from pdverify.numerics.kept import Kept
from reference_fem import curved_mesh as cm


def couple_density(C: float, te: np.ndarray, I: float, width: float):
    """The line density of a couple C on a section line with tangent te: the bending stress -C t / I along te
    times the thickness (per unit length of the line); its moment about the mid-height is C."""

    def density(sq, tq):
        return te[:, None, None] * (-C * tq / I * width)[None]

    return density


def local_components(load, tan: np.ndarray, nor: np.ndarray):
    """(tangential, normal) components of a load's (axial, value) in its frame, at frames (…, 2)."""
    if getattr(load, "frame", "local") == "global":
        g = np.array([load.axial, load.value])
        return tan @ g, nor @ g
    return np.full(tan.shape[:-1], float(load.axial)), np.full(tan.shape[:-1], float(load.value))


def node_dofs(basis) -> tuple[np.ndarray, np.ndarray]:
    """(x-DOFs, y-DOFs) of every node (vertices, and the mid-side / centre nodes of q8 / q9), paired."""
    xs, ys = [basis.nodal_dofs[0]], [basis.nodal_dofs[1]]
    for d in (basis.facet_dofs, basis.interior_dofs):
        if d.shape[0]:
            xs.append(d[0])
            ys.append(d[1])
    return np.concatenate(xs), np.concatenate(ys)


def _distributed(scene: Scene, bm, basis, load, top: int, mid: int) -> list[np.ndarray]:
    """Nodal forces of a distributed load: its normal part on the loaded face's row of edges, its tangential
    part (when it has one) on the mid-line's (per unit axis length both), in this order."""
    geo, L = bm.geo, scene.length
    a, b = scene.span(load)

    def profile(sq):
        return np.ones_like(sq) if load.shape == "uniform" else np.sin(np.pi * sq / L)

    def normal_part(sq, tq):
        tq_, nq_ = geo.frame(sq)
        _, qn = local_components(load, tq_, nq_)
        return np.moveaxis(nq_ * (qn * profile(sq))[..., None], -1, 0)

    def tangential_part(sq, tq):
        tq_, nq_ = geo.frame(sq)
        qt, _ = local_components(load, tq_, nq_)
        return np.moveaxis(tq_ * (qt * profile(sq))[..., None], -1, 0)

    parts = [cm.line_forces(bm, basis, *cm.row_edges(bm, top, a, b), normal_part)]
    if load.axial != 0.0 or load.frame == "global":
        parts.append(cm.line_forces(bm, basis, *cm.row_edges(bm, mid, a, b), tangential_part))
    return parts


def _at_end(scene: Scene, bm, basis, load, i: int, te: np.ndarray, ne: np.ndarray) -> np.ndarray:
    """Nodal forces of a point load at an end face i: a force as a parabolic shear traction along ne (the
    Timoshenko shear distribution) plus a uniform traction for its part along te; a moment as the linear
    normal traction of :func:`couple_density`."""
    h, I, width = scene.section.depth, scene.section.I, scene.section.width
    if isinstance(load, PointForce):
        ft, fn = local_components(load, te, ne)

        def end_force(sq, tq, ft=float(ft), fn=float(fn)):
            tau = 1.5 * fn / h * (1 - (2 * tq / h) ** 2)  # parabolic shear, per face length
            return ne[:, None, None] * tau[None] + te[:, None, None] * (ft / h)

        return cm.line_forces(bm, basis, *cm.face_edges(bm, i), end_force)
    return cm.line_forces(bm, basis, *cm.face_edges(bm, i), couple_density(load.value, te, I, width))


def load_vector(scene: Scene, bm, basis, tan_s: np.ndarray, nor_s: np.ndarray, top: int, mid: int) -> np.ndarray:
    """F (basis.N): the work-equivalent nodal forces of the scene's loads on the mesh ``bm`` (stations bm.s with
    tangents tan_s and normals nor_s; node rows ``top``, the loaded face, and ``mid``, the mid-line)."""
    s, L = bm.s, scene.length
    ns = len(s)
    F = np.zeros(basis.N)
    for load in scene.loads:
        if isinstance(load, Distributed):
            for part in _distributed(scene, bm, basis, load, top, mid):
                F += part
            continue
        at_end = min(abs(load.position - 0.0), abs(load.position - L)) < 1e-12 * L
        i = 0 if load.position < L / 2 else ns - 1
        if at_end:
            F += _at_end(scene, bm, basis, load, i, tan_s[i], nor_s[i])
            continue
        k = int(np.argmin(np.abs(s - load.position)))
        if isinstance(load, PointForce):
            ft, fn = local_components(load, tan_s[k], nor_s[k])
            topk, midn = bm.vid[k, top], bm.vid[k, mid]
            F[basis.nodal_dofs[:, topk]] += fn * nor_s[k]
            if ft != 0.0:
                F[basis.nodal_dofs[:, midn]] += ft * tan_s[k]
        else:  # the end moment's traction on the section line s = s_k (a force pair would be singular)
            C = couple_density(load.value, tan_s[k], scene.section.I, scene.section.width)
            F += cm.line_forces(bm, basis, *cm.face_edges(bm, k), C)
    return F


def load_resultant(F: np.ndarray, basis, geo) -> list[float]:
    """(Fx, Fy, Mz about the left end of the axis) of the assembled loads: a check of the load assembly against
    the scene's beam loads."""
    xd = (
        np.concatenate([basis.nodal_dofs[0], basis.facet_dofs[0]]) if basis.facet_dofs.shape[0] else basis.nodal_dofs[0]
    )
    yd = (
        np.concatenate([basis.nodal_dofs[1], basis.facet_dofs[1]]) if basis.facet_dofs.shape[0] else basis.nodal_dofs[1]
    )
    rel = basis.doflocs[:, xd] - geo.position(np.array([0.0]))[0][:, None]
    return [float(F[xd].sum()), float(F[yd].sum()), float(np.sum(rel[0] * F[yd] - rel[1] * F[xd]))]


def _face_means(bm, basis, i: int, sup: str, tan: np.ndarray, nor: np.ndarray, h: float) -> list[np.ndarray]:
    """``pin = face``: the rows of ∫ φ u·d dt = 0 on end face i of height h (consistent line integrals), the
    parabola-weighted mean normal displacement and, pinned, the mean tangential displacement."""
    dirs = [(nor, lambda tq: 1.5 / h * (1 - (2 * tq / h) ** 2))]
    if sup == "pinned":
        dirs.append((tan, lambda tq: np.full_like(tq, 1.0 / h)))
    return [
        cm.line_forces(bm, basis, *cm.face_edges(bm, i), lambda sq, tq, d=d, phi=phi: d[:, None, None] * phi(tq)[None])
        for d, phi in dirs
    ]


def support_conditions(scene: Scene, pin: str, bm, basis, tan_s: np.ndarray, nor_s: np.ndarray, mid: int):
    """The supports as constraints on the end faces' DOFs: (fixed, pairs, tangents, crows). ``pairs`` (2, k) are
    the x/y DOFs to be rotated into the end frame with unit ``tangents`` (2, k); ``fixed`` lists the held entries
    of the rotated vector (tangential in the x-slot, normal in the y-slot); ``crows`` are rows C u = 0 of the
    face-mean (``pin = face``) and guided constraints."""
    ns = len(bm.s)
    fixed, pairs, tangents, crows = [], [], [], []
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        i = 0 if side == 0 else ns - 1
        if not isinstance(sup, str) or sup == "free":  # an elastic end: its springs are stiffness (.plane_scenes)
            continue
        if sup in ("pinned", "roller") and pin == "face":
            crows.extend(_face_means(bm, basis, i, sup, tan_s[i], nor_s[i], scene.section.depth))
            continue
        if sup in ("pinned", "roller"):
            face = basis.nodal_dofs[:, [bm.vid[i, mid]]]
        else:
            face = cm.face_node_pairs(bm, basis, i)
        pairs.append(face)
        tangents.append(np.repeat(tan_s[i][:, None], face.shape[1], axis=1))
        if sup in ("clamped", "pinned"):
            fixed.append(face.ravel())
        elif sup == "roller":
            fixed.append(face[1])  # u' y-slot = normal component
        else:  # guided: every face node's tangential component equals the first one's (no rotation)
            for k in range(1, face.shape[1]):
                row = np.zeros(basis.N)
                row[face[:, k]] += tan_s[i]
                row[face[:, 0]] -= tan_s[i]
                crows.append(row)
    return fixed, pairs, tangents, crows


_REDUCED = Kept(6, budget=cm.KEPT_DOFS, size=lambda kept: kept[0].shape[0])  # (K, supports) digest -> the reduced
# operator: another load on the same strip and supports, on each of a scene's grids


def constrained_system(K, F: np.ndarray, N: int, fixed: list, pairs: list, tangents: list, crows: list, key=None):
    """(Kf, Ff, free, T, S, key) of the supports of :func:`support_conditions`: u = T u' rotates the end faces' DOFs
    into their frames (T None when no rotation is needed), the held entries of u' are eliminated (``free``: the
    others), and u'_free = S v eliminates one master DOF per constraint row (S None without such rows). The
    reduced operator (Kf, free, T, S) depends on K and the supports only: it is kept for the last few (K,
    supports) of up to :data:`reference_fem.curved_mesh.KEPT_DOFS` unknowns, and another load only reduces F.
    ``key``: a digest that determines K (the caller's assembly key), else K's bytes are hashed; the returned key
    determines Kf (the solve's factorisation cache takes it instead of hashing Kf)."""
    key = key or digest(K.data, K.indices, K.indptr)
    key = digest(*fixed, *pairs, *tangents, *crows, params=(N, key))
    Kf, free, T, S = _REDUCED.get(key, lambda: _reduced_operator(K, N, fixed, pairs, tangents, crows))
    Ff = (F if T is None else T.T @ F)[free]  # the held DOFs are zero: condensing them leaves F's free rows
    return Kf, (Ff if S is None else S.T @ Ff), free, T, S, key


def _reduced_operator(K, N: int, fixed: list, pairs: list, tangents: list, crows: list):
    """(Kf, free, T, S) of :func:`constrained_system`."""
    T = None
    if pairs:
        pr, tg = np.hstack(pairs), np.hstack(tangents)
        if not (np.all(tg[0] == 1.0) and np.all(tg[1] == 0.0)):
            T = cm.rotation_matrix(N, pr, tg)
            K = (T.T @ K @ T).tocsr()
    held = np.unique(np.concatenate(fixed)) if fixed else np.zeros(0, dtype=np.int64)
    free = np.setdiff1d(np.arange(N), held)
    Kf = K[free][:, free].tocsr()
    S = None
    if crows:  # eliminate one master dof per face-mean constraint: u_f = S v
        C = np.vstack(crows)
        if T is not None:
            C = np.asarray((T.T @ C.T).T)
        S = cm.constraint_basis(C[:, free])
        Kf = (S.T @ Kf @ S).tocsr()
    for a in (Kf.data, Kf.indices, Kf.indptr, free):
        a.flags.writeable = False  # shared by the loads' solves
    return Kf, free, T, S


def reactions(r: np.ndarray, basis, geo, length: float) -> dict[str, float]:
    """Support reactions from r = K u - F (the nodal forces the supports put on the strip; round-off elsewhere),
    summed over the nodes nearer each end: force along the end normal (+z for a straight beam), axial along the
    end tangent, moment counter-clockwise about the end of the axis."""
    ends = geo.position(np.array([0.0, length]))
    tan, nor = geo.frame(np.array([0.0, length]))
    xd, yd = node_dofs(basis)
    loc = basis.doflocs[:, xd]
    near_left = np.hypot(*(loc - ends[0][:, None])) <= np.hypot(*(loc - ends[1][:, None]))
    out = {}
    for k, side in enumerate(("left", "right")):
        sel = near_left if k == 0 else ~near_left
        fx, fy = r[xd[sel]], r[yd[sel]]
        arm = loc[:, sel] - ends[k][:, None]
        f = np.array([fx.sum(), fy.sum()])
        out[f"force_{side}"] = float(f @ nor[k])
        out[f"axial_{side}"] = float(f @ tan[k])
        out[f"moment_{side}"] = float(np.sum(arm[0] * fy - arm[1] * fx))
    return out


def full_displacement(uf: np.ndarray, free: np.ndarray, N: int, T, S) -> np.ndarray:
    """u (N) from the solution uf of :func:`constrained_system`'s reduced system: u = T (S uf on the free
    entries, zero on the held ones)."""
    if S is not None:
        uf = S @ uf
    u = np.zeros(N)
    u[free] = uf
    if T is not None:
        u = T @ u
    return u
