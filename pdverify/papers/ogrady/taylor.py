"""Taylor ends of the linear bond-pair operator (O'Grady & Foster 2014; ghost rules: docs/design/formulas.md §1):
the strong-form operator Σ_j c_j D_j² w = q with degree-4 Taylor ghost points (``form = direct``) and the same operator
split into two second-order equations on the curvature and the deflection (``form = mixed``)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.contract import System
from ...core.errors import InputError
from ...core.scene import Scene
from ...numerics.band import Band
from ...numerics.families import ghost_stencil_system, stencil_operator
from ...numerics.ghosts import curvature_end_rows, taylor_ghosts
from ...numerics.loads import body_loads, end_loads
from .calibration import calibration_name


def operator_stencil(j: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Offsets and coefficients of Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j})."""
    offs = np.array([-2, -1, 0, 1, 2])
    coef = np.array([1.0, -4.0, 6.0, -4.0, 1.0])
    return (np.asarray(j)[:, None] * offs[None, :]).ravel(), (np.asarray(c)[:, None] * coef[None, :]).ravel()


def operator(n_rows: int, row0: int, n_cols: int, j: np.ndarray, c: np.ndarray) -> sp.csr_matrix:
    """The operator of :func:`operator_stencil` for rows k = row0 .. row0 + n_rows - 1 of a grid of
    n_cols points (families truncated at the grid's ends)."""
    return stencil_operator(n_rows, row0, n_cols, *operator_stencil(j, c), truncate=True)


