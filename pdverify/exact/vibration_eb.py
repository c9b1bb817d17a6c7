"""Natural frequencies of the uniform Euler-Bernoulli beam (textbook): EI w'''' = rho A omega^2 w, w = e^{lambda x}
with lambda^4 = beta^4 = rho A omega^2 / EI. The general solution written bounded,

    w = a cos(beta x) + b sin(beta x) + c e^{-beta x} + d e^{-beta (L - x)},

and each end's two conditions (it holds w, else the shear w''' = 0; it holds w', else the moment w'' = 0) give a
4 x 4 determinant in z = beta L whose entries stay of order one (every derivative divided by beta^k). Its roots,
bracketed by a scan in z and refined by Brent's method, are z_k; omega_k = z_k^2 sqrt(EI / (rho A)) / L^2
(clamped-free 1.8751, 4.6941, ...; pinned-pinned k pi).
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.optimize import brentq


def _rows(z: float, at_right: bool, held: tuple[bool, bool]) -> np.ndarray:
    """The two end-condition rows (of a, b, c, d) at x = 0 or L, in units where beta = 1 and L = z."""
    x = z if at_right else 0.0
    e1, e2 = np.exp(-x), np.exp(-(z - x))
    c, s = np.cos(x), np.sin(x)
    # k-th derivatives of (cos, sin, e^{-x}, e^{-(z - x)}) for k = 0..3
    der = [
        [c, s, e1, e2],
        [-s, c, -e1, e2],
        [-c, -s, e1, e2],
        [s, -c, -e1, e2],
    ]
    w_held, rot_held = held
    return np.array([der[0] if w_held else der[3], der[1] if rot_held else der[2]])


def determinant(z: float, left: tuple[bool, bool], right: tuple[bool, bool]) -> float:
    return float(np.linalg.det(np.vstack([_rows(z, False, left), _rows(z, True, right)])))


def eb_roots(left: tuple[bool, bool], right: tuple[bool, bool], count: int, step: float = 0.01) -> np.ndarray:
    """The first ``count`` roots z = beta L > 0 of the frequency equation (``left``, ``right``: (w held, w' held)).
    The scan starts past z = 0, where every pair has a root of the rigid or static solutions."""
    return np.array(_roots(tuple(left), tuple(right), count, step))


@functools.lru_cache(maxsize=64)
def _roots(left: tuple[bool, bool], right: tuple[bool, bool], count: int, step: float) -> tuple[float, ...]:
    out = []
    z0 = 0.05
    f0 = determinant(z0, left, right)
    while len(out) < count:
        z1 = z0 + step
        f1 = determinant(z1, left, right)
        if f0 == 0.0:
            out.append(z0)
        elif f0 * f1 < 0:
            out.append(brentq(determinant, z0, z1, args=(left, right), xtol=1e-15, rtol=1e-15))
        z0, f0 = z1, f1
        if z0 > (count + 2) * np.pi + 10:
            raise ValueError("no roots found: a mechanism")
    return tuple(out[:count])


def eb_frequencies(EI: float, rhoA: float, length: float, left, right, count: int) -> np.ndarray:
    """The first ``count`` circular frequencies (rad/s) of a uniform Euler-Bernoulli beam."""
    z = eb_roots(left, right, count)
    return z**2 * np.sqrt(EI / rhoA) / length**2
