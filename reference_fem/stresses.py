"""Stresses of a ``fem-plane-stress`` solution: at given points (through-section profiles at stations) and at
the nodes (the VTU's fields), from the displacement gradient of the element basis (no smoothing).

Plane stress (thickness = section width; lam = the plane-stress Lame constant E nu / (1 - nu^2), mu = G):
sigma_xx = lam (e_xx + e_zz) + 2 mu e_xx, sigma_zz = lam (e_xx + e_zz) + 2 mu e_zz, tau_xz = 2 mu e_xz,
von Mises (plane stress) = sqrt(s_xx^2 - s_xx s_zz + s_zz^2 + 3 tau^2).
"""

from __future__ import annotations

import numpy as np


def _components(grad: np.ndarray, lam: float, mu: float) -> dict[str, np.ndarray]:
    """Stress components from the displacement gradient grad[i, j] = du_i/dx_j (any trailing shape)."""
    exx, ezz, exz = grad[0, 0], grad[1, 1], 0.5 * (grad[0, 1] + grad[1, 0])
    sxx = lam * (exx + ezz) + 2 * mu * exx
    szz = lam * (exx + ezz) + 2 * mu * ezz
    txz = 2 * mu * exz
    vm = np.sqrt(sxx**2 - sxx * szz + szz**2 + 3 * txz**2)
    return {"sigma_xx": sxx, "sigma_zz": szz, "tau_xz": txz, "von_mises": vm}


def gradient_at(basis, u: np.ndarray, points: np.ndarray, elements: np.ndarray) -> np.ndarray:
    """du_i/dx_j (2, 2, N) at the physical points (2, N) inside the given elements (N,): the reference
    coordinates by the mapping's Newton inverse, then the element's basis gradients there, all points at once
    (one pass per local basis function)."""
    X = basis.mapping.invF(points[:, :, None], tind=elements)  # (2, N, 1) reference coordinates
    grad = np.zeros((2, 2, points.shape[1]))
    for i in range(basis.Nbfun):
        g = basis.elem.gbasis(basis.mapping, X, i, tind=elements)[0].grad[..., 0]  # (2, 2, N)
        grad += u[basis.element_dofs[i, elements]] * g
    return grad


def at_points(basis, u: np.ndarray, points: np.ndarray, lam: float, mu: float) -> dict[str, np.ndarray]:
    """Stresses at physical points (2, N) of a straight-edged mesh (a point on an element edge is taken in one
    of the elements that share it)."""
    elements = basis.mesh.element_finder()(points[0], points[1])
    return _components(gradient_at(basis, u, points, elements), lam, mu)


def through_section(
    basis, u: np.ndarray, stations: np.ndarray, height: float, samples: int, lam: float, mu: float
) -> list[dict]:
    """Profiles sigma_xx(z), sigma_zz(z), tau_xz(z) at each station x (straight axis along x, z from -h/2 to
    h/2 in ``samples`` points): [{"x": x, "z": [...], "sigma_xx": [...], ...}, ...]."""
    z = np.linspace(-height / 2, height / 2, samples)
    xs = np.repeat(np.asarray(stations, float), samples)
    s = at_points(basis, u, np.vstack([xs, np.tile(z, len(stations))]), lam, mu)
    out = []
    for k, x in enumerate(stations):
        part = slice(k * samples, (k + 1) * samples)
        out.append(
            {"x": float(x), "z": z.tolist(), **{c: s[c][part].tolist() for c in ("sigma_xx", "sigma_zz", "tau_xz")}}
        )
    return out
