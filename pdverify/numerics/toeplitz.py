"""Banded operators that are Toeplitz away from their ends: what the fast large-horizon solver needs to know.

A PD beam operator on a uniform grid is a block stencil (``p`` unknowns per point, interleaved) that is the
same on every row except within a few horizons of the ends, where ghost points, truncated families and held
supports change it. Here, for a :class:`~pdverify.numerics.band.Band`:

* the unknowns held by unit rows (:meth:`Band.fix`) and the block stencil of the interior rows;
* the end correction C = A - T: the entries where A differs from the truncated block Toeplitz matrix T of the
  interior stencil (the operator is "Toeplitz plus an end correction" when C lives within a few stencil
  reaches of the ends: the test of grid uniformity);
* the product T x by FFT (O(n log n), whatever the horizon) plus C x (sparse);
* the parity of each end (a held end: odd reflection through the support one step beyond the last unknown;
  an end whose last point moves: even reflection through it) and the solve with the interior operator
  under those reflections, which the sine transforms diagonalise exactly: DST-I (odd-odd) or the
  DST-III/DST-II pair (odd-even), frequency by frequency a p x p solve with the stencil's symbol
  Λ(θ) = T_0 + 2 Σ_q T_q cos(qθ) (Strang 1986; the τ algebra of Bini & Capovani 1983; Chan & Jin,
  *An Introduction to Iterative Toeplitz Solvers*, SIAM 2007, ch. 3). With odd (point-reflection) ghost ends
  the interior PD operator is exactly this matrix, and sin(kπx/L) its eigenvectors.

Pure functions, arrays in, arrays out.
"""

from __future__ import annotations

import numpy as np
import scipy.fft as fft
import scipy.sparse as sp

from .band import Band


def held_unknowns(B: Band) -> np.ndarray:
    """Unknowns held by a unit row and an empty column (:meth:`Band.fix`), sorted."""
    cand = np.flatnonzero(B.diag(0) == 1.0)
    if not len(cand):
        return cand
    col_nnz = np.count_nonzero(B.data[:, cand], axis=0)  # a column of A is a column of data
    cand = cand[col_nnz == 1]
    offs = B.offsets
    cols = cand[:, None] + offs[None, :]
    ok = (cols >= 0) & (cols < B.n)
    vals = np.zeros(cols.shape)
    vals[ok] = B.data[np.broadcast_to(B.upper - offs, cols.shape)[ok], cols[ok]]
    return cand[np.count_nonzero(vals, axis=1) == 1]


def free_range(held: np.ndarray, n: int) -> tuple[int, int] | None:
    """(lo, hi): the unknowns not held when they are one contiguous run lo .. hi - 1, else None."""
    keep = np.ones(n, bool)
    keep[held] = False
    free = np.flatnonzero(keep)
    if not len(free) or free[-1] + 1 - free[0] != len(free):
        return None
    return int(free[0]), int(free[-1]) + 1


def sub_band(B: Band, lo: int, hi: int) -> Band:
    """The square block rows/columns lo .. hi - 1 of B as a Band sharing B's storage (a view: the entries of
    those columns whose rows fall outside the block must be zero, as for held unknowns)."""
    V = Band.__new__(Band)
    V.n, V.lower, V.upper = hi - lo, B.lower, B.upper
    V.data = B.data[:, lo:hi]
    return V


def block_stencil(B: Band, row0: int, p: int) -> np.ndarray:
    """The block row of point ``row0 // p`` (rows row0 .. row0 + p - 1): T[q, a, b] = A[row0 + a, row0 + p q + b]
    for q = -R .. R (index q + R), R the block reach of the band."""
    R = (max(B.lower, B.upper) + p - 1) // p + 1
    T = np.zeros((2 * R + 1, p, p))
    q = np.arange(-R, R + 1)
    for a in range(p):
        for b in range(p):
            cols = row0 + p * q + b
            T[:, a, b] = B.values(np.full(len(q), row0 + a), cols)
    nz = np.flatnonzero(np.abs(T).reshape(len(q), -1).max(axis=1) > 0)
    if not len(nz):
        return np.zeros((1, p, p))
    r = int(max(abs(q[nz[0]]), abs(q[nz[-1]])))
    return T[R - r : R + r + 1]


