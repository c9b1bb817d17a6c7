"""A load path reduced to one curve (pdverify/measure/paths.py): the load factor against the deflection at the point
where it is largest at the path's largest factor."""

import numpy as np

from pdverify.measure.paths import peak_history


def test_the_peak_point_is_taken_at_the_largest_factor_and_followed_along_the_path():
    x = np.linspace(0.0, 2.0, 5)
    shape = np.array([0.0, -1.0, -2.0, -1.5, 0.0])  # largest at x = 1
    steps = [{"factor": f, "w": f * shape + r * np.array([0, 0, 0, -3.0, 0])} for f, r in ((0, 0), (1, 0), (0, 0.5))]
    got = peak_history(x, steps)  # the residual step's largest |w| (x = 1.5) is not the peak point
    assert got["x"] == 1.0 and np.array_equal(got["factor"], [0, 1, 0]) and np.array_equal(got["w"], [0, -2.0, 0])


def test_steps_without_deflections_at_the_points_give_no_curve():
    x = np.linspace(0.0, 1.0, 3)
    assert peak_history(x, []) is None
    assert peak_history(x, [{"factor": 1.0, "w": np.zeros(4)}]) is None
