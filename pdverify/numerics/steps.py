"""How many time steps (or output samples) a run asks for, refused past a stated limit before the loop starts.

A transient run takes ``end_time / time_step`` steps; a time step of 1e-30 s or an end time of 1e30 s asks for
~1e27, which no machine finishes. The count is checked when the step is known, before any step is taken, and a
count over ``MAX_STEPS`` is an :class:`~pdverify.core.errors.InputError` (exit 2) naming the fields and the fix.
"""

from __future__ import annotations

import math

from ..core.errors import InputError

MAX_STEPS = 10_000_000  # time steps of one run: ~10^7 explicit steps of a 1,000-point beam take minutes
MAX_SAMPLES = 10_000_000  # output samples of one history (dynamics.output_interval)


def step_count(end_time: float, dt: float, given: bool, limit: int = MAX_STEPS) -> int:
    """ceil(end_time / dt) (an end time within 1e-9 steps of a whole number of them takes that number), or an
    InputError when it passes ``limit``; ``given``: the step is the scene's ``dynamics.time_step`` (else the model's
    stable step, which only a shorter end time or a coarser grid lengthens)."""
    n = float(end_time) / float(dt)
    if not n <= limit:  # also nan
        fix = (
            "shorten dynamics.end_time or lengthen dynamics.time_step"
            if given
            else "shorten dynamics.end_time or use fewer points (the stable step grows with the spacing)"
        )
        raise InputError(
            f"dynamics.end_time = {end_time:g} s with a time step of {dt:.3g} s is {n:.3g} steps, over the limit of "
            f"{limit:.0e}: {fix}"
        )
    return max(1, int(math.ceil(n - 1e-9)))


def sample_count(end_time: float, interval: float, limit: int = MAX_SAMPLES) -> int:
    """round(end_time / interval) output samples, or an InputError naming dynamics.output_interval."""
    n = float(end_time) / float(interval)
    if not n <= limit:
        raise InputError(
            f"dynamics.output_interval = {interval:g} s is {n:.3g} samples of dynamics.end_time = {end_time:g} s, over "
            f"the limit of {limit:.0e}: lengthen output_interval or leave it out (2,000 samples)"
        )
    return max(1, int(round(n)))
