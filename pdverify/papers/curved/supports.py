"""pd-curved on straight beams with supports inside the span, elastic supports and segments (docs/scenes.md).

Every support inside the span and every segment end is a break of the axis, as a point load is (:mod:`.particles`):
two coincident particles, continuity of u_t, u_n and φ, and the jumps of N, Q, M. A support replaces the jump of
each resultant it reacts to:

* rigid, in the slots it holds (:data:`pdverify.core.scene.HELD`: pinned u_t, u_n; roller u_n; clamped all three):
  the held value is zero, u_c = 0, and the jump is its reaction;
* a spring (``stiffness`` on u_n, ``rotational_stiffness`` on φ): R⁺ - R⁻ = -F_c + k_c u_c (its force -k_c u_c
  acts with the loads F there).

An elastic end holds nothing rigidly: the end's resultant condition gains the spring's force (at s = L: R = F - k u;
at s = 0: -R = F - k u). Each particle's EA, kGA and EI are its segment's (a segment's particles lie inside it, the
interface being a break), so the constitutive law is exact piece by piece and N, Q, M are continuous across an
interface.

Reactions (``info["reactions"]``, keyed as exact-timoshenko's: ``force`` along n, ``axial`` along t, moment
counter-clockwise): at an inner support -(R⁺ - R⁻) - F, at the ends -R(0) - F and R(L) - F, from the resultants at
the particles. On a curved axis they are the ends' in the frame (t, n) of the axis there; on a straight one n = +z.
"""

from __future__ import annotations

import numpy as np

from ...core.scene import HELD, Scene, Spring

_SLOT_KEYS = ("axial", "force", "moment")  # slots t, n, φ; on a straight beam n = +z


def held_slots(sup) -> tuple[bool, bool, bool]:
    """What a support holds rigidly per slot (t, n, φ): a named end or inner support (HELD); none for a spring."""
    kind = sup if isinstance(sup, str) else sup.type
    return HELD.get(kind, (False, False, False))


def spring_slots(sup) -> tuple[float, float, float]:
    """A spring's stiffness per slot (t, n, φ): none along the axis, ``stiffness`` on u_n, ``rotational_stiffness``
    on φ; zeros for a rigid support."""
    if isinstance(sup, Spring) or getattr(sup, "type", None) == "spring":
        return 0.0, float(sup.stiffness or 0.0), float(sup.rotational_stiffness or 0.0)
    return 0.0, 0.0, 0.0


BREAK = 1e-9  # of the length: positions this close are one break (a support on a load's place, merged breaks)


def support_breaks(scene: Scene) -> list[float]:
    """The positions inside the span that are breaks without a load: the inner supports and the segments' ends."""
    out = [s.position for s in scene.supports.inner]
    out += [g.end for g in scene.segments[:-1]] if scene.segments else []
    return out


def support_at(scene: Scene, position: float):
    """The inner support at ``position`` (within BREAK L), or None."""
    for s in scene.supports.inner:
        if abs(s.position - position) <= BREAK * scene.length:
            return s
    return None


def particle_stiffness(scene: Scene, segs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(EA, kGA, EI) per particle: the scene's, or each grid's segment's (read at its middle: a segment's end is a
    break, so a grid lies inside one segment)."""
    n = sum(len(g) for g in segs)
    if scene.uniform:
        return np.full(n, scene.EA), np.full(n, scene.kGA), np.full(n, scene.EI)
    out = np.empty((3, n))
    k = 0
    for g in segs:  # a few grids
        mid = 0.5 * (g[0] + g[-1])
        for a, b, sec, mat in scene.pieces():
            if a <= mid <= b:
                out[:, k : k + len(g)] = [[mat.E * sec.A], [sec.k * mat.G * sec.A], [mat.E * sec.I]]
                break
        k += len(g)
    return out[0], out[1], out[2]


def axial_mechanism(scene: Scene) -> str | None:
    """One line when nothing holds a straight beam along its axis (rollers, guided and free ends and springs slide),
    for a scene with supports inside the span or springs (the end-only scenes have the plane's rank test)."""
    ends = [s for s in (scene.supports.left, scene.supports.right) if isinstance(s, str)]
    if any(held_slots(s)[0] for s in ends + list(scene.supports.inner)):
        return None
    sup = scene.supports
    return (
        f"supports = {sup.kind('left')}-{sup.kind('right')}: nothing holds the beam along its axis (rollers, guided "
        "and free ends and springs slide), so the axial translation is a mechanism; make one support pinned or clamped"
    )


def reactions(scene: Scene, segs, offs, resultants: np.ndarray, point_loads) -> dict[str, float]:
    """The supports' forces and moments on the beam (module docstring): ``resultants`` (3, particles) of N, Q, M;
    ``point_loads(position) -> (F_t, F_n, C)`` the scene's point loads at a position."""
    L = scene.length

    def carries(sup, c):  # a slot the support neither holds nor springs carries no reaction: 0, not a rounding
        return held_slots(sup)[c] or spring_slots(sup)[c] > 0.0

    out = {}
    N_last = offs[-1] - 1
    for side, k, sign, at in (("left", 0, -1.0, 0.0), ("right", N_last, 1.0, L)):
        F = point_loads(at)
        sup = getattr(scene.supports, side)
        for c in (1, 2):  # force and moment (the axial reaction beside them where the end holds u_t)
            out[f"{_SLOT_KEYS[c]}_{side}"] = float(sign * resultants[c, k] - F[c]) if carries(sup, c) else 0.0
        if held_slots(getattr(scene.supports, side))[0]:
            out[f"axial_{side}"] = float(sign * resultants[0, k] - F[0])
    for i, s in enumerate(scene.supports.inner):
        j = int(np.argmin([abs(g[-1] - s.position) for g in segs[:-1]]))
        ka, kb = offs[j + 1] - 1, offs[j + 1]
        F = point_loads(s.position)
        for c in (1, 2):
            jump = float(-(resultants[c, kb] - resultants[c, ka]) - F[c])
            out[f"{_SLOT_KEYS[c]}_inner_{i}"] = jump if carries(s, c) else 0.0
        if held_slots(s)[0]:
            out[f"axial_inner_{i}"] = float(-(resultants[0, kb] - resultants[0, ka]) - F[0])
    return out
