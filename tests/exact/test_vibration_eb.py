"""The Euler-Bernoulli beam's natural frequencies (pdverify.exact.vibration_eb) against the textbook roots."""

import numpy as np
import pytest

from pdverify.exact.vibration import beam_end
from pdverify.exact.vibration_eb import eb_frequencies, eb_roots

# beta L of the first five modes (Blevins, Formulas for natural frequency and mode shape, Table 8-1; the higher
# ones from the asymptotic forms (2k -+ 1) pi / 2 + small terms, to the digits given)
ROOTS = {
    ("clamped", "free"): [1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839],
    ("pinned", "pinned"): [np.pi * k for k in range(1, 6)],
    ("clamped", "clamped"): [4.73004074, 7.85320462, 10.99560784, 14.13716549, 17.27875966],
    ("clamped", "pinned"): [3.92660231, 7.06858275, 10.21017612, 13.35176878, 16.49336143],
    ("clamped", "guided"): [2.36502037, 5.49780392, 8.63937983, 11.78097245, 14.92256510],
    ("pinned", "guided"): [(k - 0.5) * np.pi for k in range(1, 6)],
}


@pytest.mark.parametrize("pair", list(ROOTS))
def test_roots_are_the_textbook_ones(pair):
    """To the 9 digits the table gives (and both orientations alike)."""
    for left, right in (pair, pair[::-1]):
        z = eb_roots(beam_end(left), beam_end(right), 5)
        assert np.abs(z - ROOTS[pair]).max() < 1e-8


def test_frequencies_scale_as_the_formula():
    """omega = (beta L)^2 sqrt(EI / rho A) / L^2: a beam twice as long vibrates four times slower."""
    a = eb_frequencies(2.0, 3.0, 1.0, beam_end("pinned"), beam_end("pinned"), 3)
    b = eb_frequencies(2.0, 3.0, 2.0, beam_end("pinned"), beam_end("pinned"), 3)
    assert np.allclose(a, (np.pi * np.arange(1, 4)) ** 2 * np.sqrt(2.0 / 3.0), rtol=1e-14)
    assert np.allclose(a / b, 4.0, rtol=1e-14)
