"""Loads on a grid of points along a straight beam: cell integrals of distributed loads, point loads as line
loads split between their two nearest points, end loads, and the warnings for a load inside a boundary layer or
narrower than the grid resolves. Shared by the one-dimensional PD models; arrays in, arrays out."""

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


def boundary_layer_warnings(scene: Scene, x: np.ndarray, reach: int) -> list[str]:
    """Point loads (force, moment, torque) strictly inside the first ``reach`` spacings of an end: the
    ghost polynomial fitted there assumes a smooth solution, so such a load is under-resolved (large errors a
    spacing from the support: docs/models/diyaroglu.md, docs/models/moyer.md). Flag it instead of hiding it.
    Positions in the scene's length unit."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if hasattr(load, "position"):
            d = min(load.position, scene.length - load.position)
            if 1e-12 * scene.length < d and within(d, reach, dx):
                out.append(
                    f"loads[{i}] at {load.position:g} is {d / dx:.3g} spacings from an end, inside the "
                    f"boundary layer of {reach} spacings: expect large errors; use at least "
                    f"{int(np.ceil(reach * scene.length / d)) + 1} points"
                )
    return out + narrow_load_warnings(scene, x)


EDGE_LAYER = 3  # spacings of an end with fitted (Taylor) ghosts within which a load's edge spoils the fit (measured)
FITTED_ENDS = ("free", "guided", "spring")  # the ends whose ghosts the PD beams fit to the real points' w


def edge_layer_warnings(scene: Scene, x: np.ndarray, measured: str, kinds=FITTED_ENDS) -> list[str]:
    """Edges of distributed loads strictly inside the first EDGE_LAYER spacings of an end of one of ``kinds``: ghosts
    fitted there extrapolate one polynomial of w across the load's jump. ``measured``: the model's own errors there,
    quoted in the warning."""
    dx, L = x[1] - x[0], scene.length
    ends = [(at, side) for at, side in ((0.0, "left"), (L, "right")) if scene.supports.kind(side) in kinds]
    out = []
    for i, ld in enumerate(scene.loads):
        if ld.type != "distributed":
            continue
        for edge in scene.span(ld):
            for at, side in ends:
                d = abs(edge - at)
                if 1e-12 * L < d and within(d, EDGE_LAYER, dx):
                    out.append(
                        f"loads[{i}] has an edge at {edge:g}, {d / dx:.3g} spacings from the {side} end "
                        f"({scene.supports.kind(side)}), inside the {EDGE_LAYER} spacings its ghosts are fitted on: "
                        f"{measured}; use at least {int(np.ceil(EDGE_LAYER * L / d)) + 1} points"
                    )
    return out


# a point force d from an inner support that holds the rotation: the PD beams' error was measured up to about
# FORCE_NEAR_HELD_ROTATION (dx / d)^2 at their default horizon of 3 dx (docs/trust.md, "a point force near a support
# that holds the rotation"). It is the horizon's: the families reach across the support and carry the loaded span's
# curvature into the other (an unloaded overhang turns), a model error that stays at a fixed horizon length; so the
# estimate is FORCE_NEAR_HELD_ROTATION (max(dx, delta / 3) / d)^2
FORCE_NEAR_HELD_ROTATION = 5.0
NEAR_TOLERANCE = 1e-3  # the error above which that estimate is a warning


def held_rotation_warnings(
    scene: Scene, dx: float, nearest: float = 4.0, delta: float | None = None, loads_constant: float | None = None
) -> list[str]:
    """Point forces at least ``nearest`` spacings from an inner support that holds the rotation (clamped, or a spring
    with a rotational stiffness) whose estimated error FORCE_NEAR_HELD_ROTATION (max(dx, delta / 3) / d)^2 (at most 1:
    the solution's own size; ``delta`` the horizon, default 3 dx) passes NEAR_TOLERANCE (nearer ones: the model's own
    warning of rows that straddle the load, where it has one); and :func:`distributed_near_held_warnings` with the
    model's ``loads_constant`` (default LOADS_NEAR_HELD_ROTATION)."""
    L, out = scene.length, []
    delta = 3.0 * dx if delta is None else float(delta)
    h = max(dx, delta / 3.0)
    for i, sup in enumerate(scene.supports.inner):
        if not (sup.type == "clamped" or (sup.type == "spring" and (sup.rotational_stiffness or 0.0) > 0.0)):
            continue
        for j, ld in enumerate(scene.loads):
            d = abs(ld.position - sup.position) if ld.type == "point_force" else 0.0
            far = d > 0.0 and not within(d, nearest, dx)
            estimate = min(FORCE_NEAR_HELD_ROTATION * (h / d) ** 2, 1.0) if far else 0.0
            if estimate > NEAR_TOLERANCE:
                most = 3.0 * d * np.sqrt(NEAR_TOLERANCE / FORCE_NEAR_HELD_ROTATION)  # the horizon that gives 1e-3
                out.append(
                    f"loads[{j}] at {ld.position:g} is {d / dx:.3g} spacings from supports.inner[{i}] at "
                    f"{sup.position:g}, which holds the rotation: the horizon's families reach across the support "
                    f"(a model error of the horizon, not of the grid), up to about {FORCE_NEAR_HELD_ROTATION:g} "
                    f"(max(spacing, horizon / 3) / distance)^2 = {estimate:.2g}; use a horizon of at most "
                    f"{most:.3g} (at a horizon of 3 spacings: at least {int(np.ceil(L / (most / 3.0))) + 1} points) "
                    "for 1e-3"
                )
    return out + distributed_near_held_warnings(scene, dx, delta, loads_constant or LOADS_NEAR_HELD_ROTATION)


