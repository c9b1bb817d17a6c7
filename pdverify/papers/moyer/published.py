"""What the published beam (pd-timoshenko ``variant = paper``, Moyer & Miraglia Section 4 as written) cannot do, as the
warnings its results carry: measured against exact-timoshenko (docs/models/moyer.md, "Known limits")."""

from __future__ import annotations

from ...core.scene import Scene


def paper_warnings(scene: Scene) -> list[str]:
    """The published beam (variant paper): Section 4 gives an end that does not hold both w and the rotation no
    traction condition, so the solution does not converge to the beam there (where both ends leave one free it is
    singular, refused); with both ends clamped its moment and shear are first order (the central differences of
    Eq. 45-46), and a point force or a couple inside stops them converging. Measured against exact-timoshenko, L/h =
    20, 81 to 641 points."""
    free = [
        f"{side} ({scene.supports.kind(side)})" for side in ("left", "right") if scene.supports.kind(side) != "clamped"
    ]
    if free:
        return [
            f"variant = paper: the {' and '.join(free)} end{'s' if len(free) > 1 else ''} free unknowns have no "
            "traction condition (Section 4 as published), so the solution does not converge to the beam (under a "
            "uniform load: clamped-free 2.1 and 1.7 times max |w| off exact-timoshenko at 41 and 161 points, "
            "clamped-pinned 207 and 12 times, spring ends 1.2 and 0.95 times); use variant energy or corrected"
        ]
    inside = {
        ld.type for ld in scene.loads if ld.type in ("point_force", "point_moment") and 0.0 < ld.position < scene.length
    }
    more = ""
    if "point_force" in inside:
        more += (
            "; under a point force inside the beam w stops converging about 9 % off and V beside it 3.3 times max |V|"
        )
    if "point_moment" in inside:
        more += "; beside a couple M stays 54 % of max |M| off (it does not converge)"
    return [
        "variant = paper: its moment and shear are first order (central differences of Eq. 45-46: V 80 %, 39 %, 19 %, "
        "9.5 % of max |V| off at 81, 161, 321, 641 points on a clamped-clamped beam under a uniform load)"
        + more
        + "; use variant energy"
    ]
