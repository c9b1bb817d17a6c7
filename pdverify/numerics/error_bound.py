"""The round-off bound of a computed solution: the solve's own error and the data error of the float64 system
(Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., ch. 7 and 15; LAPACK xGERFSX and xGBRFS),
with the norm estimators it needs (Hager 1984, Higham 1988) and the warning a result carries past
``BOUND_LIMIT``."""

from __future__ import annotations

import numpy as np

from ..core.text import apart


def hager_inverse_norm(solve, solve_t, n: int, iterations: int = 5) -> float:
    """Lower-bound estimate of ||A^-1||_1 from solves with A and A^T (Hager 1984, Higham 1988: LAPACK's
    dlacn2 with t = 1): usually exact or within a factor of 3, deterministic (no random start)."""
    return hager_norm1(solve, solve_t, n, iterations)


def hager_norm1(apply, apply_t, n: int, iterations: int = 5) -> float:
    """Lower-bound estimate of ||B||_1 of a linear operator B on R^n given only the products B x
    (``apply``) and B^T y (``apply_t``): Hager's method with Higham's extra test vector (LAPACK dlacn2)."""
    x = np.full(n, 1.0 / n)
    est, j_old = 0.0, -1
    for k in range(iterations):
        y = apply(x)
        est_new = float(np.abs(y).sum())
        if k > 0 and est_new <= est:
            break
        est = est_new
        if k == iterations - 1:  # no next vector to choose: spare the solve
            break
        z = apply_t(np.where(y >= 0, 1.0, -1.0))
        j = int(np.argmax(np.abs(z)))
        if k > 0 and (j == j_old or abs(z[j]) <= z @ x):
            break
        x = np.zeros(n)
        x[j] = 1.0
        j_old = j
    alt = (-1.0) ** np.arange(n) * (1.0 + np.arange(n) / max(n - 1, 1))  # Higham's safeguard vector
    est = max(est, 2.0 * float(np.abs(apply(alt)).sum()) / (3.0 * n))
    return est


BOUND_LIMIT = 1e-6  # relative round-off bound above which a result carries a warning (docs/trust.md)
ENTRY_ROUNDING = 4  # relative uncertainty of each independently rounded term of a row, in units of eps: the few
# roundings of an assembled entry (a product of the material, a power of the spacing and a stencil weight); a
# model whose entries carry more (weights from a local solve on rounded positions) says so: ``entry_rounding``


def forward_error_bound(solve, solve_t, correction, magnitude, x, watch=None, iterations: int = 3) -> float:
    """Round-off bound on max_i |x_i - x*_i| / max_i |x_i| over the unknowns ``watch`` (default all) of a
    computed solution x of A x* = b; ``watch`` a tuple of index arrays (fields in different units: a deflection,
    a rotation, a higher-order kinematic variable): the largest of the fields' bounds, each relative to its own
    field's largest value. In two parts:

    * the solve's own error, estimated by ``correction`` = A^-1 r, the refinement step of the residual r
      computed in extended precision (Demmel et al., ACM TOMS 32 (2006), LAPACK xGERFSX);
    * the data error of the float64 system, which refinement cannot reduce: with ``magnitude`` a map G whose
      columns are the residual's first-order changes under one relative rounding each (``matvec``,
      ``rmatvec``, ``shape``: :class:`pdverify.numerics.rounding.SharedRounding`, the entries grouped by the
      rounding they share), || A^-1 G ||_inf c eps; with ``magnitude`` an array m (each row's terms rounded
      independently: |A| |x| + |b| when nothing better is known), || |A^-1| m ||_inf c eps, Skeel's
      componentwise bound (Higham, *Accuracy and Stability*, eq. 7.31; LAPACK xGBRFS's FERR). c =
      ``ENTRY_ROUNDING``.

    The norm is estimated by Hager's method on the transpose: a few solves with A and A^T (``solve``,
    ``solve_t``) and products with G, linear in n, deterministic; like LAPACK's, an estimate of a bound,
    usually within a factor of 3 of it."""
    if isinstance(watch, tuple):
        return max(forward_error_bound(solve, solve_t, correction, magnitude, x, f, iterations) for f in watch)
    n = len(x)
    idx = np.arange(n) if watch is None else np.asarray(watch, np.int64)
    top = float(np.abs(x[idx]).max()) if len(idx) else 0.0
    ce = ENTRY_ROUNDING * np.finfo(float).eps
    step = float(np.abs(np.asarray(correction)[idx]).max()) if len(idx) else 0.0
    if hasattr(magnitude, "rmatvec"):
        G = magnitude
        gmul, gtmul, k, any_data = (lambda z: ce * G.matvec(z)), (lambda y: ce * G.rmatvec(y)), G.shape[1], True
    else:
        v = ce * np.asarray(magnitude, float)
        gmul, gtmul, k, any_data = (lambda z: v * z), (lambda y: v * y), n, bool(v.any())
        if not np.all(np.isfinite(v)):
            return float("inf")
    if not np.isfinite(step):
        return float("inf")

    def bt(y):  # B^T y for B = A^-1 G restricted to the rows idx
        z = np.zeros(n)
        z[idx] = y
        return gtmul(solve_t(z))

    est = hager_norm1(bt, lambda y: solve(gmul(y))[idx], len(idx), iterations) if any_data and k else 0.0
    if top == 0.0:  # nothing moves (every load on the supports): exact when no rounding reaches the unknowns
        return 0.0 if est + step == 0.0 else float("inf")
    total = (est + step) / top  # ||B^T||_1 = ||B||_inf
    return float(f"{total:.3g}") if np.isfinite(total) else float("inf")


def _weight(entry_rounding: float | None) -> float:
    """The matrix entries' rounding relative to ``ENTRY_ROUNDING`` (the load vector's)."""
    return 1.0 if entry_rounding is None else max(1.0, float(entry_rounding) / ENTRY_ROUNDING)


NO_DIGIT = 0.1  # a round-off bound above which the result may have no correct digit (the bound is an estimate)


def bound_warning(bound: float) -> str:
    """The one-line warning a result carries when its round-off bound passes ``BOUND_LIMIT`` (past :data:`NO_DIGIT`:
    the estimate is within a factor 3 or so, so the result may have no correct digit at all)."""
    if not bound <= NO_DIGIT:
        return (
            f"round-off bound {apart(bound, BOUND_LIMIT)} (relative error, an estimate within a factor of about 3): "
            "the result may have no correct digit (a near-mechanism, e.g. a spring far softer than the beam, or far "
            "too many points); stiffen the spring, use fewer points or a better-conditioned form"
        )
    return (
        f"round-off bound {apart(bound, BOUND_LIMIT)} (relative error) exceeds {BOUND_LIMIT:g}: at this size the "
        "linear solve may be wrong to that degree; use fewer points or a better-conditioned form"
    )


def record_bound(info: dict, bound: float) -> None:
    """``info["error_bound"] = bound``, and the warning of :func:`bound_warning` when it passes ``BOUND_LIMIT``."""
    info["error_bound"] = bound
    if not bound <= BOUND_LIMIT:
        info.setdefault("warnings", []).append(bound_warning(bound))
