"""The moment and shear of ``fem-eb`` and ``fem-timoshenko``: each element's end forces, at the nodes (the mean of
the two elements' values at an inner node) and anywhere between them by the element's statics. Arrays in, arrays
out; the models are in :mod:`reference_fem.beam`."""

from __future__ import annotations

import numpy as np

from pdverify.core.scene import Scene
from pdverify.numerics.loads import support_side

from .beam_elements import element_properties, line_load, nodal_point_loads


def end_forces(ke: np.ndarray, fe: np.ndarray, nodes: np.ndarray, u: np.ndarray, moments=None) -> np.ndarray:
    """(n_el, 4): the force and counter-clockwise moment on each element at its left and right end, k_e u_e - f_e
    (exact where the nodal values are: the element is in equilibrium with its loads). ``moments``: the two-field
    form's (p, q) per element (:func:`~reference_fem.beam_elements.natural_band`), whose k_e u_e is T^T m =
    (2p / l, p + q, -2p / l, p - q) exactly: first differences of the solved moments, where k_e u_e takes third
    differences of the nodal w (k ~ EI / l³), which lose the shear's digits on short elements and fine grids."""
    if moments is None:
        ue = np.stack([u[0:-2:2], u[1:-2:2], u[2::2], u[3::2]], axis=1)
        return np.einsum("eab,eb->ea", ke, ue) - fe
    p, q = moments
    force = 2 * p / np.diff(nodes)
    return np.stack([force, p + q, -force, p - q], axis=1) - fe


def nodal(scene: Scene, nodes: np.ndarray, end: np.ndarray) -> dict:
    """The bending moment M (sagging positive) and shear force V = dM/dx at the nodes from the elements' ``end``
    forces: at an inner node the mean of its two elements' values, which differ where a point load makes V, and a
    couple M, jump; at the end nodes the support's side, every load on them acting (as exact-eb gives them)."""
    last = nodal_point_loads(scene, nodes, 2)[-2:]  # the force and couple at the right end's node
    # on an element's left end the force is +V and the counter-clockwise moment -M; on its right end -V and +M
    M = np.r_[-end[0, 1], (end[:-1, 3] - end[1:, 1]) / 2, end[-1, 3] - last[1]]
    V = np.r_[end[0, 0], (end[1:, 0] - end[:-1, 2]) / 2, -end[-1, 2] + last[0]]
    return {"M": support_side(scene, M, "moment", ("left",)), "V": support_side(scene, V, "shear", ("left",))}


def statics(scene: Scene, nodes: np.ndarray, end: np.ndarray, w: np.ndarray, rotation: np.ndarray, shear: bool):
    """x -> {"w", "rotation", "M", "V"} anywhere on the beam: each element's left-end values (the nodal w and
    rotation, its ``end`` forces) carried across it by its distributed load q (point loads, supports and span ends
    are nodes). With M'' = V' = q, theta' = M / EI and w' - theta = -V / kGA (``shear`` False, Euler-Bernoulli: 0):
    V = V_0 + ∫ q, M = M_0 + V_0 t + ∫ (t - u) q, theta = theta_0 + (M_0 t + V_0 t²/2 + ∫ (t - u)²/2 q) / EI,
    w = w_0 + theta_0 t + (M_0 t²/2 + V_0 t³/6 + ∫ (t - u)³/6 q) / EI - (V_0 t + ∫ (t - u) q) / kGA, the integrals
    by 8-point Gauss. On a node, the element to its right (the left end's for the last node)."""
    m0, v0 = -end[:, 1], end[:, 0]
    EI, kGA = element_properties(scene, nodes)
    flex = 1.0 / kGA if shear else np.zeros_like(kGA)  # shear flexibility
    g, wg = np.polynomial.legendre.leggauss(8)

    def resultants(x):
        e = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 2)
        t = x - nodes[e]
        s = t[..., None] * (g + 1) / 2  # Gauss points on [0, t]
        q = t[..., None] / 2 * wg * line_load(scene, nodes[e][..., None] + s, nodes)  # weights folded in
        d = t[..., None] - s
        V = v0[e] + np.sum(q, axis=-1)
        M = m0[e] + v0[e] * t + np.sum(d * q, axis=-1)
        theta = rotation[e] + (m0[e] * t + v0[e] * t**2 / 2 + np.sum(d**2 / 2 * q, axis=-1)) / EI[e]
        bent = w[e] + rotation[e] * t + (m0[e] * t**2 / 2 + v0[e] * t**3 / 6 + np.sum(d**3 / 6 * q, axis=-1)) / EI[e]
        return {"w": bent - flex[e] * (v0[e] * t + np.sum(d * q, axis=-1)), "rotation": theta, "M": M, "V": V}

    return resultants
