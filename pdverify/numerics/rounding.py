"""The data error of an assembled float64 system: which of its entries share one rounding.

A linear system assembled in floating point is the exact system with every entry rounded. The first-order
change of the solution x of A x = b under relative entry perturbations a_ij (1 + d_ij), b_i (1 + e_i) is
``dx = A^-1 (e b - (d A) x)``. Skeel's componentwise bound (Higham, *Accuracy and Stability of Numerical
Algorithms*, 2nd ed., eq. 7.31) lets every d_ij take its worst sign independently: ``|A^-1| (|A| |x| + |b|)``.
An assembly does not round that way. A stencil written once and repeated along the grid, a diagonal set to
twice an off-diagonal, a rotation coupling written with opposite signs in two rows: these entries are one
rounded number, copied (a copy, a sign change or a power of two leaves its relative error unchanged). Their
perturbations are one d, so they keep what the exact entries keep: a difference stencil still annihilates a
rigid motion, a uniform load stays uniform. Letting them differ turns a beam's rounding of its shear modulus into
a spring of stiffness eps kGA / dx^2 under every point: a relative error of eps (L/dx)^2 (L/h)^2 where the
solution moves by eps.

This module groups the entries by their significand (``frexp``: equal significands are equal up to a power of
two and a sign) and gives the linear map G from the groups' perturbations to the residual change,
``G[:, g] = sum over the entries of group g of a_ij x_j`` (the matrix's groups) and ``b_i`` (the load vector's,
grouped the same way), so that the worst case over one d per group in [-c eps, c eps] is
``c eps || A^-1 G ||_inf`` (:func:`pdverify.numerics.error_bound.forward_error_bound` estimates it by Hager's method
with products by G and G^T). A group holds entries computed alike: two independently rounded numbers share a
significand by chance with probability about 2^-52 per pair, and entries that are exact (1, 2, 0.5) are
counted as rounded.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

LAGS = 8  # the longest period of interleaved unknowns per point looked for
SAMPLE = 1 << 16  # values sampled to choose the period


def significand_groups(values: np.ndarray) -> tuple[np.ndarray, int]:
    """(group id of each value, number of groups): values with equal |significand| (``frexp``) share a group; the
    ids (int32 below 2^31 groups) are the ranks of the sorted distinct significands. An assembled stencil repeats:
    along each of the ``period`` sequences of interleaved unknowns (the lag up to :data:`LAGS` at which a sample
    repeats most) a diagonal is a few runs of one value. The runs' values are sorted and grouped by significand once,
    and each run's group is spread along it (the same ids whatever the period: it only decides the runs' lengths)."""
    v = np.asarray(values, float).ravel()
    if v.size == 0:
        return np.zeros(0, np.int64), 0
    cut = SAMPLE // 16  # 16 stretches spread over the values (a band's first rows may be all padding)
    head = v if v.size <= SAMPLE else np.concatenate([v[a : a + cut] for a in range(0, v.size - cut, v.size // 16)])
    repeats = [int(np.count_nonzero(head[lag:] == head[:-lag])) for lag in range(1, min(LAGS, head.size - 1) + 1)]
    period = 1 + int(np.argmax(repeats)) if repeats else 1
    phases = [v[phase::period] for phase in range(period)]  # the interleaved sequences, not values
    starts = [np.flatnonzero(np.r_[True, sub[1:] != sub[:-1]]) for sub in phases]  # runs of one value
    runs = np.concatenate([sub[st] for sub, st in zip(phases, starts)])
    group, count = _ranks(np.frexp(np.abs(runs))[0])
    ids = np.int32 if count < 2**31 else np.int64  # a band's stored entries: half the bytes
    run_group = group.astype(ids)
    out = np.zeros(v.size, ids)
    at = 0
    for phase, st in enumerate(starts):  # each run's group along it: a cumulative sum of steps, in place
        seq = out[phase::period]
        seq[st] = np.diff(run_group[at : at + len(st)], prepend=0)
        np.cumsum(seq, out=seq)
        at += len(st)
    return out, count


def _ranks(values: np.ndarray) -> tuple[np.ndarray, int]:
    """(rank of each value among the distinct values, sorted; number of distinct values): ``np.unique``'s inverse.
    Past :data:`SAMPLE` values (a 2D mesh's entries, which repeat little along its diagonals) by hashing the values
    and sorting only the distinct ones (``pandas.factorize(sort=True)``: the same ranks, a few times faster than a
    sort of them all)."""
    if values.size <= SAMPLE:
        keys, rank = np.unique(values, return_inverse=True)
        return rank, len(keys)
    import pandas as pd  # imported only here: a small solve does not load it

    rank, keys = pd.factorize(values, sort=True)
    return rank, len(keys)


class _Rounding:
    """What the two layouts share: the load vector's columns (grouped like the matrix's) and their products with z
    and y."""

    def _load_part(self, b, k_matrix: int) -> None:
        bgid, kb = significand_groups(b)
        self.bgid = bgid + k_matrix
        self.bterms = np.asarray(b, float) * self.s
        self.k = k_matrix + kb

    @property
    def shape(self) -> tuple[int, int]:
        return (self.n, self.k)

    def _add_load(self, out: np.ndarray, z: np.ndarray) -> np.ndarray:
        out += self.bterms * z[self.bgid]
        return out

    def _load_t(self, out: np.ndarray, y: np.ndarray) -> np.ndarray:
        out += np.bincount(self.bgid, weights=self.bterms * y, minlength=self.k)
        return out


class SharedRounding(_Rounding):
    """The map G (n x k) of the module docstring for a system given by its entries (``rows``, ``cols``, ``vals``; CSR
    in :meth:`from_csr`) at the solution ``x`` with load vector ``b``; ``row_scale`` multiplies G's rows (the
    symmetric scaling of a system solved as diag(s) A diag(s)); ``weight`` multiplies the matrix's columns (its
    entries' rounding in units of the load vector's). ``matvec(z)`` = G z (z in R^k), ``rmatvec(y)`` = G^T y, the
    entries in any order. The products are sparse matrix-vector products of the terms held as a matrix whose column
    indices are the groups (a group met twice in a row is summed there): CSR with ``indptr`` (the entries in CSR order,
    row by row: :func:`csr_layout`), else COO."""

    def __init__(
        self, rows, cols, vals, x, b, row_scale=None, n: int = 0, weight: float = 1.0, groups=None, indptr=None
    ):
        self.n = int(n)
        self.s = np.ones(self.n) if row_scale is None else np.asarray(row_scale, float)
        x = weight * np.asarray(x, float)
        self.rows = rows
        self.terms = vals * x[cols] * self.s[rows]  # a_ij x_j, scaled by row
        self.gid, k_matrix = significand_groups(vals) if groups is None else groups
        self._load_part(b, k_matrix)
        shape = (self.n, k_matrix)  # taken as they are: no copy, no sort, no sum of a row's repeated groups
        if indptr is None:
            self.G = sp.coo_matrix((self.terms, (rows, self.gid)), shape=shape, copy=False)
        else:
            self.G = sp.csr_matrix((self.terms, self.gid, indptr), shape=shape, copy=False)

    @classmethod
    def from_csr(cls, K, x, b, row_scale=None, weight: float = 1.0, layout=None) -> SharedRounding:
        """``layout``: :func:`csr_layout` of K made before (a matrix met again with another load)."""
        rows, cols, vals, groups, indptr = csr_layout(K)[0] if layout is None else layout
        return cls(rows, cols, vals, x, b, row_scale, K.shape[0], weight, groups, indptr)

    def matvec(self, z: np.ndarray) -> np.ndarray:
        """G z: each entry's term times its group's weight, summed by row; plus the load vector's."""
        z = np.asarray(z, float)
        return self._add_load(self.G @ z[: self.G.shape[1]], z)

    def rmatvec(self, y: np.ndarray) -> np.ndarray:
        """G^T y: each group's terms weighted by their rows' y, summed by group."""
        y = np.asarray(y, float)
        out = np.zeros(self.k)
        out[: self.G.shape[1]] = self.G.T @ y
        return self._load_t(out, y)


