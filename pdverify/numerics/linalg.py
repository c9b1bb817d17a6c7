"""Linear solves shared by the models: sparse LU or banded LU, singularity checks, condition estimates.

``solve_linear(K, b, what=...)`` is the one entry point a static model needs: it picks a banded LU
when the matrix is narrow-banded (the PD and beam operators are), else SuperLU, raises
:class:`~pdverify.core.errors.SolveError` with one clear line for a singular or non-finite system, and
returns the solution with an info dict (solver, bandwidth, 1-norm condition estimate, residual).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..core.errors import SolveError
from . import factorcache
from .band import Band, bandwidths, canonical_csr, csr_rows
from .error_bound import (  # noqa: F401 - re-exported: the models import the bound's pieces from here
    BOUND_LIMIT,
    ENTRY_ROUNDING,
    _weight,
    bound_warning,
    forward_error_bound,
    hager_inverse_norm,
    hager_norm1,
    record_bound,
)
from .rounding import BandRounding, SharedRounding, csr_layout


def diagonal_scaling(d: np.ndarray) -> np.ndarray:
    """s = 1 / sqrt|d| (1 where d = 0) of the symmetric equilibration diag(s) K diag(s) every banded solve
    applies: mixed DOFs (deflection, rotation) differ by powers of the element length."""
    d = np.abs(d)
    return np.where(d > 0, 1.0 / np.sqrt(np.where(d > 0, d, 1.0)), 1.0)


def banded_lu(K: sp.csr_matrix, lower: int, upper: int, s: np.ndarray):
    """LU (LAPACK gbtrf) of diag(s) K diag(s): K scattered into a :class:`~pdverify.numerics.band.Band`, scaled
    there and copied once into the Fortran array gbtrf factorises in place.
    Returns (solve, solve_transposed); raises numpy.linalg.LinAlgError when a pivot is exactly zero."""
    from scipy.linalg import lapack

    B = Band.from_sparse(K, lower, upper).scale(s)
    n = B.n
    colsum = np.zeros(n)  # ||diag(s) K diag(s)||_1 before the factors overwrite it; row by row (elementwise adds:
    for row in B.data:  # the same bits whatever the array's alignment)
        colsum += np.abs(row)
    anorm = float(colsum.max())
    lu, piv, info = lapack.dgbtrf(B.lapack(), lower, upper, overwrite_ab=1)
    if info > 0:
        raise np.linalg.LinAlgError(f"zero pivot at unknown {info - 1}")

    def solve(y, trans=0):
        x, inf = lapack.dgbtrs(lu, lower, upper, np.asarray(y, float), piv, trans=trans)
        if inf != 0:
            raise np.linalg.LinAlgError(f"gbtrs info {inf}")
        return x

    memo: list[float] = []  # the estimate, made once per factorisation (a shared one is asked again)

    def cond() -> float:
        """1-norm condition estimate ||A||_1 * est ||A^-1||_1 from the factors, rounded to 6 digits (an
        estimate has no use for 17, and sums differ in the last bit with the arrays' alignment).
        ||A^-1||_1 by Hager's method with Higham's extra test vector (the algorithm of LAPACK's dlacn2):
        a few band solves, linear in n. (LAPACK's dgbcon does the same, but its time as called here grows
        faster than n; scipy's onenormest costs a large share of a small solve.)"""
        if not memo:
            inv = hager_inverse_norm(solve, lambda y: solve(y, 1), n)
            memo.append(float(f"{anorm * inv:.6g}") if np.isfinite(inv) else float("inf"))
        return memo[0]

    solve.cond = cond
    return solve, (lambda y: solve(y, 1))


def scale_symmetric(K: sp.csr_matrix, s: np.ndarray) -> sp.csr_matrix:
    """diag(s) K diag(s) entry by entry (no sparse products)."""
    K = canonical_csr(K)
    return sp.csr_matrix((K.data * (s[csr_rows(K)] * s[K.indices]), K.indices, K.indptr), shape=K.shape)


def condition_estimate(K: sp.spmatrix, solve, solve_t=None) -> float:
    """1-norm condition number estimate ||K||_1 est ||K^-1||_1: ||K||_1 exact (its largest absolute column sum),
    ||K^-1||_1 by Hager's method (:func:`hager_inverse_norm`, a few solves, deterministic: the same estimate on every
    run, where scipy's onenormest starts from random vectors), rounded to 6 digits as the banded path's."""
    n = K.shape[0]
    if n <= 100:  # dense is exact and cheap only for small systems (an inverse is O(n^3))
        return float(np.linalg.cond(K.toarray(), 1))
    if solve_t is None:
        solve_t = spla.splu(sp.csc_matrix(K.T)).solve  # Hager's method also needs K^-T
    anorm = float(np.asarray(abs(K).sum(axis=0)).max())
    inv = hager_inverse_norm(solve, solve_t, n)
    return float(f"{anorm * inv:.6g}") if np.isfinite(inv) else float("inf")


REFINE_MOST = 10  # refinement steps at most: past ``steps``, only while each step at least halves the last


def refine(
    K: sp.spmatrix, b: np.ndarray, u: np.ndarray, solve, steps: int = 3, most: int = REFINE_MOST, Kl=None
) -> tuple[np.ndarray, list[float]]:
    """Mixed-precision iterative refinement: residual r = b - K u in extended precision (x87 long
    double, eps 1.1e-19), correction solved in float64. Converges to the exact solution of the
    float64 matrix K while cond(K) * eps64 < 1, by a factor of about cond(K) * eps64 per step; it cannot repair
    the rounding of K's entries. ``steps`` steps, then more (up to ``most``) while each step at least halves the
    last and is above 4 eps: an ill-conditioned K contracts slowly, and a fixed count would leave its last step's
    error in the solution (Wilkinson; Higham, *Accuracy and Stability*, §12.1). ``Kl``: K in long double, made
    before (:func:`long_double`)."""
    Kl = long_double(K)[0] if Kl is None else Kl
    bl = np.asarray(b, np.longdouble)
    ul = np.asarray(u, np.longdouble)
    history: list[float] = []
    eps = np.finfo(float).eps
    for i in range(max(steps, most)):
        r = bl - Kl @ ul
        du = solve(np.asarray(r, float))
        ul = ul + du
        history.append(float(np.abs(du).max() / max(np.abs(ul).max(), 1e-300)))
        if history[-1] < 1e-17:
            break
        if i + 1 >= steps and (history[-1] <= 4 * eps or len(history) < 2 or history[-1] > 0.5 * history[-2]):
            break
    return np.asarray(ul, float), history


def long_double(K: sp.spmatrix) -> tuple[sp.spmatrix, int]:
    """(K with its entries in long double, in K's format, and the bytes it takes): the matrix of the
    extended-precision residuals."""
    Kl = K.astype(np.longdouble)
    return Kl, sum(getattr(Kl, a).nbytes for a in ("data", "indices", "indptr") if hasattr(Kl, a))


def eliminate(K: sp.spmatrix, b: np.ndarray, fixed) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """Master–slave elimination of zero DOFs: (K_ff, b_f, free) by row/column selection (no products)."""
    K = sp.csr_matrix(K)
    n = K.shape[0]
    keep = np.ones(n, bool)
    keep[np.asarray(fixed, dtype=np.int64)] = False
    free = np.flatnonzero(keep)
    if len(free) == n:
        return K, np.asarray(b), free
    lo, hi = free[0], free[-1] + 1
    if hi - lo == len(free):  # contiguous (supports at the ends): slices
        return K[lo:hi, lo:hi].tocsr(), np.asarray(b)[lo:hi], free
    return K[free][:, free].tocsr(), np.asarray(b)[free], free


SMALL = 20_000  # up to this many unknowns: condition estimate, refinement and residual by default


def solve_band(
    B: Band,
    b: np.ndarray,
    what: str = "system",
    scaling: np.ndarray | None = None,
    watch=None,
    magnitude=None,
    refine: bool = False,
    entry_rounding: float | None = None,
) -> tuple[np.ndarray, dict]:
    """Solve B u = b for a :class:`~pdverify.numerics.band.Band` (B is consumed: scaled in place).

    The path of large systems: symmetric diagonal scaling diagonal by diagonal (``scaling``, default
    1/sqrt|diag|), LAPACK gbtrf on one copy, gbtrs; then the correction of a residual computed in extended
    precision (applied, one or two steps of iterative refinement, when ``refine``; else only measured, so the
    solution is that of the LU alone) and :func:`forward_error_bound` (``info["error_bound"]``, over the
    unknowns ``watch``; its data term over the band's entries grouped by the rounding they share,
    :mod:`pdverify.numerics.rounding`, or ``magnitude(u)``, the size of each row's independently rounded terms):
    a few extra banded solves and products, all linear in n. B's scaled band is kept
    beside its factors for the residual (one more band of memory)."""
    from scipy.linalg import lapack

    b = np.asarray(b, dtype=float)
    if not np.all(np.isfinite(b)):
        raise SolveError(f"{what}: the load vector holds NaN/inf; check the scene's numbers")
    if not np.all(np.isfinite(B.data)):
        raise SolveError(f"{what}: the assembled matrix holds NaN/inf; check the scene's numbers")
    s = diagonal_scaling(B.diag(0)) if scaling is None else np.asarray(scaling, float)
    B.scale(s)
    lo, up = B.lower, B.upper
    info: dict = {
        "system_unknowns": B.n,
        "bandwidth_lower": lo,
        "bandwidth_upper": up,
        "scaling": "symmetric diagonal",
        "solver": "banded LU (LAPACK gbtrf/gbtrs, assembled in place)",
    }
    lu, piv, inf = lapack.dgbtrf(B.lapack(), lo, up, overwrite_ab=1)
    if inf > 0:
        raise SolveError(
            f"{what}: the system matrix is singular (zero pivot at unknown {inf - 1}); the supports do "
            "not hold the beam (a mechanism) or the discretisation is degenerate"
        )

    def solve(y, trans=0):
        return lapack.dgbtrs(lu, lo, up, y, piv, trans=trans)[0]

    bs = s * b
    y = solve(bs)
    if not np.all(np.isfinite(y)):
        raise SolveError(
            f"{what}: the solution is not finite; the matrix holds NaN/inf, or the system is "
            "singular or too ill-conditioned"
        )
    steps, r0 = [], None
    while True:  # the correction of a residual in extended precision: applied when refine (a second time only when
        r = extended_residual(B, bs, y)  # the first was large); the last one is measured, not applied: the
        r0 = r if r0 is None else r0  # estimate of the error of the solution returned
        dy = solve(r)
        size = float(np.abs(dy).max() / max(np.abs(y).max(), 1e-300))
        if not refine or len(steps) == 2 or (steps and size <= 0.01 * BOUND_LIMIT):
            break
        y = y + dy
        steps.append(size)
    if refine:
        info["refinement"] = steps
    with np.errstate(all="ignore"):
        u = s * y
    _require_finite(u, what)
    # the data error's map: the scaled band's entries grouped by shared rounding (numerics/rounding.py)
    if magnitude is None:
        m = BandRounding(B.data, B.upper, y, bs, _weight(entry_rounding))
    else:
        m = s * magnitude(u)
    record_bound(info, _scaled_bound(solve, lambda z: solve(z, 1), s, s * dy, m, u, watch, 2))
    np.abs(B.data, out=B.data)
    size = (B.matvec(np.abs(y)) + np.abs(bs)).max()  # the residual relative to the size of its terms
    info["residual"] = float(np.abs(r0).max() / size) if size > 0 else 0.0  # of the unrefined solution
    B.data = None  # consumed
    return u, info


def extended_residual(B: Band, b: np.ndarray, y: np.ndarray, block: int = 1 << 14) -> np.ndarray:
    """b - B y with every product and sum in extended precision (x87 long double, eps 1.1e-19), rounded
    once to float64; by blocks of rows, so the long-double temporaries stay in cache (one pass over B)."""
    n, ld = B.n, np.longdouble
    r = np.empty(n)
    offsets = [o for o in B.offsets.tolist() if B.diag(o).any()]  # an all-zero diagonal subtracts nothing
    for i0 in range(0, n, block):  # blocks of rows, not rows: n / block iterations
        i1 = min(n, i0 + block)
        acc = np.asarray(b[i0:i1], ld)
        for o in offsets:
            lo, hi = max(i0, -o), min(i1, n - o)  # rows whose column i + o exists
            if hi > lo:
                k0 = max(0, -o)  # element k of the diagonal is row k + k0
                acc[lo - i0 : hi - i0] -= B.diag(o)[lo - k0 : hi - k0].astype(ld) * y[lo + o : hi + o].astype(ld)
        r[i0:i1] = acc
    return r


def _require_finite(u: np.ndarray, what: str) -> None:
    if not np.all(np.isfinite(u)):
        raise SolveError(
            f"{what}: the solution overflows float64 (NaN/inf); the scene's numbers are too far from 1 "
            "in these units (e.g. a modulus near 1e-300): rescale them"
        )


def _scaled_bound(solve, solve_t, s, correction, magnitude, u, watch, iterations: int = 3) -> float:
    """:func:`forward_error_bound` for u = S y where (S A S) y = S b was solved (``solve``, ``solve_t``:
    with S A S and its transpose; ``magnitude``: of the scaled rows; ``correction`` in u's units): the
    bound on y's errors, each weighted by s, relative to max |u| over ``watch``."""
    return forward_error_bound(
        lambda z: s * solve(z), lambda z: solve_t(s * z), correction, magnitude, u, watch, iterations
    )


def solve_linear(
    K: sp.spmatrix | Band,
    b: np.ndarray,
    what: str = "system",
    condition: bool | None = None,
    banded_max: int = 64,
    refinement: bool | None = None,
    scaling: np.ndarray | None = None,
    watch=None,
    magnitude=None,
    refine_in_place: bool = False,
    entry_rounding: float | None = None,
    bound: bool = True,
    key: str | None = None,
) -> tuple[np.ndarray, dict]:
    """Solve K u = b. Banded LU when the bandwidth is at most ``banded_max``, else sparse LU.

    Raises SolveError naming ``what`` when K is singular (a mechanism, missing supports) or the
    solution is not finite. ``info`` holds solver, bandwidths, condition estimate, relative residual.
    The condition estimate (a few extra solves) and mixed-precision refinement (``refinement``; None =
    automatic) are made by default up to 20,000 unknowns only.

    ``K`` may be a :class:`~pdverify.numerics.band.Band` (assembled in LAPACK's layout): above ``SMALL`` unknowns,
    with the checks left at their defaults, it is factorised in place (:func:`solve_band`); otherwise it
    is converted and solved like a sparse matrix (same numbers as the sparse route).

    Every solve carries ``info["error_bound"]``, :func:`forward_error_bound` over the unknowns ``watch``
    (default all; its data term over K's entries grouped by the rounding they share, or ``magnitude(u)``: the
    size of each row's independently rounded terms), and a warning when it passes ``BOUND_LIMIT``.
    ``refine_in_place``: refine on the in-place path too (:func:`solve_band`; off by default there, so its
    solutions are the LU's). ``scaling``: the symmetric scaling s of
    diag(s) K diag(s) (default 1/sqrt|diag K|; a saddle-point system with zero diagonal needs its own).
    ``entry_rounding``: the relative uncertainty of the matrix's entries in units of eps (default
    ``ENTRY_ROUNDING``), for the bound's data term; entries that share one rounding count once
    (:mod:`pdverify.numerics.rounding`). ``watch`` a tuple of index arrays: the largest of the fields' bounds, each
    relative to its own field (unknowns in different units). ``bound = False`` (a sparse K): no
    residual, no bound (a Newton correction, whose error the next iteration's residual sees); the same solution.
    ``key``: a digest that determines K to the bit (the caller's: a reduced operator kept under it), used by the
    factorisation cache (:mod:`~pdverify.numerics.factorcache`) instead of hashing K's arrays again.
    """
    if isinstance(K, Band):
        if (
            K.n > SMALL
            and condition is not True
            and refinement is not True
            and K.lower <= banded_max
            and K.upper <= banded_max
        ):
            return solve_band(K, b, what, scaling, watch, magnitude, refine_in_place, entry_rounding)
        K = K.tocsr()
    K, b = _finite_system(K, b, what)
    n = K.shape[0]
    # symmetric diagonal equilibration S K S (S u') = S b: removes the powers of the element length
    # between mixed DOFs from the condition number
    s = diagonal_scaling(K.diagonal()) if scaling is None else np.asarray(scaling, float)
    lo, up = bandwidths(K)
    info: dict = {"system_unknowns": n, "bandwidth_lower": lo, "bandwidth_upper": up, "scaling": "symmetric diagonal"}
    u, solve, solve_t, info["solver"], Ks, info["factorisation"], info["factorisation_shared"] = _lu_solve(
        K, s * b, s, lo, up, banded_max, what, key
    )
    if not np.all(np.isfinite(u)):
        raise SolveError(f"{what}: the solution is not finite; the system is singular or too ill-conditioned")
    with np.errstate(all="ignore"):
        u = s * u
    _require_finite(u, what)
    # Refinement against the UNSCALED matrix (so the scaling's rounding is corrected too), on by default
    # up to 20,000 unknowns (three extra banded solves). It reduces the solve's own round-off; it cannot remove
    # the rest: the rounding of the assembled entries themselves (data error ~ cond * eps, cond ~ N^4
    # for the fourth-order operators); see tests/verification/test_hard_cases.py for the floor.
    if refinement is None:
        refinement = n <= SMALL
    # K in long double for the extended-precision residuals: kept beside the factorisation up to SMALL unknowns
    # (another load on the same operator takes it), made afresh above (its copy would crowd the kept factors out)
    keep = n <= SMALL and (refinement or bound)
    Kl = factorcache.derived(info["factorisation"], "long double", lambda: long_double(K)) if keep else None
    if refinement:
        u, info["refinement"] = refine(K, b, u, lambda r: s * solve(s * r), Kl=Kl)
    if bound:
        layout = (
            None
            if magnitude is not None
            else factorcache.derived(info["factorisation"], "rounding", lambda: csr_layout(K))
        )
        _residual_and_bound(info, K, b, u, s, solve, solve_t, magnitude, watch, _weight(entry_rounding), layout, Kl)
    if condition is None:
        condition = n <= SMALL
    if condition:  # of the scaled matrix, the one that was factorised
        info["cond"] = _condition(K, Ks, s, solve, solve_t)  # for the record: the warning is the error bound's
        # (cond * eps overstates the two-field forms' round-off by orders of magnitude: docs/trust.md)
    return u, info


def _finite_system(K: sp.spmatrix, b: np.ndarray, what: str) -> tuple[sp.csr_matrix, np.ndarray]:
    """(K in canonical CSR, b as floats); SolveError naming ``what`` when either holds NaN or inf."""
    K = canonical_csr(K)
    b = np.asarray(b, dtype=float)
    if not np.all(np.isfinite(K.data)) or not np.all(np.isfinite(b)):
        raise SolveError(f"{what}: the assembled matrix or load vector holds NaN/inf; check the scene's numbers")
    return K, b


def _lu_solve(
    K: sp.csr_matrix, bs: np.ndarray, s: np.ndarray, lo: int, up: int, banded_max: int, what: str, key: str | None
):
    """(y, solve, solve_t, solver, Ks, key, shared): the LU of diag(s) K diag(s), banded (LAPACK gbtrf,
    :func:`banded_lu`) when the bandwidth is at most ``banded_max`` and the band is narrow for the size, else sparse
    (SuperLU of the scaled CSR matrix Ks; None on the banded path), factorised once for the solve of ``bs``, the
    refinement and the condition estimate, or taken from :mod:`~pdverify.numerics.factorcache` when the same matrix
    was factorised before (``key``: its digest, of K's arrays or of the caller's ``key`` for K, with the scaling
    and the solver's parameters; ``shared``: taken). SolveError naming ``what`` when a pivot is zero."""
    arrays = (K.indptr, K.indices, K.data) if key is None else ()
    key = factorcache.digest(*arrays, s, params=(lo, up, banded_max, key))

    def make():
        """(the factorisation, the bytes of its factors)."""
        n = K.shape[0]
        if max(lo, up) <= banded_max and n > 2 * (lo + up + 1):
            solve, solve_t = banded_lu(K, lo, up, s)  # factorised once, reused by refinement and cond
            return ("banded LU (LAPACK gbtrf/gbtrs)", solve, solve_t, None), 8 * n * (2 * lo + up + 1)
        Ks = scale_symmetric(K, s)
        lu = spla.splu(Ks.tocsc())
        size = 12 * lu.nnz + Ks.data.nbytes + Ks.indices.nbytes  # values and indices (lu.L, lu.U: copies)
        return ("sparse LU (SuperLU)", lu.solve, (lambda z: lu.solve(z, trans="T")), Ks), size

    try:
        (solver, solve, solve_t, Ks), shared = factorcache.factorised(key, make)
        y = solve(bs)
    except (np.linalg.LinAlgError, RuntimeError) as exc:
        raise SolveError(
            f"{what}: the system matrix is singular ({exc}); the supports do not hold the beam "
            "(a mechanism) or the discretisation is degenerate"
        ) from None
    return y, solve, solve_t, solver, Ks, key, shared


def _residual_and_bound(
    info: dict, K, b, u, s, solve, solve_t, magnitude, watch, weight=1.0, layout=None, Kl=None
) -> None:
    """``info["residual"]``: max |K u - b| relative to the size of its terms (the unscaled system), and the
    round-off bound of :func:`forward_error_bound` (``info["error_bound"]``, a warning past ``BOUND_LIMIT``) with
    the correction of the residual computed in extended precision. ``layout``: K's :func:`csr_layout`, kept with
    its factorisation; ``Kl``: K in long double (:func:`long_double`)."""
    r = K @ u - b  # residual of the unscaled system, relative to the size of its terms
    scale = np.abs(K).dot(np.abs(u)).max() + np.abs(b).max()
    info["residual"] = float(np.abs(r).max() / scale) if scale > 0 else 0.0
    Kl = long_double(K)[0] if Kl is None else Kl
    rl = np.asarray(np.asarray(b, np.longdouble) - Kl @ np.asarray(u, np.longdouble), float)
    m = SharedRounding.from_csr(K, u, b, s, weight, layout=layout) if magnitude is None else s * magnitude(u)
    record_bound(info, _scaled_bound(solve, solve_t, s, s * solve(s * rl), m, u, watch))


def _condition(K, Ks, s, solve, solve_t) -> float:
    """1-norm condition estimate of the scaled matrix diag(s) K diag(s) (the one factorised): from the banded LU's
    factors above 100 unknowns (no sparse copy, no extra LU), else :func:`condition_estimate`; NaN if the estimate
    fails (an estimate only: a solve never fails for it)."""
    try:
        if hasattr(solve, "cond") and K.shape[0] > 100:  # banded: from the LU factors
            return solve.cond()
        return condition_estimate(Ks if Ks is not None else scale_symmetric(K, s), solve, solve_t)
    except Exception:  # an estimate only; never fail a solve for it
        return float("nan")
