"""Kernels of ``pd-eb`` (Diyaroglu, Oterkus & Oterkus 2019): the PD curvature (Eq. 11a with Eq. 32 or the discrete
calibration), the paper's fictitious layers and master–slave end conditions (Eq. 37–42, Appendix A1–A12), the
corrected variant's Taylor ghost points and its two forms (the fourth-order system and the mixed form of two
second-order equations). Arrays in, arrays out; the model, its variants and their reasons are in model.py.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.scene import Scene
from ...numerics.band import Band
from ...numerics.families import ghost_stencil_system, partial_volumes, stencil_operator
from ...numerics.ghosts import curvature_end_rows, poly_ghosts, taylor_ghosts
from ...numerics.loads import body_loads, end_loads

MIRROR_SIGN = {"clamped": 1.0, "guided": 1.0, "pinned": -1.0, "roller": -1.0, "free": 0.0}  # Eq. 39–41
GRAM_MIN_ROW = 200  # entries a row of DT above which K = a (DT)^T DT is formed by Band.gram (docs/performance.md)


def curvature_weights(m: float, dx: float, variant: str) -> np.ndarray:
    """c_j, j = 1..J, of kappa_k = Σ_j c_j (w_{k+j} + w_{k-j} - 2 w_k) (Eq. 11a with Eq. 32 or discrete)."""
    if variant == "paper":
        delta = (m + 0.015) * dx
        J = int(np.floor(delta / dx + 1e-12))
        j = np.arange(1, J + 1)
        return dx / (delta * j**2 * dx**2)  # d V / xi² with d = 1/(A delta), V = A dx
    j, beta = partial_volumes(m)
    return beta / (j**2 * dx**2 * beta.sum())


def curvature_operator(n_rows: int, row0: int, n_cols: int, c: np.ndarray) -> sp.csr_matrix:
    """Sparse D: rows are points row0 .. row0 + n_rows - 1 of a column grid of n_cols points."""
    J = len(c)
    j = np.arange(1, J + 1)
    offsets = np.concatenate([[0], -j, j])
    return stencil_operator(n_rows, row0, n_cols, offsets, np.concatenate([[-2.0 * c.sum()], c, c]))


def fixed_points(scene: Scene, n: int) -> list[int]:
    """End points held at w = 0 (clamped and pinned supports) of a grid of n points."""
    held = ("clamped", "pinned", "roller")  # no axial unknown: roller = pinned
    return [i for i, sup in ((0, scene.supports.left), (n - 1, scene.supports.right)) if sup in held]


# -- paper: fictitious layers (Eq. 37–42, Appendix A) ---------------------------------------------


def _appendix_rows(n: int, G: int, J: int, dx: float, left: str, right: str, layer: dict):
    """(k, columns, values) of the curvature rows that replace the full-family ones: at a free end the first point
    by Eq. A1 (one-sided second difference, d1 = 1/(A dx)), the p-th (p = 1..J-1) by the reduced horizon
    (p + 0.015) dx with d_p = 1/(A delta_p) (Eq. A7–A12); at an end with the 2.015 dx layer (``layer[side]``) the
    real points whose family would reach past its two fictitious points by the horizon 2.015 dx. Extended columns
    (G ghosts, n real, G ghosts)."""
    for side, sup in ((0, left), (1, right)):
        if sup != "free":
            continue
        o = 1 if side == 0 else -1
        for pnt in range(min(J, n)):
            k = pnt if side == 0 else n - 1 - pnt
            e = k + G
            if pnt == 0:  # Eq. A1 with d1 = 1/(A dx): one-sided second difference
                cols, vals = [e, e + o, e + 2 * o], [1 / dx**2, -2 / dx**2, 1 / dx**2]
            else:  # Eq. A7/A10: reduced horizon (p + 0.015) dx, d_p = 1/(A delta_p)
                cp = curvature_weights(float(pnt), dx, "paper")
                cols = [e] + [e + j for j in range(1, len(cp) + 1)] + [e - j for j in range(1, len(cp) + 1)]
                vals = [-2 * cp.sum()] + list(cp) + list(cp)
            yield k, np.array(cols), np.array(vals)
    for side in (0, 1):
        if not layer[side]:
            continue
        c2 = curvature_weights(2.0, dx, "paper")  # delta = 2.015 dx, d = 1 / (A delta)
        for pnt in range(J - 2):  # real points whose family would reach past the two fictitious points
            k = pnt if side == 0 else n - 1 - pnt
            e = k + G
            yield k, np.array([e, e + 1, e - 1, e + 2, e - 2]), np.array([-2 * c2.sum(), c2[0], c2[0], c2[1], c2[1]])


def paper_curvature(n: int, G: int, c: np.ndarray, dx: float, left: str, right: str, layer: dict) -> sp.csr_matrix:
    """D (n x n + 2G): the curvature of the real points on the extended grid (Eq. 11a), the rows of
    :func:`_appendix_rows` in place of the full-family ones near free ends and 2.015 dx layers."""
    D = curvature_operator(n, G, n + 2 * G, c).tocoo()
    keep = np.ones(D.nnz, bool)
    rr, cc, vv = [D.row], [D.col], [D.data]
    for k, cols, vals in _appendix_rows(n, G, len(c), dx, left, right, layer):
        keep &= D.row != k
        rr.append(np.full(len(cols), k))
        cc.append(cols)
        vv.append(vals)
    rr[0], cc[0], vv[0] = D.row[keep], D.col[keep], D.data[keep]
    return sp.csr_matrix((np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=D.shape)


def mirror_map(n: int, G: int, left: str, right: str, layer: dict) -> sp.csr_matrix:
    """T: extended (ghost + real) <- real, the master–slave map of the fictitious points (Eq. 39–41): mirror images
    of the real points at clamped and guided ends (w_{-j} = w_j), negative ones at simply supported ends (w_{-j} =
    -w_j; two points with the 2.015 dx layer), none at a free end."""
    tr, tc, tv = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
    for side, sup in ((0, left), (1, right)):
        sign = MIRROR_SIGN[sup]
        if sign == 0.0:
            continue
        j = np.arange(1, (2 if layer[side] else G) + 1)
        g = G - j if side == 0 else G + n - 1 + j
        r = j if side == 0 else n - 1 - j
        ok = (r >= 0) & (r < n)
        tr.append(g[ok]), tc.append(r[ok]), tv.append(np.full(ok.sum(), sign))
    return sp.csr_matrix((np.concatenate(tv), (np.concatenate(tr), np.concatenate(tc))), shape=(n + 2 * G, n))


def fictitious_curvature(T: sp.csr_matrix, n: int, G: int, c: np.ndarray) -> sp.csr_matrix:
    """The curvature (Eq. 37) of the fictitious points that exist (those of T's rows), each from the points that
    exist: the family truncated at the layer's outer edge."""
    J = len(c)
    alive = np.zeros(n + 2 * G, bool)
    alive[np.unique(T.tocoo().row)] = True  # the real points and the fictitious points that exist
    ghosts = np.flatnonzero(alive & ((np.arange(n + 2 * G) < G) | (np.arange(n + 2 * G) >= G + n)))
    jj = np.arange(1, J + 1)
    cols = np.c_[ghosts, ghosts[:, None] - jj, ghosts[:, None] + jj]
    vals = np.broadcast_to(np.r_[-2 * c.sum(), c, c], cols.shape)
    ok = (cols >= 0) & (cols < n + 2 * G)
    ok[ok] = alive[cols[ok]]  # the family truncated at the layer's outer edge
    return sp.csr_matrix(
        (vals[ok], (np.broadcast_to(np.arange(len(ghosts))[:, None], cols.shape)[ok], cols[ok])),
        shape=(len(ghosts), n + 2 * G),
    )


def paper_system(scene: Scene, x: np.ndarray, c: np.ndarray, a: float, A: float, reading: str = "energy"):
    """(K, b, fixed, info) of the paper's boundary treatment in one of three readings (``reading``):

    * ``energy``: U = Σ over the real points of a kappa² V / 2 (Eq. 2, 10a), kappa (Eq. 11a) using the
      fictitious points as mirror images of real ones (w = T w_real, Eq. 39-41), K = a (D T)^T (D T):
      Eq. 42 applied to the real points' energy;
    * ``literal``: Eq. 37 written for every point of the extended grid, fictitious ones included (their
      kappa from the points that exist: the family truncated at the layer's outer edge), then
      K̂ = T^T K T (Eq. 42): the fictitious points' energy counts too;
    * ``layer``: ``literal`` with the fictitious layer of 2.015 dx at simply supported ends (Section
      "Simply supported boundary condition": two mirrored points; the real points whose family reaches past
      them use the horizon 2.015 dx with d = 1 / (A 2.015 dx), as Eq. A10-A12). In the energy reading the
      layer changes nothing: the only real point whose family reaches past it is the support point, whose
      curvature is zero under the negative mirror either way."""
    n, dx, J = len(x), x[1] - x[0], len(c)
    G = J
    left, right = scene.supports.left, scene.supports.right
    layer = {
        side: reading == "layer" and sup in ("pinned", "roller") and J > 2 for side, sup in ((0, left), (1, right))
    }
    D = paper_curvature(n, G, c, dx, left, right, layer)
    T = mirror_map(n, G, left, right, layer)
    if reading in ("literal", "layer"):  # Eq. 37 on the fictitious points of supported ends as well
        D = sp.vstack([D, fictitious_curvature(T, n, G, c)]).tocsr()
    DT = (D @ T).tocsr()
    wide = int(np.diff(DT.indptr).max(initial=0)) > GRAM_MIN_ROW  # wide rows: the dense blocks' Gram by BLAS
    K = Band.gram(DT, a) if wide else Band.from_sparse(a * (DT.T @ DT))
    b = body_loads(scene, x) / A
    fixed = fixed_points(scene, n)
    return K, b, fixed, {"ghosts_per_end": G, "boundary": "mirror images, Appendix free ends", "reading": reading}


# -- corrected: Taylor ghost points ---------------------------------------------------------------


def ghost_map(scene: Scene, n: int, dx: float, G: int, curvature_ends: bool = False, sups=None, EIs=None):
    """Taylor ghost points of both ends (docs/design/formulas.md §1): w_ghost = Gm w_real + g0.
    Returns (rows, cols, values) of the ghost rows of E in extended numbering (G ghosts, n real,
    G ghosts), the constant part e0 (length n + 2G) and the end loads handled by the ghosts.
    ``curvature_ends``: free and guided ends take their moment and shear through conditions on the
    curvature (:func:`curvature_end_rows`); their ghost w only extrapolate (free: cubic through the
    first four points; guided: degree 4 with w' = 0), so no third difference of w carries the shear.
    ``sups``, ``EIs``: the ends' support names and bending stiffnesses (default the scene's: a spring end is
    passed as "free", its spring's force and moment being end loads)."""
    P, C = end_loads(scene)
    sups = (scene.supports.left, scene.supports.right) if sups is None else sups
    EIs = (scene.EI, scene.EI) if EIs is None else EIs
    p = min(4, n)
    er, ec, ev = [], [], []
    e0 = np.zeros(n + 2 * G)
    skip = {0: set(), n - 1: set()}
    for side, sup in enumerate(sups):
        EI = EIs[side]
        # internal moment and the third s-derivative coefficient EI d3w/ds3 at the end
        if side == 0:
            M_end, V3 = -C[0], -P[0]  # M(0+) = -C0, EI w'''(0) = P0 -> d3/ds3 = -w'''
        else:
            M_end, V3 = C[1], -P[1]  # M(L-) = C1, EI w'''(L) = -P1
        if curvature_ends and sup in ("free", "guided"):
            Gm, g0 = poly_ghosts((4,) if sup == "free" else (1,), G, p)[0], np.zeros(G)
        else:
            Gm, g0 = taylor_ghosts(sup, G, dx, M_end, V3, EI, p)
        real = np.arange(p) if side == 0 else n - 1 - np.arange(p)
        ghost = G - 1 - np.arange(G) if side == 0 else G + n + np.arange(G)
        er.append(np.repeat(ghost, p)), ec.append(np.tile(real, G)), ev.append(Gm.ravel())
        e0[ghost] = g0
        skip[0 if side == 0 else n - 1] = {"point_force", "point_moment"}  # end loads: in the ghosts or reactions
    return np.concatenate(er), np.concatenate(ec), np.concatenate(ev), e0, skip


def corrected_system(scene: Scene, x: np.ndarray, c: np.ndarray, a: float, A: float, loads=None):
    """(K, b, fixed, info) of the corrected variant's strong form: K_ext = a D2 D1 (D1: kappa on the real points and
    J ghosts each side; D2: on the real points), a Toeplitz operator whose stencil is the self-convolution of the
    curvature stencil, the 2J ghosts per end by :func:`ghost_map`. ``loads(skip)``: (q, curv) of the point loads
    (:func:`.mixed.point_load_terms`; default the split of Eq. 25 and no curvature terms): b = (q - EI D2 curv) / A."""
    n, dx, J = len(x), x[1] - x[0], len(c)
    G = 2 * J
    st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])
    g_rows, g_cols, g_vals, e0, skip = ghost_map(scene, n, dx, G)
    K, r = ghost_stencil_system(np.arange(-G, G + 1), a * np.convolve(st, st), G, n, g_rows, g_cols, g_vals, e0)
    if loads is None:
        q, curv = body_loads(scene, x, skip_ends=skip), np.zeros(n + 2 * J)
    else:
        q, curv = loads(skip)
    b = (q - scene.EI * np.convolve(curv, st[::-1], mode="valid")) / A - r
    fixed = fixed_points(scene, n)
    return K, b, fixed, {"ghosts_per_end": G, "boundary": "Taylor ghost points (degree 4, 4 real points)"}


