"""PDDO functions (pdverify/models/_pddo.py): exactness for polynomials up to the degree, family
layout, the expected order on a smooth function, and the vectorised construction at 1e5 points."""

import math
import time

import numpy as np
import pytest

from pdverify.models._pddo import derivative_matrices, families, pddo_weights


def _grid(kind, n=31):
    if kind == "uniform":
        return np.linspace(0.0, 2.0, n)
    rng = np.random.default_rng(3)
    return np.sort(np.r_[0.0, rng.uniform(0, 2, n - 2), 2.0])


@pytest.mark.parametrize("kind", ["uniform", "random"])
@pytest.mark.parametrize("P", [2, 3, 4, 5, 6])
def test_polynomials_up_to_the_degree_are_exact(P, kind):
    s = _grid(kind)
    size = 2 * (P // 2) + 3
    fam = families(len(s), size)
    w = pddo_weights(s, fam, P, (0, 1, 2))
    for q in range(P + 1):
        f = (s - 0.7) ** q
        for r in (0, 1, 2):  # the orders pd-curved uses (higher ones are exact too, up to more round-off)
            exact = math.factorial(q) / math.factorial(q - r) * (s - 0.7) ** (q - r) if r <= q else 0 * s
            got = (w[r] * f[fam]).sum(axis=1)
            # round-off grows like cond(A) / h^r; h = the local family size
            h = np.abs(s[fam] - s[:, None]).max(axis=1)
            tol = 1e-7 * (2.0 ** q) / h**r  # cond(A) reaches 4e8 at P = 6
            assert np.all(np.abs(got - exact) <= tol), (P, q, r, np.abs(got - exact).max())


def test_degree_plus_one_is_not_exact():
    """The test above can fail: x^(P+1) is not differentiated exactly."""
    s = _grid("uniform")
    fam = families(len(s), 7)
    w = pddo_weights(s, fam, 4, (1, 2))
    f = s**6
    assert np.abs((w[2] * f[fam]).sum(axis=1) - 30 * s**4).max() > 1e-4


def test_families_shift_inward_and_keep_their_size():
    fam = families(10, 5)
    assert fam.shape == (10, 5)
    assert list(fam[0]) == [0, 1, 2, 3, 4] and list(fam[-1]) == [5, 6, 7, 8, 9]
    assert list(fam[5]) == [3, 4, 5, 6, 7]
    with pytest.raises(ValueError):
        families(4, 5)


@pytest.mark.parametrize("P, order", [(2, 2), (4, 4), (6, 6)])
def test_second_derivative_converges_at_the_expected_order(P, order):
    """Interior (centred) families: g^2 is exact for degree P + 1 by symmetry, so the error of f'' is
    O(h^P) (h the spacing) over the whole grid including the one-sided end families (O(h^(P-1)) there)."""
    errs = []
    for n in (41, 81):
        s = np.linspace(0, 1, n)
        D = derivative_matrices(s, P, 2 * (P // 2) + 3, (2,))[2]
        errs.append(np.abs(D @ np.sin(3 * s) + 9 * np.sin(3 * s))[n // 4: 3 * n // 4].max())
    assert math.log2(errs[0] / errs[1]) > order - 0.3


def test_one_hundred_thousand_points_in_seconds():
    s = np.linspace(0, 1, 100_001)
    t0 = time.perf_counter()
    D = derivative_matrices(s, 6, 9, (1, 2))
    elapsed = time.perf_counter() - t0
    assert D[2].shape == (100_001, 100_001)
    assert elapsed < 10.0, elapsed
