"""Loads on a grid of points along a straight beam: cell integrals of distributed loads, point loads as line
loads split between their two nearest points, end loads (their warnings: :mod:`.load_warnings`). Shared by the
one-dimensional PD models; arrays in, arrays out."""

from __future__ import annotations

import numpy as np

from ..core.geometry import geometry
from ..core.scene import Distributed, PointForce, PointMoment, PointTorque, Scene

TIE = 1e-9  # spacings: a distance this close to a threshold of whole spacings counts as on it, so that the rounding
# of a position (a scaled or mirrored scene's) decides no warning either way


def within(d: float, spacings: float, dx: float) -> bool:
    """Whether the distance ``d`` is strictly less than ``spacings`` spacings ``dx`` (by more than ``TIE``)."""
    return d < (spacings - TIE) * dx


# -- loads -----------------------------------------------------------------------------------


def cell_integral(
    load: Distributed, scene: Scene, lo: np.ndarray, hi: np.ndarray, value: float | None = None
) -> np.ndarray:
    """∫ over [lo, hi] ∩ span of the load's shape times ``value`` (default: the transverse
    ``load.value``; pass ``load.axial`` or ``load.torque`` for the other components)."""
    v = load.value if value is None else value
    a, b = scene.span(load)
    lo, hi = np.clip(lo, a, b), np.clip(hi, a, b)
    if load.shape == "uniform":
        return v * (hi - lo)
    k = np.pi / scene.length
    return v * (np.cos(k * lo) - np.cos(k * hi)) / k


def body_loads(scene: Scene, x: np.ndarray, skip_ends: dict | None = None) -> np.ndarray:
    """Line load q_k (N/m) on the points: cell averages of distributed loads, P/dx for point forces
    (split linearly between the two nearest points), -dm/dx couples for point moments (Eq. 25).
    ``skip_ends``: {0 or n-1: set of load types} handled elsewhere (by ghost points or reactions)."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    q = np.zeros(n)
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    skip_ends = skip_ends or {}
    for load in scene.loads:
        if isinstance(load, Distributed):
            q += cell_integral(load, scene, lo, hi) / (hi - lo)
            continue
        pos = load.position / dx
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1:
            t = 0.0
        node = i if t < 1e-9 else None
        if node is not None and load.type in skip_ends.get(node, ()):
            continue
        if isinstance(load, PointForce):
            q[i] += load.value * (1 - t) / dx
            if t > 0:
                q[i + 1] += load.value * t / dx
        elif isinstance(load, PointMoment):
            # ccw couple C: q = -C delta'(x - a), with the delta split linearly between the two nearest
            # points (weights 1 - t, t) and each point's delta' a central dipole (-C/(2dx²) left, +C/(2dx²) right)
            C = load.value
            for node, wgt in ((i, 1.0 - t), (i + 1, t)):
                if wgt == 0.0:
                    continue
                left, right = node - 1, node + 1
                if left < 0:
                    left, right = 0, 1
                if right > n - 1:
                    left, right = n - 2, n - 1
                arm = (right - left) * dx
                q[left] -= wgt * C / (arm * dx)
                q[right] += wgt * C / (arm * dx)
    return q


END_POINT = 1e-12  # of the length: a position this close to an end is on its end point
POINT_SPAN = 1e-9  # of the length: a narrower distributed load is a point force (narrow_spans_as_points)


def narrow_spans_as_points(scene: Scene, fraction: float) -> Scene:
    """The scene with each distributed load narrower than ``fraction`` of the length replaced by its resultant at
    its span's middle (a point force; its torque a point torque, listed after the loads), which differs from it by
    O((span / L)^2) relative: below eps / 100 for ``fraction`` = :data:`POINT_SPAN`, where the models that round
    span ends to their points or nodes round both ends to one and lose the load, and others lose digits. The loads
    keep their indices."""
    L = scene.length
    loads, torques = [], []
    for load in scene.loads:
        a, b = scene.span(load) if isinstance(load, Distributed) else (0.0, L)
        if not (isinstance(load, Distributed) and b - a < fraction * L):
            loads.append(load)
            continue
        mid, width = 0.5 * (a + b), b - a
        value = load.value * float(scene.load_shape(load, mid)) * width
        loads.append(
            PointForce(type="point_force", position=mid, value=value, axial=load.axial * width, frame=load.frame)
        )
        if load.torque:
            torques.append(PointTorque(type="point_torque", position=mid, value=load.torque * width))
    return (
        scene
        if len(torques) == 0 and all(a is b for a, b in zip(loads, scene.loads))
        else scene.model_copy(update={"loads": loads + torques})
    )


def end_side(scene: Scene, position: float) -> str | None:
    """The end ("left" or "right") whose point ``position`` is on (within END_POINT L), else None."""
    for side, xe in (("left", 0.0), ("right", scene.length)):
        if abs(position - xe) <= END_POINT * scene.length:
            return side
    return None


def onto_end_points(scene: Scene) -> Scene:
    """The scene with every point load within :func:`end_side`'s reach of an end moved exactly onto it: a solution
    whose end conditions take only a load at 0 or L exactly would take one a few eps inside the span in its field and
    then, at the end point, once more as that end's load."""
    loads = [
        ld.model_copy(update={"position": 0.0 if side == "left" else scene.length})
        if isinstance(ld, (PointForce, PointMoment)) and (side := end_side(scene, ld.position)) is not None
        else ld
        for ld in scene.loads
    ]
    changed = any(a is not b for a, b in zip(loads, scene.loads))
    return scene.model_copy(update={"loads": loads}) if changed else scene