# -- corrected, mixed form: (kappa, w) per position -----------------------------------------------


def mixed_ghost_coupling(gpos, g_cols, g_vals, e0, n: int, J: int, st: np.ndarray, h2: float):
    """The ghost w (outside the beam) = Gm w_real + g0 on the kappa rows p whose family reaches them: (rows, cols,
    vals) onto the real w columns and the constant part (rhs of the kappa rows, length 2 (n + 2J)). ``gpos``: the
    ghost entries' positions (< 0 or > n - 1), ``g_cols`` their real points, ``e0`` indexed by position + 2J."""
    G = 2 * J
    p = np.unique(np.clip(np.r_[np.arange(-J, J), np.arange(n - J, n + J)], -J, n - 1 + J))  # rows reaching a ghost
    ge, kp = np.nonzero(np.abs(gpos[:, None] - p[None, :]) <= J)  # (ghost entry, kappa row) within a family
    rows, cols = 2 * (p[kp] + J), 2 * (g_cols[ge] + J) + 1
    vals = -h2 * st[gpos[ge] - p[kp] + J] * g_vals[ge]
    rhs = np.zeros(2 * (n + 2 * J))
    gp = np.unique(gpos)
    gi, kq = np.nonzero(np.abs(gp[:, None] - p[None, :]) <= J)
    np.add.at(rhs, 2 * (p[kq] + J), h2 * st[gp[gi] - p[kq] + J] * e0[gp[gi] + G])
    return rows, cols, vals, rhs


