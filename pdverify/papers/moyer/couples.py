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
them: the rotation is second order up to the couple. The ramp runs towards an end beyond those rows, one with no
segment joint on the way first, then the farther; through a joint the moment stays -1, so γ_s' = -1/EI steps with
EI (the compliance integrated piece by piece: :func:`singular_part`), which the bonds across it (harmonic means of
the pieces' EI, :mod:`.pieces`) carry exactly.
Where no end lies beyond the rows (a beam a few horizons long) or a joint lies within them (the kink and the change
of section would share rows), the couple is put on the two points around it, warned (:func:`couple_warnings`).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import Scene
from ...core.text import spacings
from ...numerics.load_warnings import layer_fix


def couple_column(op, scene: Scene, x: np.ndarray, m: int, weights: np.ndarray, a: float):
    """(rows, u_s): the rows (per length, interleaved w, γ) of a unit counter-clockwise couple at a and the singular
    part u_s they are the action of (module docstring); None where no ramp fits."""
    dx = x[1] - x[0]
    reach = (m + 3) * dx
    L = x[-1]
    if near_joint(scene, a, reach) is not None:  # the rows about a would mix two stiffnesses
        return None
    cuts = [g.end for g in scene.segments[:-1]]
    crosses = {side: any((c - a) * side > 0 for c in cuts) for side in (1, -1)}
    # an end reached without crossing a joint first (the end reactions come out closer), then the farther
    for side in sorted((1, -1), key=lambda s: (crosses[s], -(L - a if s == 1 else a))):
        far = L - a if side == 1 else a
        if far <= reach + dx:
            continue
        g, w = singular_part(stiffness_pieces(scene), x, a, side)
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


def shear_free(scene: Scene, x: np.ndarray, a: float, us: np.ndarray) -> np.ndarray:
    """The kink of a couple's singular part ``us`` (interleaved w, γ; ramped to the side where it is not zero) at a
    alone: γ = -(x - a)₊ / EI(a) and w with w' = γ on that side, through any joint. Its intervals' discrete shear strain
    is zero away from a (a quadratic w, a linear γ), where ``us``'s is not at the joints it bends at: what the
    recovered shear takes out of the solution instead of ``us``."""
    side = 1 if np.abs(us[1::2][x > a]).max(initial=0.0) > 0.0 else -1
    EI = float(scene.stiffness_at(np.array([a]))["EI"][0])
    g, w = singular_part([(float(x[0]), float(x[-1]), EI)], x, a, side)  # one piece: the stiffness at a throughout
    return np.column_stack((w, g)).ravel()


def near_joint(scene: Scene, a: float, reach: float) -> float | None:
    """The segment joint nearest a when it lies within ``reach`` of it (the couple's rows), else None."""
    cuts = [g.end for g in scene.segments[:-1]]
    near = min(cuts, key=lambda c: abs(c - a), default=None)
    return near if near is not None and abs(near - a) < reach else None


def couple_warnings(scene: Scene, m: int, dx: float, fixed: tuple | None) -> list[str]:
    """Point couples off a joint but within the (m + 3) spacings of their rows from one (on a joint:
    ``couple_at_joint_warnings``): put on the two points around them, the rotation near them first order; ``fixed``
    as :func:`~pdverify.numerics.load_warnings.layer_fix`'s (a fixed horizon length)."""
    out, tol = [], 1e-9 * scene.length
    for i, ld in enumerate(scene.loads):
        if ld.type != "point_moment" or ld.value == 0.0 or (j := near_joint(scene, ld.position, (m + 3) * dx)) is None:
            continue
        d = abs(ld.position - j)
        if d > tol:
            out.append(
                f"loads[{i}], a point moment at {ld.position:g}, is {spacings(d / dx)} from the segment joint at "
                f"{j:g}, inside the {spacings(m + 3, 'g')} its kink's rows reach: it is put on the two points around "
                f"it and the rotation near it is first order in the spacing ({NEAR_JOINT}); "
                + layer_fix(d, dx, scene.length, m + 3, fixed)
            )
    return out


NEAR_JOINT = "measured 4.5e-2 of max |rotation| at 161 points, 3.2 spacings from a joint"
RESULTANT_ROUNDING = 64  # a few dozen roundings per term of the rows' sums (the stencil's entries, the volumes)


def _resultants(col, x, a, weights, arm=lambda v: v):
    """(couple, force) of the rows ``col`` (interleaved w, γ, per length) about a."""
    dx = x[1] - x[0]
    couple = float((col[1::2] * weights[1::2]).sum() * dx + (col[0::2] * weights[0::2] * arm(x - a)).sum() * dx)
    return couple, float((col[0::2] * weights[0::2]).sum() * dx)


def stiffness_pieces(scene: Scene) -> list[tuple[float, float, float]]:
    """(start, end, EI) of each stretch of the beam (:meth:`~pdverify.core.scene.Scene.pieces`)."""
    return [(start, end, mat.E * sec.I) for start, end, sec, mat in scene.pieces()]


def singular_part(pieces, x: np.ndarray, a: float, side: int) -> tuple[np.ndarray, np.ndarray]:
    """(γ_s, w_s) at x of a unit couple at a, ramped towards the end ``side`` (+1 right, -1 left): the moment -1 on
    that side, γ_s' = -1/EI through every piece (start, end, EI) of ``pieces`` on the way (γ_s = -∫ ds/EI, the
    compliance integrated piece by piece), w_s' = γ_s; zero on the other side."""
    t = side * (x - a)  # the distance from a towards that end
    g, w = np.zeros_like(x), np.zeros_like(x)
    for start, end, EI in pieces:
        q0, q1 = sorted((side * (start - a), side * (end - a)))
        q0 = max(q0, 0.0)
        if q1 <= q0:
            continue
        length, s = q1 - q0, np.clip(t - q0, 0.0, q1 - q0)  # the stretch of [a, x] in this piece
        g -= s / EI
        w -= (s * s / 2 + length * np.maximum(t - q1, 0.0)) / EI  # its integral over [a, x]
    return g, side * w
