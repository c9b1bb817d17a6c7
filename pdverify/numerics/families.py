"""Families of a one-dimensional PD horizon m dx and the Toeplitz stencil operators built on them: the family
offsets and volume fractions (whole cells, the Oterkus/Madenci partial volumes, the cells' parts inside m dx),
sparse Toeplitz operators, and a stencil system with its ghost points eliminated. Arrays in, arrays out."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .band import Band

# -- families --------------------------------------------------------------------------------


MEMBER_TIE = 1e-9  # a cell inside the horizon by less than this share of itself is no member: m = horizon_length / dx
# rounds (2.5 at one scale, 2.5000000000000004 at another), and a member of weight 4e-16 would change J and the layers


def partial_volumes(m: float) -> tuple[np.ndarray, np.ndarray]:
    """Family offsets j and volume fractions beta_j of the cells [j - 1/2, j + 1/2] dx inside m dx (a share below
    MEMBER_TIE: none)."""
    J = int(np.ceil(m + 0.5 - 1e-12))
    j = np.arange(1, J + 1)
    beta = np.clip(m - (j - 0.5), 0.0, 1.0)
    return j[beta > MEMBER_TIE], beta[beta > MEMBER_TIE]


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
    offsets add up). Built diagonal by diagonal (``scipy.sparse.diags``: C speed, far faster than COO
    triplets on large grids). ``truncate``: drop entries outside the grid instead of raising."""
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
    numbering). K = K_ext E as a :class:`~pdverify.numerics.band.Band` (the truncated Toeplitz part by diagonals
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
