"""How many output samples a run asks for (and its time steps: :func:`pdverify.numerics.timeint.step_count`), refused
past a stated limit before the loop starts.

A transient run takes ``end_time / time_step`` steps; a time step of 1e-30 s or an end time of 1e30 s asks for
~1e27, which no machine finishes. The count is checked when the step is known, before any step is taken, and a
count over ``MAX_STEPS`` is an :class:`~pdverify.core.errors.InputError` (exit 2) naming the fields and the fix.
"""

from __future__ import annotations

import numpy as np

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


def aligned_steps(end_time: float, dt: float, output_interval: float | None, limit: float | None = None):
    """(steps, step) of a run whose histories are sampled every ``output_interval``: the largest step at most ``dt``
    that divides the interval, so that the samples fall on its multiples exactly (where a reference samples them:
    a step that does not divide it leaves each sample up to half a step off, a first-order error of a comparison),
    when ``end_time`` is a whole number of intervals; None otherwise, or without an interval, or with one shorter
    than ``dt`` (every step is then a sample). Both counts are checked against their limits (:func:`sample_count`,
    :func:`step_count`; ``limit``: the stable step, for the advice)."""
    if not output_interval or float(output_interval) < float(dt):
        return None
    sample_count(end_time, output_interval)
    intervals = float(end_time) / float(output_interval)
    whole = round(intervals)
    if whole < 1 or abs(intervals - whole) > 1e-9 * max(1.0, intervals):
        return None
    per = max(1, int(np.ceil(float(output_interval) / float(dt) - 1e-9)))
    step = float(end_time) / (whole * per)
    step_count(end_time, step, "default", limit)
    return whole * per, step
