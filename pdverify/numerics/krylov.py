"""Preconditioned Krylov solves of banded operators that are Toeplitz away from their ends (large horizons).

A PD beam operator with horizon m spacings has a band of half-width ~2m, so banded LU costs O(n m²). On a uniform
grid the operator is a block stencil plus an end correction (:mod:`pdverify.numerics.toeplitz`), and its interior
is diagonalised by a sine transform. This module solves A x = b by

* **mixed-precision iterative refinement** (Wilkinson; Carson & Higham, SIAM J. Sci. Comput. 40 (2018) A817):
  the residual r = b - A x of the assembled band in extended precision (:func:`~pdverify.numerics.linalg.
  extended_residual`), the correction A d = r solved approximately, x += d, until the correction falls below a
  tenth of the round-off bound's data part (the error that no solve of the float64 matrix can remove: the
  stopping tolerance *is* the round-off bound), or stops falling;
* **inner solves** by the conjugate-gradient method (a symmetric band) or restarted GMRES (Saad & Schultz 1986;
  right-preconditioned, otherwise), the product by FFT plus the sparse end correction (O(n log n) + the
  correction's entries), preconditioned by the sine-transform solve of the interior operator
  (:class:`~pdverify.numerics.toeplitz.SineSolve`): with odd (point-reflection) ghost ends that is the operator
  itself, so a pinned-pinned beam converges in one or two iterations, and other held ends differ from it by a
  correction of low rank (a few outlying eigenvalues: clamped ends add a few iterations, whatever m).

The result carries the same round-off bound as the banded path (:func:`~pdverify.numerics.linalg.
forward_error_bound`: the last refinement step, a conservative estimate of the solve's own error, plus
|| |A^-1| c eps (|A| |x| + |b|) ||, estimated by Hager's method with inner solves, or by one sample of random signs
where that is larger: Hager's transposed solves may be inexact at a large condition). Every step is linear in the
band's size or n log n: no factorisation, memory O(n) beside the band.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..core.errors import InputError
from .band import Band
from .linalg import ENTRY_ROUNDING, extended_residual, forward_error_bound, hager_norm1, record_bound
from .toeplitz import (
    SineSolve,
    ToeplitzProduct,
    block_stencil,
    end_correction,
    end_parities,
    free_range,
    held_unknowns,
    is_even,
    sub_band,
)

SOLVERS = ("auto", "banded", "krylov")
KRYLOV_MIN_HALF_BANDWIDTH = 256  # "auto" below this half-bandwidth: banded LU (docs/solvers.md: the crossover)
KRYLOV_MIN_UNKNOWNS = 2_000
INNER_RTOL = 1e-8  # relative residual reduction of each refinement step's inner solve
ESTIMATE_RTOL = 1e-4  # ... of the solves inside the round-off estimates (an estimate needs one digit)
SAMPLE_SEED = 2018  # the random signs of the data bound's sample (fixed: the same bound on every run)
INNER_MAXITER = 300
REFINE_MAX = 8
PERIODS = (1, 2, 3, 4)  # unknowns per point tried


@dataclass
class Plan:
    """What the Krylov path knows about a band: the free block lo .. hi - 1, ``period`` unknowns per point, the
    interior block stencil T (T[q + R] = T_q), the end parities, symmetry and the end correction C."""

    lo: int
    hi: int
    period: int
    stencil: np.ndarray
    parities: tuple[str, str]
    symmetric: bool
    correction: sp.csr_matrix

    @property
    def reach(self) -> int:
        return (len(self.stencil) - 1) // 2


def plan(B, forced: bool = False) -> tuple[Plan | None, str]:
    """(plan, reason): the Krylov plan of ``B`` or None and the one-line reason it does not apply. Deterministic:
    a function of the matrix alone. ``forced`` (``solver = "krylov"``) skips the size thresholds and accepts ends
    that move (even reflections: free or guided ends), which the preconditioner copes with less well."""
    if not isinstance(B, Band):
        return None, "the assembled operator is not a band (Band)"
    half = max(B.lower, B.upper)
    if not forced and half < KRYLOV_MIN_HALF_BANDWIDTH:
        return None, f"half-bandwidth {half} below {KRYLOV_MIN_HALF_BANDWIDTH}"
    held = held_unknowns(B)
    rng = free_range(held, B.n)
    if rng is None:
        return None, "the unknowns not held are not one contiguous run (e.g. a two-field form with held ghosts)"
    lo, hi = rng
    n = hi - lo
    if not forced and n < KRYLOV_MIN_UNKNOWNS:
        return None, f"{n} unknowns, below {KRYLOV_MIN_UNKNOWNS}"
    V = sub_band(B, lo, hi)
    found = _interior(V)
    if found is None:
        return None, "no block stencil repeats along the interior rows (a non-uniform grid or varying coefficients)"
    p, T = found
    R = (len(T) - 1) // 2
    if n // p < 4 * p * (R + 1) or n % p:
        return None, "too few points for the stencil's reach"
    scale = np.abs(T).max()
    if not is_even(T, 1e-10):
        return None, "the interior stencil is not reflection-invariant (T_-q != T_q)"
    C = end_correction(V, T, p, 64 * np.finfo(float).eps * scale)
    edge = 4 * p * (R + 1)
    rows = np.flatnonzero(np.diff(C.indptr))
    if len(rows) and np.any((rows >= edge) & (rows < n - edge)):
        return None, "the operator differs from its interior stencil away from the ends (a non-uniform grid)"
    parities = end_parities(V, T, C, min(p * (R + 1), n // 2))
    if parities == ("even", "even"):
        return None, "neither end is held (a rigid motion of the interior operator)"
    if not forced and parities != ("odd", "odd"):
        return None, f"an end that moves ({parities[0]}-{parities[1]} reflections): the preconditioner is slow there"
    symmetric = _symmetric(V, 64 * np.finfo(float).eps * scale)
    if parities != ("odd", "odd") and not symmetric:
        return None, (
            "an end that moves and a non-symmetric operator: the transposed solves of the round-off bound do not "
            "converge reliably there"
        )
    return Plan(lo, hi, p, T, parities, symmetric, C), "band Toeplitz away from its ends"


def _interior(V: Band):
    """(p, T): the smallest period p whose block stencil is the same at rows a third, a half and two thirds
    along (to 1e-12 of its largest entry), else None."""
    n = V.n
    for p in PERIODS:
        if n % p or n < 12 * p:
            continue
        rows = [p * (n // p * k // 6) for k in (2, 3, 4)]
        Ts = [block_stencil(V, r, p) for r in rows]
        if any(t.shape != Ts[0].shape for t in Ts):
            continue
        tol = 1e-12 * np.abs(Ts[0]).max()
        if all(np.abs(t - Ts[1]).max() <= tol for t in Ts):
            return p, Ts[1]
    return None


def _symmetric(V: Band, tol: float) -> bool:
    """A = A^T to ``tol`` (entry by entry, diagonal o against diagonal -o)."""
    for o in range(1, min(V.lower, V.upper) + 1):
        if np.abs(V.diag(o) - V.diag(-o)).max(initial=0.0) > tol:
            return False
    return V.lower == V.upper or not (
        any(np.any(V.diag(o)) for o in range(min(V.lower, V.upper) + 1, V.upper + 1))
        or any(np.any(V.diag(-o)) for o in range(min(V.lower, V.upper) + 1, V.lower + 1))
    )


# -- the iterations --------------------------------------------------------------------------------------


def pcg(apply, b, precond, rtol: float, maxiter: int = INNER_MAXITER):
    """Preconditioned conjugate gradients for a symmetric positive definite operator (Hestenes & Stiefel 1952):
    (x, iterations, converged) with ||b - A x||_2 <= rtol ||b||_2; converged False also when a curvature
    p^T A p <= 0 shows the operator or the preconditioner is not positive definite."""
    x = np.zeros_like(b)
    r = b.copy()
    target = rtol * np.linalg.norm(b)
    if target == 0.0:
        return x, 0, True
    z = precond(r)
    d = z.copy()
    rz = r @ z
    for k in range(1, maxiter + 1):
        Ad = apply(d)
        curv = d @ Ad
        if not curv > 0 or not rz > 0:
            return x, k, False
        a = rz / curv
        x += a * d
        r -= a * Ad
        if np.linalg.norm(r) <= target:
            return x, k, True
        z = precond(r)
        rz_new = r @ z
        d = z + (rz_new / rz) * d
        rz = rz_new
    return x, maxiter, False


def gmres(apply, b, precond, rtol: float, maxiter: int = INNER_MAXITER, restart: int = 60):
    """Right-preconditioned restarted GMRES (Saad & Schultz 1986; modified Gram–Schmidt, Givens rotations):
    (x, iterations, converged) with ||b - A x||_2 <= rtol ||b||_2."""
    x = np.zeros_like(b)
    target = rtol * np.linalg.norm(b)
    if target == 0.0:
        return x, 0, True
    its = 0
    while its < maxiter:
        r = b - apply(x) if its else b.copy()
        beta = np.linalg.norm(r)
        if beta <= target:
            return x, its, True
        m = min(restart, maxiter - its)
        Q = np.zeros((m + 1, len(b)))
        H = np.zeros((m + 1, m))
        Z = np.zeros((m, len(b)))
        cs, sn, g = np.zeros(m), np.zeros(m), np.zeros(m + 1)
        Q[0], g[0] = r / beta, beta
        k = 0
        for k in range(m):
            Z[k] = precond(Q[k])
            w = apply(Z[k])
            for _ in range(2):  # classical Gram-Schmidt, twice (Giraud et al., Numer. Math. 101 (2005) 87)
                h = Q[: k + 1] @ w
                w -= Q[: k + 1].T @ h
                H[: k + 1, k] += h
            H[k + 1, k] = np.linalg.norm(w)
            if H[k + 1, k] > 0:
                Q[k + 1] = w / H[k + 1, k]
            for i in range(k):
                H[i, k], H[i + 1, k] = cs[i] * H[i, k] + sn[i] * H[i + 1, k], -sn[i] * H[i, k] + cs[i] * H[i + 1, k]
            rho = np.hypot(H[k, k], H[k + 1, k])
            cs[k], sn[k] = (H[k, k] / rho, H[k + 1, k] / rho) if rho > 0 else (1.0, 0.0)
            H[k, k], H[k + 1, k] = rho, 0.0
            g[k + 1], g[k] = -sn[k] * g[k], cs[k] * g[k]
            its += 1
            if abs(g[k + 1]) <= target or H[k + 1, k] == 0 and rho == 0:
                break
        y = np.linalg.lstsq(np.triu(H[: k + 1, : k + 1]), g[: k + 1], rcond=None)[0]
        x = x + Z[: k + 1].T @ y
        if abs(g[k + 1]) <= target:
            return x, its, True
    return x, its, bool(np.linalg.norm(b - apply(x)) <= target)


class Inner:
    """Approximate solves with the free block of a :class:`Plan`'s band (or its transpose): FFT product plus end
    correction, sine-transform preconditioner, CG or GMRES. ``exact`` products use the band itself."""

    def __init__(self, V: Band, pl: Plan, transpose: bool = False, exact: bool = False):
        T = pl.stencil.transpose(0, 2, 1) if transpose else pl.stencil  # T_q^T is the stencil of A^T (T even)
        npos = (pl.hi - pl.lo) // pl.period
        self.C = pl.correction.T.tocsr() if transpose else pl.correction
        self.toeplitz = ToeplitzProduct(T, npos)
        self.precond = SineSolve(T, npos, pl.parities)
        self.cg = pl.symmetric and self.precond.definite
        self.V, self.transpose, self.exact = V, transpose, exact
        # GMRES minimises the residual of the rows equilibrated by their sums |T| 1 + |C| 1 (ghost rows of a few
        # huge entries would otherwise own the residual's norm); constant along the interior, so the sine
        # preconditioner still fits
        sums = ToeplitzProduct(np.abs(T), npos)(np.ones(V.n)) + abs(self.C) @ np.ones(V.n)
        self.row_scale = 1.0 / np.where(sums > 0, sums, 1.0)
        self.iterations: list[int] = []
        self.converged = True

    def apply(self, x):
        if self.exact:
            return band_product(self.V, x, transpose=self.transpose)
        return self.toeplitz(x) + self.C @ x

    def __call__(self, r, rtol: float = INNER_RTOL):
        r = np.asarray(r, float)
        if self.cg:
            x, its, ok = pcg(self.apply, r, self.precond, rtol)
            if not ok:  # not positive definite after all: GMRES from here on
                self.cg = False
        if not self.cg:
            D = self.row_scale
            x, its, ok = gmres(lambda z: D * self.apply(z), D * r, lambda y: self.precond(y / D), rtol)
        self.iterations.append(its)
        self.converged &= ok
        return x

    @property
    def method(self) -> str:
        return "conjugate gradients" if self.cg else "GMRES(60)"


def band_product(V: Band, x: np.ndarray, transpose: bool = False, absolute: bool = False) -> np.ndarray:
    """A x, A^T x or |A| |x| of a band, diagonal by diagonal (scipy's DIA product in C)."""
    data = np.abs(V.data) if absolute else V.data
    D = sp.dia_matrix((data, V.offsets), shape=V.shape)
    return (D.T if transpose else D) @ (np.abs(x) if absolute else np.asarray(x, float))


def solve_krylov(
    B: Band, b: np.ndarray, pl: Plan, what: str = "system", watch=None, magnitude=None, condition: bool = False
) -> tuple[np.ndarray, dict]:
    """Solve B u = b by refinement with inner Krylov solves (module docstring); B is not modified. ``watch``,
    ``magnitude``: as for :func:`~pdverify.numerics.linalg.solve_linear`'s round-off bound (``info["error_bound"]``,
    a warning past ``BOUND_LIMIT`` or when an inner iteration does not converge)."""
    b = np.asarray(b, float)
    if not (np.all(np.isfinite(b)) and np.all(np.isfinite(B.data))):
        raise InputError(f"{what}: the assembled matrix or load vector holds NaN/inf; check the scene's numbers")
    lo, hi = pl.lo, pl.hi
    V = sub_band(B, lo, hi)
    bf = b[lo:hi]
    inner = Inner(V, pl)
    x = inner(bf)
    steps, floor, estimate, r0 = [], None, None, None
    for _ in range(REFINE_MAX):
        r = extended_residual(V, bf, x)
        r0 = r if r0 is None else r0
        d = inner(r)
        steps.append(float(np.abs(d).max()) / max(float(np.abs(x).max()), 1e-300))
        x = x + d  # the last step applied, and kept as a conservative estimate of the error it leaves
        if floor is None:  # the data part of the round-off bound: the refinement's tolerance
            solves = len(inner.iterations)
            floor, estimate, mag, sampled = _data_bound(V, bf, x, pl, inner, watch, magnitude, B.n)
            estimates = inner.iterations[solves:] + (estimate.iterations if estimate is not inner else [])
            del inner.iterations[solves:]
        if steps[-1] <= 0.1 * floor or steps[-1] <= 4 * np.finfo(float).eps:
            break
        if len(steps) > 1 and steps[-1] > 0.5 * steps[-2]:  # no longer contracting
            if inner.exact:
                break
            inner.exact = True  # the FFT product's rounding holds it back: the band's own product from here
    u = b.copy()  # held unknowns: unit rows, u = b there
    u[lo:hi] = x
    w = _watched(watch, pl)
    top = float(np.abs(x[w]).max()) if len(w) else 0.0
    solve_term = float(np.abs(d[w]).max()) / top if top > 0 else 0.0
    total = floor + solve_term
    bound = float(f"{total:.3g}") if np.isfinite(total) else float("inf")
    info = {
        "system_unknowns": B.n,
        "bandwidth_lower": B.lower,
        "bandwidth_upper": B.upper,
        "solver": f"Krylov ({inner.method}, sine-transform preconditioner, FFT products; refinement in extended "
        "precision)" + (" (band products)" if inner.exact else ""),
        "preconditioner": f"sine transform of the interior stencil: {pl.period} unknown(s) per point, reach "
        f"{pl.reach} points, {pl.parities[0]}-{pl.parities[1]} end reflections, {pl.correction.nnz} end entries",
        "krylov_iterations": inner.iterations[:],
        "estimate_iterations": estimates,
        "refinement": steps,
        "krylov_converged": inner.converged,
        "residual": float(np.abs(r0).max() / mag.max()) if mag.max() > 0 else 0.0,  # of the first iterate
        "error_bound": bound,
    }
    if condition:
        info["cond"] = _cond(V, inner, estimate)
    if sampled:
        info.setdefault("warnings", []).append(
            f"{what}: the round-off bound is a sample of random signs ({floor:.2g}), above Hager's estimate of the "
            "same norm: the transposed inner solves that estimate needs are inexact at this condition, so the "
            "worst case may be larger still"
            + (", and cond (the same estimate's) may be low too" if condition else "")
            + "; solver = banded gives LAPACK's estimate"
        )
    if not inner.converged:
        info.setdefault("warnings", []).append(
            f"{what}: an inner Krylov iteration stopped at {INNER_MAXITER} steps unconverged; the round-off bound "
            "says how far the result may be from the solution; solver = banded solves it directly"
        )
    record_bound(info, bound)
    return u, info


def _magnitude(pl: Plan, bf, x, magnitude, n: int):
    """The size of each row's independently rounded terms: |T| |x| + |C| |x| + |b| (>= |A| |x| + |b|, the stencil's
    part by FFT), or the model's ``magnitude(u)``."""
    if magnitude is None:
        ax = np.abs(x)
        return ToeplitzProduct(np.abs(pl.stencil), len(x) // pl.period)(ax) + abs(pl.correction) @ ax + np.abs(bf)
    u = np.zeros(n)
    u[pl.lo : pl.hi] = x
    return np.asarray(magnitude(u), float)[pl.lo : pl.hi]


def _data_bound(V: Band, bf, x, pl: Plan, inner: Inner, watch, magnitude, n: int):
    """(|| |A^-1| c eps m ||_inf / max |x| over ``watch``, the transposed inner solver, m, sampled): the part of the
    round-off bound that refinement cannot reduce (:func:`~pdverify.numerics.linalg.forward_error_bound` with no
    solve error), by Hager's method with loose inner solves, or the larger :func:`_sample` of the same norm
    (``sampled``): Hager's method needs transposed solves, which the inner iteration may leave inexact in the rows of
    a few huge entries (ghost rows) however long it runs, and then follows the wrong column."""
    estimate = inner if pl.symmetric else Inner(V, pl, transpose=True)
    mag = _magnitude(pl, bf, x, magnitude, n)
    w = _watched(watch, pl)
    value = forward_error_bound(
        lambda z: inner(z, ESTIMATE_RTOL), lambda z: estimate(z, ESTIMATE_RTOL), np.zeros_like(x), mag, x, w, 2
    )
    sample = _sample(V, inner, mag, x, w)
    return max(value, sample), estimate, mag, sample > value


def _sample(V: Band, inner: Inner, mag: np.ndarray, x: np.ndarray, w: np.ndarray) -> float:
    """|| A^-1 (c eps m s) ||_inf / max |x| over ``w`` for one vector s of random signs (:data:`SAMPLE_SEED`): a lower
    bound of Hager's norm || |A^-1| c eps m ||_inf (|s_j| <= 1), from forward solves only, refined against the
    band's own product to one digit. Random signs, not one sign: rounding every entry by the same factor only scales
    the system (Kenney & Laub, SIAM J. Sci. Comput. 15 (1994) 36: small-sample statistical estimation)."""
    signs = np.where(np.random.default_rng(SAMPLE_SEED).random(len(x)) < 0.5, -1.0, 1.0)
    z = ENTRY_ROUNDING * np.finfo(float).eps * mag * signs
    d, steps = inner(z, ESTIMATE_RTOL), []
    for _ in range(REFINE_MAX):
        step = inner(z - band_product(V, d), ESTIMATE_RTOL)
        d = d + step
        steps.append(float(np.abs(step).max()))
        if steps[-1] <= 0.1 * np.abs(d).max() or (len(steps) > 1 and steps[-1] > 0.5 * steps[-2]):
            break
    top = float(np.abs(x[w]).max()) if len(w) else 0.0
    return float(np.abs(d[w]).max()) / top if top > 0 else 0.0


def _watched(watch, pl: Plan) -> np.ndarray:
    """The watched unknowns in the free block's numbering (all of them by default)."""
    if watch is None:
        return np.arange(pl.hi - pl.lo)
    w = np.asarray(watch, np.int64)
    return w[(w >= pl.lo) & (w < pl.hi)] - pl.lo


def _cond(V: Band, inner: Inner, estimate: Inner) -> float:
    """1-norm condition estimate ||A||_1 est ||A^-1||_1 (Hager's method with loose inner solves), 6 digits."""
    norm = float(band_product(V, np.ones(V.n), transpose=True, absolute=True).max())
    inv = hager_norm1(lambda z: inner(z, ESTIMATE_RTOL), lambda z: estimate(z, ESTIMATE_RTOL), V.n)
    return float(f"{norm * inv:.6g}") if np.isfinite(inv) else float("inf")
