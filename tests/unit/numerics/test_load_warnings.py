"""The end-layer advice (pdverify.numerics.load_warnings: layer_fix) at a fixed horizon length."""

import pytest

from pdverify.numerics.load_warnings import layer_fix


@pytest.mark.parametrize("spacings", [7.0, 8.0, 8.5])
def test_the_advice_never_names_a_horizon_of_no_spacings(spacings):
    """A layer 2 horizons + 6 spacings wide, the load ``spacings`` from the end: where the horizon that leaves it is a
    spacing or less ("below 0.0375 (e.g. 0, 0 spacings)" for a load 8 spacings in, which the model then refused), the
    advice names a horizon of one spacing and the points that leave the layer; a whole number of spacings at least one
    otherwise."""
    dx = 3.0 / 160
    text = layer_fix(spacings * dx, dx, 3.0, 36.0, (2.0, 6.0, 0.3))
    if spacings - 6.0 > 2.0:
        assert "(e.g. " in text and float(text.split("(e.g. ")[1].split(",")[0]) >= dx
    else:  # one spacing on a grid whose (a + b) spacings fall short of the load's distance (sweep 34 S34-3)
        assert "(e.g. " not in text
        delta, points = text.split("give horizon_length = ")[1].split(" (one spacing) and ")
        fine = 3.0 / (int(points.split()[0]) - 1)
        assert float(delta) == pytest.approx(fine) and (2.0 + 6.0) * fine < spacings * dx
