"""Shared pieces of the one-dimensional PD beam models (pd-eb, pd-bond-pair, pd-higher-order, pd-timoshenko).

Families and partial volumes of a horizon m dx, Toeplitz stencil operators with ghost points eliminated,
load placement on a point grid (cell integrals of distributed loads, point loads as line loads, end loads,
the boundary-layer warning), and the Taylor ghost-point closures of the corrected variants (design note §1):
a degree-4 polynomial satisfying a support's conditions, fitted to the first four real points. Arrays in,
arrays out; each model module imports these and holds only its own paper's equations.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import numpy as np
import scipy.sparse as sp

from ..band import Band
from ..scene import Distributed, PointForce, PointMoment, Scene

# -- families --------------------------------------------------------------------------------


def partial_volumes(m: float) -> tuple[np.ndarray, np.ndarray]:
    """Family offsets j and volume fractions beta_j of the cells [j - 1/2, j + 1/2] dx inside m dx."""
    J = int(np.ceil(m + 0.5 - 1e-12))
    j = np.arange(1, J + 1)
    beta = np.clip(m - (j - 0.5), 0.0, 1.0)
    return j[beta > 0], beta[beta > 0]


def family(m: float, dx: float, variant: str, volumes: str = "full") -> tuple[np.ndarray, np.ndarray]:
    """Offsets j = 1..J and their volume fractions beta_j. Paper, delta = (m + 0.015) dx: ``volumes = "full"``
    every member inside delta a whole cell (Diyaroglu et al., pd-bond-pair), ``"partial"`` the Oterkus/Madenci
    convention (a member with delta - dx/2 < xi < delta + dx/2 gets (delta + dx/2 - xi)/dx: 0.515 for the third
    neighbour at 3.015 dx). Corrected: the cells' parts inside m dx (beta = 1/2 at xi = m dx)."""
    if variant == "paper":
        if volumes == "full":
            J = int(np.floor(m + 0.015 + 1e-12))
            return np.arange(1, J + 1), np.ones(J)
        return partial_volumes(m + 0.015)
    return partial_volumes(m)


# -- operators ------------------------------------------------------------------------------


def stencil_operator(
    n_rows: int, row0: int, n_cols: int, offsets: np.ndarray, coefs: np.ndarray, truncate: bool = False
) -> sp.csr_matrix:
    """Sparse Toeplitz operator: row r holds ``coefs`` at columns r + row0 + ``offsets`` (repeated
    offsets add up). Built diagonal by diagonal (``scipy.sparse.diags``, C speed: 25x faster than COO
    triplets at 10^6 points). ``truncate``: drop entries outside the grid instead of raising."""
    offsets = np.asarray(offsets, dtype=np.int64) + row0
    coefs = np.asarray(coefs, dtype=float)
    u, inv = np.unique(offsets, return_inverse=True)
    vals = np.bincount(inv.ravel(), weights=coefs, minlength=len(u))
    if not truncate and (u.min() < 0 or n_rows - 1 + u.max() > n_cols - 1):
        raise ValueError("stencil leaves the grid")
    return sp.diags(list(vals), list(u), shape=(n_rows, n_cols), format="csr")


def ghost_stencil_system(offsets, coefs, G: int, n: int, g_rows, g_cols, g_vals, e0) -> tuple[Band, np.ndarray]:
    """(K, r): the Toeplitz operator whose row i (real point i) holds ``coefs`` at extended columns
    i + G + ``offsets`` (extended grid: G ghosts, n real points, G ghosts), with the ghosts eliminated by
    w_ext = E w + e0 (E: identity on the real points, ghost rows (g_rows, g_cols, g_vals) in extended
    numbering). K = K_ext E as a :class:`~pdverify.band.Band` (the truncated Toeplitz part by diagonals
    plus the few ghost entries of the boundary rows), r = K_ext e0."""
    offsets = np.asarray(offsets, dtype=np.int64)
    coefs = np.asarray(coefs, dtype=float)
    g_rows, g_cols, g_vals = (np.asarray(v) for v in (g_rows, g_cols, g_vals))
    band = np.unique(np.r_[0 : min(n, G), max(0, n - G) : n])  # rows whose family reaches a ghost
    cols = band[:, None] + G + offsets[None, :]
    ghost = (cols < G) | (cols >= G + n)
    rr = np.broadcast_to(band[:, None], cols.shape)[ghost]
    cc = cols[ghost]
    vv = np.broadcast_to(coefs[None, :], cols.shape)[ghost]
    r = np.zeros(n)
    np.add.at(r, rr, vv * np.asarray(e0, float)[cc])
    # the ghost columns through E's ghost rows onto the real columns: a product of two small matrices
    N = n + 2 * G
    Cg = sp.csr_matrix((vv, (np.searchsorted(band, rr), cc)), shape=(len(band), N))
    P = (Cg @ sp.csr_matrix((g_vals, (g_rows, g_cols)), shape=(N, n))).tocoo()
    rows, cols_r, vals = band[P.row], P.col.astype(np.int64), P.data
    reach = int(max(np.abs(offsets).max(), np.abs(cols_r - rows).max() if len(rows) else 0))
    K = Band(n, reach, reach).add_stencil(offsets, coefs)
    K.add_entries(rows, cols_r, vals)
    return K, r


