"""The derivative of a point field between its jumps and kinks (`pdverify/numerics/recovery.py`): the shear force
V = dM/dx of the beams' recovered moments."""

import numpy as np

from pdverify.numerics.recovery import derivative


def moment(x, edges, q):
    """A moment whose shear kinks at ``edges`` (a load per length q on [edges[0], edges[1]], zero elsewhere): M'' = q
    there, V = M' continuous; exact (M, V)."""
    a, b = edges
    s = np.clip(x, a, b)
    V = 100.0 + q * (s - a)
    M = 100.0 * x + q * np.where(x < a, 0.0, np.where(x > b, (b - a) * (x - b) + (b - a) ** 2 / 2, (s - a) ** 2 / 2))
    return M, V


def test_kinks_a_spacing_or_two_apart_are_differenced_across_and_mirror():
    """Two load edges 1.4 spacings apart (a short load) on 41 points: cutting at both left stretches of one or two
    points, whose one-sided differences (and a gap filled from the left) put V 5 % of its largest value off on one
    side of the load and not on the other. Differenced across, V is first order at the points beside them only."""
    x = np.linspace(0.0, 2.0, 41)
    dx = x[1] - x[0]
    edges = (0.3, 0.3 + 1.4 * dx)
    M, V = moment(x, edges, -4000.0)
    got = derivative(x, M, kinks=edges)
    assert np.abs(got - V).max() <= 0.5 * 4000.0 * dx  # half the load on a spacing: first order at a point
    far = np.abs(x - 0.335) > 3 * dx
    assert np.abs(got - V)[far].max() <= 1e-9 * np.abs(V).max()  # second order elsewhere: exact on a quadratic
    mirrored = derivative(x, M[::-1], kinks=(x[-1] - edges[1], x[-1] - edges[0]))[::-1]
    assert np.abs(mirrored + got).max() <= 1e-9 * np.abs(V).max()  # the mirror image's shear, mirrored


def test_kinks_far_apart_are_cut_as_jumps_are():
    """Kinks with three points or more on each side: one-sided differences on each side, exact on a piecewise
    quadratic moment, the point on a kink the mean of its sides' extrapolations."""
    x = np.linspace(0.0, 2.0, 41)
    M, V = moment(x, (0.5, 1.2), -4000.0)
    assert np.abs(derivative(x, M, kinks=(0.5, 1.2)) - V).max() <= 1e-9 * np.abs(V).max()
    assert np.abs(derivative(x, M) - V).max() > 10.0  # not cut: first order beside each kink