def expected_diagonal(T: np.ndarray, offset: int, rows: np.ndarray, p: int) -> np.ndarray:
    """The entries A[i, i + offset] of the block Toeplitz matrix of stencil T at the rows ``rows`` (block
    offset q = (offset + a - b) / p with a = i mod p, b = (i + offset) mod p)."""
    R = (len(T) - 1) // 2
    a = rows % p
    b = (rows + offset) % p
    q = (offset + a - b) // p
    out = np.zeros(len(rows))
    ok = np.abs(q) <= R
    out[ok] = T[q[ok] + R, a[ok], b[ok]]
    return out


def end_correction(B: Band, T: np.ndarray, p: int, tol: float) -> sp.csr_matrix:
    """C = A - T_trunc (T_trunc: the block Toeplitz matrix of stencil T truncated to B's size), keeping the
    entries above ``tol`` in magnitude: one pass over the band, diagonal by diagonal."""
    rows, cols, vals = [], [], []
    n = B.n
    period = np.arange(n)
    for o in B.offsets.tolist():
        d = B.diag(o)
        k0 = max(0, -o)  # element k is row k + k0
        r = period[k0 : k0 + len(d)]
        if p == 1:
            R = (len(T) - 1) // 2
            diff = d - (T[o + R, 0, 0] if abs(o) <= R else 0.0)
        else:
            diff = d - expected_diagonal(T, o, r, p)
        big = np.flatnonzero(np.abs(diff) > tol)
        if len(big):
            rows.append(r[big]), cols.append(r[big] + o), vals.append(diff[big])
    if not rows:
        return sp.csr_matrix((n, n))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))