# -- loads -----------------------------------------------------------------------------------


def cell_integral(
    load: Distributed, scene: Scene, lo: np.ndarray, hi: np.ndarray, value: float | None = None
) -> np.ndarray:
    """∫ over [lo, hi] ∩ span of the load's shape times ``value`` (default: the transverse
    ``load.value``; pass ``load.axial`` or ``load.torque`` for the other components)."""
    v = load.value if value is None else value
    a, b = scene.span(load)
    lo, hi = np.clip(lo, a, b), np.clip(hi, a, b)
    if load.shape == "uniform":
        return v * (hi - lo)
    k = np.pi / scene.length
    return v * (np.cos(k * lo) - np.cos(k * hi)) / k


def body_loads(scene: Scene, x: np.ndarray, skip_ends: dict | None = None) -> np.ndarray:
    """Line load q_k (N/m) on the points: cell averages of distributed loads, P/dx for point forces
    (split linearly between the two nearest points), -dm/dx couples for point moments (Eq. 25).
    ``skip_ends``: {0 or n-1: set of load types} handled elsewhere (by ghost points or reactions)."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    q = np.zeros(n)
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    skip_ends = skip_ends or {}
    for load in scene.loads:
        if isinstance(load, Distributed):
            q += cell_integral(load, scene, lo, hi) / (hi - lo)
            continue
        pos = load.position / dx
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1:
            t = 0.0
        node = i if t < 1e-9 else None
        if node is not None and load.type in skip_ends.get(node, ()):
            continue
        if isinstance(load, PointForce):
            q[i] += load.value * (1 - t) / dx
            if t > 0:
                q[i + 1] += load.value * t / dx
        elif isinstance(load, PointMoment):
            # ccw couple C: q = -C delta'(x - a), with the delta split linearly between the two nearest
            # points (weights 1 - t, t) and each point's delta' a central dipole (-C/(2dx²) left, +C/(2dx²) right)
            C = load.value
            for node, wgt in ((i, 1.0 - t), (i + 1, t)):
                if wgt == 0.0:
                    continue
                left, right = node - 1, node + 1
                if left < 0:
                    left, right = 0, 1
                if right > n - 1:
                    left, right = n - 2, n - 1
                arm = (right - left) * dx
                q[left] -= wgt * C / (arm * dx)
                q[right] += wgt * C / (arm * dx)
    return q


def end_loads(scene: Scene) -> tuple[dict, dict]:
    """Point force and moment applied exactly at the left (x = 0) and right (x = L) ends."""
    P = {0: 0.0, 1: 0.0}
    C = {0: 0.0, 1: 0.0}
    for load in scene.loads:
        if isinstance(load, (PointForce, PointMoment)):
            for side, xe in ((0, 0.0), (1, scene.length)):
                if abs(load.position - xe) <= 1e-12 * scene.length:
                    (P if isinstance(load, PointForce) else C)[side] += load.value
    return P, C


def boundary_layer_warnings(scene: Scene, x: np.ndarray, reach: int) -> list[str]:
    """Point loads (force, moment, torque) strictly inside the first ``reach`` spacings of an end: the
    ghost polynomial fitted there assumes a smooth solution, so such a load is under-resolved (measured:
    pd-eb 85-300 % error for a force one spacing from the support at 101 points, 1e-4 at 1601;
    pd-timoshenko, 201 points, L/h = 20: 59 % one spacing from a pinned end, 2 % from a clamped one,
    0.2 % at five spacings). Flag it instead of hiding it. Positions in the scene's length unit."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if hasattr(load, "position"):
            d = min(load.position, scene.length - load.position)
            if 1e-12 * scene.length < d < reach * dx:
                out.append(
                    f"loads[{i}] at {load.position:g} is {d / dx:.3g} spacings from an end, inside the "
                    f"boundary layer of {reach} spacings: expect large errors; use at least "
                    f"{int(np.ceil(reach * scene.length / d)) + 1} points"
                )
    return out + narrow_load_warnings(scene, x)


