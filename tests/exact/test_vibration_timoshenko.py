"""The Timoshenko beam's natural frequencies (pdverify/exact/vibration.py: TimoshenkoBeam.scan): the first ``count``
roots of the characteristic determinant, the same whatever count is asked and in what order."""

import numpy as np
import pytest

from pdverify.exact.vibration import TimoshenkoBeam

HELD_W = (True, False)  # a pinned or roller end: w held, the rotation free


def pinned_pinned(slenderness: float) -> TimoshenkoBeam:
    """A rectangle of depth 1 / slenderness on a unit span, E = rho = 1, nu = 1/3, k = 5/6."""
    h = 1.0 / slenderness
    A, I, G = h, h**3 / 12, 1.0 / (2 * (1 + 1 / 3))
    return TimoshenkoBeam(I, 5 / 6 * G * A, A, I, 1.0, HELD_W, HELD_W)


@pytest.mark.parametrize("slenderness", [40.0, 13.3, 5.0, 2.0])
def test_the_cut_off_counts_only_once_the_scan_passes_it(slenderness):
    """Pinned-pinned, both ends free in rotation: w = 0 with a uniform rotation is a mode at the cut-off
    sqrt(kGA / rho I), known before the scan reaches it. It counted at once, so asking for k modes stopped one root
    early and gave the cut-off as mode k (L/h = 13.3: 10475 Hz as the 5th mode where it is 1794 Hz). The first k of
    every count are the same, and the cut-off is a mode where it falls among them."""
    beam = pinned_pinned(slenderness)
    everything = TimoshenkoBeam(beam.EI, beam.kGA, beam.rA, beam.rI, 1.0, HELD_W, HELD_W).scan(12)
    for count in range(1, 12):
        fresh = TimoshenkoBeam(beam.EI, beam.kGA, beam.rA, beam.rI, 1.0, HELD_W, HELD_W).scan(count)
        assert np.array_equal(fresh, everything[:count]), count
    assert np.all(np.diff(everything) > 0)
    if everything[-1] > beam.cutoff:  # L/h = 2: the cut-off is the 3rd mode
        assert np.isclose(everything, beam.cutoff, rtol=1e-9).sum() == 1
