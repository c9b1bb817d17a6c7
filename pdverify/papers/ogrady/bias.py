"""The continuous-alpha variant's known bias: the size of its error on any grid, for the warning its results carry."""

from __future__ import annotations

import numpy as np

from .calibration import pair_family


def continuous_alpha_bias(m: float) -> str:
    """alpha = 3 EI / delta^3 (the continuous horizon integral of Eq. 5, delta = (m + 0.015) dx) on the family the
    operator sums is stiffer than the beam by sum_j j^2 beta_j / ((m + 0.015)^3 / 3), so every deflection is too
    small by 1 - 1 / that on any grid (docs/models/ogrady.md, "Calibration of alpha")."""
    j, beta = pair_family(m, 1.0, "continuous-alpha")
    stiff = float(np.sum(j**2 * beta)) / ((m + 0.015) ** 3 / 3.0)
    return (
        f"variant = continuous-alpha does not converge to the beam: its alpha makes every deflection "
        f"{1 - 1 / stiff:.1%} too small at horizon {m:g}, on any grid; variant = paper or corrected converges"
    )


def bias_warnings(params: dict) -> list[str]:
    """The known bias of the run's variant, if it has one."""
    return [continuous_alpha_bias(params["horizon"])] if params["variant"] == "continuous-alpha" else []
