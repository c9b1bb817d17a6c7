"""The continuous-alpha variant's known bias: the size of its error on any grid, for the warning its results carry."""

from __future__ import annotations

import numpy as np

from ...core.scene import Scene
from .calibration import pair_family
from .limit import end_kinds


def continuous_alpha_bias(m: float) -> str:
    """alpha = 3 EI / delta^3 (the continuous horizon integral of Eq. 5, delta = (m + 0.015) dx) on the family the
    operator sums is stiffer than the beam by s = sum_j j^2 beta_j / ((m + 0.015)^3 / 3), so every deflection is too
    small by 1 - 1 / s on any grid, or too large by 1 / s - 1 where s < 1 (docs/models/ogrady.md, "Calibration of
    alpha")."""
    j, beta = pair_family(m, 1.0, "continuous-alpha")
    stiff = float(np.sum(j**2 * beta)) / ((m + 0.015) ** 3 / 3.0)
    size = f"{1 - 1 / stiff:.1%} too small" if stiff >= 1 else f"{1 / stiff - 1:.1%} too large"
    return (
        f"variant = continuous-alpha does not converge to the beam: its alpha makes every deflection {size} at "
        f"horizon {m:g}, on any grid; variant = paper or corrected converges"
    )


TAYLOR_HORIZON = 4  # the largest horizon (spacings) at which Taylor ends at a free or guided end stay as accurate as
# mirror ends under a load the ghost polynomial cannot follow (docs/models/ogrady.md, "Taylor ends at large horizons")


def taylor_end_bias(scene: Scene, params: dict) -> list[str]:
    """Taylor ghost ends (docs/design/formulas.md §1) carry a degree-4 polynomial fitted to the first points over the
    whole horizon: at a free or guided end under a sine-shaped load (the scene's one load whose solution is not a
    piecewise polynomial) their error grows much faster with the horizon than the model's nonlocality."""
    kinds = end_kinds(scene)
    sine = any(ld.type == "distributed" and ld.shape == "sine" for ld in scene.loads)
    if params["ends"] != "taylor" or not kinds & {"free", "guided"} or not sine or params["horizon"] <= TAYLOR_HORIZON:
        return []
    return [
        f"ends = taylor at a free or guided end with horizon {params['horizon']:g} > {TAYLOR_HORIZON}: the ghost "
        "polynomial is carried over the whole horizon and its error grows faster than the model's (a cantilever "
        "under a sine load, 321 points: 3.5e-4, 1.0e-3, 1.6e-2 at horizon 6, 8, 16, where mirror ends give 1.6e-4, "
        f"2.8e-4, 1.2e-3); use ends = mirror or horizon <= {TAYLOR_HORIZON}"
    ]


def bias_warnings(scene: Scene, params: dict) -> list[str]:
    """The known biases of the run's variant and ends, if it has any."""
    out = [continuous_alpha_bias(params["horizon"])] if params["variant"] == "continuous-alpha" else []
    return out + taylor_end_bias(scene, params)
