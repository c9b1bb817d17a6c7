"""Peridynamic differential-operator (PDDO) functions in 1D (Curved PDDO beam 2024, §3.2; written out in
docs/design/formulas.md §2).

At particle k with family H_k (particles j, xi = s_j - s_k, volume V_j), the PD functions

    g^r(xi) = w(|xi|) Σ_{q=0..P} a^r_q xi^q,   Σ_j xi_j^p g^r(xi_j) V_j = r! delta_pr  (p, r = 0..P)

give f^(r)(s_k) ≈ Σ_j f(s_j) g^r(xi_j) V_j. With A_pq = Σ_j w xi^{p+q} V_j the coefficients solve
A a^r = r! e_r. Weight w = exp(-(2 xi/delta)²) with delta = the largest |xi| of the family. xi is
scaled by delta before A is formed (A is a Hankel moment matrix and loses digits fast), and all
families are solved at once, as the equivalent weighted least-squares problem in a Legendre basis (see
:func:`pddo_weights`): Householder QR of every family's (size x P+1) matrix, column by column with each
step vectorised over the families (:func:`householder_solve`). Derivatives of polynomials of degree <= P
are reproduced exactly (tests/papers/curved/test_pddo.py).

Pure functions, arrays in, arrays out; no Python loop over particles.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp


def cell_volumes(s: np.ndarray) -> np.ndarray:
    """Tributary length of each particle (half cells at the two ends)."""
    s = np.asarray(s, float)
    edges = np.concatenate([[s[0]], (s[1:] + s[:-1]) / 2, [s[-1]]])
    return np.diff(edges)


def families(n: int, size: int) -> np.ndarray:
    """(n, size) particle indices: a window of ``size`` consecutive particles centred on each particle
    (odd ``size``; an even one reaches one further to the right), shifted inward near the ends so every
    family keeps ``size`` members (the paper: horizons may differ per particle)."""
    if size > n:
        raise ValueError(f"family of {size} particles does not fit in {n}")
    start = np.clip(np.arange(n) - (size - 1) // 2, 0, n - size)
    return start[:, None] + np.arange(size)[None, :]


def legendre_columns(z: np.ndarray, degree: int) -> np.ndarray:
    """(degree + 1, ...) Legendre polynomials L_q(z), q = 0..degree: ``np.polynomial.legendre.legvander``
    with the degree first (the same three-term recurrence, hence the same values)."""
    v = np.empty((degree + 1,) + z.shape)
    v[0] = 1.0
    if degree > 0:
        v[1] = z
        for q in range(2, degree + 1):  # (P-1)-loop over the degree
            v[q] = (v[q - 1] * z * (2 * q - 1) - v[q - 2] * (q - 1)) / q
    return v


def householder_solve(A: np.ndarray, d: np.ndarray) -> np.ndarray:
    """For every matrix A[:, :, k] (m x p, m >= p, full column rank; the batch index last): Householder QR
    A = Q R as LAPACK's ``dgeqr2`` (reflectors H = I - tau v v^T, v_0 = 1, beta = -sign(alpha) ||x||), then
    Q R^(-T) d for the p x r right-hand sides d (the same for every k). Returns (m, r, n).

    Written as a (p)-loop over the columns with every operation vectorised over the batch: a batched
    ``np.linalg.qr`` + ``solve`` spends its time per matrix (LAPACK calls on 7 x 5 matrices, copies in and
    out); the arithmetic is the same up to the summation order (round-off). ``A`` is overwritten by R (upper
    part) and the reflectors."""
    m, p, n = A.shape
    taus, vs = [], []
    for k in range(p):  # over the p <= 11 columns, not over particles
        x = A[k:, k]
        alpha = x[0].copy()
        xnorm = np.sqrt(np.einsum("in,in->n", x[1:], x[1:])) if m - k > 1 else np.zeros(n)
        zero = xnorm == 0.0  # H = I (LAPACK: tau = 0)
        beta = np.where(zero, alpha, -np.copysign(np.hypot(alpha, xnorm), alpha))
        den = np.where(zero, 1.0, alpha - beta)
        tau = np.where(zero, 0.0, (beta - alpha) / np.where(zero, 1.0, beta))
        v = x[1:] / den
        if k + 1 < p:  # apply H to the remaining columns
            Y = A[k:, k + 1 :]
            w = Y[0] + np.einsum("in,ijn->jn", v, Y[1:])
            tw = tau * w
            Y[0] -= tw
            Y[1:] -= v[:, None, :] * tw[None]
        A[k, k] = beta
        taus.append(tau), vs.append(v)
    # R^T y = d by forward substitution (R upper triangular: A[i, j], i <= j)
    r = d.shape[1]
    y = np.zeros((m, r, n))
    for i in range(p):
        acc = np.broadcast_to(d[i][:, None], (r, n)).copy()
        for j in range(i):
            acc -= A[j, i][None, :] * y[j]
        y[i] = acc / A[i, i][None, :]
    # Q [y; 0] = H_0 H_1 ... H_(p-1) [y; 0]
    for k in range(p - 1, -1, -1):
        v, tau = vs[k], taus[k]
        w = y[k] + np.einsum("in,ijn->jn", v, y[k + 1 :])
        tw = tau * w
        y[k] -= tw
        y[k + 1 :] -= v[:, None, :] * tw[None]
    return y


def pddo_weights(
    s: np.ndarray,
    fam: np.ndarray,
    degree: int,
    orders=(0, 1, 2),
    volumes: np.ndarray | None = None,
    centers: np.ndarray | None = None,
) -> dict[int, np.ndarray]:
    """PDDO coefficients: {r: (n, size) array c} with f^(r)(x_k) ≈ Σ_j c[k, j] f(s[fam[k, j]]), x_k = s_k
    (or ``centers[k]``: any point, e.g. output positions between particles).

    ``degree`` P (Taylor order), ``fam`` from :func:`families` (>= P + 1 members each)."""
    s = np.asarray(s, float)
    P = int(degree)
    if fam.shape[1] < P + 1:
        raise ValueError(f"degree {P} needs families of at least {P + 1} particles (got {fam.shape[1]})")
    for r in orders:
        if r > P:
            raise ValueError(f"derivative order {r} exceeds the degree {P}")
    V = cell_volumes(s) if volumes is None else np.asarray(volumes, float)
    x = s if centers is None else np.asarray(centers, float)
    famT = np.ascontiguousarray(fam.T)  # (size, n): the batch index last, every operation over contiguous rows
    xi = s[famT] - x[None, :]
    delta = np.abs(xi).max(axis=0)  # (n,)
    z = xi / delta[None, :]
    wV = np.exp(-((2.0 * z) ** 2)) * V[famT] / delta[None, :]  # weight x volume, volumes in units of delta
    # Solved as a weighted least-squares problem instead of the normal equations A a = r! e_r (A = B^T W B,
    # cond(A) = 4e8 at P = 6, which left a 4e-8 consistency floor): with the Legendre basis L_q(z) and the
    # QR factors of W^(1/2) L, g^r = W^(1/2) Q y with R^T y = T^(-T) r! e_r (T: monomials in Legendre
    # coefficients). Same functions g^r in exact arithmetic; the round-off drops to ~sqrt(cond A) eps.
    sw = np.sqrt(wV)
    A = np.ascontiguousarray(np.moveaxis(legendre_columns(z, P), 0, 1)) * sw[:, None, :]  # (size, P+1, n)
    T = np.zeros((P + 1, P + 1))
    for p in range(P + 1):  # a (P+1)-loop over the degree, not over particles
        col = np.polynomial.legendre.poly2leg(np.eye(P + 1)[p])
        T[: len(col), p] = col
    c = np.diag([float(math.factorial(r)) for r in range(P + 1)])
    d = np.linalg.solve(T.T, c)  # Legendre moments of each g^r (columns r)
    orders = tuple(orders)
    g = householder_solve(A, d[:, list(orders)])  # (size, len(orders), n): g^r(xi_j) V_j / sqrt(w V)
    out = {}
    for i, r in enumerate(orders):
        out[r] = np.ascontiguousarray((g[:, i, :] * sw / delta[None, :] ** r).T)
    return out


def nearest_families(s: np.ndarray, x: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """The (len(x), size) indices of the ``size`` consecutive particles of s centred on the particle at or right of
    each point x, and of those centred on the particle at or left of it: a point between two particles has no
    family centred on it (size odd), and these two are each other's mirror images (the same family for a point on
    a particle, or where a family is shifted inside at an end of s)."""
    right = np.searchsorted(s, x)
    left = np.searchsorted(s, x, side="right") - 1
    fam = [np.clip(c - size // 2, 0, len(s) - size)[:, None] + np.arange(size)[None, :] for c in (right, left)]
    return fam[0], fam[1]


def operator(fam: np.ndarray, coef: np.ndarray, n_cols: int | None = None) -> sp.csr_matrix:
    """Sparse matrix of the stencils: row k holds coef[k] at columns fam[k]."""
    n, size = fam.shape
    n_cols = n if n_cols is None else n_cols
    rows = np.repeat(np.arange(n), size)
    return sp.csr_matrix((np.ravel(coef), (rows, np.ravel(fam))), shape=(n, n_cols))


def derivative_weights(
    s: np.ndarray, degree: int, size: int, orders=(1, 2)
) -> tuple[np.ndarray, dict[int, np.ndarray]]:
    """(fam, {r: c}): the families of the particles s (one segment) and their PDDO derivative weights
    (:func:`pddo_weights`). Weights below 1e-10 of their row's largest are round-off of exact zeros (g^1(0)
    of a symmetric family) and are set to 0."""
    fam = families(len(s), size)
    w = pddo_weights(s, fam, degree, orders)
    out = {}
    for r in orders:
        c = w[r]
        out[r] = np.where(np.abs(c) < 1e-10 * np.abs(c).max(axis=1, keepdims=True), 0.0, c)
    return fam, out


def derivative_matrices(s: np.ndarray, degree: int, size: int, orders=(1, 2)) -> dict[int, sp.csr_matrix]:
    """{r: D_r} sparse PDDO derivative matrices on the particles s (one segment), from
    :func:`derivative_weights`."""
    fam, w = derivative_weights(s, degree, size, orders)
    return {r: operator(fam, c) for r, c in w.items()}
