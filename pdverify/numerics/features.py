"""The scene's features along the axis (its ends, supports, loads' positions and ends, segment ends) and whether a
uniform grid places them apart. Arrays in, arrays out."""

from __future__ import annotations

import numpy as np

from ..core.scene import Scene


def features(scene: Scene) -> np.ndarray:
    """The positions along the axis of the scene's features, sorted, those within 1e-9 of the length of another as
    one: its ends, the supports inside, the point loads and prescribed displacements, the ends of distributed loads
    and of segments."""
    at = [0.0, scene.length] + [s.position for s in scene.supports.inner]
    for load in scene.loads:
        at += list(scene.span(load)) if load.type == "distributed" else [load.position]
    for g in scene.segments:
        at += [g.start, g.end]
    at = np.unique(np.asarray(at, float))
    keep = np.r_[True, np.diff(at) > 1e-9 * scene.length]
    return at[keep]


def unresolved_features_warnings(scene: Scene, spacing: float) -> list[str]:
    """Two features (:func:`features`) closer than one spacing: a grid of uniform points does not place them apart,
    so what lies between them (a load's share, a short soft segment) is not resolved and the result near them is
    not the model's converged answer (a 1 mm soft segment between two torques, pd-torsion at 161 points: 86 % off)."""
    at = features(scene)
    gaps = np.diff(at)
    close = np.flatnonzero(gaps < spacing * (1 - 1e-9))
    if not len(close):
        return []
    i = int(close[np.argmin(gaps[close])])
    return [
        f"features at x = {at[i]:.6g} and {at[i + 1]:.6g} (supports, point loads, load and segment ends) lie "
        f"{gaps[i]:.3g} apart, within one spacing ({spacing:.3g}): the grid does not place them apart, so the result "
        f"near them is not the model's converged one; use at least {int(np.ceil(scene.length / gaps[i])) + 1} points"
    ]
