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
