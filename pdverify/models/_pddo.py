"""Peridynamic differential-operator (PDDO) functions in 1D (seed 004 §3.2; design note §2).

At particle k with family H_k (particles j, xi = s_j - s_k, volume V_j), the PD functions

    g^r(xi) = w(|xi|) Σ_{q=0..P} a^r_q xi^q,   Σ_j xi_j^p g^r(xi_j) V_j = r! delta_pr  (p, r = 0..P)

give f^(r)(s_k) ≈ Σ_j f(s_j) g^r(xi_j) V_j. With A_pq = Σ_j w xi^{p+q} V_j the coefficients solve
A a^r = r! e_r. Weight w = exp(-(2 xi/delta)²) with delta = the largest |xi| of the family. xi is
scaled by delta before A is formed (A is a Hankel moment matrix and loses digits fast), and all
families are solved at once (batched ``np.linalg.qr`` and ``np.linalg.solve`` on (n, P+1, P+1) stacks), as the
equivalent weighted least-squares problem in a Legendre basis (see :func:`pddo_weights`). Derivatives of
polynomials of degree <= P are reproduced exactly (tests/test_pddo.py).

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
    family keeps ``size`` members (the seed: horizons may differ per particle)."""
    if size > n:
        raise ValueError(f"family of {size} particles does not fit in {n}")
    start = np.clip(np.arange(n) - (size - 1) // 2, 0, n - size)
    return start[:, None] + np.arange(size)[None, :]


def pddo_weights(s: np.ndarray, fam: np.ndarray, degree: int, orders=(0, 1, 2),
                 volumes: np.ndarray | None = None, centers: np.ndarray | None = None) -> dict[int, np.ndarray]:
    """PDDO coefficients: {r: (n, size) array c} with f^(r)(x_k) ≈ Σ_j c[k, j] f(s[fam[k, j]]), x_k = s_k
    (or ``centers[k]``: any point, e.g. output positions between particles).

    ``degree`` P (Taylor order), ``fam`` from :func:`families` (>= P + 1 members each)."""
    s = np.asarray(s, float)
    P = int(degree)
    if fam.shape[1] < P + 1:
        raise ValueError(f"degree {P} needs families of at least {P + 1} particles (got {fam.shape[1]})")
    V = cell_volumes(s) if volumes is None else np.asarray(volumes, float)
    x = s if centers is None else np.asarray(centers, float)
    xi = s[fam] - x[:, None]  # (n, size)
    delta = np.abs(xi).max(axis=1)  # (n,)
    z = xi / delta[:, None]
    wV = np.exp(-(2.0 * z) ** 2) * V[fam] / delta[:, None]  # weight x volume, volumes in units of delta
    # Solved as a weighted least-squares problem instead of the normal equations A a = r! e_r (A = B^T W B,
    # cond(A) = 4e8 at P = 6, which left a 4e-8 consistency floor): with the Legendre basis L_q(z) and the
    # QR factors of W^(1/2) L, g^r = W^(1/2) Q y with R^T y = T^(-T) r! e_r (T: monomials in Legendre
    # coefficients). Same functions g^r in exact arithmetic; the round-off drops to ~sqrt(cond A) eps.
    Lv = np.polynomial.legendre.legvander(z, P)  # (n, size, P+1)
    sw = np.sqrt(wV)
    Qm, R = np.linalg.qr(sw[:, :, None] * Lv)  # reduced: (n, size, P+1), (n, P+1, P+1)
    T = np.zeros((P + 1, P + 1))
    for p in range(P + 1):  # a (P+1)-loop over the degree, not over particles
        col = np.polynomial.legendre.poly2leg(np.eye(P + 1)[p])
        T[: len(col), p] = col
    c = np.diag([float(math.factorial(r)) for r in range(P + 1)])
    d = np.linalg.solve(T.T, c)  # Legendre moments of each g^r (columns r)
    y = np.linalg.solve(np.swapaxes(R, 1, 2), np.broadcast_to(d, R.shape))  # (n, P+1, P+1 (r))
    g = np.swapaxes(np.einsum("njq,nqr->njr", Qm, y) * sw[:, :, None], 1, 2)  # (n, r, size): g^r(xi_j) V_j
    out = {}
    for r in orders:
        if r > P:
            raise ValueError(f"derivative order {r} exceeds the degree {P}")
        out[r] = g[:, r, :] / delta[:, None] ** r
    return out


def nearest_families(s: np.ndarray, x: np.ndarray, size: int) -> np.ndarray:
    """(len(x), size) indices of the ``size`` consecutive particles of s around each point x."""
    idx = np.searchsorted(s, x)
    start = np.clip(idx - size // 2, 0, len(s) - size)
    return start[:, None] + np.arange(size)[None, :]


def operator(fam: np.ndarray, coef: np.ndarray, n_cols: int | None = None) -> sp.csr_matrix:
    """Sparse matrix of the stencils: row k holds coef[k] at columns fam[k]."""
    n, size = fam.shape
    n_cols = n if n_cols is None else n_cols
    rows = np.repeat(np.arange(n), size)
    return sp.csr_matrix((np.ravel(coef), (rows, np.ravel(fam))), shape=(n, n_cols))


def derivative_matrices(s: np.ndarray, degree: int, size: int, orders=(1, 2)) -> dict[int, sp.csr_matrix]:
    """{r: D_r} sparse PDDO derivative matrices on the particles s (one segment). Weights below 1e-10 of
    their row's largest are round-off of exact zeros (g^1(0) of a symmetric family) and are set to 0."""
    fam = families(len(s), size)
    w = pddo_weights(s, fam, degree, orders)
    out = {}
    for r in orders:
        c = w[r]
        c = np.where(np.abs(c) < 1e-10 * np.abs(c).max(axis=1, keepdims=True), 0.0, c)
        out[r] = operator(fam, c)
    return out
