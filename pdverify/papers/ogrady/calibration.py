"""The bond-pair families and the calibration of alpha (O'Grady & Foster 2014, Eq. 5 and §3.1).

Energy equivalence under a uniform curvature kappa (Eq. 3–5): a pair of bonds of length xi deviates from straight
by xi kappa, so the bending energy of a point's family is (alpha / 2) kappa² Σ_j omega_j xi_j² beta_j dx per unit
length, and alpha = EI / Σ_j omega_j xi_j² beta_j dx carries EI exactly. The variants differ in the family they sum
and in whether the sum is the discrete one:

* ``paper``: §3.1, alpha = c dx / m with c = EI and m = Σ_{i=1}^{n} omega(xi_i) xi_i² over the n points within
  delta = m dx (whole nodes, beta = 1; the horizon may be fractional: the nodes with xi <= delta);
* ``corrected``: the same discrete sum over the cells' parts inside delta (beta = 1/2 for the last member at a
  whole m), so that a point's family is the segment [-delta, delta] exactly;
* ``continuous-alpha``: a reconstruction from the truncated text, not the paper: the continuous integral of Eq. 5,
  alpha = 3 EI / delta³ (omega = 1), with delta = (m + 0.015) dx (Diyaroglu et al.'s horizon) on whole cells.
  On the family the operator sums it is too stiff by Σ_j j² / ((m + 0.015)³ / 3): 1.53 at m = 3.
"""

from __future__ import annotations

import numpy as np

from ...numerics.families import family

VARIANTS = ("corrected", "paper", "continuous-alpha")


def pair_family(m: float, dx: float, variant: str) -> tuple[np.ndarray, np.ndarray]:
    """(j, beta): the family's offsets j = 1..J (xi_j = j dx) and volume fractions of ``variant``."""
    if variant == "paper":
        J = int(np.floor(m + 1e-9))
        return np.arange(1, J + 1), np.ones(J)
    if variant == "continuous-alpha":
        return family(m, dx, "paper")  # whole cells within (m + 0.015) dx
    return family(m, dx, "corrected")


def horizon_length(m: float, dx: float, variant: str) -> float:
    """delta of ``variant``: (m + 0.015) dx for ``continuous-alpha``, m dx otherwise."""
    return (m + (0.015 if variant == "continuous-alpha" else 0.0)) * dx


def alpha(EI, m: float, dx: float, variant: str, omega=None):
    """alpha of Eq. 5 (``continuous-alpha``) or of its discrete form (§3.1; ``paper``, ``corrected``); ``omega``:
    the weights omega_j of the family's members (default 1). ``EI`` may be an array (one alpha per value)."""
    j, beta = pair_family(m, dx, variant)
    if variant == "continuous-alpha":
        if omega is not None:
            raise ValueError("continuous-alpha is defined for omega = 1")
        return 3.0 * np.asarray(EI) / horizon_length(m, dx, variant) ** 3
    om = np.ones(len(j)) if omega is None else np.asarray(omega, float)
    return np.asarray(EI) / np.sum(om * (j * dx) ** 2 * beta * dx)


def spring_constants(EI: float, m: float, dx: float, variant: str, omega=None) -> np.ndarray:
    """c_j = alpha omega_j beta_j dx / xi_j² of the linear operator Σ_j c_j D_j² w = q (D_j the second difference
    over offset j): Σ_j c_j xi_j⁴ = EI for the discrete calibrations."""
    j, beta = pair_family(m, dx, variant)
    om = np.ones(len(j)) if omega is None else np.asarray(omega, float)
    return alpha(EI, m, dx, variant, omega) * om * beta * dx / (j * dx) ** 2


def calibration_name(variant: str) -> str:
    """What ``info["alpha_calibration"]`` says of ``variant``."""
    return {
        "paper": "discrete, whole nodes within delta (O'Grady & Foster 2014, §3.1)",
        "corrected": "discrete, the cells' parts inside delta",
        "continuous-alpha": "continuous (3 EI / delta^3, a reconstruction)",
    }[variant]