def csr_layout(K) -> tuple[tuple, int]:
    """((rows, cols, values, (group ids, groups)), bytes): the entries of the CSR matrix K in its own order and
    their significand groups, what :class:`SharedRounding` needs of K whatever the solution and load. The groups are
    the ranks of the distinct significands whatever the order (:func:`significand_groups`); sorting the entries
    diagonal by diagonal first, so that a repeated stencil's runs are found, cost more than it saved: a 2D mesh's
    entries repeat little (0.13 s against 0.09 s on a q8 strip's 945,000 entries), and a 1D model's CSR systems are
    small."""
    K = K.tocsr()
    C = K.tocoo()
    rows, cols, vals = C.row.astype(np.int64), C.col.astype(np.int64), C.data.copy()  # (K's own stay writable)
    gid, k = significand_groups(vals)
    indptr = K.indptr.astype(gid.dtype)  # the CSR matrix of G's terms takes one index type
    for a in (rows, cols, vals, gid, indptr):
        a.flags.writeable = False
    return (rows, cols, vals, (gid, k), indptr), rows.nbytes + cols.nbytes + vals.nbytes + gid.nbytes + indptr.nbytes


class BandRounding(_Rounding):
    """:class:`SharedRounding` for a matrix held by diagonals (``data[upper - o, j] = A[j - o, j]``,
    :class:`pdverify.numerics.band.Band`'s layout; the band's own scaling already applied): the products run
    diagonal by diagonal on ``data`` itself, so the only copy is one group id per stored entry."""

    def __init__(self, data: np.ndarray, upper: int, x, b, weight: float = 1.0):
        self.data, self.upper = data, int(upper)
        self.x = weight * np.asarray(x, float)  # the weight of the matrix's columns, carried by x
        self.n = data.shape[1]
        self.live = np.flatnonzero(data.any(axis=1)).tolist()  # the diagonals that hold a nonzero entry
        self.s = np.ones(self.n)
        gid, k_matrix = significand_groups(data)
        self.k_matrix = k_matrix
        self.gid = gid.astype(np.int32 if k_matrix < 2**31 else np.int64, copy=False).reshape(data.shape)
        self._load_part(b, k_matrix)
        self.runs = {r: _runs(self.gid[r, cs]) for _, cs, r in self._diagonals()}  # a stencil repeated: a few runs

    def _diagonals(self):
        """(row slice, column slice, data row) of every stored diagonal that holds a nonzero entry (an all-zero one
        adds nothing: interleaved unknowns leave whole diagonals empty): entry j of the column slice is A[j - o, j]."""
        n = self.n
        for r in self.live:  # the band's diagonals, not its points
            o = self.upper - r
            yield slice(max(0, -o), n - max(0, o)), slice(max(0, o), n + min(0, o)), r

    def matvec(self, z: np.ndarray) -> np.ndarray:
        z = np.asarray(z, float)
        out = np.zeros(self.n)
        for rs, cs, r in self._diagonals():
            out[rs] += self.data[r, cs] * self.x[cs] * z[self.gid[r, cs]]
        return self._add_load(out, z)

    def rmatvec(self, y: np.ndarray) -> np.ndarray:
        """G^T y: each stored entry's term a_ij x_j y_i summed by group; diagonal by diagonal when the matrix has
        fewer groups than rows (a stencil repeated along the grid), else in one sum over the whole band."""
        y = np.asarray(y, float)
        if self.k_matrix <= self.n:
            out = np.zeros(self.k)
            for rs, cs, r in self._diagonals():
                terms = self.data[r, cs] * self.x[cs] * y[rs]
                if self.runs[r] is not None:  # each run's sum, then the runs' sums by group
                    starts, groups = self.runs[r]
                    terms, ids = np.add.reduceat(terms, starts), groups
                else:
                    ids = self.gid[r, cs]
                out[: self.k_matrix] += np.bincount(ids, weights=terms, minlength=self.k_matrix)
            return self._load_t(out, y)
        w = np.zeros(self.data.shape)
        for rs, cs, r in self._diagonals():
            w[r, cs] = self.data[r, cs] * self.x[cs] * y[rs]
        return self._load_t(np.bincount(self.gid.ravel(), weights=w.ravel(), minlength=self.k), y)


# a diagonal is summed by its runs of one group where it has at most 1 / RUN_SHARE as many runs as entries
RUN_SHARE = 8


def _runs(ids: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(the start of each run of one group id along a diagonal, its id), or None where the runs are too many (or the
    diagonal empty) for summing run by run (``np.add.reduceat``) to beat one weighted count of every entry."""
    if ids.size == 0:
        return None
    starts = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]])
    return (starts, ids[starts]) if len(starts) * RUN_SHARE <= ids.size else None