def symbol(T: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Λ(θ) = Σ_q T_q e^{i q θ} of a block stencil with T_{-q} = T_q (a real, even symbol), at every θ: an FFT
    when θ is a grid of the sine transforms, else the cosine sums. Shape (len(theta), p, p)."""
    R = (len(T) - 1) // 2
    q = np.arange(-R, R + 1)
    return np.einsum("kq,qab->kab", np.cos(np.outer(theta, q)), T)


def symbol_on_grid(T: np.ndarray, npos: int, parities: tuple[str, str]) -> np.ndarray:
    """Λ at the frequencies of the sine transform of ``npos`` points with the given end parities, by FFT:
    odd-odd θ_k = π k / (npos + 1), k = 1 .. npos (DST-I); otherwise θ_k = π (2k + 1) / (2 npos) (DST-III)."""
    R = (len(T) - 1) // 2
    odd_odd = parities == ("odd", "odd")
    L = 2 * (npos + 1) if odd_odd else 4 * npos  # θ_k = 2π j / L at j = k (odd-odd) or 2k + 1
    if L <= 2 * R:
        theta = np.pi * (np.arange(1, npos + 1) / (npos + 1) if odd_odd else (2 * np.arange(npos) + 1) / (2 * npos))
        return symbol(T, theta)
    c = np.zeros((L,) + T.shape[1:])
    c[: R + 1] = T[R:]
    if R:
        c[-R:] = T[:R]
    F = fft.fft(c, axis=0).real  # Σ_q T_q e^{-i q θ} = Σ_q T_q cos(q θ) for an even stencil
    idx = np.arange(1, npos + 1) if odd_odd else 2 * np.arange(npos) + 1
    return F[idx]


def is_even(T: np.ndarray, rtol: float) -> bool:
    """T_{-q} = T_q for every q (the stencil of a symmetric, reflection-invariant interior), to ``rtol``."""
    return bool(np.abs(T - T[::-1]).max() <= rtol * max(np.abs(T).max(), 1e-300))


class SineSolve:
    """x = M^-1 r for the interior operator M of stencil T on ``npos`` points (p unknowns each) with the end
    ``parities`` ("odd": reflection through the point one step beyond the last unknown, w = 0 there; "even":
    reflection through the last unknown), diagonalised by the sine transforms: a forward transform, a p x p
    solve per frequency, the inverse transform; O(n log n). With an even end M is used in its symmetric form
    (V Λ^-1 V^T, the end point's weight in the transform's inner product taken as 1): symmetric positive
    definite when every Λ(θ) is, as the conjugate-gradient method needs."""

    def __init__(self, T: np.ndarray, npos: int, parities: tuple[str, str]):
        if parities == ("even", "even"):
            raise ValueError("even reflections at both ends: the symbol vanishes at θ = 0 (a rigid motion)")
        self.npos, self.p, self.parities = npos, T.shape[1], parities
        lam = symbol_on_grid(T, npos, ("odd", "odd") if parities == ("odd", "odd") else ("odd", "even"))
        self.definite = bool(np.all(np.linalg.eigvalsh(0.5 * (lam + lam.transpose(0, 2, 1)))[:, 0] > 0))
        self.inverse = np.linalg.inv(lam)

    def __call__(self, r: np.ndarray) -> np.ndarray:
        R = np.asarray(r, float).reshape(self.npos, self.p)
        flip = self.parities == ("even", "odd")
        if flip:
            R = R[::-1]
        if self.parities == ("odd", "odd"):
            X = fft.idst(np.einsum("kab,kb->ka", self.inverse, fft.dst(R, 1, axis=0)), 1, axis=0)
        else:
            R = R.copy()
            R[-1] *= 2.0  # V^T r = DST-III(W^-1 r) / 2, W = diag(1, .., 1, 1/2)
            X = fft.dst(np.einsum("kab,kb->ka", self.inverse, fft.dst(R, 3, axis=0)), 2, axis=0) / (2 * self.npos)
        if flip:
            X = X[::-1]
        return X.reshape(-1)


class ToeplitzProduct:
    """y = T_trunc x for the block Toeplitz matrix of stencil T on ``npos`` points, by FFT (rows past the ends
    truncated: the stencil meets zeros there): O(n log n) whatever the stencil's reach."""

    def __init__(self, T: np.ndarray, npos: int):
        self.R, self.p, self.npos = (len(T) - 1) // 2, T.shape[1], npos
        self.L = fft.next_fast_len(npos + 2 * self.R, real=True)
        k = np.zeros((self.L,) + T.shape[1:])
        k[: len(T)] = T[::-1]  # y_i = Σ_q T_q x_{i+q}: a convolution with the reversed stencil
        self.kernel = fft.rfft(k, axis=0)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        X = fft.rfft(np.asarray(x, float).reshape(self.npos, self.p), n=self.L, axis=0)
        Y = fft.irfft(np.einsum("kab,kb->ka", self.kernel, X), n=self.L, axis=0)
        return Y[self.R : self.R + self.npos].reshape(-1)


def end_parities(B: Band, T: np.ndarray, C: sp.csr_matrix, reach: int) -> tuple[str, str]:
    """Per end, "odd" when the operator (stencil T, end correction C) does not annihilate a rigid translation of
    every component on the rows within ``reach`` unknowns of that end (a support holds the deflection there: the
    held point, one step beyond the last unknown, is the centre of an odd reflection), else "even" (the end
    point moves). The test is relative to |T| 1 + |C| 1 on those rows, at 1e-8."""
    n, p = B.n, T.shape[1]
    D = sp.dia_matrix((B.data, B.offsets), shape=B.shape)
    ends = (slice(0, min(reach, n)), slice(max(0, n - reach), n))
    worst = [0.0, 0.0]
    for c in range(p):
        one = np.zeros(n)
        one[c::p] = 1.0
        y = np.abs(D @ one)
        scale = ToeplitzProduct(np.abs(T), n // p)(one) + abs(C) @ one
        for side, rows in enumerate(ends):
            top = scale[rows].max()
            worst[side] = max(worst[side], float(y[rows].max() / top) if top > 0 else 0.0)
    return tuple("odd" if w > 1e-8 else "even" for w in worst)