def factored_stencils(j: np.ndarray, c: np.ndarray, EI: float, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """(r, s): the operator of :func:`operator_stencil` written as (EI / dx⁴) D1 r D1, D1 = (1, -2, 1).

    w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j} = D_j² w and D_j = D1 T_j with T_j the triangle
    stencil (1, 2, .., j, .., 2, 1) (offsets 1-j .. j-1), so Σ_j c_j D_j² = D1 (Σ_j c_j T_j²) D1. r =
    Σ_j c_j T_j² dx⁴ / EI (offsets -2(J-1) .. 2(J-1); its sum is Σ_j c_j j⁴ dx⁴ / EI, 1 for the discrete
    calibration), s = D1 * r (offsets -(2J-1) .. 2J-1)."""
    J = int(np.max(j))
    r = np.zeros(4 * J - 3)
    for jj, cj in zip(j, c):
        tri = np.r_[np.arange(1, jj + 1), np.arange(jj - 1, 0, -1)].astype(float)
        t2 = np.convolve(tri, tri)
        mid = 2 * (J - 1)
        r[mid - 2 * (jj - 1) : mid + 2 * (jj - 1) + 1] += cj * t2 * dx**4 / EI
    return r, np.convolve([1.0, -2.0, 1.0], r)


HELD_W = ("clamped", "pinned", "roller")  # supports that hold w (roller: pinned's transverse conditions)
D1 = {-1: 1.0, 0: -2.0, 1: 1.0}  # the second difference of the mixed form's first equation


def mixed_ends(scene: Scene, n: int, dx: float, G: int, Jk: int, q: np.ndarray):
    """The ends of the mixed form (:meth:`PDBondPair.assemble_mixed`): (ghosts, conditions). At clamped, pinned and
    roller ends the G ghost w outside the beam by the degree-4 Taylor polynomial of ``taylor_ghosts`` (end loads
    through the moment and shear at the end), ghosts = (positions, real points, weights, (position, constant)
    rows); at free and guided ends the end conditions on k = D1 w (the curvature stencil c = 1/dx²;
    :func:`~pdverify.numerics.ghosts.curvature_end_rows`): conditions = (rows, cols, vals, (row, rhs) rows) lists,
    round-off ~N eps instead of ~N³ eps through Taylor ghosts of w."""
    P, C = end_loads(scene)
    g_pos, g_real, g_val, g_const = [], [], [], []
    k_rows, k_cols, k_vals, k_rhs = [], [], [], []  # the end rows of free and guided ends (on k)
    kidx = lambda p: 2 * (np.asarray(p) + Jk)  # noqa: E731  (unknown k_p)
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
        if sup in ("free", "guided"):
            q_end = q[0 if side == 0 else n - 1]
            er_, ec_, ev_, rr_, rv_ = curvature_end_rows(
                sup, side, n, dx, np.array([1 / dx**2]), M_end, V3, scene.EI, q_end, Jk, kidx, lambda p_: kidx(p_) + 1
            )
            k_rows.append(er_), k_cols.append(ec_), k_vals.append(ev_), k_rhs.append(np.c_[rr_, rv_])
            continue
        Gm, g0 = taylor_ghosts("pinned" if sup == "roller" else sup, G, dx, M_end, V3, scene.EI, min(4, n))
        real = np.arange(4) if side == 0 else n - 1 - np.arange(4)
        pos = -1 - np.arange(G) if side == 0 else n + np.arange(G)
        g_pos.append(np.repeat(pos, 4)), g_real.append(np.tile(real, G)), g_val.append(Gm.ravel())
        g_const.append(np.stack([pos, g0], axis=1))
    g_pos, g_real = (np.concatenate(v) if v else np.zeros(0, np.int64) for v in (g_pos, g_real))
    g_val = np.concatenate(g_val) if g_val else np.zeros(0)
    g_const = np.concatenate(g_const) if g_const else np.zeros((0, 2))
    return (g_pos, g_real, g_val, g_const), (k_rows, k_cols, k_vals, k_rhs)


def ghost_rows(g_pos, g_real, g_val, g_const, n: int, Jk: int):
    """The ghost w in the first equation k_p - (w_{p+1} - 2 w_p + w_{p-1}) = 0 of the rows p within the grid
    whose second difference reaches a ghost position (|g - p| <= 1): (rows, cols, vals) lists onto the real w
    columns and the constant part (rhs, length 2 (n + 2 Jk))."""
    rows, cols, vals = [], [], []
    rhs = np.zeros(2 * (n + 2 * Jk))
    for o, w_o in D1.items():
        p = g_pos - o
        ok = (p >= -Jk) & (p <= n - 1 + Jk)
        rows.append(2 * (p[ok] + Jk)), cols.append(2 * (g_real[ok] + Jk) + 1), vals.append(-w_o * g_val[ok])
        pc = g_const[:, 0].astype(np.int64) - o
        okc = (pc >= -Jk) & (pc <= n - 1 + Jk)
        np.add.at(rhs, 2 * (pc[okc] + Jk), w_o * g_const[okc, 1])
    return rows, cols, vals, rhs


def mixed_band(npos: int, Jk: int, st: np.ndarray, rows, cols, vals, cleared) -> Band:
    """The band of the mixed form, unknowns (k_p, w_p) interleaved at the positions p = -Jk .. n-1+Jk: the block
    stencil of k_p - D1 w and Σ_o s_o k_{p+o}, the rows ``cleared`` (free and guided end conditions) emptied, then
    the entries (rows, cols, vals) of the ghosts and end conditions added."""
    off = np.r_[cols - rows, -2 * Jk - 1, 2 * Jk + 1]
    M = Band(2 * npos, int(-off.min()), int(off.max()))
    blocks = {o: [[1.0 if o == 0 else 0.0, -D1.get(o, 0.0)], [st[o + Jk], 0.0]] for o in range(-Jk, Jk + 1)}
    M.add_block_stencil(2, blocks)
    if cleared is not None:
        M.clear_rows(np.unique(cleared))
    M.add_entries(rows, cols, vals)
    return M


def assemble_taylor(scene: Scene, params: dict, c: np.ndarray, j: np.ndarray):
    """The direct form with the spring constants ``c`` of the family offsets ``j``:
    (K, b, fixed, info): the strong-form operator on all real points as a
    :class:`~pdverify.numerics.band.Band` (Toeplitz by diagonals + the ghost entries), the supported points
    ``fixed`` held at w = 0 (unit rows, ``Band.fix``)."""
    n = params["points"]
    x = np.linspace(0.0, scene.length, n)
    dx = x[1] - x[0]
    G = 2 * int(j.max())
    if G + 1 > n:
        raise InputError(
            f"horizon = {params['horizon']:g}: the stencil (2 x {j.max()} points) does not fit in "
            f"{n} points; use more points or a smaller horizon"
        )
    N = n + 2 * G
    left, right = scene.supports.left, scene.supports.right
    er, ec, ev = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
    e0 = np.zeros(N)
    skip = {}
    # Taylor ghosts (the mirror ends go through the energy form, :meth:`energy_model`)
    P, C = end_loads(scene)
    for side, sup in ((0, left), (1, right)):
        M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
        # roller: the transverse conditions of pinned (the axial one does not enter this path)
        Gm, g0 = taylor_ghosts("pinned" if sup == "roller" else sup, G, dx, M_end, V3, scene.EI, min(4, n))
        real = np.arange(4) if side == 0 else n - 1 - np.arange(4)
        ghost = G - 1 - np.arange(G) if side == 0 else G + n + np.arange(G)
        er.append(np.repeat(ghost, 4)), ec.append(np.tile(real, G)), ev.append(Gm.ravel())
        e0[ghost] = g0
        skip[0 if side == 0 else n - 1] = {"point_force", "point_moment"}
    cat = lambda v, dt: np.concatenate(v[1:]) if len(v) > 1 else np.zeros(0, dt)  # noqa: E731
    K, r = ghost_stencil_system(*operator_stencil(j, c), G, n, cat(er, int), cat(ec, int), cat(ev, float), e0)
    b = body_loads(scene, x, skip_ends=skip) - r
    fixed = [i for i, sup in ((0, left), (n - 1, right)) if sup in ("clamped", "pinned", "roller")]
    K.fix(fixed, b)
    info = {"ghosts_per_end": G, "alpha_calibration": calibration_name(params["variant"])}
    return K, b, fixed, info


def assemble_mixed(scene: Scene, params: dict, c: np.ndarray, j: np.ndarray):
    """With the spring constants ``c`` of the family offsets ``j``: the Taylor-ghost operator split in two
    second-order equations (``form = mixed``)::

        k_p - (w_{p+1} - 2 w_p + w_{p-1}) = 0          p = -(2J-1) .. n-1+2J-1
        Σ_o s_o k_{i+o}                  = dx⁴ q_i / EI  (real points i)

    (:func:`factored_stencils`): the same discrete solution as the fourth-order system, but no matrix
    of fourth differences is formed, so the round-off floor falls from ~N⁴ eps to ~N² eps (as pd-eb's
    mixed form). At clamped, pinned and roller ends ghost w (outside the beam, up to 2J spacings) enter
    the first equation through the Taylor map w_g = Gm w_real + g0; at free and guided ends the first
    equation of the end point and of the positions outside is replaced by the end conditions on k
    (:func:`~pdverify.numerics.ghosts.curvature_end_rows`, :func:`mixed_ends`). Unknowns interleaved (k_p,
    w_p) in LAPACK's band layout; the w of positions outside the beam and of supported points are held at zero.
    Returns the :class:`~pdverify.registry.System` (free: the unknowns not held; ``info["Jk"]``): w of real
    point i is unknown 2 (i + Jk) + 1."""
    n = params["points"]
    x = np.linspace(0.0, scene.length, n)
    dx = x[1] - x[0]
    J = int(j.max())
    G, Jk = 2 * J, 2 * J - 1
    if G + 1 > n:
        raise InputError(
            f"horizon = {params['horizon']:g}: the stencil (2 x {J} points) does not fit in "
            f"{n} points; use more points or a smaller horizon"
        )
    _, st = factored_stencils(j, c, scene.EI, dx)
    skip = {0: {"point_force", "point_moment"}, n - 1: {"point_force", "point_moment"}}
    q = body_loads(scene, x, skip_ends=skip)
    ghosts, (k_rows, k_cols, k_vals, k_rhs) = mixed_ends(scene, n, dx, G, Jk, q)
    rows, cols, vals, rhs = ghost_rows(*ghosts, n, Jk)
    cat = lambda a, dt: np.concatenate([np.asarray(v, dt).ravel() for v in a])  # noqa: E731
    rows, cols, vals = cat(rows + k_rows, np.int64), cat(cols + k_cols, np.int64), cat(vals + k_vals, float)
    npos = n + 2 * Jk
    M = mixed_band(npos, Jk, st, rows, cols, vals, cat(k_rows, np.int64) if k_rows else None)
    if k_rows:  # free/guided end rows: the conditions on k instead
        kr = np.concatenate([np.asarray(v, float).reshape(-1, 2) for v in k_rhs])
        rhs[kr[:, 0].astype(np.int64)] = kr[:, 1]
    rhs[2 * Jk + 1 : 2 * (n + Jk) : 2] = q * dx**4 / scene.EI
    fixed = [i for i, sup in ((0, scene.supports.left), (n - 1, scene.supports.right)) if sup in HELD_W]
    held = np.r_[2 * np.arange(Jk) + 1, 2 * (n + Jk + np.arange(Jk)) + 1, 2 * (np.asarray(fixed, np.int64) + Jk) + 1]
    M.fix(held, rhs)
    return System(
        M,
        rhs,
        np.delete(np.arange(2 * npos), held),
        {
            "ghosts_per_end": G,
            "form": "mixed (curvature and deflection)",
            "Jk": Jk,
            "alpha_calibration": calibration_name(params["variant"]),
        },
    )
