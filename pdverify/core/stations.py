"""Stations along the axis for through-section outputs (option ``stations`` of fem-plane-stress and
pd-higher-order): positions in the scene's length unit, as in a load's ``position``."""

from __future__ import annotations

import numpy as np

from .errors import InputError

STATIONS_HELP = (
    "through-section stresses sigma_xx(z), sigma_zz(z), tau_xz(z) at these positions along the axis, comma "
    "separated, e.g. '0.25,0.5' (m, as a load's position; '' = none): info.sections"
)


def parse_stations(value: str, length: float) -> np.ndarray:
    """The positions of ``value`` ("0.25,0.5"), each within [0, length]; empty for ''."""
    text = str(value).strip()
    if not text:
        return np.zeros(0)
    try:
        xs = np.array([float(p) for p in text.split(",")])
    except ValueError:
        raise InputError(f"stations = {value!r}: give positions separated by commas, e.g. '0.25,0.5'") from None
    bad = xs[~np.isfinite(xs) | (xs < 0) | (xs > length)]
    if len(bad):
        raise InputError(f"stations = {value!r}: {bad[0]:g} is not on the beam (0 <= x <= {length:g})")
    return xs
