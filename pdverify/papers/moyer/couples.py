"""Point couples on the nonlocal bending of variant ``energy`` (:mod:`.energy`).

A couple C at a makes the exact rotation kink there: γ' = M/EI steps by -C/EI. The bending bonds reach a horizon
δ = mΔ, so a couple put on one or two points' rotation rows is felt by the bonds as a load, not as a kink: the
discrete γ then differs from the kinked one by O(δ C/EI) within a horizon of a (first order in the rotation's largest
error; the deflection, its integral, stays second order). Instead the couple is applied as the operator's own action
on the kink: with the singular part of the exact solution

    γ_s = -(x - a)₊ / EI,   w_s = -(x - a)₊² / (2 EI)    (towards the left end: -(a - x)₊ / EI, (a - x)₊² / (2 EI))

(w_s' = γ_s: no shear strain), the load is K (C u_s) on the rows within the horizon and the shear stencil of a,
(m + 3) Δ, and zero elsewhere (away from a the operator is exact on γ_s, a straight line; the end row that its
slope would load is left out). Its rows carry the couple C and no net force, and the exactly kinked solution solves
them: the rotation is second order up to the couple. The ramp runs towards the end farther from a, which must lie
beyond those rows with no segment interface on the way; where none does (a beam a few horizons long), the couple
is put on the two points around it as before.
"""

from __future__ import annotations

import numpy as np

from ...core.scene import Scene


def couple_column(op, scene: Scene, x: np.ndarray, m: int, weights: np.ndarray, a: float):
    """(rows, u_s): the rows (per length, interleaved w, γ) of a unit counter-clockwise couple at a and the singular
    part u_s they are the action of (module docstring); None where no ramp fits."""
    dx = x[1] - x[0]
    reach = (m + 3) * dx
    L = x[-1]
    cuts = [g.end for g in scene.segments[:-1]]
    for side in sorted((1, -1), key=lambda s: -(L - a if s == 1 else a)):  # the farther end first
        far = L - a if side == 1 else a
        beyond = [c for c in cuts if (c - a) * side > -reach]
        if far <= reach + dx or beyond:
            continue
        EI = _stiffness_at(scene, a)
        r = np.maximum(side * (x - a), 0.0)
        g = -r / EI  # the slope of γ steps by -1/EI at a
        w = -side * r**2 / (2 * EI)  # w' = γ
        us = np.column_stack((w, g)).ravel()
        col = op @ us
        near = np.repeat(np.abs(x - a) <= reach, 2)
        col = np.where(near, col, 0.0)
        couple, force = _resultants(col, x, a, weights)
        # the rows' sums cancel terms of the shear stiffness's size: their rounding, eps times the same sums of
        # |K| |u_s|, grows as (L/h)^2 and is allowed beside the ramp's exactness
        size = np.where(near, abs(op.tocsr()) @ np.abs(us), 0.0)
        c_size, f_size = _resultants(size, x, a, weights, np.abs)
        tol = 1e-8 + RESULTANT_ROUNDING * np.finfo(float).eps * np.array([c_size, f_size * L])
        if abs(couple - 1.0) <= tol[0] and abs(force) * L <= tol[1]:
            return col, us
    return None


RESULTANT_ROUNDING = 64  # a few dozen roundings per term of the rows' sums (the stencil's entries, the volumes)


def _resultants(col, x, a, weights, arm=lambda v: v):
    """(couple, force) of the rows ``col`` (interleaved w, γ, per length) about a."""
    dx = x[1] - x[0]
    couple = float((col[1::2] * weights[1::2]).sum() * dx + (col[0::2] * weights[0::2] * arm(x - a)).sum() * dx)
    return couple, float((col[0::2] * weights[0::2]).sum() * dx)


def _stiffness_at(scene: Scene, a: float) -> float:
    for start, end, sec, mat in scene.pieces():
        if start <= a <= end:
            return mat.E * sec.I
    return scene.EI
