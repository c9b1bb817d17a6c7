"""Beam axis geometry: position, tangent angle and curvature as functions of the arc length s.

Axis types (scene ``[axis]``):

* ``straight``: r(s) = (s, 0) for s in [0, beam.length];
* ``arc``: r = R (cos a, sin a) with a = start_angle + s / R (counter-clockwise), opening angle Θ,
  length R Θ; curvature 1/R;
* ``polynomial``: y(x) = Σ c_i x^i on x_range = [x0, x1]; s(x) = ∫ sqrt(1 + y'²) dx (Gauss–Legendre),
  inverted by Newton; curvature y'' / (1 + y'²)^(3/2).

The plane is (x, y) with y playing the role of the straight beam's z (up). Tangent t = (cos θ, sin θ),
normal n = e_z × t = (-sin θ, cos θ), so for a straight beam t = +x and n = +z (up).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as P

from .scene import Axis


def _arclength_pairs(c: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """∫_a^b sqrt(1 + y'²) dx for arrays of intervals, 16-point Gauss–Legendre each."""
    gx, gw = np.polynomial.legendre.leggauss(16)
    dc = P.polyder(c)
    a, b = np.asarray(a, float)[:, None], np.asarray(b, float)[:, None]
    xs = (a + b) / 2 + (b - a) / 2 * gx[None, :]
    return np.sum((b - a) / 2 * gw[None, :] * np.sqrt(1 + P.polyval(xs, dc) ** 2), axis=1)


def _arclength(c: np.ndarray, x0: float, x: np.ndarray, panels: int = 32) -> np.ndarray:
    """s(x) from x0 for many x (composite Gauss–Legendre, round-off accurate for smooth y)."""
    x = np.atleast_1d(np.asarray(x, float))
    edges = x0 + (x[:, None] - x0) * np.linspace(0, 1, panels + 1)[None, :]
    return _arclength_pairs(c, edges[:, :-1].ravel(), edges[:, 1:].ravel()).reshape(x.size, panels).sum(axis=1)


def axis_length(axis: Axis, straight_length: float | None = None) -> float:
    if axis.type == "straight":
        return float(straight_length) if straight_length is not None else float("nan")
    if axis.type == "arc":
        return float(axis.radius * np.deg2rad(axis.opening_angle_deg))
    c = np.asarray(axis.coefficients, float)
    x0, x1 = axis.x_range
    return float(_arclength(c, x0, np.array([x1]))[0])


@dataclass(frozen=True)
class AxisGeometry:
    """Evaluate the axis at arc lengths s: ``position(s)`` (n, 2), ``angle(s)`` θ, ``curvature(s)`` κ = dθ/ds."""

    axis: Axis
    length: float

    def _x_of_s(self, s) -> np.ndarray:
        """Invert s(x): a dense table for the start, then Newton to round-off."""
        c = np.asarray(self.axis.coefficients, float)
        x0, x1 = self.axis.x_range
        dc = P.polyder(c)
        s = np.asarray(s, float)
        nodes = np.linspace(x0, x1, 2001)
        table = np.concatenate([[0.0], np.cumsum(_arclength_pairs(c, nodes[:-1], nodes[1:]))])
        x = np.interp(s.ravel(), table, nodes)
        for _ in range(30):
            step = (_arclength(c, x0, x) - s.ravel()) / np.sqrt(1 + P.polyval(x, dc) ** 2)
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
            ang = np.deg2rad(a.start_angle_deg) + s / a.radius
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
            return np.deg2rad(a.start_angle_deg) + s / a.radius + np.pi / 2
        x = self._x_of_s(s)
        return np.arctan(P.polyval(x, P.polyder(np.asarray(a.coefficients, float))))

    def curvature(self, s) -> np.ndarray:
        s = np.asarray(s, float)
        a = self.axis
        if a.type == "straight":
            return np.zeros_like(s)
        if a.type == "arc":
            return np.full_like(s, 1.0 / a.radius)
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
