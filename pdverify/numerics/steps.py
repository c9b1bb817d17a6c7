"""How many output samples a run asks for (and its time steps: :func:`pdverify.numerics.timeint.step_count`), refused
past a stated limit before the loop starts.

A transient run takes ``end_time / time_step`` steps; a time step of 1e-30 s or an end time of 1e30 s asks for
~1e27, which no machine finishes. The count is checked when the step is known, before any step is taken, and a
count over ``MAX_STEPS`` is an :class:`~pdverify.core.errors.InputError` (exit 2) naming the fields and the fix.
"""

from __future__ import annotations

from ..core.errors import InputError
from .timeint import MAX_STEPS, step_count  # noqa: F401 (the count of a run's steps, re-exported beside the samples')

MAX_SAMPLES = 10_000_000  # output samples of one history (dynamics.output_interval)


def sample_count(end_time: float, interval: float, limit: int = MAX_SAMPLES) -> int:
    """round(end_time / interval) output samples, or an InputError naming dynamics.output_interval."""
    n = float(end_time) / float(interval)
    if not n <= limit:
        raise InputError(
            f"dynamics.output_interval = {interval:g} s is {n:.3g} samples of dynamics.end_time = {end_time:g} s, over "
            f"the limit of {limit:.0e}: lengthen output_interval or leave it out (2,000 samples)"
        )
    return max(1, int(round(n)))