def mixed_end_rows(scene: Scene, n: int, dx: float, c: np.ndarray, q: np.ndarray, sups=None, EIs=None) -> list:
    """The end conditions of free and guided ends on k = dx² kappa (:func:`curvature_end_rows`), instead of
    Taylor ghosts of w: [(rows, cols, vals, rhs rows, rhs values)], left end first. ``sups``, ``EIs`` as
    :func:`ghost_map`."""
    J = len(c)
    P, C = end_loads(scene)
    sups = (scene.supports.left, scene.supports.right) if sups is None else sups
    EIs = (scene.EI, scene.EI) if EIs is None else EIs
    ends = []
    for side, sup in enumerate(sups):
        if sup in ("free", "guided"):
            M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
            ends.append(
                curvature_end_rows(
                    sup,
                    side,
                    n,
                    dx,
                    c,
                    M_end,
                    V3,
                    EIs[side],
                    q[0 if side == 0 else -1],
                    J,
                    lambda p_: 2 * (np.asarray(p_) + J),
                    lambda p_: 2 * (np.asarray(p_) + J) + 1,
                )
            )
    return ends


def mixed_matrix(npos: int, J: int, st: np.ndarray, h2: float, ghost: tuple, ends: list, diag=None) -> Band:
    """The band of the mixed form: unknowns k_p = h² kappa_p and w_p (entries of order one), kappa rows (dof 0)
    k_p - h² Σ_o st_o w_{p+o}, w rows (dof 1) h² Σ_o st_o k_{p+o}; the ghost entries (:func:`mixed_ghost_coupling`)
    added, the end rows of free and guided ends written over their kappa rows. ``diag``: the kappa rows' own
    coefficient per position instead of 1 (k then a scaled moment: :mod:`.mixed`)."""
    rows, cols, vals = ghost
    off = (
        np.r_[cols - rows, -2 * J - 1, 2 * J + 1]
        if not ends
        else np.r_[cols - rows, -2 * J - 1, 2 * J + 1, np.concatenate([e[1] - e[0] for e in ends])]
    )
    M = Band(2 * npos, int(-off.min()), int(off.max()))
    blocks = {o: [[1.0 if o == 0 else 0.0, -h2 * st[o + J]], [h2 * st[o + J], 0.0]] for o in range(-J, J + 1)}
    M.add_block_stencil(2, blocks)
    if diag is not None:
        change = np.flatnonzero(np.asarray(diag) != 1.0)
        M.add_entries(2 * change, 2 * change, np.asarray(diag)[change] - 1.0)
    M.add_entries(rows, cols, vals)
    for e_rows, e_cols, e_vals, _, _ in ends:
        M.clear_rows(np.unique(e_rows))
        M.add_entries(e_rows, e_cols, e_vals)
    return M
