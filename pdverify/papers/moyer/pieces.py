"""Scenes beyond one uniform span for the Moyer & Miraglia models: segments of their own section and material,
supports inside the span and elastic supports (docs/scenes.md). Arrays in, arrays out.

**Segments.** A bond (a PD sum's pair of points) or an interval (the shear strain ψ̄'s) that lies in one segment
takes its stiffness; one that crosses an interface takes the harmonic mean over its length,

    S_ab = (x_b - x_a) / ∫_{x_a}^{x_b} ds / S(s),

the stiffness of the two parts in series: the bond's (or interval's) difference of the field is then exact for a
resultant that is constant along it (M for the bending bonds, V for the shear intervals, N for the rod's bonds),
whatever the interface's place between the points. Points beyond the ends (ghosts) continue the end segment.

**Supports inside the span and springs** (:mod:`.constraints` solves with them). A support at a between the points
x_i and x_{i+1} (t = (a - x_i)/Δ) holds the value the points interpolate linearly there, c·u = (1 - t) u_i + t u_{i+1};
its unknown force (moment) acts on the beam exactly as the model's own point force (couple) at a, the load column f
of a unit load there (:func:`load_column`: split linearly between the same two points, as every variant applies a
point load), so c is the adjoint of f. An elastic support is the same pair with the force -k c·u.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.contract import missing_torsion_constant
from ...core.errors import InputError
from ...core.scene import Scene, Spring, Supports

STIFFNESS_KEYS = ("EI", "EA", "kGA", "GJ")


def piece_stiffness(scene: Scene, key: str) -> list[tuple[float, float, float]]:
    """(start, end, S) of each segment for S = EI, EA, kGA or GJ."""
    out = []
    for a, b, sec, mat in scene.pieces():
        if key == "GJ" and sec.J is None:
            raise InputError(missing_torsion_constant(scene, "pd-torsion"))
        S = {"EI": mat.E * sec.I, "EA": mat.E * sec.A, "kGA": sec.k * mat.G * sec.A, "GJ": mat.G * (sec.J or 0.0)}
        out.append((a, b, S[key]))
    return out


def compliance(scene: Scene, x, key: str) -> np.ndarray:
    """∫_0^x ds / S(s) at the positions x (the end segments continued beyond the ends)."""
    x = np.asarray(x, float)
    pieces = piece_stiffness(scene, key)
    out = np.zeros_like(x)
    for k, (a, b, S) in enumerate(pieces):
        lo = -np.inf if k == 0 else a
        hi = np.inf if k == len(pieces) - 1 else b
        part = np.clip(x, lo, hi) - np.clip(0.0, lo, hi)
        out += part / S
    return out


def bond_stiffness(scene: Scene, xa, xb, key: str) -> np.ndarray:
    """The series (harmonic-mean) stiffness of the bonds or intervals [xa, xb] (module docstring); a zero-length
    one (a point's own entry) takes the stiffness at its point."""
    xa, xb = np.broadcast_arrays(np.asarray(xa, float), np.asarray(xb, float))
    d = xb - xa
    c = compliance(scene, xb, key) - compliance(scene, xa, key)
    same = np.abs(d) <= 1e-14 * scene.length
    if np.any(same):
        at = compliance(scene, xa[same] + 1e-9 * scene.length, key) - compliance(scene, xa[same], key)
        c = c.copy()
        c[same], d = at, np.where(same, 1e-9 * scene.length, d)
    return d / c


def plain_ends(scene: Scene) -> Scene:
    """The scene as the variants' end closures see it: an elastic end is a free end (its spring is added by
    :mod:`.constraints`) and the supports inside the span are left out."""
    sup = scene.supports
    if sup.simple:
        return scene
    ends = {
        side: ("free" if isinstance(getattr(sup, side), Spring) else getattr(sup, side)) for side in ("left", "right")
    }
    return scene.model_copy(update={"supports": Supports(left=ends["left"], right=ends["right"])})


@dataclass(frozen=True)
class Hold:
    """One support condition on one unknown of the model: ``label`` its reaction's name (``left``, ``right``,
    ``inner_<i>``), ``slot`` the unknown at each point (0: w, u or the twist; 1: the beam's rotation), ``reaction``
    its key prefix (force, moment, axial, torque), ``position``, ``stiffness`` (None: rigid)."""

    label: str
    slot: int
    reaction: str
    position: float
    stiffness: float | None


# per kind of model: the unknowns (slot, reaction key, inner support types that hold it rigidly, spring stiffness)
_SLOTS = {
    "beam": (
        (0, "force", ("pinned", "roller", "clamped"), "stiffness"),
        (1, "moment", ("clamped",), "rotational_stiffness"),
    ),
    "axial": ((0, "axial", ("pinned", "clamped"), "stiffness"),),
    "torsion": ((0, "torque", ("pinned", "roller", "clamped"), "rotational_stiffness"),),
}


def holds(scene: Scene, kind: str) -> list[Hold]:
    """The conditions of the elastic ends and of the supports inside the span on the unknowns of a ``kind`` =
    beam, axial (rod) or torsion model: a rod's axial spring is the spring's ``stiffness``, a torsion bar's its
    ``rotational_stiffness``; a roller holds a beam's deflection and a bar's twist, not a rod's axial displacement."""
    out = []
    sup = scene.supports
    for side, at in (("left", 0.0), ("right", scene.length)):
        end = getattr(sup, side)
        if isinstance(end, Spring):
            for slot, key, _, spring in _SLOTS[kind]:
                k = getattr(end, spring)
                if k:
                    out.append(Hold(side, slot, key, at, float(k)))
    for i, s in enumerate(sup.inner):
        for slot, key, rigid, spring in _SLOTS[kind]:
            if s.type in rigid:
                out.append(Hold(f"inner_{i}", slot, key, s.position, None))
            elif s.type == "spring" and getattr(s, spring):
                out.append(Hold(f"inner_{i}", slot, key, s.position, float(getattr(s, spring))))
    return out


def holds_somewhere(scene: Scene, kind: str, held_ends: tuple[str, ...]) -> bool:
    """True when an end (``held_ends``: the support names that hold the unknown), a spring or an inner support holds
    a rod's or torsion bar's unknown (else it is a mechanism along the axis)."""
    ends = (scene.supports.left, scene.supports.right)
    return any(isinstance(e, str) and e in held_ends for e in ends) or bool(holds(scene, kind))


def interpolation(x: np.ndarray, a: float) -> tuple[np.ndarray, np.ndarray]:
    """(points, weights) of the linear interpolation at a on the uniform grid x: one point when a is on it (within
    1e-9 of the spacing), else the two around it; beyond either end point (an end face of the cell grid, half a cell
    out) the extrapolation from the two nearest, alike at both ends."""
    dx = x[1] - x[0]
    pos = (a - x[0]) / dx
    i = int(np.clip(np.floor(pos + 1e-9), 0, len(x) - 2))
    t = pos - i
    if abs(t) < 1e-9:
        return np.array([i]), np.array([1.0])
    if abs(1 - t) < 1e-9:
        return np.array([i + 1]), np.array([1.0])
    return np.array([i, i + 1]), np.array([1 - t, t])
