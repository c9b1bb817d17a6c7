"""The warning of a load near an end that holds the deflection: the PD beams' deflection under a point force or a
distributed load a distance d (its centroid's) from a clamped or pinned end is off by about C (h / d)² of the load's
own deflection, h = max(spacing, horizon / 3): second order at a fixed d, but at a fixed number of spacings it does
not fall, and a load close to a clamp bends the beam little, so the error is large beside max |w| (the ends' ghosts
and the families at the support carry the load's curvature; docs/trust.md, "Loads near an end"). A point load in
the end's layer is left to that layer's warning."""

from __future__ import annotations

import numpy as np

from ..core.scene import Distributed, PointForce, Scene
from ..core.text import rounded_up
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning

CLOSEST = 2.5  # in h: nearer, the estimate is not measured (benchmarks/end_loads.py starts there) and the error can
# pass the solution's own size (a patch on the first 2 spacings of a cantilever: 0.86 of max |w| at 201 points)
NEAR = 0.25  # a load is near an end when d is below this share of the length: farther off the end's part is no larger
# than the beam's own discretisation error (a uniform load: 7.4e-4 at 41 points where C (h / d)² is 1.6e-3), which
# --estimate gives
KIND = {"clamped": "clamped", "pinned": "pinned", "roller": "pinned"}  # the constant each end takes (guided and free
# ends: not measured, not estimated)
STIFF = 100.0  # k L³ / EI from which a spring end holds the deflection as a pin does (the PD beams' errors of the pin
# to 3 digits at 1e8-1e12 N/m on a 1 m beam of EI 4.2e4 N m², k L³ / EI 2.4e3-2.4e7); a softer one moves with the load


def end_kind(scene: Scene, side: str) -> str:
    """The constant an end takes: its :data:`KIND`; a spring end of translational stiffness only, past :data:`STIFF`,
    the pinned end's; "" for the others (a soft spring, whose end moves with the load; a rotational spring, where
    the PD beams' own warnings of a first-order end apply)."""
    sup = getattr(scene.supports, side)
    if isinstance(sup, str):
        return KIND.get(sup, "")
    EI = float(scene.stiffness_at([0.0 if side == "left" else scene.length])["EI"][0])
    stiff = sup.stiffness * scene.length**3 >= STIFF * EI
    return "pinned" if stiff and not sup.rotational_stiffness else ""


_GX, _GW = np.polynomial.legendre.leggauss(16)


def arm(scene: Scene, load, end: float) -> float:
    """The distance from ``end`` of a point force, or of a distributed load's centroid (its shape's, on its span)."""
    if isinstance(load, PointForce):
        return abs(load.position - end)
    a, b = scene.span(load)
    s = (a + b) / 2 + (b - a) / 2 * _GX
    q = np.abs(scene.load_shape(load, s)) * _GW
    return abs(float((q * s).sum() / q.sum()) - end) if q.sum() > 0 else 0.0


def end_load_warnings(constants: dict, scene: Scene, info: dict) -> list[str]:
    """One line per load whose ``constants[kind]`` (h / d)² passes :data:`TOLERANCE` at an end it is near (d below
    :data:`NEAR` of the length; kind: :func:`end_kind`; the larger of the two ends), with the points that bring
    it to the tolerance; none for a point load in the end's layer, which its own warning in ``info`` names."""
    dx, delta = float(info.get("spacing", 0.0)), float(info.get("horizon", 0.0))
    if not dx:
        return []
    h = max(dx, delta / 3.0)
    said = info.get("warnings", [])
    sides = (("left", 0.0), ("right", scene.length))
    ends = [(side, at, constants.get(end_kind(scene, side), 0.0)) for side, at in sides]  # once per end
    out = []
    for i, ld in enumerate(scene.loads):
        layer = any(w.startswith(f"loads[{i}] at ") and "boundary layer" in w for w in said)  # the layer's own
        if not isinstance(ld, (PointForce, Distributed)) or not ld.value or layer:
            continue
        near = []  # (estimate, side, d, c) at each end that takes a constant
        for side, end, c in ends:
            d = arm(scene, ld, end)
            if c and 1e-9 * dx < d < NEAR * scene.length:
                near.append((min(c * (h / d) ** 2, 1.0), side, d, c))
        if not near or (top := max(near))[0] <= TOLERANCE:
            continue
        est, side, d, c = top
        what = "a point force at" if isinstance(ld, PointForce) else "a distributed load, its centroid at"
        at = d if side == "left" else scene.length - d
        head = f"loads[{i}] ({what} {at:g}) is {d / dx:.3g} spacings from the {side} end ({scene.supports.kind(side)})"
        if d < CLOSEST * h:
            points = int(np.ceil(scene.length / d * max(CLOSEST, np.sqrt(c / TOLERANCE)) * (h / dx))) + 1
            out.append(
                f"{head}: nearer than {CLOSEST:g} h (h = max(spacing, horizon / 3)) its deflection is not estimated: "
                f"expect large errors, up to the solution's own size (docs/trust.md); use at least {points} points"
            )
            continue
        points = int(np.ceil(scene.length / dx * np.sqrt(est / TOLERANCE))) + 1
        out.append(
            f"{head}: the deflection is off by about {c:g} (h / d)² of the load's own (h = max(spacing, horizon / 3), "
            f"d its distance), here {rounded_up(est)}, which a load close to the end makes large beside max |w| "
            f"(docs/trust.md); second order: use at least {points} points for 1e-3"
        )
    return out
