"""Beam axis geometry: position, tangent angle and curvature as functions of the arc length s.

Axis types (scene ``[axis]``):

* ``straight``: r(s) = (s, 0) for s in [0, beam.length];
* ``arc``: r = R (cos a, sin a) with a = start_angle + σ s / R, σ = +1 (``direction = "counterclockwise"``,
  the default) or -1 (``"clockwise"``), opening angle Θ, length R Θ; tangent angle a + σ π/2, curvature σ/R
  (signed: κ = dθ/ds). The clockwise arc from start angle 180° - a0 is the mirror image about x = 0 of the
  counter-clockwise one from a0, with the same s at mirrored points;
* ``polynomial``: y(x) = Σ c_i x^i on x_range = [x0, x1]; s(x) = ∫ sqrt(1 + y'²) dx (Gauss–Legendre),
  inverted by Newton; curvature y'' / (1 + y'²)^(3/2).

The plane is (x, y) with y playing the role of the straight beam's z (up). Tangent t = (cos θ, sin θ),
normal n = e_z × t = (-sin θ, cos θ), so for a straight beam t = +x and n = +z (up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as P

from .scene import HELD, Axis

_GL16 = np.polynomial.legendre.leggauss(16)


def arclength_pairs(c: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """∫_a^b sqrt(1 + y'²) dx for arrays of intervals, 16-point Gauss–Legendre each."""
    gx, gw = _GL16
    dc = P.polyder(c)
    a, b = np.asarray(a, float)[:, None], np.asarray(b, float)[:, None]
    xs = (a + b) / 2 + (b - a) / 2 * gx[None, :]
    return np.sum((b - a) / 2 * gw[None, :] * np.sqrt(1 + P.polyval(xs, dc) ** 2), axis=1)


def arclength(c: np.ndarray, x0: float, x: np.ndarray, panels: int = 32) -> np.ndarray:
    """s(x) from x0 for many x (composite Gauss–Legendre, round-off accurate for smooth y)."""
    x = np.atleast_1d(np.asarray(x, float))
    edges = x0 + (x[:, None] - x0) * np.linspace(0, 1, panels + 1)[None, :]
    return arclength_pairs(c, edges[:, :-1].ravel(), edges[:, 1:].ravel()).reshape(x.size, panels).sum(axis=1)


def axis_length(axis: Axis, straight_length: float | None = None) -> float:
    if axis.type == "straight":
        return float(straight_length) if straight_length is not None else float("nan")
    if axis.type == "arc":
        return float(axis.radius * np.deg2rad(axis.opening_angle_deg))
    c = np.asarray(axis.coefficients, float)
    x0, x1 = axis.x_range
    return float(arclength(c, x0, np.array([x1]))[0])


def start_angle(axis: Axis) -> float:
    """The arc's start angle in radians, reduced to one turn in degrees first: fmod is exact in floating point,
    whereas the radians of 1e15 degrees carry an error of ~1e-3 in their sine and cosine."""
    return float(np.deg2rad(math.fmod(axis.start_angle_deg, 360.0)))


def _turn(axis: Axis) -> float:
    """σ = +1 for a counter-clockwise arc, -1 for a clockwise one (the sign of its curvature)."""
    return -1.0 if axis.direction == "clockwise" else 1.0


@dataclass(frozen=True)
class AxisGeometry:
    """Evaluate the axis at arc lengths s: ``position(s)`` (n, 2), ``angle(s)`` θ, ``curvature(s)`` κ = dθ/ds."""

    axis: Axis
    length: float

    def _x_of_s(self, s) -> np.ndarray:
        """Invert s(x): a dense table for the start, then Newton to round-off (:meth:`abscissae`)."""
        return self.abscissae(s)

    def abscissae(self, s, local: bool = False) -> np.ndarray:
        """x(s) on a polynomial axis: s(x) inverted by Newton from a start read off a dense table (2001 nodes).

        ``local = False``: each step integrates s from x0 (:func:`arclength`, 32 panels of 16 points).
        ``local = True`` (pd-curved, many particles): each step integrates from the table node below the start
        (one panel over about 1/2000 of the axis; the nodes' s by the composite rule from x0, at the nodes used
        only): 16 instead of 512 integrand values per point and step, bounded temporaries, the same root to
        round-off (the two differ by up to 4 ulp, each within 2 ulp of 40-digit roots:
        tests/papers/curved/test_pd_curved.py).
        """
        c = np.asarray(self.axis.coefficients, float)
        x0, x1 = (float(v) for v in self.axis.x_range)
        dc = P.polyder(c)
        s = np.asarray(s, float)
        sv = s.ravel()
        nodes = np.linspace(x0, x1, 2001)
        table = np.concatenate([[0.0], np.cumsum(arclength_pairs(c, nodes[:-1], nodes[1:]))])
        x = np.interp(sv, table, nodes)
        if local:
            j = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 1)
            used, inv = np.unique(j, return_inverse=True)
            base, a = arclength(c, x0, nodes[used])[inv], nodes[j]
        for _ in range(30):  # Newton iterations (converged in 2-3)
            s_x = base + arclength_pairs(c, a, x) if local else arclength(c, x0, x)
            step = (s_x - sv) / np.sqrt(1 + P.polyval(x, dc) ** 2)
            x = x - step
            if np.max(np.abs(step), initial=0.0) < 1e-15 * max(1.0, abs(x1 - x0)):
                break
        return x.reshape(s.shape)

    def position(self, s) -> np.ndarray:
        s = np.asarray(s, float)
        a = self.axis
        if a.type == "straight":
            return np.stack([s, np.zeros_like(s)], axis=-1)
        if a.type == "arc":
            ang = start_angle(a) + _turn(a) * s / a.radius
            return a.radius * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
        x = self._x_of_s(s)
        return np.stack([x, P.polyval(x, np.asarray(a.coefficients, float))], axis=-1)

    def angle(self, s) -> np.ndarray:
        """Tangent direction θ(s) (rad, from +x, counter-clockwise)."""
        s = np.asarray(s, float)
        a = self.axis
        if a.type == "straight":
            return np.zeros_like(s)
        if a.type == "arc":
            sigma = _turn(a)
            return start_angle(a) + sigma * (s / a.radius + np.pi / 2)
        x = self._x_of_s(s)
        return np.arctan(P.polyval(x, P.polyder(np.asarray(a.coefficients, float))))

    def curvature(self, s) -> np.ndarray:
        s = np.asarray(s, float)
        a = self.axis
        if a.type == "straight":
            return np.zeros_like(s)
        if a.type == "arc":
            return np.full_like(s, _turn(a) / a.radius)
        c = np.asarray(a.coefficients, float)
        x = self._x_of_s(s)
        d1, d2 = P.polyval(x, P.polyder(c)), P.polyval(x, P.polyder(c, 2))
        return d2 / (1 + d1**2) ** 1.5

    def frame(self, s) -> tuple[np.ndarray, np.ndarray]:
        """Unit tangent t and normal n = e_z × t at s, each (…, 2)."""
        th = self.angle(s)
        t = np.stack([np.cos(th), np.sin(th)], axis=-1)
        n = np.stack([-np.sin(th), np.cos(th)], axis=-1)
        return t, n