# distributed loads beside such a support: the same mechanism, measured (docs/trust.md; pd-eb and pd-timoshenko, 2,496
# cases: benchmarks/loads_near_held_rotation.py) at most 6.9 (max(dx, delta / 3) / d)^2 max(l, d) / d with d the arm
# of one side's distributed loads about the support and l the length of the other side, which the families turn,
# weighted by that side's share of the loads' moment about the support (the median 46 times below the estimate)
LOADS_NEAR_HELD_ROTATION = 8.0
# pd-higher-order (corrected) against exact-higher-order on the same scenes (1,248 cases each, 101 and 401 points): at
# most 11.4 (max(dx, delta / 3) / d)^2 max(l, d) / d where the clamp is on a point the grid cuts (7.4 a spring of
# 1000 EI / L^3 and 1000 EI / L), and where it is not 14.3 (21.4 the spring)
HIGHER_ORDER_LOADS_NEAR_HELD_ROTATION = {"cut": 14.0, "not cut": 24.0}
_GX, _GW = np.polynomial.legendre.leggauss(24)


def side_loads(scene: Scene, at: float) -> tuple[np.ndarray, np.ndarray]:
    """([left, right] ∫ |q| |x - at| dx, [left, right] ∫ |q| dx) of the distributed transverse loads on each side of
    x = ``at`` (each load split there, its parts integrated by Gauss-Legendre: its shapes are smooth on each part)."""
    moment, total = np.zeros(2), np.zeros(2)
    for ld in scene.loads:
        if isinstance(ld, Distributed) and ld.value != 0.0:
            a, b = scene.span(ld)
            for side, (lo, hi) in enumerate(((a, min(b, at)), (max(a, at), b))):
                if hi > lo:
                    xq = (lo + hi) / 2 + (hi - lo) / 2 * _GX
                    q = np.abs(ld.value * scene.load_shape(ld, xq)) * (hi - lo) / 2
                    moment[side] += float(np.sum(_GW * q * np.abs(xq - at)))
                    total[side] += float(np.sum(_GW * q))
    return moment, total


