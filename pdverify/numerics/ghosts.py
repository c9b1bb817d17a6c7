"""Taylor ghost-point closures of the corrected PD variants: a degree-4 polynomial that satisfies a support's
conditions, fitted to the first real points, gives the fictitious points beyond an end (exact rational
arithmetic for the maps; docs/design/formulas.md). Arrays in, arrays out."""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import numpy as np

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
