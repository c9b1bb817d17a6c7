"""Peridynamic differential-operator (PDDO) functions in one dimension (seed 004 §3.2; the equations are
restored in ../shared/design/formulas-bondpair-curved.md §2, RECONSTRUCTED there and checked here).

At particle k with family H_k (members j, xi = s_j - s_k, volume V_j), functions
``g^r(xi) = w(|xi|) Σ_{q=0..P} a^r_q xi^q`` with the orthogonality ``Σ_j xi_j^p g^r(xi_j) V_j = r! δ_pr``
(p, r = 0..P) give ``f^(r)(s_k) ≈ Σ_j f(s_j) g^r(xi_j) V_j``, exact for polynomials of degree <= P.
So ``A a^r = r! e_r`` with the moment matrix ``A_pq = Σ_j w xi^(p+q) V_j`` (a Hankel matrix).

Numerics: xi is scaled by the family size delta_k = max |xi| before A is formed (A would otherwise hold
powers of the spacing from 1 to h^(2P) and lose every digit), weight ``w = exp(-(2 xi/delta)^2)``;
all families are solved at once with ``numpy.linalg.solve`` on a stacked (n, P+1, P+1) batch.
Families: the 2m+1 nearest particles (m = horizon in spacings), the window shifted inward at an end so
every family keeps its size (the seed: horizons may differ per particle).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from ..errors import InputError


def default_horizon(degree: int) -> int:
    """Half-width m of the family (in particles) large enough for degree P: 2m + 1 >= P + 3."""
    return int(math.ceil((degree + 2) / 2))


def families(n: int, m: int) -> np.ndarray:
    """(n, 2m+1) member indices: the window k-m..k+m, shifted inward near the ends."""
    K = 2 * m + 1
    if K > n:
        raise InputError(f"horizon = {m}: a family of {K} particles does not fit in {n} points; use more points "
                         "or a smaller horizon")
    start = np.clip(np.arange(n) - m, 0, n - K)
    return start[:, None] + np.arange(K)[None, :]


def volumes(s: np.ndarray) -> np.ndarray:
    """Cell lengths of the particles (half cells at the ends): the quadrature weights V_j."""
    mid = np.r_[s[0], 0.5 * (s[1:] + s[:-1]), s[-1]]
    return np.diff(mid)


def pddo_weights(s: np.ndarray, degree: int, m: int, orders=(1, 2)) -> tuple[np.ndarray, dict[int, np.ndarray]]:
    """Family indices (n, K) and, per derivative order r, the weights c^r (n, K) with
    f^(r)(s_k) ≈ Σ_j c^r_kj f(s_j) (c^r = g^r V, the 1/delta^r of the scaling included).

    Batched: one stacked solve for all particles and orders."""
    s = np.asarray(s, float)
    n = len(s)
    P = int(degree)
    fam = families(n, m)
    if fam.shape[1] < P + 1:
        raise InputError(f"degree = {P}: needs a family of at least {P + 1} particles; use horizon >= {int(math.ceil(P / 2))}")
    V = volumes(s)[fam]
    xi = s[fam] - s[:, None]
    delta = np.abs(xi).max(axis=1, keepdims=True)
    z = xi / delta
    wt = np.exp(-(2.0 * z) ** 2) * V
    powers = z[:, :, None] ** np.arange(2 * P + 1)[None, None, :]  # (n, K, 2P+1)
    mom = np.einsum("nk,nkp->np", wt, powers)  # Σ w z^p V
    A = mom[:, np.arange(P + 1)[:, None] + np.arange(P + 1)[None, :]]  # Hankel (n, P+1, P+1)
    rhs = np.zeros((P + 1, len(orders)))
    for c, r in enumerate(orders):
        if r > P:
            raise InputError(f"degree = {P}: derivatives of order {r} need degree >= {r}")
        rhs[r, c] = math.factorial(r)
    a = np.linalg.solve(A, np.broadcast_to(rhs, (n, P + 1, len(orders))))  # (n, P+1, R)
    g = np.einsum("nkq,nqr->nkr", powers[:, :, : P + 1], a) * wt[:, :, None]  # g^r V at the members
    out = {r: g[:, :, c] / delta ** r for c, r in enumerate(orders)}
    return fam, out


def operator(fam: np.ndarray, c: np.ndarray, n: int) -> sp.csr_matrix:
    """Sparse (n, n) matrix of one derivative from family indices and weights."""
    rows = np.repeat(np.arange(fam.shape[0]), fam.shape[1])
    return sp.csr_matrix((c.ravel(), (rows, fam.ravel())), shape=(fam.shape[0], n))


def derivative_operators(s: np.ndarray, degree: int, m: int, orders=(1, 2)) -> dict[int, sp.csr_matrix]:
    """{r: D_r} sparse derivative matrices on the particles s (any spacing)."""
    fam, c = pddo_weights(s, degree, m, orders)
    return {r: operator(fam, c[r], len(s)) for r in orders}
