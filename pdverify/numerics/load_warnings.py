"""The warnings a grid's loads and supports call for in the one-dimensional PD models: a point load inside an end's
boundary layer (and what leaves it, at a horizon given as a multiple of the spacing or as a length), a load's edge in
the reach of fitted ghosts, loads beside a support that holds the rotation, a couple at a segment joint, a load
narrower than the grid resolves."""

from __future__ import annotations

import numpy as np

from ..core.scene import Distributed, PointMoment, Scene
from ..core.text import counted, listed, more_points, rounded_down, rounded_up, spacings
from .loads import TIE, within
from .recovery import STRETCH

# the words of the lines that name a feature (a load, its edge, an inner support, a joint) inside a zone a number of
# spacings wide next to an end, where the model takes it differently (its boundary layer, its fitted ghosts, its cell
# averages); two grids that put a feature on different sides of such a zone treat the scene differently there
ZONES = ("inside the boundary layer of", "its ghosts are fitted on", "where the model takes it by its cell averages")


def zoned(lines: list[str]) -> set[str]:
    """The features (``loads[2]``, ``supports.inner[0]``) that ``lines`` name inside an end's zone (:data:`ZONES`)."""
    return {w.split(" ", 1)[0] for w in lines if any(z in w for z in ZONES)}


def boundary_layer_warnings(scene: Scene, x: np.ndarray, reach: int, fixed: tuple | None = None) -> list[str]:
    """Point loads (force, moment, torque) strictly inside the first ``reach`` spacings of an end: the
    ghost polynomial fitted there assumes a smooth solution, so such a load is under-resolved (large errors a
    spacing from the support: docs/models/diyaroglu.md, docs/models/moyer.md). Flag it instead of hiding it.
    Positions in the scene's length unit. ``fixed``: (a, b, delta) when the horizon is a given length delta and the
    layer is a delta + b spacings wide (reach = a m + b, m = delta / dx): more points do not leave it, and the fix
    named is a shorter horizon (:func:`layer_fix`)."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if hasattr(load, "position"):
            d = min(load.position, scene.length - load.position)
            if 1e-12 * scene.length < d and within(d, reach, dx):
                fix = layer_fix(d, dx, scene.length, reach, fixed)
                out.append(
                    f"loads[{i}] at {load.position:g} is {spacings(d / dx)} from an end, inside the "
                    f"boundary layer of {spacings(reach, 'g')}: expect large errors; {fix}"
                )
    return out + narrow_load_warnings(scene, x)


def horizon_layer(params: dict, dx: float, reach: float, per_horizon: float) -> tuple | None:
    """``fixed`` of :func:`boundary_layer_warnings` for a model whose end layer is ``reach`` = per_horizon m + b
    spacings: (per_horizon, b, delta) when ``params`` give the horizon as a length delta (m = delta / dx), b taken one
    horizon's rounding wider (m rounds up to whole spacings), else None."""
    if params.get("horizon_length") is None:
        return None
    delta = float(params["horizon_length"])
    return (per_horizon, reach - per_horizon * (delta / dx) + per_horizon, delta)


def layer_fix(d: float, dx: float, length: float, reach: float, fixed: tuple | None) -> str:
    """What leaves a layer of ``reach`` spacings ``dx`` a distance ``d`` from its end: more points when the horizon
    is a multiple of the spacing; at a fixed horizon length delta (``fixed`` = (a, b, delta): the layer is at most
    a delta + b spacings) a shorter horizon, and where the b spacings leave no room for a horizon of a whole spacing at
    these points, a horizon of one spacing on a grid fine enough that (a + b) spacings fall short of d."""
    if fixed is None:
        return more_points(np.ceil((reach - TIE) * length / d) + 1)
    a, b, delta = fixed
    wide = f"{counted(a, 'horizon')} and {spacings(b, 'g')}"
    head = f"at horizon_length = {delta:.6g} the layer is up to {wide} wide, so more points alone "
    below = (d - b * dx) / a
    whole = int(np.floor(below / dx * (1 - 1e-9)))  # the largest whole number of spacings below it
    if whole >= 1:  # room for a horizon of a spacing at least
        e_g = f"{whole * dx:.6g}, {spacings(whole, 'g')}"
        return head + f"do not leave it: give horizon_length below {rounded_down(below)} (e.g. {e_g})"
    n = int(np.floor(length * (a + b) / d * (1 + 1e-9))) + 2  # (a + b) spacings of the new grid below d
    return head + (
        f"do not leave it: give horizon_length = {length / (n - 1):.12g} (one spacing) and {n} points, or more points "
        "with a horizon of one spacing"
    )


