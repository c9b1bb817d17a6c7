"""The orders pd-timoshenko, pd-rod and pd-torsion lose under point loads and springs, as warnings with their measured
numbers (docs/models/moyer.md, "Known limits"): arrays and scenes in, lines out."""

from __future__ import annotations

from ...core.scene import Scene, Spring
from ...core.text import listed
from ...numerics.recovery import kink_positions
from .pieces import holds


def rod_points_loaded(model, scene: Scene) -> list[float]:
    """Where a single point of pd-rod (pd-torsion) carries a force inside the member: its point forces (torques),
    and the supports and springs inside that act on its unknown (:func:`.pieces.holds`: a rod's pinned, clamped and
    a spring's ``stiffness``; a bar's pinned, roller, clamped and a spring's ``rotational_stiffness``)."""
    torsion = model.unknowns == "torsion"
    return [
        ld.position
        for ld in scene.loads
        if (ld.type == "point_torque" if torsion else ld.type == "point_force" and ld.axial != 0.0)
        and 0.0 < ld.position < scene.length
    ] + [h.position for h in holds(scene, model.unknowns) if h.label.startswith("inner")]


def rod_point_load_order(model, scene: Scene, params: dict) -> list[str]:
    """pd-rod's and pd-torsion's first-order warning: a point force (torque), a support or a spring inside, m > 1."""
    inside = rod_points_loaded(model, scene)
    torsion = model.unknowns == "torsion"
    if params["horizon"] <= 1 or not inside:
        return []
    what = "a point torque" if torsion else "an axial point force"
    return [
        f"{model.name} converges at first order near {what}, a support or a spring inside (x = {listed(inside)}): "
        "the load on one point makes a spike about a horizon wide (m = 3: 2.15e-2, 1.07e-2, 5.37e-3 at 101, 201, 401 "
        "points on a centre load; 1.2e-1, 3.0e-2, 7.6e-3 at 101, 401, 1601 on two spans over a rigid support under "
        "a sine load; a stiff spring at mid-span of a free-free bar 5.1e-2, 2.6e-2, 1.3e-2 at 101, 201, 401; more at "
        "a longer horizon, and the resultant near a spring a few spacings from an end up to 0.2 of its largest); "
        "with horizon = 1 the points are exact"
    ]


def beam_points_loaded(scene: Scene) -> list[float]:
    """Where a transverse point force acts inside the beam (not at its ends), in the scene's order."""
    return [
        ld.position
        for ld in scene.loads
        if ld.type == "point_force" and ld.value != 0.0 and 0.0 < ld.position < scene.length
    ]


def point_force_order(model, scene: Scene, params: dict) -> list[str]:
    """The known losses of order under a point load (docs/models/moyer.md, "Known limits"): the corrected beam's
    transverse point force inside the beam (its jump in shear falls between the collocation points' PD sums); the
    rod's and the bar's point force (torque) or rigid support inside, for m > 1 (the load on one point, P / (A Δ),
    makes a spike of u about a horizon wide)."""
    if not model.bending:
        return rod_point_load_order(model, scene, params)
    if params["variant"] != "corrected":
        return []
    out, inside = [], beam_points_loaded(scene)
    if inside:
        out.append(
            "variant = corrected converges at first order near a point force inside the beam "
            f"(x = {listed(inside)}): the error halves, not quarters, per halving of the spacing "
            "(1.0e-3, 5.0e-4, 2.5e-4 at 321, 641, 1281 points on a centre force, L/h = 5), and the shear at the points "
            "beside it does not converge (76 % of max |V| off at 81 to 641 points, clamped-clamped, L/h = 20); "
            "variant = energy is second order there"
        )
    edges = kink_positions(scene)  # the distributed loads' ends inside the beam
    if len(edges):
        out.append(
            "variant = corrected: the shear beside a distributed load's edge inside the beam (x = "
            f"{listed(edges)}) converges at first order (1.14e-2, 5.7e-3, 2.8e-3 of max |V| at "
            "101, 201, 401 points: a cantilever loaded on its first 0.1 m, L/h = 20); variant = energy is second "
            "order there"
        )
    couples = [ld.position for ld in scene.loads if ld.type == "point_moment" and 0.0 < ld.position < scene.length]
    if couples:
        out.append(
            "variant = corrected: the moment at the points beside a couple inside the beam (x = "
            f"{listed(couples)}) does "
            "not converge (54 % of max |M| off at 81 to 641 points, a centre couple on a clamped-clamped beam, L/h = "
            "20); variant = energy is second order there"
        )
    rigid = [f"supports.inner[{i}]" for i, sup in enumerate(scene.supports.inner) if sup.type != "spring"]
    springs = [f"supports.inner[{i}]" for i, sup in enumerate(scene.supports.inner) if sup.type == "spring"]
    if springs:
        out.append(
            f"variant = corrected converges at first order near a spring inside the beam ({', '.join(springs)}): its "
            "force is a point force on the two points around it, and the shear at the points beside it does not "
            "converge (34 % of max |V| off at 101, 401 and 1601 points, M 2.5e-2, 6.2e-3, 1.6e-3 of max |M|: a "
            "spring of 2e6 N/m at mid-span of a pinned-pinned beam under a uniform load, L/h = 25); variant = energy "
            "is second order there"
        )
    ends = [
        s for s in ("left", "right") if isinstance(e := getattr(scene.supports, s), Spring) and e.rotational_stiffness
    ]
    if ends:
        out.append(
            f"variant = corrected: the shear at the point next to a spring end with rotational stiffness "
            f"({' and '.join(ends)}) converges at first order (1.08, 0.27, 0.067 of max |V| off at 101, 401, 1601 "
            "points: a cantilever on a spring of 1e6 N/m and 5e4 N m/rad under a tip force; w and M are not "
            "affected); variant = energy is exact there"
        )
    if rigid:
        out.append(
            f"variant = corrected converges at first order near a rigid support inside the beam ({', '.join(rigid)}): "
            "its reaction is a point force (and couple) on the two points around it (2.9e-2, 1.4e-2, 7.1e-3, 3.5e-3 "
            "at 101 ... 801 points, a clamp at 0.3 L of a pinned-pinned beam under a uniform load, L/h = 20; "
            "1.3e-2 ... 1.1e-3 with a pin at mid-span), and the shear at the points beside it does not converge (73 % "
            "of max |V| off at 41 to 641 points, a pin at 0.6 L of a pinned-free beam under a uniform load, L/h = 20; "
            "at a clamp there V 74 % and M 12 %); variant = energy is second order there"
        )
    return out
