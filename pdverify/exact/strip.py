"""Exact plane-stress solution of a simply supported strip loaded on its top face by p0 sin(pi x / L).

Timoshenko & Goodier, *Theory of Elasticity* (3rd ed., 1970), §24 "Solution of the two-dimensional problem in
the form of a Fourier series": an Airy stress function phi = sin(alpha x) f(z), alpha = pi / L, with
sigma_xx = phi_zz, sigma_zz = phi_xx, tau_xz = -phi_xz solves the biharmonic equation when

    f'''' - 2 alpha^2 f'' + alpha^4 f = 0,
    f = A cosh(alpha z) + C z sinh(alpha z) + B sinh(alpha z) + D z cosh(alpha z).

Strip 0 <= x <= L, -c <= z <= c (c = h/2), z up. Face conditions (the traction p(x) = p0 sin(alpha x) per unit area
on the top face, +z; the bottom face free): sigma_zz(x, c) = p, sigma_zz(x, -c) = 0, tau_xz(x, +-c) = 0, i.e.
f(c) = -p0 / alpha^2, f(-c) = 0, f'(+-c) = 0. Split into the even part (A, C) and the odd part (B, D), each
carrying -p0 / (2 alpha^2) at z = c with zero slope at z = c: two 2 x 2 systems. The ends x = 0, L carry
sigma_xx = 0 and the shear traction tau_xz(0, z) of the solution itself (their resultant is the support reaction),
so "simply supported" here means exactly these end tractions; the beam models and the plane-stress reference load
the ends differently, which by Saint-Venant changes the stresses only within ~ h of the ends.

Displacements (plane stress, e_xx = (s_xx - nu s_zz)/E, e_zz = (s_zz - nu s_xx)/E, gamma = 2 (1 + nu) tau / E),
integrated with no rigid motion (w = 0 at both ends for every z; mean u over the left end face zero):

    w = sin(alpha x) [f''' / alpha^2 - (2 + nu) f'] / E,    u = -cos(alpha x) (f'' + nu alpha^2 f) / (alpha E) + u0

(the z-independent part of the compatibility condition, f''' / alpha - alpha^3 F - 2 alpha f' = const, is what makes
w's integration constant drop out). Checked in tests/exact/test_exact.py: the strains of (u, w) are those of the
stresses, the face conditions hold, and for a slender strip sigma_xx tends to M z / I.
"""

from __future__ import annotations

import numpy as np


def _coefficients(alpha: float, c: float, p0: float) -> tuple[float, float, float, float]:
    ac = alpha * c
    ch, sh = np.cosh(ac), np.sinh(ac)
    rhs = np.array([-p0 / (2 * alpha**2), 0.0])
    # even part: f_e(c) = A ch + C c sh, f_e'(c) = A alpha sh + C (sh + ac ch)
    A, C = np.linalg.solve(np.array([[ch, c * sh], [alpha * sh, sh + ac * ch]]), rhs)
    # odd part: f_o(c) = B sh + D c ch, f_o'(c) = B alpha ch + D (ch + ac sh)
    B, D = np.linalg.solve(np.array([[sh, c * ch], [alpha * ch, ch + ac * sh]]), rhs)
    return A, B, C, D


def _f(alpha: float, z: np.ndarray, A: float, B: float, C: float, D: float) -> tuple[np.ndarray, ...]:
    """f, f', f'', f''' at z."""
    a = alpha
    ch, sh = np.cosh(a * z), np.sinh(a * z)
    f = A * ch + B * sh + C * z * sh + D * z * ch
    f1 = A * a * sh + B * a * ch + C * (sh + a * z * ch) + D * (ch + a * z * sh)
    f2 = A * a**2 * ch + B * a**2 * sh + C * (2 * a * ch + a**2 * z * sh) + D * (2 * a * sh + a**2 * z * ch)
    f3 = A * a**3 * sh + B * a**3 * ch + C * (3 * a**2 * sh + a**3 * z * ch) + D * (3 * a**2 * ch + a**3 * z * sh)
    return f, f1, f2, f3


def sine_loaded_strip(
    x, z, length: float, height: float, youngs_modulus: float, poissons_ratio: float, p0: float
) -> dict[str, np.ndarray]:
    """Stresses and displacements at the points (x, z) (broadcast) of the strip of the module docstring.

    ``p0``: the top-face traction's amplitude per unit area (+z; a beam load q0 sin(pi x / L) in N/m on a
    section of width b gives p0 = q0 / b). Returns sigma_xx, sigma_zz, tau_xz (Pa), u, w (m)."""
    x, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(z, float))
    alpha, E, nu = np.pi / length, youngs_modulus, poissons_ratio
    A, B, C, D = _coefficients(alpha, height / 2, p0)
    f, f1, f2, f3 = _f(alpha, z, A, B, C, D)
    s, co = np.sin(alpha * x), np.cos(alpha * x)
    c = height / 2
    zf = np.linspace(-c, c, 201)  # u0: the mean of u over the left end face is zero (Simpson, exact to 1e-12)
    g = _f(alpha, zf, A, B, C, D)
    wts = np.r_[1, np.tile([4, 2], 99), 4, 1] / (3 * 200)
    u0 = float(np.sum(wts * (g[2] + nu * alpha**2 * g[0]))) / (alpha * E)
    return {
        "sigma_xx": s * f2,
        "sigma_zz": -(alpha**2) * s * f,
        "tau_xz": -alpha * co * f1,
        "w": s * (f3 / alpha**2 - (2 + nu) * f1) / E,
        "u": -co * (f2 + nu * alpha**2 * f) / (alpha * E) + u0,
    }