EDGE_LAYER = 6  # spacings of an end with fitted (Taylor) ghosts within which a load's edge spoils the fit (measured:
# pd-eb's V 7.8e-3 with the edge 5 spacings from a guided end, exact from 6; pd-bond-pair's w 1e-3 at 5, 5e-4 at 6)
FITTED_ENDS = ("free", "guided", "spring")  # the ends whose ghosts the PD beams fit to the real points' w


def edge_layer_warnings(
    scene: Scene, x: np.ndarray, measured: str, kinds=FITTED_ENDS, layer: int = EDGE_LAYER
) -> list[str]:
    """Edges of distributed loads strictly inside the first ``layer`` spacings of an end of one of ``kinds``: ghosts
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
                if 1e-12 * L < d and within(d, layer, dx):
                    out.append(
                        f"loads[{i}] has an edge at {edge:g}, {spacings(d / dx)} from the {side} end "
                        f"({scene.supports.kind(side)}), inside the {spacings(layer, 'g')} its ghosts are fitted on: "
                        f"{measured}; {more_points(np.ceil((layer - TIE) * L / d) + 1)}"
                    )
    return out


# a point force d from an inner support that holds the rotation: the PD beams' error was measured up to about
# FORCE_NEAR_HELD_ROTATION (dx / d)^2 at their default horizon of 3 dx (docs/trust.md, "a point force near a support
# that holds the rotation"). It is the horizon's: the families reach across the support and carry the loaded span's
# curvature into the other (an unloaded overhang turns), a model error that stays at a fixed horizon length; so the
# estimate is FORCE_NEAR_HELD_ROTATION (max(dx, delta / 3) / d)^2 (at most 1), times (l / a)^TURNED_POWER where the
# loaded span a (to the next support that holds the deflection, else the beam's end) is shorter than the other side l
# (to the beam's end), which turns: relative to the loaded span's own small deflection, the other side's turn counts
# l / a times more, and where nothing holds its deflection (a free or guided end, a spring) it swings about the
# support, (l / a)^1.5 (measured: docs/trust.md)
FORCE_NEAR_HELD_ROTATION = 5.0
TURNED_POWER = {"held": 1.0, "swings": 1.5}
NEAR_TOLERANCE = 1e-3  # the error above which that estimate is a warning


def held_rotation_warnings(
    scene: Scene, dx: float, nearest: float = 4.0, delta: float | None = None, loads_constant: float | None = None
) -> list[str]:
    """Point forces at least ``nearest`` spacings from an inner support that holds the rotation (clamped, or a spring
    with a rotational stiffness) whose estimated error FORCE_NEAR_HELD_ROTATION (max(dx, delta / 3) / d)^2 (at most 1:
    the solution's own size; ``delta`` the horizon, default 3 dx), times the other side's turn (:func:`turned_side`),
    passes NEAR_TOLERANCE (nearer ones: the model's own
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
            if d == 0.0 or within(d, nearest, dx):
                continue
            turned, how = turned_side(scene, i, ld.position)
            constant = FORCE_NEAR_HELD_ROTATION * turned
            # at most the solution's own size beside the support (d under a spacing: the estimate's power law does not
            # hold), times the turn of the other side, which may pass it
            estimate = min(FORCE_NEAR_HELD_ROTATION * (h / d) ** 2, 1.0) * turned
            if estimate > NEAR_TOLERANCE:
                most = 3.0 * d * np.sqrt(NEAR_TOLERANCE / constant)  # the horizon that gives 1e-3
                out.append(
                    f"loads[{j}] at {ld.position:g} is {spacings(d / dx)} from supports.inner[{i}] at "
                    f"{sup.position:g}, which holds the rotation: the horizon's families reach across the support "
                    f"(a model error of the horizon, not of the grid), up to about {FORCE_NEAR_HELD_ROTATION:g} "
                    f"(max(spacing, horizon / 3) / distance)^2 (at most 1){how} = {estimate:.2g}; use a horizon of "
                    f"at most {most:.3g} (at a horizon of 3 spacings: at least {int(np.ceil(L / (most / 3.0))) + 1} "
                    "points) for 1e-3"
                )
    return out + distributed_near_held_warnings(scene, dx, delta, loads_constant or LOADS_NEAR_HELD_ROTATION)


def turned_side(scene: Scene, i: int, at: float) -> tuple[float, str]:
    """(max(1, l / a)^TURNED_POWER, its term in the warning's formula) for a load at ``at`` beside
    ``scene.supports.inner[i]``: a the loaded span's length (to the next support inside that holds the deflection on
    that side, else to the beam's end), l the other side's (to the beam's end); the other side "swings" when neither
    its end (a free or guided end, a spring) nor a support inside on it holds the deflection."""
    L, pos = scene.length, scene.supports.inner[i].position
    right = at > pos
    others = [s.position for k, s in enumerate(scene.supports.inner) if k != i and s.holds_deflection]
    loaded = min([L - pos if right else pos] + [abs(p - pos) for p in others if (p > pos) == right and p != pos])
    other = pos if right else L - pos
    if other <= loaded:
        return 1.0, ""
    end = "left" if right else "right"
    held = scene.supports.holds_deflection_at(end) or any(
        s.holds_deflection and ((s.position < pos) if right else (s.position > pos))
        for k, s in enumerate(scene.supports.inner)
        if k != i
    )
    power = TURNED_POWER["held" if held else "swings"]
    term = f" (l / a)^{power:g} (a, l: the loaded side's and the other side's lengths, {loaded:.3g} and {other:.3g})"
    return (other / loaded) ** power, term


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


def couple_deflection_warnings(
    scene: Scene, x: np.ndarray, w: np.ndarray, delta: float, constant: float, shear: np.ndarray | None = None
) -> list[str]:
    """One line where the estimate ``constant`` Σ |C| h² / (EI max |w|) of the deflection's error beside the point
    moments inside the span passes NEAR_TOLERANCE (h = max(spacing, ``delta`` / 3), ``delta`` the horizon; the sum
    over the couples: their errors add where they are near each other), with the points that bring it there: a model
    that takes a couple C as a force pair on the points around it leaves w beside it off by about c |C| h² / EI,
    second order, large beside max |w| where the couples deflect the beam little (the model's ``constant``, measured:
    docs/trust.md). ``shear``: the result's shear force, for a model exact where the beam carries no shear (w
    piecewise quadratic: pd-timoshenko ``energy``); the estimate is then times the couples' share carried as shear,
    min(1, L max |V| / Σ |C|), since the couples are a part that leaves V zero, which such a model solves exactly,
    and a rest of about that size."""
    top = float(np.abs(w).max()) if len(w) else 0.0
    L = scene.length
    couples = [
        (i, ld)
        for i, ld in enumerate(scene.loads)
        if isinstance(ld, PointMoment) and ld.value and 0.0 < ld.position < L
    ]
    if top == 0.0 or not couples:
        return []
    dx = float(x[1] - x[0])
    h = max(dx, delta / 3.0)
    at = np.array([ld.position for _, ld in couples])
    values = np.abs([ld.value for _, ld in couples])
    size = np.sum(values / scene.stiffness_at(at)["EI"])  # Σ |C| / EI
    estimate = constant * size * h**2 / top
    share = 1.0 if shear is None else min(1.0, L * float(np.abs(shear).max(initial=0.0)) / float(values.sum()))
    estimate *= share
    if not estimate > NEAR_TOLERANCE:
        return []
    points = int(np.ceil(1.1 * L / dx * np.sqrt(estimate / NEAR_TOLERANCE))) + 1
    names = ", ".join(str(i) for i, _ in couples)
    which = (
        f"loads[{names}], a point moment at {at[0]:g}: the deflection beside it"
        if len(couples) == 1
        else f"loads[{names}], point moments at {listed(at)}: the deflection beside them"
    )
    return [
        f"{which} is off by up to about {constant:g} {'|C|' if len(couples) == 1 else 'Σ |C|'} h² / EI (h = "
        f"max(spacing, horizon / 3)"
        + (
            f"; times the share of the couples the beam carries as shear, L max |V| / Σ |C| = {share:.2g}"
            if share < 1
            else ""
        )
        + f"), here {rounded_up(estimate)} of max |w| (large where the "
        f"{'couple deflects' if len(couples) == 1 else 'couples deflect'} the beam little); second order: use at "
        f"least {points} points for 1e-3"
    ]


# a distributed load that a PD beam takes by its cell averages, not by its jumps (pd-eb's corrected variant: an edge
# within the 2 J spacings of an end where the rows of its kinks would leave the grid; or one so near an end that the
# shear's differences cross it, numerics.recovery.STRETCH): the shear beside each of its
# edges inside the beam, the far one too, is off by up to about c (|q| dx + |q'| dx^2), q and q' the load and its
# slope at the edge (a sine load's value is small near an end, its slope is not), and an edge farther than
# CELL_REACH spacings beyond the layer by that times 2 |1/2 - f| (at least CELL_FLOOR), f its place between two points
# (a cell's average is right for an edge on a point or half-way: measured 0.05 there, 0.6 at f = 0.02); measured:
# benchmarks/load_edges.py, docs/trust.md "A load taken by its cell averages"
CELL_REACH, CELL_FLOOR = 4, 0.1


def cell_place(t: float) -> float:
    """The share of the constant an edge ``t`` spacings from the beam's start takes beyond the layer: 2 |1/2 - f| for f
    its place between two points, at least CELL_FLOOR (the edge on a point counts as half-way)."""
    f = t % 1.0
    if min(f, 1.0 - f) < 1e-9:
        f = 0.5
    return max(2.0 * abs(0.5 - f), CELL_FLOOR)


def cell_average_warnings(
    scene: Scene, x: np.ndarray, V: np.ndarray, loads: list, constant: float, reach: float, params=None
) -> list[str]:
    """One line per distributed load ``loads[k]`` (indices into the scene's loads) that the model takes by its cell
    averages because an edge lies within ``reach`` spacings of an end, where ``constant`` (|q| dx + |q'| dx²) summed
    over its edges inside the beam (beyond ``reach`` + CELL_REACH spacings of both ends times :func:`cell_place`)
    passes NEAR_TOLERANCE of the shear ``V``'s largest (the model's, on ``x``); an edge that the fitted ends' own line
    names counts too (its share of the shear's error reaches the far edge). ``params``: the run's, whose
    ``horizon_length`` makes a layer that more points do not leave (:func:`horizon_layer`)."""
    dx, L = x[1] - x[0], scene.length
    fixed = horizon_layer(params or {}, dx, reach, 2)
    top = float(np.max(np.abs(V))) if len(V) else 0.0
    if not (top > 0.0 and np.isfinite(top)):
        return []
    out = []
    for i in loads:
        ld = scene.loads[i]
        edges = [e for e in scene.span(ld) if 1e-12 * L < e < L * (1 - 1e-12)]
        if not edges:
            continue
        k = np.pi / L if ld.shape == "sine" else 0.0
        q = [abs(ld.value * float(scene.load_shape(ld, e))) for e in edges]
        slope = [abs(ld.value * k * np.cos(k * e)) for e in edges]
        place = [1.0 if within(min(e, L - e), reach + CELL_REACH, dx) else cell_place(e / dx) for e in edges]
        total = sum(constant * p * (a * dx + b * dx * dx) for a, b, p in zip(q, slope, place, strict=True)) / top
        if total <= NEAR_TOLERANCE:
            continue
        d, side = min((min(e, L - e), "left" if e < L - e else "right") for e in edges)
        # beside fitted ghosts the edge must leave their layer too (edge_layer_warnings: EDGE_LAYER spacings)
        fit = EDGE_LAYER if scene.supports.kind(side) in FITTED_ENDS else 0
        if fixed is None:  # the edge leaves the layer, or the estimate falls as dx: whichever comes first
            n = min(np.ceil((reach - TIE) * L / d), np.ceil((L / dx) * total / NEAR_TOLERANCE))
            fix = more_points(max(n, np.ceil((fit - TIE) * L / d)) + 1)
        else:
            fix = layer_fix(d, dx, L, reach, fixed if not fit else (fixed[0], max(fixed[1], fit), fixed[2]))
        out.append(
            f"loads[{i}] has an edge {spacings(d / dx)} from the {side} end ({scene.supports.kind(side)}), within "
            f"the {spacings(reach, 'g')} where the model takes it by its cell averages (the rows of its jump would "
            f"leave the grid) or differences the shear across it: the shear beside its edges (x = {listed(edges)}) is "
            f"off by up to about {constant:g} (|q| spacing + |q'| spacing²) (q, q' the load and its slope at an edge), "
            f"here {rounded_up(total)} of max |V| (docs/trust.md); {fix}"
        )
    return out


def slope_jump_warnings(scene: Scene, x: np.ndarray, V: np.ndarray, skip: list, constant: float) -> list[str]:
    """One line per sine load (not in ``skip``: the loads another line covers) whose slope jumps at an edge inside the
    beam, where ``constant`` Σ |q'| dx² over those edges passes NEAR_TOLERANCE of the shear ``V``'s largest (the
    model's, on ``x``): the shear, differenced from the moment beside such an edge (:func:`.recovery.derivative`), is
    off by about that at any horizon, second order, and large beside max |V| where the load is small and its slope is
    not (a short patch near an end). A patch of at most STRETCH spacings, whose two edges the differences take
    together, leaves no such error (measured 4e-6 and below). The constant measured: benchmarks/slope_jumps.py,
    docs/trust.md."""
    dx, L = float(x[1] - x[0]), scene.length
    top = float(np.max(np.abs(V))) if len(V) else 0.0
    if not (top > 0.0 and np.isfinite(top)):
        return []
    out = []
    for i, ld in enumerate(scene.loads):
        if not isinstance(ld, Distributed) or ld.shape == "uniform" or not ld.value or i in skip:
            continue
        a, b = scene.span(ld)
        if b - a <= (STRETCH + TIE) * dx:
            continue
        edges = [e for e in (a, b) if 1e-12 * L < e < L * (1 - 1e-12)]
        total = sum(constant * abs(ld.value * np.pi / L * np.cos(np.pi * e / L)) * dx * dx for e in edges) / top
        if not total > NEAR_TOLERANCE:
            continue
        points = int(np.ceil(1.05 * L / dx * np.sqrt(total / NEAR_TOLERANCE))) + 1
        out.append(
            f"loads[{i}] (a sine load) ends inside the beam at x = {listed(edges)}, where its slope q' jumps: the "
            f"shear beside {'it' if len(edges) == 1 else 'them'} is off by up to about {constant:g} |q'| spacing², "
            f"here {rounded_up(total)} of max |V| (large where the load is small beside its slope, near an end; "
            f"docs/trust.md); second order: use at least {points} points for 1e-3"
        )
    return out
