"""The classical elastic-perfectly plastic Euler-Bernoulli beam on statically determinate scenes, for the tests of the
bond-pair load path: M(x) by statics, kappa(M) by inverting the section's fibre law (pdverify.core.section), w by
integrating kappa twice (trapezoid on 200,001 points: 1e-10 relative); unloading is elastic."""

import numpy as np
from scipy.integrate import cumulative_trapezoid

X = 200001


def kappa_of(profile, E, sy):
    """kappa(M) of the section: the fibre law M(kappa) inverted on a fine grid (monotone, exact at its nodes)."""
    ky = sy / E / profile.extreme_fibre
    k = np.r_[np.linspace(0.0, ky, 50), ky * np.geomspace(1.0 + 1e-9, 200.0, 200001)]
    M = profile.fibre_moment(k, E, sy)
    return lambda m: np.sign(m) * np.interp(np.abs(m), M, k)


def deflections(kappa, x, held: str):
    """w with w'' = kappa: ``pinned`` w(0) = w(L) = 0, ``clamped`` w(0) = w'(0) = 0."""
    w = cumulative_trapezoid(cumulative_trapezoid(kappa, x, initial=0.0), x, initial=0.0)
    return w - w[-1] * x / x[-1] if held == "pinned" else w


def simply_supported_uniform(profile, E, sy, L, q):
    """(x, w loaded, w unloaded) under the uniform load q (up positive)."""
    x = np.linspace(0.0, L, X)
    M = -q * x * (L - x) / 2
    k = kappa_of(profile, E, sy)(M)
    return x, deflections(k, x, "pinned"), deflections(k - M / (E * profile.inertia), x, "pinned")


def cantilever_tip(profile, E, sy, L, P):
    """(x, w loaded, w unloaded), clamped at 0, the force P (up positive) at L."""
    x = np.linspace(0.0, L, X)
    M = P * (L - x)
    k = kappa_of(profile, E, sy)(M)
    return x, deflections(k, x, "clamped"), deflections(k - M / (E * profile.inertia), x, "clamped")
