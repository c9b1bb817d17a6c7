"""The warning of a load near an end that holds the deflection: the PD beams' deflection under a point force or a
distributed load a distance d (its centroid's) from a clamped or pinned end is off by about C (h / d)² of the load's
own deflection, h = max(spacing, horizon / 3): second order at a fixed d, but at a fixed number of spacings it does
not fall, and a load close to a clamp bends the beam little, so the error is large beside max |w| (the ends' ghosts
and the families at the support carry the load's curvature; docs/trust.md, "Loads near an end"). A point load in
the end's layer is left to that layer's warning."""

from __future__ import annotations

import functools

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.result import quantity_of
from ..core.scene import Distributed, PointForce, Scene
from ..core.scene_file import parse_scene
from ..core.text import rounded_up, spacings
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning

CLOSEST = 2.5  # in h: nearer, the estimate is not measured (benchmarks/end_loads.py starts there) and the error can
# pass the solution's own size (a patch on the first 2 spacings of a cantilever: 0.86 of max |w| at 201 points)
NEAR = 0.25  # a load is near an end when d is below this share of the length: farther off the end's part is no larger
# than the beam's own discretisation error (a uniform load: 7.4e-4 at 41 points where C (h / d)² is 1.6e-3), which
# --estimate gives
KIND = {"clamped": "clamped", "pinned": "pinned", "roller": "pinned", "free": "free", "guided": "guided"}  # the
# constant each end takes (springs: :func:`end_kind`); at free and guided ends only the line of a load nearer than
# CLOSEST h, where the model's ghosts carry it (a patch on the last spacings: up to 3 times max |w| at any grid)


def end_kind(scene: Scene, side: str) -> str:
    """The constant an end takes: its :data:`KIND`; a spring end "spring" (its M and the deflection beside it carry
    the pin's error whatever its stiffness: a soft one moves with the load, so w's share is smaller) or, with a
    rotational stiffness, "rotational spring" (pd-eb's and pd-timoshenko's clamped constant, an upper one for a soft
    rotational spring; pd-bond-pair takes none: its end slope there is first order, its own warning); "" for the
    others."""
    sup = getattr(scene.supports, side)
    if isinstance(sup, str):
        return KIND.get(sup, "")
    return "rotational spring" if sup.rotational_stiffness else "spring"


_GX, _GW = np.polynomial.legendre.leggauss(16)


def arm(scene: Scene, load, end: float) -> float:
    """The distance from ``end`` of a point force, or of a distributed load's centroid (its shape's, on its span)."""
    if isinstance(load, PointForce):
        return abs(load.position - end)
    a, b = scene.span(load)
    s = (a + b) / 2 + (b - a) / 2 * _GX
    q = np.abs(scene.load_shape(load, s)) * _GW
    return abs(float((q * s).sum() / q.sum()) - end) if q.sum() > 0 else 0.0


def shares(scene: Scene, exact):
    """i -> the response to ``loads[i]`` alone beside the whole's, in ``exact`` (scene -> the exact beam's result on
    the result's points): the larger of max |w_i| / max |w| and max |M_i| / max |M| (1 for the only load; loads that
    oppose each other make the whole smaller than one's own, and an error that is the load's own larger beside it);
    1 where the exact beam does not solve the scene (its dynamics dropped: the loads' static part). The whole solved
    once."""
    base = {k: v for k, v in scene.to_dict().items() if k != "dynamics"}

    def response(loads: list) -> np.ndarray:
        r = exact(parse_scene({**base, "loads": loads}, source="end-load share"))
        return np.array([np.abs(r.w).max(), np.abs(quantity_of(r.w, r.rotation, r.fields, "moment")).max()])

    @functools.cache
    def whole() -> np.ndarray:
        return response(base["loads"])

    def share(i: int) -> float:
        if len(scene.loads) == 1:
            return 1.0
        try:
            own, all_ = response([base["loads"][i]]), whole()
        except (InputError, SolveError):
            return 1.0
        with np.errstate(divide="ignore", invalid="ignore"):
            return float(np.nanmax(np.where(all_ > 0, own / all_, np.inf)))

    return share


