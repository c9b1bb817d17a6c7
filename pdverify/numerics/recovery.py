"""Derivatives of a point field that does not cross its jumps: the shear force V = dM/dx of a moment recovered at the
points, where a point force or a support inside the span makes V jump. Arrays in, arrays out."""

from __future__ import annotations

import numpy as np


def jump_positions(scene, quantity: str) -> np.ndarray:
    """Where ``quantity`` jumps or kinks, so that a difference of its parent must not straddle it: the shear (the
    derivative of the moment) jumps at point forces and supports inside the span that hold the deflection and kinks
    where a distributed load starts or ends; the moment (EI times the derivative of the rotation) jumps at couples
    and clamped inner supports and the curvature at interfaces."""
    at = []
    for load in scene.loads:
        if quantity == "shear" and load.type == "point_force" and load.value != 0.0:
            at.append(load.position)
        if quantity == "moment" and load.type == "point_moment" and load.value != 0.0:
            at.append(load.position)
    for s in scene.supports.inner:
        if (quantity == "shear" and s.holds_deflection) or (quantity == "moment" and s.holds_rotation):
            at.append(s.position)
    if quantity == "moment":
        at += [g.start for g in scene.segments[1:]]
    if quantity == "shear":  # where the load per length jumps, V kinks: a difference across it is first order
        for load in scene.loads:
            if load.type == "distributed" and load.value != 0.0:
                at += [v for v in scene.span(load) if 0.0 < v < scene.length]
    return np.array(sorted(at), float)


def derivative(x: np.ndarray, f: np.ndarray, jumps=()) -> np.ndarray:
    """df/dx at the points x (uniform spacing) by second-order differences within each stretch between jumps
    (``numpy.gradient``: central inside a stretch, one-sided at its ends), so that no difference takes values from
    both sides of a jump; first order on a stretch of two points, the neighbour's value on one of a single point. At
    a point exactly on a jump (whose own value is ambiguous) the mean of the two stretches' quadratic
    extrapolations to it (second order where the derivative only kinks there)."""
    x, f = np.asarray(x, float), np.asarray(f, float)
    n = len(x)
    dx = x[1] - x[0]
    t = (np.asarray(jumps, float) - x[0]) / dx
    t = np.unique(t[(t > 1e-9) & (t < n - 1 - 1e-9)])  # a jump at an end point cuts nothing
    on = np.round(t[np.abs(t - np.round(t)) <= 1e-9]).astype(np.int64)
    cuts = np.unique(np.r_[np.floor(t[np.abs(t - np.round(t)) > 1e-9]) + 0.5, on]).tolist()
    out = np.full(n, np.nan)
    bounds = [-0.5, *cuts, n - 0.5]
    for lo, hi in zip(bounds[:-1], bounds[1:]):  # a few stretches, one per jump
        i0 = int(np.floor(lo)) + 1
        i1 = int(np.ceil(hi)) - 1  # the points strictly inside (lo, hi)
        m = i1 - i0 + 1
        if m >= 3:
            out[i0 : i1 + 1] = np.gradient(f[i0 : i1 + 1], dx, edge_order=2)
        elif m == 2:
            out[i0 : i1 + 1] = (f[i1] - f[i0]) / dx
    edges = np.asarray(bounds)
    for k in on:  # the mean of the two stretches' extrapolations to the point (quadratic where they have 3 points)
        vals = []
        left = k - 1 - int(np.floor(edges[edges < k].max()))  # points of the stretch ending at k - 1
        right = int(np.ceil(edges[edges > k].min())) - k - 1
        if left >= 3:
            vals.append((5 * f[k - 1] - 8 * f[k - 2] + 3 * f[k - 3]) / (2 * dx))
        elif left == 2:
            vals.append((f[k - 1] - f[k - 2]) / dx)
        if right >= 3:
            vals.append((-5 * f[k + 1] + 8 * f[k + 2] - 3 * f[k + 3]) / (2 * dx))
        elif right == 2:
            vals.append((f[k + 2] - f[k + 1]) / dx)
        out[k] = np.mean(vals) if vals else np.nan
    for k in np.flatnonzero(np.isnan(out)):  # a stretch of one point
        nb = [out[j] for j in (k - 1, k + 1) if 0 <= j < n and np.isfinite(out[j])]
        out[k] = np.mean(nb) if nb else 0.0
    return out
