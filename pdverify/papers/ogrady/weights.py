"""Cross-section weights omega(xi) of the bond pairs (O'Grady & Foster 2014, Eq. 6) and the moment-curvature law they
imply for elastic-perfectly plastic pairs (Eq. 7).

The paper maps a bond's length onto a fibre's distance from the neutral axis, y = (xi / delta)(t / 2), and from the
moment analogy M_E = ∫ E kappa y² b dy ~ M_PD = ∫ alpha kappa |xi| omega dxi takes (Eq. 6) omega = |xi| b(y). Under a
uniform curvature kappa a pair deviates by xi kappa and carries the moment a min(xi kappa, phi_c) (Eq. 7, the critical
angle phi_c = 2 delta eps_c / t), so the section moment is M(kappa) = alpha Σ_j omega_j beta_j dx xi_j min(xi_j kappa,
phi_c): it weights the fibre at y by omega(xi) xi, i.e. b y² for the paper's weight, one power of y more than the fibre
theory's ∫ b y sigma(y) dy. The weight that reproduces the fibre curve is omega = b(y) (``fibre``; each member the mean
of b over its cell): then M(kappa) = E ∫ b y min(y kappa, eps_c) dy in the limit of many members. Both are calibrated to
EI exactly (alpha from Eq. 5 / §3.1); they differ once pairs yield: the paper's weight gives the rectangle a shape
factor 4/3 (the fibre theory 3/2).
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.section import Profile
from .calibration import alpha, horizon_length, pair_family

WEIGHTS = ("uniform", "paper", "fibre")


def section_depth_map(profile: Profile, delta: float):
    """y(xi) = (xi / delta) c: the member at xi stands for the fibre at that distance from the centroid (c the extreme
    fibre's distance: t / 2 of a symmetric section)."""
    c = profile.extreme_fibre
    return lambda xi: np.asarray(xi, float) / delta * c


def check_section(profile: Profile | None, weight: str) -> None:
    """InputError when a section weight other than ``uniform`` cannot be made for ``profile``: none given, or one not
    symmetric about its centroid (a pair maps onto the fibres at +-y)."""
    if weight == "uniform":
        return
    if profile is None:
        raise InputError(
            f"weight = {weight}: a section weight needs the section's shape; give width and height or a shape"
        )
    if not profile.symmetric:
        raise InputError(
            f"weight = {weight}: the bond pairs map a pair onto the fibres at +-y, so the section must be symmetric "
            "about its centroid; use weight = uniform"
        )


def weights(profile: Profile | None, weight: str, m: float, dx: float, variant: str) -> np.ndarray | None:
    """omega_j of the family's members (None for ``uniform``): ``paper`` = xi_j b(y_j) (Eq. 6 at the member),
    ``fibre`` = the mean of b over the member's cell within the horizon (per its volume fraction)."""
    if weight == "uniform":
        return None
    check_section(profile, weight)
    j, beta = pair_family(m, dx, variant)
    delta = horizon_length(m, dx, variant)
    yc, y_of = profile.centroid, section_depth_map(profile, delta)
    xi = j * dx
    if weight == "paper":
        return xi * profile.width(yc + y_of(xi))
    # the member's cell within the horizon, mapped onto the fibres: omega beta dx = ∫_cell b(y(xi)) dxi
    lo, hi = y_of(np.clip(xi - dx / 2, 0.0, delta)), y_of(np.clip(xi + dx / 2, 0.0, delta))
    return profile.integral(0, yc + lo, yc + hi) * (delta / profile.extreme_fibre) / (beta * dx)


def critical_angle(profile: Profile, E: float, yield_stress: float, delta: float) -> float:
    """phi_c = 2 delta eps_c / t (Eq. 7: the longest pairs yield with the extreme fibre), t / 2 = the extreme fibre's
    distance from the centroid."""
    return delta * (yield_stress / E) / profile.extreme_fibre


def pd_moment_curvature(
    profile: Profile, E: float, yield_stress: float, weight: str, m: float, dx: float, variant: str, kappa
):
    """M(kappa) of the bond-pair beam under a uniform curvature from a straight, unstressed state, with
    elastic-perfectly plastic pairs (Eq. 7, small rotations): alpha Σ_j omega_j beta_j dx xi_j clip(xi_j kappa,
    phi_c)."""
    j, beta = pair_family(m, dx, variant)
    om = weights(profile, weight, m, dx, variant)
    om = np.ones(len(j)) if om is None else om
    a = alpha(E * profile.inertia, m, dx, variant, om)
    phi_c = critical_angle(profile, E, yield_stress, horizon_length(m, dx, variant))
    xi = j * dx
    k = np.asarray(kappa, float)[..., None]
    return a * np.sum(om * beta * dx * xi * np.clip(xi * k, -phi_c, phi_c), axis=-1)


def shape_factors(profile: Profile, weight: str, m: float, dx: float, variant: str) -> dict[str, float]:
    """The fully plastic over the first-yield moment of the bond-pair section (``pd``: the longest member yields first,
    at kappa = phi_c / xi_J) and of the fibre theory (``fibre`` = Z / S)."""
    E, sy = 1.0, 1.0  # the ratio depends on neither
    j, _ = pair_family(m, dx, variant)
    delta = horizon_length(m, dx, variant)
    phi_c = critical_angle(profile, E, sy, delta)
    k_first = phi_c / (j.max() * dx)
    My = float(pd_moment_curvature(profile, E, sy, weight, m, dx, variant, k_first))
    Mp = float(pd_moment_curvature(profile, E, sy, weight, m, dx, variant, 1e6 * k_first))
    return {"pd": Mp / My, "fibre": profile.shape_factor}


def moment_curvature_curve(
    profile: Profile, E: float, yield_stress: float, weight: str, m: float, dx: float, variant: str, points: int = 61
) -> dict[str, list[float]]:
    """:func:`pd_moment_curvature` from zero to six times the fibre theory's first-yield curvature
    (yield_stress / (E c), c the extreme fibre's distance), as lists: what the pairs' section does beside the
    classical law (:meth:`~pdverify.core.section.Profile.fibre_moment`)."""
    kappa = np.linspace(0.0, 6.0 * yield_stress / (E * profile.extreme_fibre), points)
    moment = pd_moment_curvature(profile, E, yield_stress, weight, m, dx, variant, kappa)
    return {"kappa": kappa.tolist(), "moment": np.asarray(moment, float).tolist()}