def narrow_load_warnings(scene: Scene, x: np.ndarray) -> list[str]:
    """Partial loads that lie inside one point's cell [x_i - dx/2, x_i + dx/2]: the PD models place distributed loads
    by cell averages, so such a load acts on that point as a whole, moved by up to half a spacing (a first-order
    error; measured: a 0.9 mm load on a clamped–clamped 2 m beam at 401 points, 2.9e-3 to 3.2e-3 in pd-eb,
    pd-bond-pair, pd-higher-order and pd-timoshenko, the same at 801; 1.1e-5 to 1.1e-4 at 1601 points, where it
    straddles two cells). Flag it."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if isinstance(load, Distributed) and (load.start is not None or load.end is not None):
            a = 0.0 if load.start is None else float(load.start)
            b = scene.length if load.end is None else float(load.end)
            if np.floor((a - x[0]) / dx + 0.5) == np.floor((b - x[0]) / dx + 0.5):
                out.append(
                    f"loads[{i}] from {a:g} to {b:g} lies inside one point's cell (spacing {dx:.3g}): it acts on "
                    "that point as a whole, moved by up to half a spacing (a first-order error); use at least "
                    f"{int(np.ceil(2 * scene.length / (b - a))) + 1} points"
                )
    return out


# -- Taylor ghost points (corrected variants) ------------------------------------------------

# roller = pinned: no axial unknown
_FIXED = {"clamped": (0, 1), "pinned": (0, 2), "roller": (0, 2), "free": (2, 3), "guided": (1, 3)}


def _solve_exact(A: list[list[Fraction]], B: list[list[Fraction]]) -> list[list[Fraction]]:
    """X with A X = B, A square and regular, by Gauss–Jordan elimination in exact rationals."""
    n = len(A)
    M = [list(A[i]) + list(B[i]) for i in range(n)]
    for k in range(n):
        piv = next(i for i in range(k, n) if M[i][k] != 0)
        M[k], M[piv] = M[piv], M[k]
        M[k] = [v / M[k][k] for v in M[k]]
        for i in range(n):
            if i != k and M[i][k] != 0:
                f = M[i][k]
                M[i] = [a - f * b for a, b in zip(M[i], M[k])]
    return [row[n:] for row in M]


@cache
def ghost_maps(support: str, n_ghost: int, p: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """(G, C): ghost values w(t) at t = 1..n_ghost spacings outside the end, for a degree-4 polynomial
    in t = s/dx with the support's coefficients fixed (``_FIXED``), fitted by least squares to the
    first ``p`` real points (t = 0, -1, ..., -(p-1)): w_ghost = G w_real[:p] + C c_fixed.

    Computed in exact rational arithmetic and rounded once: the matrices hold small integers, and a
    LAPACK pseudo-inverse rounds differently from one CPU's kernels to another's. The discrete
    cantilever is so sensitive to these coefficients (its constant-curvature mode is pinned by the
    free-end ghosts only) that the last bit of G moved the 6,401-point mixed-form solution from
    5.5e-7 to 1.6e-5 between OpenBLAS's Haswell and SkylakeX kernels; with G exact both give 3.6e-6."""
    fixed = _FIXED[support]
    free = [q for q in range(5) if q not in fixed]
    Vr = [[Fraction(-i) ** q for q in range(5)] for i in range(p)]
    Vg = [[Fraction(t) ** q for q in range(5)] for t in range(1, n_ghost + 1)]
    A = [[row[q] for q in free] for row in Vr]  # p x k
    At = [list(col) for col in zip(*A)]  # k x p
    N = [[sum(a * b for a, b in zip(r1, r2)) for r2 in At] for r1 in At]  # A^T A
    X = _solve_exact(N, At)  # (A^T A)^-1 A^T, k x p
    G = [[sum(row[q] * X[a][i] for a, q in enumerate(free)) for i in range(p)] for row in Vg]
    C = [[row[f] - sum(G[g][i] * Vr[i][f] for i in range(p)) for f in fixed] for g, row in enumerate(Vg)]
    Gf, Cf = np.array(G, dtype=float), np.array(C, dtype=float)
    Gf.flags.writeable = Cf.flags.writeable = False
    return Gf, Cf


