"""Band: diagonal-by-diagonal assembly equals the same matrix built entry by entry, and its in-place
LAPACK solve equals a sparse direct solve."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from pdverify.core.errors import SolveError
from pdverify.numerics.band import Band
from pdverify.numerics.linalg import solve_band, solve_linear


def dense_stencil(n, offsets, coefs, r0=0, r1=None):
    A = np.zeros((n, n))
    for i in range(r0, n if r1 is None else r1):
        for o, c in zip(offsets, coefs):
            if 0 <= i + o < n:
                A[i, i + o] += c
    return A


def test_stencil_truncated_at_the_ends_and_repeated_offsets_add():
    offs, coefs = [-2, -1, 0, 1, 2, 1], [1.0, -4.0, 6.0, -4.0, 1.0, 0.5]
    B = Band(9, 2, 2).add_stencil(offs, coefs)
    assert np.array_equal(B.toarray(), dense_stencil(9, offs, coefs))
    B = Band(9, 2, 2).add_stencil(offs, coefs, rows=(3, 7))
    assert np.array_equal(B.toarray(), dense_stencil(9, offs, coefs, 3, 7))


def test_block_stencil_equals_entrywise_interleaved_assembly():
    rng = np.random.default_rng(1)
    ndof, npts = 3, 7
    blocks = {o: rng.normal(size=(ndof, ndof)) for o in (-2, -1, 0, 1, 2)}
    varying = rng.normal(size=npts - 2)  # a position-dependent entry on points 1..npts-2
    blocks[1] = [[blocks[1][a][b] if (a, b) != (2, 0) else varying for b in range(ndof)] for a in range(ndof)]
    B = Band(ndof * npts, ndof * 3, ndof * 3).add_block_stencil(ndof, blocks, points=(1, npts - 1))
    A = np.zeros((ndof * npts, ndof * npts))
    for p in range(1, npts - 1):
        for o, C in blocks.items():
            if 0 <= p + o < npts:
                for a in range(ndof):
                    for b in range(ndof):
                        c = C[a][b]
                        A[ndof * p + a, ndof * (p + o) + b] += c if np.isscalar(c) else c[p - 1]
    assert np.allclose(B.toarray(), A, rtol=0, atol=1e-15)


def test_entries_fix_sparse_round_trip_matvec_and_scale():
    rng = np.random.default_rng(2)
    n = 40
    K = sp.diags([rng.normal(size=n - abs(k)) for k in range(-3, 5)], list(range(-3, 5)), format="csr")
    B = Band.from_sparse(K)
    assert (B.lower, B.upper) == (3, 4) and abs(B.tocsr() - K).max() == 0
    x = rng.normal(size=n)
    assert np.allclose(B @ x, K @ x, rtol=1e-14, atol=1e-14)
    B.add_entries([0, 0, 5], [2, 2, 3], [1.0, 2.0, -1.0])
    A = K.toarray()
    A[0, 2] += 3.0
    A[5, 3] -= 1.0
    assert np.allclose(B.toarray(), A)
    with pytest.raises(ValueError):
        B.add_entries([0], [9], [1.0])  # outside the band
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    assert np.array_equal(B.values(i, j), A)  # entry by entry, zero outside the band
    assert np.array_equal(B.values([n - 1, n - 1, 0, -1], [n, n + 2, -1, 0]), np.zeros(4))  # and outside the matrix
    s = rng.uniform(0.5, 2.0, size=n)
    assert np.allclose(B.copy().scale(s).toarray(), s[:, None] * A * s[None, :])
    B.fix([0, 17])
    A[[0, 17], :] = 0.0
    A[:, [0, 17]] = 0.0
    A[0, 0] = A[17, 17] = 1.0
    assert np.allclose(B.toarray(), A)


def test_in_place_solve_equals_sparse_solve_and_detects_singular():
    rng = np.random.default_rng(3)
    n = 30_000  # above the size where solve_linear converts to CSR
    main = 4.0 + rng.uniform(size=n)
    K = sp.diags(
        [-np.ones(n - 2), -np.ones(n - 1), main, -np.ones(n - 1), 0.5 * np.ones(n - 3)], [-2, -1, 0, 1, 3], format="csr"
    )
    b = rng.normal(size=n)
    u, info = solve_linear(Band.from_sparse(K), b)
    assert "in place" in info["solver"]
    assert np.abs(u - spla.spsolve(K.tocsc(), b)).max() < 1e-12 * np.abs(u).max()
    S = Band(n, 1, 1).add_stencil([-1, 0, 1], [1.0, -2.0, 1.0])
    S.diag(0)[:] = 0.0
    S.diag(1)[:] = 0.0
    S.diag(-1)[:] = 0.0  # the zero matrix: singular
    with pytest.raises(SolveError, match="singular"):
        solve_band(S, np.ones(n), what="zero beam")


@pytest.mark.parametrize("shape, reach", [((300, 300), 40), ((340, 300), 25), ((120, 300), 3)])
def test_gram_is_the_sparse_product(shape, reach):
    """Band.gram(A, s) = s A^T A entry by entry within the inner products' rounding: each entry sums at most L
    products (L the most entries of a column), so each way is within gamma_L (|A|^T |A|) of the exact (Higham,
    Accuracy and Stability, eq. 3.4), and the two within twice that. Rows in any order, some empty, some reaching
    past the others (the appended rows of a ghost layer)."""
    rng = np.random.default_rng(7)
    nr, n = shape
    centre = rng.integers(0, n, nr)
    rows = np.repeat(np.arange(nr), 2 * reach + 1)
    cols = (centre[:, None] + np.arange(-reach, reach + 1)).ravel()
    keep = (cols >= 0) & (cols < n) & (rng.random(cols.size) < 0.9)
    A = sp.csr_matrix((rng.standard_normal(keep.sum()), (rows[keep], cols[keep])), shape=shape)
    A = A[np.r_[0 : nr // 2, nr // 2 + 5 : nr]]  # a few rows fewer, and empty rows kept by the shape below
    A = sp.vstack([A, sp.csr_matrix((3, n))]).tocsr()
    got = Band.gram(A, 2.5).toarray()
    want = (2.5 * (A.T @ A)).toarray()
    L = int(np.diff(A.tocsc().indptr).max())
    gamma = L * np.finfo(float).eps / (1 - L * np.finfo(float).eps)
    assert np.all(np.abs(got - want) <= 2 * gamma * 2.5 * (abs(A).T @ abs(A)).toarray() + 1e-300)
