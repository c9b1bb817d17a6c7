"""The local higher-order beam theory of Yang, Oterkus & Oterkus 2020 that ``pd-higher-order`` discretises and
``exact-higher-order`` solves exactly: the kinematics u = z theta + z^3 theta*, w = w + z^2 w* (four unknowns per
point, in this order), the coefficients of the plane-stress energy density Q = m^T C m of the bond measures
(Eq. 9 / Eq. 15) and the work of a point load on the four unknowns (Eq. 16b)."""

from __future__ import annotations

import numpy as np

from ..core.scene import PointForce, PointMoment

NF = 4  # DOFs per point: theta, theta*, w, w*
TH, TS, W, WS = range(NF)


def coefficients(E: float, nu: float, G: float, h: float) -> np.ndarray:
    """C (5x5) of Q = m^T C m for the bond measures m = (a, s, c, g, e): Eq. 9 / Eq. 15."""
    Ep = E / (1.0 - nu * nu)
    C = np.zeros((5, 5))
    C[0, 0] = C[1, 1] = Ep * h**3 / 12
    C[0, 1] = C[1, 0] = Ep * h**3 / 12 * nu
    C[2, 0] = C[0, 2] = Ep * h**5 / 80
    C[2, 1] = C[1, 2] = Ep * h**5 / 80 * nu
    C[2, 2] = Ep * h**7 / 448
    C[3, 3] = G * h
    C[4, 4] = G * h**5 / 80
    C[3, 4] = C[4, 3] = G * h**3 / 12
    return C


def point_work(load: PointForce | PointMoment, h: float, faces: bool, at_end: bool) -> np.ndarray:
    """The generalised force (theta, theta*, w, w*) of a point load, the coefficients of its work (Eq. 16b; with
    ``faces``, where the plane-stress reference applies it): a force P on w, and on w* P h^2/4 on the top face,
    P h^2/20 as an end's parabolic shear; a counter-clockwise moment C as -C on theta, and at an end (a linear
    normal traction) -3 C h^2/20 on theta*."""
    g = np.zeros(NF)
    if isinstance(load, PointForce):
        g[W] = load.value
        if faces:
            g[WS] = load.value * h * h * (1 / 20 if at_end else 1 / 4)
    else:
        g[TH] = -load.value
        if faces and at_end:
            g[TS] = -load.value * 3 * h * h / 20
    return g


D1 = np.zeros((5, 4))
D1[[0, 2, 3, 4], [0, 1, 2, 3]] = 1.0  # a = theta', c = theta*', g = w' + ..., e = w*' + ...
D0 = np.zeros((5, 4))
D0[[1, 3, 4], [3, 0, 1]] = 2.0, 1.0, 3.0  # s = 2 w*, g = ... + theta, e = ... + 3 theta*


def system_matrix(nu: float, shear_ratio: float) -> np.ndarray:
    """M (8 x 8) of z' = M z for z = (y, N), the theory's equilibrium (Eq. 9) as a first-order system along the beam,
    in units of h and E' b h; shear_ratio = G / E'."""
    C = coefficients(1.0 - nu * nu, nu, shear_ratio, 1.0)  # E' = 1
    K11, K10, K00 = D1.T @ C @ D1, D1.T @ C @ D0, D0.T @ C @ D0
    Ki = np.linalg.inv(K11)
    return np.block([[-Ki @ K10, Ki], [K00 - K10.T @ Ki @ K10, K10.T @ Ki]])


def layer_width(nu: float, shear_ratio: float, h: float) -> float:
    """The widest of the boundary layers an end or a load starts (the eigenvalues of :func:`system_matrix` off 0
    are of order 1/h; the layer decays as exp(-Re(lambda) x / h)): h / min |Re lambda|. About 0.11 h at nu = 0.3."""
    lam = np.linalg.eigvals(system_matrix(nu, shear_ratio))
    fast = np.abs(lam.real)[np.abs(lam) > 1e-3 * np.abs(lam).max()]
    return float(h / fast.min())