@cache
def poly_ghosts(fixed: tuple[int, ...], n_ghost: int, p: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """(G, C): values at t = 1..n_ghost of the degree-4 polynomial in t whose coefficients ``fixed`` are
    given and the others fitted by least squares to the values at t = 0, -1, .., -(p-1):
    v_ghost = G v[:p] + C c_fixed (exact rationals, rounded once, as :func:`ghost_maps`)."""
    free = [q for q in range(5) if q not in fixed]
    Vr = [[Fraction(-i) ** q for q in range(5)] for i in range(p)]
    Vg = [[Fraction(t) ** q for q in range(5)] for t in range(1, n_ghost + 1)]
    A = [[row[q] for q in free] for row in Vr]
    At = [list(col) for col in zip(*A)]
    X = _solve_exact([[sum(a * b for a, b in zip(r1, r2)) for r2 in At] for r1 in At], At)
    G = [[sum(row[q] * X[a][i] for a, q in enumerate(free)) for i in range(p)] for row in Vg]
    C = [[row[f] - sum(G[g][i] * Vr[i][f] for i in range(p)) for f in fixed] for g, row in enumerate(Vg)]
    return np.array(G, dtype=float), np.array(C, dtype=float)


def curvature_end_rows(
    support: str,
    side: int,
    n: int,
    dx: float,
    c: np.ndarray,
    M_end: float,
    V3: float,
    EI: float,
    q_end: float,
    reach: int,
    kidx,
    widx,
):
    """End conditions of a free or guided end written on k = dx² kappa (kappa = Σ_j c_j (w_{+j} + w_{-j}
    - 2 w), so k = dx² (w'' + mu w'''') + .., mu = Σ_j c_j (j dx)⁴ / 12), replacing the curvature rows of
    the end point and the ``reach`` positions outside it: (rows, cols, vals, rhs_rows, rhs_vals).

    In the outward coordinate t = s / dx: k(0) = dx² (M + mu q) / EI (free), dk/dt(0) = dx³ V / EI
    (free and guided); the outside k by a degree-4 polynomial with those coefficients fitted to the first
    four k (:func:`poly_ghosts`); guided: the end point's curvature with w' = 0 imposed through
    w(j dx) = w(-j dx) + (j dx)³ w''' / 3 + O(dx⁵). Written on k, the shear is a first difference of k
    (round-off ~N eps); through Taylor ghosts of w it is a third difference of w (~N³ eps).
    ``kidx``/``widx``: unknown numbers of k and w at a grid position."""
    j = np.arange(1, len(c) + 1)
    mu = np.sum(c * (j * dx) ** 4) / 12
    a0, a1 = dx * dx * (M_end + mu * q_end) / EI, dx**3 * V3 / EI
    fix, fixed_vals = ((0, 1), np.array([a0, a1])) if support == "free" else ((1,), np.array([a1]))
    Gk, Ck = poly_ghosts(fix, reach)
    end, o = (0, -1) if side == 0 else (n - 1, 1)
    inner, outer = end - o * np.arange(4), end + o * np.arange(1, reach + 1)
    rows = [np.repeat(kidx(outer), 5)]
    cols = [np.c_[kidx(outer), np.tile(kidx(inner), (reach, 1))].ravel()]
    vals = [np.c_[np.ones(reach), -Gk].ravel()]
    rr, rv = [kidx(outer)], [Ck @ fixed_vals]
    if support == "free":
        rows.append([kidx(end)]), cols.append([kidx(end)]), vals.append([1.0])
        rr.append([kidx(end)]), rv.append([a0])
    else:
        rows.append(np.full(len(j) + 2, kidx(end)))
        cols.append(np.r_[kidx(end), widx(end - o * j), widx(end)])
        vals.append(np.r_[1.0, -2 * dx * dx * c, 2 * dx * dx * c.sum()])
        rr.append([kidx(end)]), rv.append([dx * dx * np.sum(c * (j * dx) ** 3) * V3 / (3 * EI)])
    cat = lambda a, dt: np.concatenate([np.asarray(v, dt).ravel() for v in a])  # noqa: E731
    return cat(rows, np.int64), cat(cols, np.int64), cat(vals, float), cat(rr, np.int64), cat(rv, float)


def taylor_ghosts(
    support: str, n_ghost: int, dx: float, M_end: float, V_coef: float, EI: float, p: int = 4
) -> tuple[np.ndarray, np.ndarray]:
    """Ghost values as an affine map of the first p real points: w_g = G w_real[:p] + g0.

    s is the distance from the end into the ghost region (ghost i at s = i dx, real point i at
    s = -i dx). w(s) = Σ_{q<=4} c_q s^q with the support's coefficients fixed: c0 = 0 (w = 0),
    c1 = 0 (w' = 0), c2 = M_end / (2 EI), c3 = V_coef / (6 EI) (the third s-derivative, see caller).
    The fit is made in t = s/dx (:func:`ghost_maps`, exact).
    """
    fixed = _FIXED[support]
    values = {0: 0.0, 1: 0.0, 2: M_end / (2 * EI), 3: V_coef / (6 * EI)}
    G, C = ghost_maps(support, n_ghost, p)
    fvals = np.array([values[q] * dx**q for q in fixed])
    return G, C @ fvals
