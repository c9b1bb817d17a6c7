"""Dispersion relations: frequency against wavenumber of a discrete operator's interior stencil and of the
continuum it discretises (the report draws them: pdverify/report/waves.py).

A wave u_p = û e^{i(kx_p - ωt)} on the interior rows M u_tt = -K u of a stencil {o: C_o} (nf x nf blocks,
:class:`~pdverify.papers.moyer.kernels.EndPatched`) gives ω² as the eigenvalues of M⁻¹ Σ_o C_o e^{i k Δ o}
(one branch per field: the rod's axial branch; the beam's bending and shear branches). The continuum: the
rod ω = c k; the Timoshenko beam (Timoshenko's frequency equation with w = e^{ikx})

    ρA ρI ω⁴ - ω² (ρA EI k² + ρI kGA k² + ρA kGA) + EI kGA k⁴ = 0,

the lower root the bending branch, the upper one the shear branch (ω → sqrt(kGA/ρI) as k → 0).
"""

from __future__ import annotations

import numpy as np


def stencil_branches(blocks: dict, mass: np.ndarray, kdx: np.ndarray) -> np.ndarray:
    """ω (rad/s) of the stencil's branches at the wavenumbers ``kdx`` = k Δ, (len(kdx), nf), ascending per
    row; a negative or complex ω² gives the square root of its real part (marked by its sign: -sqrt(-Re))."""
    kdx = np.atleast_1d(np.asarray(kdx, float))
    nf = len(mass)
    S = np.zeros((len(kdx), nf, nf), complex)
    for o, C in blocks.items():
        S += np.exp(1j * kdx * o)[:, None, None] * (np.asarray(C, float) / np.asarray(mass, float)[:, None])[None]
    lam = np.sort(np.linalg.eigvals(S).real, axis=1)
    return np.sign(lam) * np.sqrt(np.abs(lam))


def timoshenko_branches(k: np.ndarray, EI: float, kGA: float, rhoA: float, rhoI: float) -> np.ndarray:
    """(bending, shear) ω (rad/s) of the Timoshenko beam at wavenumbers k, (len(k), 2)."""
    k = np.atleast_1d(np.asarray(k, float))
    a = rhoA * rhoI
    b = rhoA * EI * k**2 + rhoI * kGA * k**2 + rhoA * kGA
    c = EI * kGA * k**4
    disc = np.sqrt(b * b - 4 * a * c)
    upper = (b + disc) / (2 * a)
    lower = c / (a * upper)  # the product of the roots is c/a: no cancellation at small k
    return np.sqrt(np.stack([lower, upper], 1))
