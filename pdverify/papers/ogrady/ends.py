"""The bond-pair energy form's ends and loads (mirror ends and the nonlinear path): the axial condition of
each support (the scene's vocabulary, ``pdverify.core.scene.HELD``), the scenes refused for want of an axial
reaction, and the placement of point forces (linear split) and point moments (couples on centred chords).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import HELD, PointForce, PointMoment, Scene

AXIAL_HELD = {sup: held[0] for sup, held in HELD.items()}
"""Axial condition of each support, the same at both ends: the scene's vocabulary (``pdverify.core.scene.HELD``,
docs/supports.md): clamped and pinned hold the axial displacement; roller, guided (a sleeve: rotation held,
slides along and across the axis) and free leave it free."""


def held_dofs(left: str, right: str, n: int) -> list[int]:
    """Held real DOFs (2 i = axial u, 2 i + 1 = transverse w of point i) of supports ``left``/``right``.
    When no end holds the axial displacement the middle point does: it removes the axial rigid motion only,
    since dead transverse loads and couples have no axial resultant, so its reaction is zero (scenes with
    axial loads and no end holding them are refused, :func:`axial_mechanism`); a mirror scene holds the same
    point."""
    held = []
    for s, sup in ((0, left), (n - 1, right)):
        if sup in ("clamped", "pinned", "roller"):
            held.append(2 * s + 1)
        if AXIAL_HELD[sup]:
            held.append(2 * s)
    if not (AXIAL_HELD[left] or AXIAL_HELD[right]):
        held.append(2 * (n // 2))
    return held


def axial_mechanism(scene: Scene) -> str | None:
    """The one-line reason a scene cannot be solved with an axial unknown, or None: no end holds the
    axial displacement (roller, guided, free) while a load has an axial component."""
    left, right = scene.supports.left, scene.supports.right
    if AXIAL_HELD[left] or AXIAL_HELD[right]:
        return None
    axial = [i for i, l in enumerate(scene.loads) if getattr(l, "axial", 0.0)]
    if not axial:
        return None
    return (
        f"supports = {left}-{right}: no end holds the axial displacement (roller and guided slide, free is "
        f"free), so the axial load of loads[{axial[0]}] has no reaction (a mechanism along the axis; ends = "
        "mirror and the nonlinear path carry u); hold one end axially (clamped or pinned)"
    )


def _split(position: float, n: int, dx: float) -> tuple[int, float]:
    """(i, t): position = (i + t) dx with 0 <= t < 1 (t = 0 at the last point)."""
    pos = position / dx
    i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
    t = pos - i
    if abs(t) < 1e-9 or i == n - 1:
        t = 0.0
    return i, t


def point_forces(scene: Scene, n: int, dx: float) -> np.ndarray:
    """Nodal forces (u, w interleaved) of the point forces, split linearly between the two nearest
    points (the consistent load of a linear interpolant: second order for a force anywhere)."""
    F = np.zeros(2 * n)
    for load in scene.loads:
        if isinstance(load, PointForce):
            i, t = _split(load.position, n, dx)
            for node, wgt in ((i, 1.0 - t), (i + 1, t)):
                if wgt:
                    F[2 * node + 1] += wgt * load.value
                    F[2 * node] += wgt * load.axial
    return F


def point_couples(scene: Scene, n: int, dx: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a, c, C): follower couples C on the chords a -> c whose sum represents the point moments.

    A moment at (i + t) dx is split linearly between points i and i + 1 (weights 1 - t, t); at an
    interior point k it acts on the centred chord (k - 1, k + 1), whose direction is the rotation at k
    to second order; at an end point on 2 x chord (0, 1) - chord (0, 2) (the one-sided second-order
    slope (-3 w_0 + 4 w_1 - w_2) / (2 dx); mirrored at the right end)."""
    a, c, C = [], [], []
    for load in scene.loads:
        if not isinstance(load, PointMoment):
            continue
        i, t = _split(load.position, n, dx)
        for node, wgt in ((i, 1.0 - t), (i + 1, t)):
            if not wgt:
                continue
            if 0 < node < n - 1:
                a.append(node - 1), c.append(node + 1), C.append(wgt * load.value)
            elif node == 0:
                a += [0, 0]
                c += [1, 2]
                C += [2 * wgt * load.value, -wgt * load.value]
            else:
                a += [n - 2, n - 3]
                c += [n - 1, n - 1]
                C += [2 * wgt * load.value, -wgt * load.value]
    return np.array(a, int), np.array(c, int), np.array(C, float)