def end_load_warnings(constants: dict, scene: Scene, info: dict, exact) -> list[str]:
    """One line per end where the sum over the loads near it (d below :data:`NEAR` of the length, each at the end
    where its estimate is the larger) of ``constants[kind]`` (h / d)² times the load's share (:func:`shares`,
    ``exact`` the exact beam's solve) passes :data:`TOLERANCE` (kind: :func:`end_kind`), with the points that bring it
    to the tolerance (the errors of loads near one end add: a patch cut into pieces is the patch); one line per load
    nearer than :data:`CLOSEST` h, not estimated; none for a point load in the end's layer, which its own warning in
    ``info`` names."""
    dx, delta = float(info.get("spacing", 0.0)), float(info.get("horizon", 0.0))
    if not dx:
        return []
    h = max(dx, delta / 3.0)
    said = info.get("warnings", [])
    sides = (("left", 0.0), ("right", scene.length))
    ends = [(side, at, constants.get(end_kind(scene, side), 0.0)) for side, at in sides]  # once per end
    out, share, parts = [], shares(scene, exact), {side: [] for side, _ in sides}
    for i, ld in enumerate(scene.loads):
        layer = any(w.startswith(f"loads[{i}] at ") and "boundary layer" in w for w in said)  # the layer's own
        if not isinstance(ld, (PointForce, Distributed)) or not ld.value or layer:
            continue
        near = []  # (C (h / d)², side, d, c) at each end that takes a constant
        for side, end, c in ends:
            d = arm(scene, ld, end)
            if c and 1e-9 * dx < d < NEAR * scene.length:
                near.append((c * (h / d) ** 2, side, d, c))
        if not near:
            continue
        own, side, d, c = max(near)
        part = share(i)
        est = min(own * part, 1.0)
        if d >= CLOSEST * h * (1.0 - 1e-9):  # at the bound whatever the rounding of a scaled scene's positions
            if end_kind(scene, side) not in ("free", "guided"):  # past 2.5 h a free end's error falls faster than
                parts[side].append((i, est, d, part))  # (h / d)² (3e-6 at 10 h): its ghosts' own line speaks there
        elif est > TOLERANCE:
            at = d if side == "left" else scene.length - d
            more = int(np.ceil(scene.length / d * max(CLOSEST, np.sqrt(c / TOLERANCE)) * (h / dx))) + 1
            out.append(
                f"loads[{i}] ({describe(ld)} {at:g}) is {spacings(d / dx)} from the {side} end "
                f"({scene.supports.kind(side)}): nearer than {CLOSEST:g} h (h = max(spacing, horizon / 3)) its "
                "deflection and moment are not estimated: expect large errors, up to the solution's own size "
                f"(docs/trust.md); use at least {more} points"
            )
    c_of = {side: c for side, _, c in ends}
    turn = constants.get("rotation")  # the rotation's error beside the estimate's, measured (None: not measured)
    for side, items in parts.items():
        total = min(sum(est for _, est, _, _ in items), 1.0)
        if total <= TOLERANCE:  # the line speaks where w and M need it; the rotation's part rides along
            continue
        worst = total * max(1.0, turn or 1.0)
        more = int(np.ceil(scene.length / dx * np.sqrt(worst / TOLERANCE))) + 1
        kind = scene.supports.kind(side)
        if len(items) == 1:
            (i, _, d, part), ld = items[0], scene.loads[items[0][0]]
            at = d if side == "left" else scene.length - d
            head = f"loads[{i}] ({describe(ld)} {at:g}) is {spacings(d / dx)} from the {side} end ({kind})"
            # its response alone is the whole's (to rounding: a scaled copy of the scene reads the same)
            alone = abs(part - 1.0) <= 1e-9
            whole = "" if alone else f" ({part:.2g} times the whole's: the load's own response beside all's)"
            what = f"of the load's own (h = max(spacing, horizon / 3), d its distance){whole}"
        else:
            names = ", ".join(str(i) for i, *_ in items[:6]) + (", ..." if len(items) > 6 else "")
            nearest = min(d for *_, d, _ in items)
            head = (
                f"loads[{names}] ({len(items)} loads in the quarter of the beam next to the {side} end ({kind}), the "
                f"nearest {spacings(nearest / dx)} from it)"
            )
            what = (
                "of each load's own (h = max(spacing, horizon / 3), d its distance), summed with each load's response "
                "beside the whole's"
            )
        which = (
            "the deflection, the rotation and the moment" if turn and turn <= 1.0 else "the deflection and the moment"
        )
        rotation = (
            f", the rotation up to {turn:g} times that ({rounded_up(total * turn)})" if turn and turn > 1.0 else ""
        )
        out.append(
            f"{head}: {which} are off by about {c_of[side]:g} (h / d)² {what}, here {rounded_up(total)}{rotation}, "
            "which a load close to the end makes large beside their largest values (docs/trust.md); second order: "
            f"use at least {more} points for 1e-3"
        )
    return out


def describe(load) -> str:
    """How a warning names where a load acts: a point force's position, a distributed load's centroid."""
    return "a point force at" if isinstance(load, PointForce) else "a distributed load, its centroid at"