def geometry(scene) -> AxisGeometry:
    return AxisGeometry(scene.axis, scene.length)


# -- supports against the rigid-body motions of the plane ----------------------------------------------


def axis_abscissae(scene, s: np.ndarray) -> np.ndarray:
    """x(s) on the scene's polynomial axis, inverted once for many particles (:meth:`AxisGeometry.abscissae`,
    ``local = True``)."""
    return geometry(scene).abscissae(s, local=True)


def constraint_rows(scene) -> np.ndarray:
    """Rows (k, 3): what the two ends' supports hold, applied to the plane's rigid-body motions.

    A rigid motion is u(r) = (a - ω y, b + ω x), φ = ω (r relative to the left end). A held displacement along
    d at the end point r gives the row (d_x, d_y, (x d_y - y d_x) / L) acting on (a, b, ω L); a held rotation
    the row (0, 0, 1) (φ = ω, scaled by L; scaling a row keeps the rank). Which directions each support
    holds: :data:`pdverify.core.scene.HELD` (tangential, normal, rotation)."""

    geo = geometry(scene)
    L = scene.length
    s = np.array([0.0, L])
    r = geo.position(s)
    r = r - r[:1]
    t, n = geo.frame(s)
    rows = []
    for k, sup in enumerate((scene.supports.left, scene.supports.right)):
        held_t, held_n, held_phi = HELD[sup] if isinstance(sup, str) else (False, False, False)  # a spring: none
        for held, d in ((held_t, t[k]), (held_n, n[k])):
            if held:
                rows.append([d[0], d[1], (r[k, 0] * d[1] - r[k, 1] * d[0]) / L])
        if held_phi:
            rows.append([0.0, 0.0, 1.0])
    return np.array(rows, float).reshape(-1, 3)


RANK_TOL = 1e-8  # singular values below RANK_TOL x the largest count as zero: geometry is known to round-off,
# and a near-mechanism this close would amplify the loads by > 1e8 anyway


def rigid_body_modes(scene) -> np.ndarray:
    """The rigid-body motions (a, b, ω L) the supports leave free, one per row (an orthonormal basis of the
    null space of :func:`constraint_rows`; empty when the supports hold the beam in the plane)."""
    C = constraint_rows(scene)
    if C.shape[0] == 0:
        return np.eye(3)
    _, sv, Vt = np.linalg.svd(C)
    rank = int(np.sum(sv > RANK_TOL * sv[0]))
    return Vt[rank:]


def _describe(mode: np.ndarray, scene) -> str:
    a, b, wl = mode
    L = scene.length
    if abs(wl) < RANK_TOL:
        d = np.where(np.abs([a, b]) < RANK_TOL, 0.0, [a, b])
        d = (d if d[np.argmax(np.abs(d))] > 0 else -d) + 0.0  # the sign is arbitrary: show it positive (no -0)
        return f"a rigid translation along ({d[0]:.4g}, {d[1]:.4g})"
    centre = geometry(scene).position(np.array([0.0]))[0] + np.array([-b, a]) * L / wl
    centre = np.where(np.abs(centre) < RANK_TOL * L, 0.0, centre)
    return f"a rigid rotation about ({centre[0]:.6g}, {centre[1]:.6g})"


def mechanism_message(scene) -> str | None:
    """One line naming the supports and the rigid-body motion they leave free, or None when there is none.

    The 3-column rank test of :func:`constraint_rows`: e.g. a ring (360° arc) pinned at both ends (both pins
    at one point: the rotation about it is free), roller ends on an arc (their normals meet at the centre),
    a straight beam on two rollers (the axial translation is free)."""
    modes = rigid_body_modes(scene)
    if len(modes) == 0:
        return None
    one = len(modes) == 1
    what = _describe(modes[0], scene) if one else f"{len(modes)} independent rigid-body motions"
    return (
        f"supports = {scene.supports.left}-{scene.supports.right}: a mechanism on this {scene.axis.type} axis "
        f"({what} {'is' if one else 'are'} not held by the supports' displacement and rotation conditions); hold "
        "more at one end "
        "(e.g. clamped, or pinned instead of roller)"
    )
