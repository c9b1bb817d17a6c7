"""The entries' rounding groups (pdverify/numerics/rounding.py: significand_groups): values with equal |significand|
share a group, and the ids are the ranks of the sorted distinct significands, whatever the layout of the values
(runs along interleaved unknowns, padding first, no repeats at all)."""

import numpy as np
import pytest

from pdverify.numerics.rounding import SAMPLE, significand_groups


def reference(values: np.ndarray) -> tuple[np.ndarray, int]:
    """The definition, value by value: the rank of each value's |significand| among the distinct ones."""
    keys, group = np.unique(np.frexp(np.abs(np.ravel(values)))[0], return_inverse=True)
    return group, len(keys)


rng = np.random.default_rng(7)
LAYOUTS = {
    "one value": np.array([2.5]),
    "signs and powers of two": np.array([0.0, -0.0, 3.0, 1.5, -3.0, 6.0, 0.75]),
    "no repeats": rng.normal(size=5000),
    "few values, no order": rng.choice([1.0, 2.0, -0.5, 3.3, 0.0, 1e-300], size=5000),
    "two unknowns interleaved": np.tile([4.0, -1.25], 3000),
    "three interleaved, with end rows": np.r_[rng.normal(size=7), np.tile([1.0, 7.0, 7.0], 2000), rng.normal(size=5)],
    "a band past the sample, padding first": np.r_[np.zeros(SAMPLE), np.tile([3.0, 5.0, -2.0, 0.1], SAMPLE // 2)],
    "a period longer than any looked for": np.tile(rng.normal(size=11), 700),
    "past the sample, few repeats": np.r_[rng.normal(size=2 * SAMPLE), rng.choice([0.0, -0.0, 1.5], SAMPLE)],
}


@pytest.mark.parametrize("name", LAYOUTS)
def test_groups_are_the_ranks_of_the_distinct_significands(name):
    values = LAYOUTS[name]
    got, k = significand_groups(values)
    want, k_want = reference(values)
    assert k == k_want and np.array_equal(got, want) and got.dtype == np.int32


def test_a_band_keeps_its_shape_of_values():
    band = np.vstack([np.zeros(1000), np.tile([1.0, 2.0], 500), np.tile([-4.0, 2.0], 500)])
    got, k = significand_groups(band)
    assert k == 2 and np.array_equal(got, reference(band)[0])  # 0, and 1, 2, -4 (one significand)


def band_g(data: np.ndarray, upper: int, x: np.ndarray, b: np.ndarray):
    """The map G of the module docstring, dense, entry by entry from its definition (a band in LAPACK's layout)."""
    from pdverify.numerics.rounding import BandRounding

    m = BandRounding(data, upper, x, b)
    G = np.zeros(m.shape)
    n = data.shape[1]
    for r in range(data.shape[0]):
        o = upper - r
        for j in range(max(0, o), n + min(0, o)):
            if data[r, j]:
                G[j - o, m.gid[r, j]] += data[r, j] * x[j]
    G[np.arange(n), m.bgid] += b
    return m, G


def stencil_band(n: int, rows: int) -> np.ndarray:
    """A fourth-difference band (1, -4, 6, -4, 1) times 1.1, with its first and last ``rows`` columns perturbed."""
    data = np.outer([1.0, -4.0, 6.0, -4.0, 1.0], np.full(n, 1.1))
    data[:, :rows] *= 1.0 + rng.normal(size=(5, rows))
    data[:, n - rows :] *= 1.0 + rng.normal(size=(5, rows))
    return data


@pytest.mark.parametrize(
    "data", [stencil_band(400, 3), stencil_band(400, 0), rng.normal(size=(5, 400))], ids=["ends", "runs", "random"]
)
def test_the_band_products_are_g_and_its_transpose(data):
    """BandRounding's G z and G^T y (diagonal by diagonal, a repeated stencil's runs summed run by run) equal the dense
    G of the definition, to the rounding of their sums (400 terms of each sign at most: 1e3 eps of the terms' size)."""
    n = data.shape[1]
    x, b, y = rng.normal(size=n), rng.normal(size=n), rng.normal(size=n)
    m, G = band_g(data, 2, x, b)
    z = rng.normal(size=m.shape[1])
    eps = np.finfo(float).eps
    assert np.allclose(m.matvec(z), G @ z, rtol=0, atol=1e3 * eps * (np.abs(G) @ np.abs(z)).max())
    assert np.allclose(m.rmatvec(y), G.T @ y, rtol=0, atol=1e3 * eps * (np.abs(G.T) @ np.abs(y)).max())
    repeated = np.ptp(data[:, 10:-10], axis=1).max() == 0  # a stencil repeated inside: summed by its runs
    assert any(v is not None for v in m.runs.values()) == repeated


def csr_g(K, x: np.ndarray, b: np.ndarray, s: np.ndarray):
    """The map G of the module docstring, dense, entry by entry from its definition (a CSR matrix scaled by row)."""
    from pdverify.numerics.rounding import SharedRounding

    m = SharedRounding.from_csr(K, x, b, s)
    G = np.zeros(m.shape)
    C = K.tocoo()
    for e, (i, j, a) in enumerate(zip(C.row, C.col, C.data, strict=True)):
        G[i, m.gid[e]] += s[i] * a * x[j]
    G[np.arange(K.shape[0]), m.bgid] += s * b
    return m, G


def test_the_csr_products_are_g_and_its_transpose():
    """SharedRounding's G z and G^T y (the terms held as a CSR matrix whose columns are the groups, a group met twice in
    one row summed by the product) equal the dense G of the definition, and the same terms in COO give the same bits,
    on a matrix whose rows hold one value several times (the stencil (1, -2, 1) and its multiples by powers of
    two: one group)."""
    import scipy.sparse as sp

    from pdverify.numerics.rounding import SharedRounding

    n = 300
    K = sp.diags([np.full(n - 1, 1.0), np.full(n, -2.0), np.full(n - 1, 0.5)], [-1, 0, 1], format="lil")
    K[5, 20], K[7, 7] = 1.1 * rng.normal(), 3.3
    K = K.tocsr()
    x, b, s, y = rng.normal(size=n), rng.normal(size=n), rng.uniform(0.5, 2.0, n), rng.normal(size=n)
    m, G = csr_g(K, x, b, s)
    assert m.G.shape[1] == 3  # the matrix's groups: 1, -2 and 0.5; 1.1 x; 3.3
    z = rng.normal(size=m.shape[1])
    eps = np.finfo(float).eps
    assert np.allclose(m.matvec(z), G @ z, rtol=0, atol=8 * eps * (np.abs(G) @ np.abs(z)).max())
    assert np.allclose(m.rmatvec(y), G.T @ y, rtol=0, atol=n * eps * (np.abs(G.T) @ np.abs(y)).max())
    anyorder = SharedRounding(m.rows, K.tocoo().col, K.tocoo().data, x, b, s, n, 1.0, (m.gid, 3))  # no indptr: COO
    assert anyorder.G.format == "coo" and m.G.format == "csr"
    assert np.array_equal(anyorder.matvec(z), m.matvec(z)) and np.array_equal(anyorder.rmatvec(y), m.rmatvec(y))
