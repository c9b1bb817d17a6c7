"""Every solve carries a round-off bound, at every size, that holds its error.

The systems are integer matrices times integer solutions: b = A u* is exact in float64, so the error of
the computed u against u* is the solve's alone."""

import numpy as np
import pytest

from pdverify.numerics.band import Band
from pdverify.numerics.linalg import BOUND_LIMIT, SMALL, solve_linear


def fourth_difference(n: int) -> Band:
    """[1, -4, 6, -4, 1] (the clamped beam's stencil; cond ~ n^4 / 10), exact in float64."""
    return Band(n, 2, 2).add_stencil([-2, -1, 0, 1, 2], [1.0, -4.0, 6.0, -4.0, 1.0])


def exact_pair(A: Band, seed: int = 0):
    u = np.random.default_rng(seed).integers(-1000, 1000, size=A.n).astype(float)
    return u, A.matvec(u)  # integers below 2^53: exact


@pytest.mark.parametrize("n", [2_000, SMALL + 10_000])
def test_the_bound_holds_the_error_of_an_ill_conditioned_system(n):
    """Both paths (converted and refined up to 20,000 unknowns, in place above). Measured: n = 2,000
    error 7e-11, bound 4e-4 (the data term: a worst case over the entries' rounding); n = 30,000 error
    7e-3, bound 56."""
    A = fourth_difference(n)
    u_star, b = exact_pair(A)
    u, info = solve_linear(A.copy(), b)
    err = np.abs(u - u_star).max() / np.abs(u).max()
    assert err <= info["error_bound"]
    assert info["error_bound"] > BOUND_LIMIT and any("round-off bound" in w for w in info["warnings"])


@pytest.mark.parametrize("n", [2_000, SMALL + 10_000])
def test_a_well_conditioned_system_is_not_warned(n):
    A = Band(n, 1, 1).add_stencil([-1, 0, 1], [-1.0, 4.0, -1.0])  # cond <= 3
    u_star, b = exact_pair(A, 1)  # measured: error 5e-21 .. 4e-20, bound 5e-15 (1e-13: 20x, any BLAS)
    u, info = solve_linear(A, b)
    assert np.abs(u - u_star).max() <= info["error_bound"] * np.abs(u).max() < 1e-13 * np.abs(u).max()
    assert "warnings" not in info


def test_the_bound_watches_the_named_unknowns():
    """Relative to the watched unknowns' largest value: a system whose other unknowns are 1e6 larger."""
    n = 4_000
    A = Band(n, 1, 1).add_stencil([-1, 0, 1], [-1.0, 4.0, -1.0])
    u_star, _ = exact_pair(A, 2)
    u_star[1::2] *= 1e6
    b = A.matvec(u_star)
    _, all_ = solve_linear(A.copy(), b)
    _, even = solve_linear(A.copy(), b, watch=np.arange(0, n, 2))
    assert even["error_bound"] > 1e3 * all_["error_bound"]


@pytest.mark.parametrize("n", [4_000, SMALL + 10_000])
def test_fields_in_other_units_are_bounded_each_against_its_own_size(n):
    """A tuple of fields: the largest of the fields' bounds, each relative to its own field (both paths)."""
    A = Band(n, 1, 1).add_stencil([-1, 0, 1], [-1.0, 4.0, -1.0])
    u_star, _ = exact_pair(A, 2)
    u_star[1::2] *= 1e6
    b = A.matvec(u_star)
    even, odd = np.arange(0, n, 2), np.arange(1, n, 2)
    bounds = [solve_linear(A.copy(), b, watch=w)[1]["error_bound"] for w in (even, odd)]
    _, both = solve_linear(A.copy(), b, watch=(odd, even))
    assert both["error_bound"] == max(bounds)


def test_a_solution_that_does_not_move_is_exact_not_unbounded():
    """Every load on the supports: b = 0, u = 0 exactly, whatever the matrix's rounding: bound 0, no warning (a
    relative bound of a zero solution would read inf and warn of nothing)."""
    A = fourth_difference(2_000)
    u, info = solve_linear(A, np.zeros(2_000))
    assert not u.any() and info["error_bound"] == 0.0 and "warnings" not in info


@pytest.mark.parametrize("bound", [BOUND_LIMIT * (1 + 1e-9), 1.04e-6, 3e-3])
def test_the_warning_tells_the_bound_from_the_limit(bound):
    """The warning's bound is shown with the digits that tell it from the limit ("round-off bound 1e-06 exceeds
    1e-06" before)."""
    from pdverify.numerics.error_bound import bound_warning

    shown = bound_warning(bound).split("round-off bound ")[1].split(" ")[0]
    assert float(shown) > BOUND_LIMIT and abs(float(shown) - bound) <= 0.05 * bound
