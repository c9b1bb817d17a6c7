"""Derivatives of a point field that does not cross its jumps: the shear force V = dM/dx of a moment recovered at the
points, where a point force or a support inside the span makes V jump. Arrays in, arrays out."""

from __future__ import annotations

import numpy as np


def jump_positions(scene, quantity: str) -> np.ndarray:
    """Where ``quantity`` jumps, so that a difference of its parent must not straddle it: the shear (the derivative
    of the moment) at point forces and supports inside the span that hold the deflection; the moment (EI times the
    derivative of the rotation) at couples and clamped inner supports and the curvature at interfaces. Where the
    shear kinks: :func:`kink_positions`."""
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
    return np.array(sorted(at), float)


def kink_positions(scene) -> np.ndarray:
    """Where the shear kinks (the load per length jumps: a distributed load's ends inside the span), so that a central
    difference of the moment across it is first order there."""
    at = [
        v
        for load in scene.loads
        if load.type == "distributed" and load.value != 0.0
        for v in scene.span(load)
        if 0.0 < v < scene.length
    ]
    return np.array(sorted(at), float)


STRETCH = 3  # the points on each side of a kink for it to cut the differences (fewer: they cross it)


def derivative(x: np.ndarray, f: np.ndarray, jumps=(), kinks=()) -> np.ndarray:
    """df/dx at the points x (uniform spacing) by second-order differences within each stretch between jumps
    (``numpy.gradient``: central inside a stretch, one-sided at its ends), so that no difference takes values from
    both sides of a jump; first order on a stretch of two points, interpolated from the nearest values on either side
    on one of a single point. At a point exactly on a jump (whose own value is ambiguous) the mean of the two
    stretches' quadratic extrapolations to it (second order where the derivative only kinks there). ``kinks``, where
    df/dx only kinks, cut the same way where the stretches on both sides keep at least three points, and are
    differenced across elsewhere (first order at a point, where one-sided differences over one or two points
    would be first order over several)."""
    x, f = np.asarray(x, float), np.asarray(f, float)
    n = len(x)
    dx = x[1] - x[0]

    def inside(at):  # positions in units of dx from x[0]; one at an end point cuts nothing
        t = (np.asarray(at, float) - x[0]) / dx
        return np.unique(t[(t > 1e-9) & (t < n - 1 - 1e-9)])

    t, tk = inside(jumps), inside(kinks)
    if len(tk):  # a kink is a cut where the points between it and the cuts beside it are at least 3 on each side
        cuts = np.r_[-1.0, t, tk, float(n)]
        cuts = np.unique(np.where(np.abs(cuts - np.round(cuts)) <= 1e-9, np.round(cuts), cuts))
        keep = [
            np.ceil(k - 1e-9) - np.floor(cuts[cuts < k - 1e-9].max() + 1e-9) - 1 >= STRETCH
            and np.ceil(cuts[cuts > k + 1e-9].min() - 1e-9) - np.floor(k + 1e-9) - 1 >= STRETCH
            for k in tk
        ]
        t = np.unique(np.r_[t, tk[np.asarray(keep, bool)]])
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
    gaps = np.isnan(out)  # stretches of one point (and points on a jump between them): interpolated linearly
    if gaps.all():  # between the nearest values on either side, all at once, so that a mirror image gets the same
        return np.zeros(n)
    out[gaps] = np.interp(x[gaps], x[~gaps], out[~gaps])
    return out