def end_loads(scene: Scene) -> tuple[dict, dict]:
    """Point force and moment applied exactly at the left (x = 0) and right (x = L) ends."""
    P = {0: 0.0, 1: 0.0}
    C = {0: 0.0, 1: 0.0}
    for load in scene.loads:
        if isinstance(load, (PointForce, PointMoment)) and (side := end_side(scene, load.position)) is not None:
            (P if isinstance(load, PointForce) else C)[0 if side == "left" else 1] += load.value
    return P, C


def support_couples(scene: Scene) -> tuple[dict, Scene]:
    """({side: C}, the scene without them): the couples on an end point whose support holds the rotation (clamped,
    guided). Such a couple goes into the support and bends nothing; a model that can only spread a couple over a
    spacing or two (a force pair) solves the scene without it and adds it to that end's reaction and to the end
    point's moment (its support side, :func:`support_side`). ({}, the scene) when there is none."""
    found, kept = {}, []
    for load in scene.loads:
        side = end_side(scene, load.position) if isinstance(load, PointMoment) else None
        if side is None or scene.supports.kind(side) not in ("clamped", "guided"):
            kept.append(load)
        else:
            found[side] = found.get(side, 0.0) + load.value
    return found, (scene.model_copy(update={"loads": kept}) if found else scene)


def bends_nothing(scene: Scene) -> bool:
    """True when every load of the scene acts on an end point that holds it (a force where the deflection is held,
    a couple where the rotation is): the beam stays straight, w = 0 exactly."""
    holds = {PointForce: ("clamped", "pinned", "roller"), PointMoment: ("clamped", "guided")}
    for load in scene.loads:
        side = end_side(scene, load.position) if type(load) in holds else None
        if side is None or scene.supports.kind(side) not in holds[type(load)]:
            return False
    return True


def solve_without_support_couples(solve, scene: Scene, params: dict, field: str):
    """``solve(scene, params)`` (a model's Result) of the scene without its :func:`support_couples`, which go into
    their supports: the end point's ``field`` (the moment's name) on the support's side and the end's moment
    reaction, where the model gives reactions (else the registry's statics read that moment)."""
    couples, bare = support_couples(scene)
    result = solve(bare, params)
    if field in result.fields:  # (a large-rotation path gives none)
        result.fields[field] = support_side(scene, result.fields[field], "moment", couples=couples)
    reactions = result.info.get("reactions") or {}
    for side, C in couples.items():
        if f"moment_{side}" in reactions:
            reactions[f"moment_{side}"] -= C
    return result


def support_side(scene: Scene, values: np.ndarray, field: str, sides=("left", "right"), couples=None) -> np.ndarray:
    """``values`` (the moment or the shear at the points, ``field`` "moment" or "shear") with the end points of
    ``sides`` moved from the beam's side of the loads on them to their support's side, the exact beams' end values
    (whose reactions are -M(0), M(L), V(0) and -V(L)): M(0-) = M(0+) + C, M(L+) = M(L-) - C for a couple C on the end
    point, V(0-) = V(0+) - P, V(L+) = V(L-) + P for a force P. ``couples``: {side: C} instead of the scene's couples on
    the end points (:func:`support_couples`'). For a model whose end points carry the beam's side."""
    P, C = end_loads(scene)
    if couples is not None:
        C = {0: couples.get("left", 0.0), 1: couples.get("right", 0.0)}
    load, sign = (C, 1.0) if field == "moment" else (P, -1.0)
    out = np.array(values, float)
    if "left" in sides:
        out[0] += sign * load[0]
    if "right" in sides:
        out[-1] -= sign * load[1]
    return out


def force_components(load, t: np.ndarray, n: np.ndarray) -> tuple[float, float, float]:
    """(F·t, F·n, C) of a point load at a point with unit tangent t and normal n (``frame = global``: (axial, value)
    are its global x and y components)."""
    if isinstance(load, PointMoment):
        return 0.0, 0.0, load.value
    if load.frame == "global":
        F = np.array([load.axial, load.value])
        return float(F @ t), float(F @ n), 0.0
    return load.axial, load.value, 0.0


def axis_support_side(scene: Scene, s: np.ndarray, fields: dict) -> dict:
    """``fields``' axis-frame resultants N, Q, M (and V = -Q where given) at the points of ``s`` (arc lengths) on an
    end moved from the beam's side of the point loads there to their support's side, the contract's end values for a
    curved axis: R(0-) = R(0+) + F, R(L+) = R(L-) - F with F = (F·t, F·n, C) in the axis' frame at the end (on a
    straight axis :func:`support_side`'s values). A new dict; the other fields as they are."""
    s = np.asarray(s, float)
    out = dict(fields)
    for side, sign, xe in (("left", 1.0, 0.0), ("right", -1.0, scene.length)):
        at = np.flatnonzero(np.abs(s - xe) <= END_POINT * scene.length)
        loads = [
            ld
            for ld in scene.loads
            if isinstance(ld, (PointForce, PointMoment)) and end_side(scene, ld.position) == side
        ]
        if not len(at) or not loads:
            continue
        t, n = geometry(scene).frame(np.array([xe]))
        F = sum((np.array(force_components(ld, t[0], n[0])) for ld in loads), np.zeros(3))
        for c, key in enumerate(("N", "Q", "M")):
            if key in out:
                out[key] = np.array(out[key], float)
                out[key][at] += sign * F[c]
        if "V" in out and "Q" in out:
            out["V"] = -out["Q"]
    return out
