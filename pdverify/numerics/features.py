"""The scene's features along the axis (its ends, supports, loads' positions and ends, segment ends) and whether a
uniform grid places them apart. Arrays in, arrays out."""

from __future__ import annotations

import numpy as np

from ..core.scene import Scene
from ..core.text import more_points


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
        f"near them is not the model's converged one; {more_points(np.ceil(scene.length / gaps[i]) + 1)}"
    ]


STIFFNESS_STEP = 1000.0  # EI changing this many times at a joint: the PD beams' error constant has grown 20-fold
# (a 2 m clamped-pinned beam with a soft middle fifth at 161 points; docs/models/diyaroglu.md, Known limits)


def joint_steps(scene: Scene) -> list[tuple[int, float, float]]:
    """(i, x, r) of each segment joint where EI is positive on both sides: segments[i] starts at x, and EI changes
    r-fold there (the larger side's over the smaller's, 1 where it does not change)."""
    pieces = scene.pieces()
    return [
        (i + 1, b, max(EI, EJ) / min(EI, EJ))
        for i, ((_, b, s1, m1), (_, _, s2, m2)) in enumerate(zip(pieces[:-1], pieces[1:]))
        if min(EI := m1.E * s1.I, EJ := m2.E * s2.I) > 0.0
    ]


def stiffness_step_warnings(scene: Scene) -> list[str]:
    """A segment joint where EI changes :data:`STIFFNESS_STEP` times or more: the PD beams' families reach across it,
    and their error, second order still, has a constant that grows with the step until the soft side is a hinge."""
    big = [(at, r) for _, at, r in joint_steps(scene) if r >= STIFFNESS_STEP]
    if not big:
        return []
    at, r = max(big, key=lambda s: s[1])
    return [
        f"EI changes {r:.3g}-fold at the segment joint x = {at:.6g}: the error near such a joint grows with the step "
        "(a 2 m clamped-pinned beam, a middle fifth softer, at 161 points: pd-eb 1.9e-4, 3.8e-3, 1.8e-2 and 2.9e-2 "
        "of max |w| at 1e2-, 1e3-, 1e4- and 1e6-fold, pd-bond-pair 1.0e-3 to 4.5e-2, pd-timoshenko 5.0e-4 to 7.2e-3; "
        "second order, 16 times less at 641 points); check with `pdverify solve --estimate`"
    ]
