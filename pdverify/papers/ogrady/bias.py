"""The paper variant's known bias: the size of its error on any grid, for the warning its results carry."""

from __future__ import annotations

import numpy as np

from ...numerics.families import family


def paper_bias(m: float) -> str:
    """The paper variant's bias: alpha = 3 EI / delta^3 (the continuous horizon integral, delta = (m + 0.015) dx) on
    the family the operator sums, stiffer than the beam by sum_j j^2 beta_j / ((m + 0.015)^3 / 3), so every
    deflection is too small by 1 - 1 / that on any grid (docs/models/ogrady.md, "Calibration of alpha")."""
    j, beta = family(m, 1.0, "paper")
    stiff = float(np.sum(j**2 * beta)) / ((m + 0.015) ** 3 / 3.0)
    return (
        f"variant = paper does not converge to the beam: its alpha makes every deflection {1 - 1 / stiff:.1%} too "
        f"small at horizon {m:g}, on any grid; variant = corrected converges"
    )
