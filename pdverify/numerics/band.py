"""Banded matrices assembled diagonal by diagonal.

The PD and beam operators are banded (a family of J neighbours per side, d unknowns per point:
bandwidth about d (2J + 1)) and, away from the ends, translation invariant. :class:`Band` holds such a
matrix by diagonals, ``data[upper - o, j] = A[j - o, j]`` for the offset ``o = j - i`` (C order: each
diagonal contiguous; this is scipy's DIA layout and ``scipy.linalg.solve_banded``'s), so a model writes
each stencil entry with one slice, and :meth:`Band.lapack` copies it once into the Fortran array LAPACK's
``gbtrf`` factorises in place. No sparse triplets, no CSR: at 10^6 points the sparse route spent 3–6x the
factorisation in scipy.sparse bookkeeping (``pdverify bench``).

The diagonal of offset ``o`` is row ``upper - o`` of ``data``, columns ``max(0, o)`` .. ``n - 1 + min(0, o)``;
its k-th element belongs to row ``k + max(0, -o)``.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

LAYOUT_BLOCK = 4096  # columns per block of the copy into LAPACK's column-major layout (10x faster than one copy)


def canonical_csr(K: sp.spmatrix) -> sp.csr_matrix:
    """CSR with sorted, summed indices (no duplicates): entries can then be placed by assignment."""
    K = sp.csr_matrix(K)
    if not K.has_canonical_format:
        K = K.copy()
        K.sum_duplicates()
    return K


def csr_rows(K: sp.csr_matrix) -> np.ndarray:
    """Row index of every stored entry of a CSR matrix (the COO row array, without converting)."""
    return np.repeat(np.arange(K.shape[0], dtype=np.int64), np.diff(K.indptr))


def bandwidths(K: sp.spmatrix) -> tuple[int, int]:
    """(lower, upper) bandwidth of a sparse matrix."""
    K = sp.csr_matrix(K)
    if K.nnz == 0:
        return 0, 0
    d = K.indices.astype(np.int64) - csr_rows(K)
    return int(max(0, -d.min())), int(max(0, d.max()))


class Band:
    """A square n x n matrix with ``lower`` sub- and ``upper`` super-diagonals (see the module docstring)."""

    def __init__(self, n: int, lower: int, upper: int):
        self.n, self.lower, self.upper = int(n), int(lower), int(upper)
        if self.lower < 0 or self.upper < 0 or self.n < 1:
            raise ValueError(f"band of size {n} with bandwidths ({lower}, {upper})")
        self.data = np.zeros((self.lower + self.upper + 1, self.n))

    # -- shape --------------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return (self.n, self.n)

    @property
    def offsets(self) -> np.ndarray:
        """Diagonal offsets j - i held, from ``upper`` down to ``-lower``."""
        return np.arange(self.upper, -self.lower - 1, -1)

    def diag(self, offset: int) -> np.ndarray:
        """Writable view of the diagonal A[i, i + offset]; element k is row k + max(0, -offset)."""
        if not -self.lower <= offset <= self.upper:
            raise ValueError(f"offset {offset} outside the band (-{self.lower}, {self.upper})")
        return self.data[self.upper - offset, max(0, offset) : self.n + min(0, offset)]

    # -- assembly -----------------------------------------------------------------------------
    def add_stencil(self, offsets, coefs, rows: tuple[int, int] | None = None) -> Band:
        """Toeplitz part: every row i in ``rows`` = (first, stop) gets ``coefs`` at columns i + ``offsets``
        (repeated offsets add up; entries outside the matrix are dropped, as for a truncated family)."""
        r0, r1 = (0, self.n) if rows is None else rows
        offsets = np.asarray(offsets, dtype=np.int64)
        u, inv = np.unique(offsets, return_inverse=True)
        vals = np.bincount(inv.ravel(), weights=np.asarray(coefs, float).ravel(), minlength=len(u))
        for o, c in zip(u.tolist(), vals):
            lo, hi = max(r0, -o, 0), min(r1, self.n - o, self.n)  # rows whose column i + o exists
            if hi > lo and c != 0.0:
                k0 = max(0, -o)
                self.diag(o)[lo - k0 : hi - k0] += c
        return self

    def block_stretches(self, ndof: int, blocks: dict, points: tuple[int, int] | None = None):
        """(offset, slice of :meth:`diag`, value, (lo, hi)) of every nonzero block entry of
        :meth:`add_block_stencil` (the stretch of the diagonal it writes; ``lo .. hi - 1`` the points)."""
        npts = self.n // ndof
        p0, p1 = (0, npts) if points is None else points
        for o, C in blocks.items():
            lo, hi = max(p0, -o, 0), min(p1, npts - o, npts)  # points whose partner p + o exists
            if hi <= lo:
                continue
            for a in range(ndof):
                for b in range(ndof):
                    c = C[a][b]
                    if np.isscalar(c) and c == 0.0:
                        continue
                    off = ndof * o + b - a
                    k0 = max(0, -off)  # element k of the diagonal is row k + k0
                    yield off, slice(ndof * lo + a - k0, ndof * (hi - 1) + a - k0 + 1, ndof), c, (lo - p0, hi - p0)

    def add_block_stencil(
        self, ndof: int, blocks: dict[int, np.ndarray], points: tuple[int, int] | None = None
    ) -> Band:
        """Interleaved unknowns (``ndof`` per point, point-major): for every point p in ``points`` =
        (first, stop), row ndof p + a gets ``blocks[o][a, b]`` at column ndof (p + o) + b. A block entry may be
        a scalar or an array over the points of ``points`` (position-dependent coefficients). Entries
        outside the matrix are dropped."""
        for _ in self.written(ndof, blocks, points):
            pass
        return self

    def written(self, ndof: int, blocks: dict, points: tuple[int, int] | None = None):
        """:meth:`add_block_stencil`, yielding (offset, slice of :meth:`diag`) of each stretch as it writes it."""
        for off, sl, c, (i0, i1) in self.block_stretches(ndof, blocks, points):
            self.diag(off)[sl] += c if np.isscalar(c) else np.asarray(c, float)[i0:i1]
            yield off, sl

    def values(self, rows, cols) -> np.ndarray:
        """A[rows, cols] element by element (arrays of one shape; 0 outside the band and outside the matrix)."""
        rows, cols = np.broadcast_arrays(np.asarray(rows, np.int64), np.asarray(cols, np.int64))
        off = cols - rows
        inside = (off <= self.upper) & (off >= -self.lower) & (rows >= 0) & (rows < self.n) & (cols >= 0)
        inside &= cols < self.n
        out = np.zeros(rows.shape)
        out[inside] = self.data[self.upper - off[inside], cols[inside]]
        return out

    def add_entries(self, rows, cols, vals) -> Band:
        """Scatter-add a few entries (boundary rows, ghost corrections); repeated (row, col) add up."""
        rows, cols = np.asarray(rows, np.int64).ravel(), np.asarray(cols, np.int64).ravel()
        vals = np.broadcast_to(np.asarray(vals, float), rows.shape).ravel()
        off = cols - rows
        if len(off) and (
            off.min() < -self.lower
            or off.max() > self.upper
            or rows.min() < 0
            or rows.max() >= self.n
            or cols.min() < 0
            or cols.max() >= self.n
        ):
            raise ValueError("entries outside the matrix or its band")
        np.add.at(self.data, (self.upper - off, cols), vals)
        return self

    def clear_rows(self, rows) -> Band:
        """Zero every entry of the given rows."""
        rows = np.asarray(rows, np.int64).ravel()
        if len(rows):
            off = np.arange(-self.lower, self.upper + 1)
            cols = rows[:, None] + off[None, :]
            ok = (cols >= 0) & (cols < self.n)
            self.data[(self.upper - np.broadcast_to(off, cols.shape))[ok], cols[ok]] = 0.0
        return self

    def fix(self, dofs, rhs: np.ndarray | None = None) -> Band:
        """Unknowns held at zero: their rows and columns cleared and a unit diagonal (elimination that
        keeps the numbering); ``rhs``, the right-hand side, is set to zero there in place."""
        dofs = np.asarray(dofs, np.int64).ravel()
        if rhs is not None:
            rhs[dofs] = 0.0
        self.clear_rows(dofs)
        self.data[:, dofs] = 0.0  # a column of A is a column of data
        self.data[self.upper, dofs] = 1.0
        return self

    # -- conversions and products ---------------------------------------------------------------
    def tocsr(self) -> sp.csr_matrix:
        """The same matrix as CSR (explicit zeros dropped)."""
        K = sp.dia_matrix((self.data, self.offsets), shape=self.shape).tocsr()
        K.eliminate_zeros()
        return K

    def toarray(self) -> np.ndarray:
        return self.tocsr().toarray()

    @classmethod
    def from_sparse(cls, K: sp.spmatrix, lower: int | None = None, upper: int | None = None) -> Band:
        """Scatter a sparse matrix into a band (blocks of rows: bounded temporaries)."""
        K = canonical_csr(K)
        n = K.shape[0]
        if lower is None or upper is None:
            lower, upper = bandwidths(K)
        B = cls(n, lower, upper)
        step = max(1, (1 << 20) // max(1, K.nnz // max(n, 1)))  # ~1e6 entries per block: bounded temporaries
        for r0 in range(0, n, step):  # blocks of rows, not points: ~nnz / 1e6 iterations
            r1 = min(n, r0 + step)
            a, b = K.indptr[r0], K.indptr[r1]
            rows = np.repeat(np.arange(r0, r1, dtype=np.int64), np.diff(K.indptr[r0 : r1 + 1]))
            cols = K.indices[a:b]
            B.data[B.upper + rows - cols, cols] = K.data[a:b]
        return B

    @classmethod
    def gram(cls, A: sp.spmatrix, scale: float = 1.0) -> Band:
        """scale A^T A of a sparse A whose rows each reach at most ``span`` columns, as a band of half-width ``span``:
        the rows, ordered by their first column, in blocks of span / 4 rows, each block's dense Gram matrix by BLAS
        and added diagonal by diagonal. The same matrix as the sparse product to round-off, at about 2 (2.25 span)^2
        flops per row in dense products where the sparse product makes about (2 span)^2 indexed ones; each block's
        Gram matrix holds (2.25 span)^2 numbers."""
        A = canonical_csr(A)
        n = A.shape[1]
        filled = np.flatnonzero(np.diff(A.indptr))
        if not len(filled):
            return cls(n, 0, 0)
        first = np.minimum.reduceat(A.indices, A.indptr[filled])
        last = np.maximum.reduceat(A.indices, A.indptr[filled])
        span = int((last - first).max())
        K = cls(n, span, span)
        order = np.argsort(first, kind="stable")
        rows, first, last = filled[order], first[order], last[order]
        step = max(1, span // 4)
        for b0 in range(0, len(rows), step):
            c0, c1 = int(first[b0 : b0 + step].min()), int(last[b0 : b0 + step].max()) + 1
            M = A[rows[b0 : b0 + step]][:, c0:c1].toarray()
            G = M.T @ M
            for o in range(-min(span, c1 - c0 - 1), min(span, c1 - c0 - 1) + 1):
                d = np.diagonal(G, o)  # element t: row c0 + t + max(0, -o), i.e. element c0 + t of K's diagonal o
                K.diag(o)[c0 : c0 + len(d)] += scale * d
        return K

    def matvec(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x)
        y = np.zeros(self.n, dtype=np.result_type(x, float))
        for o in self.offsets.tolist():
            d = self.diag(o)
            if o >= 0:
                y[: self.n - o] += d * x[o:]
            else:
                y[-o:] += d * x[: self.n + o]
        return y

    def __matmul__(self, x):
        return self.matvec(x)

    def scale(self, s: np.ndarray) -> Band:
        """In place: diag(s) A diag(s), diagonal by diagonal."""
        for o in self.offsets.tolist():
            d = self.diag(o)
            if o >= 0:
                d *= s[: self.n - o] * s[o:]
            else:
                d *= s[-o:] * s[: self.n + o]
        return self

    def copy(self) -> Band:
        B = Band(self.n, self.lower, self.upper)
        B.data[...] = self.data
        return B

    def lapack(self) -> np.ndarray:
        """The Fortran array ``gbtrf`` factorises in place: ``lower`` spare rows (fill-in of partial
        pivoting) on top of ``data``; one copy."""
        ab = np.empty((2 * self.lower + self.upper + 1, self.n), order="F")
        ab[: self.lower] = 0.0
        for j in range(0, self.n, LAYOUT_BLOCK):  # blocks of columns: a transposing copy that stays in cache
            ab[self.lower :, j : j + LAYOUT_BLOCK] = self.data[:, j : j + LAYOUT_BLOCK]
        return ab


class Extent:
    """The diagonals of a :class:`~pdverify.numerics.band.Band` that were written and, per diagonal, the stretch of
    its elements that was, so the row and column maxima and scales touch those only (the mixed form's band
    has 2 x 36 + 1 diagonals at P = 4, of which 10 are filled along the beam and the outer ones near the
    ends only; :class:`Band` itself would read and scale all its diagonals)."""

    def __init__(self, B: Band):
        self.B = B
        self.span: dict[int, list[tuple[int, int]]] = {}  # offset -> [(first, stop)] elements of B.diag(offset)

    def _mark(self, off: int, k0: int, k1: int):
        self.span.setdefault(off, []).append((k0, k1))

    def block(self, ndof: int, o: int, C, p0: int, p1: int):
        """``B.add_block_stencil(ndof, {o: C}, points=(p0, p1))`` and the stretches it wrote."""
        for off, sl in self.B.written(ndof, {o: C}, (p0, p1)):
            self._mark(off, sl.start, sl.stop)

    def entries(self, rows: np.ndarray, cols: np.ndarray):
        """The stretches of entries written by ``B.add_entries(rows, cols, ...)``."""
        off = cols - rows
        k = rows - np.maximum(0, -off)
        for o in np.unique(off).tolist():
            sel = k[off == o]
            self._mark(o, int(sel.min()), int(sel.max()) + 1)

    def _each(self, rows: bool):
        """(diagonal stretch, slice of its rows or columns), every written element exactly once: the
        stretches of one diagonal merged where they overlap or touch (the outer family offsets are written
        near the two ends of each segment only)."""
        for off, spans in self.span.items():
            merged: list[list[int]] = []
            for k0, k1 in sorted(spans):
                if merged and k0 <= merged[-1][1]:
                    merged[-1][1] = max(merged[-1][1], k1)
                else:
                    merged.append([k0, k1])
            d = self.B.diag(off)
            shift = max(0, -off) if rows else max(0, off)  # element k: row k + max(0, -off), column k + max(0, off)
            for k0, k1 in merged:
                yield d[k0:k1], slice(k0 + shift, k1 + shift)

    def abs_max(self, rows: bool) -> np.ndarray:
        """Largest |entry| of every row (``rows``) or column."""
        out = np.zeros(self.B.n)
        for d, sl in self._each(rows):
            np.maximum(out[sl], np.abs(d), out=out[sl])
        return out

    def scale(self, f: np.ndarray, rows: bool):
        """In place: row i (``rows``) or column i multiplied by f[i]."""
        for d, sl in self._each(rows):
            d *= f[sl]
