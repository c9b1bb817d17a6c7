"""The words of the round-off bound's warning (pdverify.numerics.error_bound.bound_warning)."""

from pdverify.numerics.error_bound import BOUND_LIMIT, NO_DIGIT, bound_warning


def test_a_bound_past_a_tenth_says_the_result_may_have_no_digit():
    """Sweep 16: a spring of 1e-9 N/m on pd-eb gave w 98 % off with 'round-off bound 0.3 ...: may be wrong to that
    degree' (the bound an estimate within a factor of about 3). Past NO_DIGIT the warning says the result may have no
    correct digit; below it, the size."""
    assert "may have no correct digit" in bound_warning(0.3) and "spring" in bound_warning(0.3)
    assert "may be wrong to that degree" in bound_warning(10 * BOUND_LIMIT)
    assert "may have no correct digit" not in bound_warning(NO_DIGIT)