def distributed_near_held_warnings(
    scene: Scene, dx: float, delta: float | None = None, constant: float = LOADS_NEAR_HELD_ROTATION
) -> list[str]:
    """Distributed loads beside an inner support that holds the rotation (clamped, or a spring with a rotational
    stiffness): the families reach across the support and turn the other side, measured up to about ``constant``
    (h / d)^2 max(l, d) / d, h = max(dx, delta / 3) (``delta`` the horizon, default 3 dx), d the arm of a side's
    distributed loads about the support, l the other side's length (the model's constant: LOADS_NEAR_HELD_ROTATION
    for pd-eb and pd-timoshenko, one of HIGHER_ORDER_LOADS_NEAR_HELD_ROTATION for pd-higher-order); warned past
    NEAR_TOLERANCE."""
    L, out = scene.length, []
    h = max(dx, (3.0 * dx if delta is None else float(delta)) / 3.0)
    for i, sup in enumerate(scene.supports.inner):
        if not (sup.type == "clamped" or (sup.type == "spring" and (sup.rotational_stiffness or 0.0) > 0.0)):
            continue
        moment, total = side_loads(scene, sup.position)
        sides = [
            (moment[s] / total[s], (sup.position, L - sup.position)[1 - s], moment[s] / moment.max())
            for s in (0, 1)
            if total[s] > 0.0
        ]
        if not sides:
            continue
        factor = max(share * max(other, d) / d**3 for d, other, share in sides)  # the worst side's
        estimate = constant * h**2 * factor  # may pass 1: the turned side moves more than the loaded
        if estimate > NEAR_TOLERANCE:
            most = 3.0 * np.sqrt(NEAR_TOLERANCE / (constant * factor))  # the horizon that gives 1e-3
            out.append(
                f"distributed loads beside supports.inner[{i}] at {sup.position:g}, which holds the rotation: the "
                "horizon's families reach across the support and turn the other side (a model error of the "
                f"horizon, not of the grid), measured up to about {constant:g} (max(spacing, horizon "
                f"/ 3) / d)^2 max(l, d) / d = {estimate:.2g} (d: the loads' arm about the support, l: the other "
                f"side's length); use a horizon of at most {most:.3g} (at a horizon of 3 spacings: at least "
                f"{int(np.ceil(L / (most / 3.0))) + 1} points) for 1e-3"
            )
    return out


def moment_rotation_warnings(scene: Scene) -> list[str]:
    """Point moments inside the beam: the curvature jumps there, and a PD model spreads the jump over its horizon, so
    the rotation near the moment is first order (a few dx/L of max |rotation|) while w stays second order."""
    return [
        f"loads[{i}], a point moment at {load.position:g}: the rotation within a few spacings of it is first order "
        "(an error of a few dx/L of max |rotation|); the deflection stays second order"
        for i, load in enumerate(scene.loads)
        if load.type == "point_moment" and 0.0 < load.position < scene.length
    ]


def couple_at_joint_warnings(scene: Scene, quantity: str, measured: str) -> list[str]:
    """Point moments on a segment joint (within 1e-9 of the length): the kink that takes a couple and the joint's
    change of section meet at one point, and ``quantity`` near it is first order in the spacing (``measured``: the
    model's own errors, quoted)."""
    joints = {g.end for g in scene.segments} & {g.start for g in scene.segments}
    tol = 1e-9 * scene.length
    return [
        f"loads[{i}], a point moment at {load.position:g}, is on a segment joint: the {quantity} near it is first "
        f"order in the spacing ({measured}); off the joint it is second order"
        for i, load in enumerate(scene.loads)
        if load.type == "point_moment" and load.value != 0.0 and any(abs(load.position - j) <= tol for j in joints)
    ]


def narrow_load_warnings(scene: Scene, x: np.ndarray) -> list[str]:
    """Partial loads that lie inside one point's cell [x_i - dx/2, x_i + dx/2]: the PD models place distributed loads
    by cell averages, so such a load acts on that point as a whole, moved by up to half a spacing (a first-order
    error: docs/regression.md, tests/verification/test_point_loads_anywhere.py). Flag it."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if isinstance(load, Distributed) and (load.start is not None or load.end is not None):
            a = 0.0 if load.start is None else float(load.start)
            b = scene.length if load.end is None else float(load.end)
            if np.floor((a - x[0]) / dx + 0.5) == np.floor((b - x[0]) / dx + 0.5):
                out.append(
                    f"loads[{i}] from {a:g} to {b:g} lies inside one point's cell (spacing {dx:.3g}): it acts on "
                    "that point as a whole, moved by up to half a spacing (a first-order error); use at least "
                    f"{int(np.ceil(2 * scene.length / (b - a))) + 1} points"
                )
    return out
