"""The warning of a rotation that is small beside a jump of the shear: a point force or a support's reaction makes V
jump by J (at an end, from nothing to the reaction), and the PD models' w (or rotation unknown) carries an error of
about c |J| h² / EI in the rotation at the points next to it (h = max(spacing, horizon / 3), c the model's
``jump_rotation``): second order, but large beside max |rotation| where the rotation is small and the shear large, as
between a point force and a support close to it (docs/trust.md, "The rotation beside a jump of the shear")."""

from __future__ import annotations

import numpy as np

from ..core.scene import PointForce, Scene
from ..core.text import rounded_up
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning

NEAR = 0.25  # a jump within this share of the length of a support held at first order is beside it
TIE = 1e-9  # estimates within this share of the largest: equal jumps, rounded apart
MARGIN = 1.1  # on the points the warning asks for: the estimate divides by the model's max |rotation|, off by its error


def shear_jumps(scene: Scene, reactions: dict, dx: float) -> list[tuple[str, float, float]]:
    """(name, position, J) of every jump of the shear: the point forces, the ends' forces and the reactions of the
    supports inside that hold the deflection (``reactions``: the result's ``force_left``, ``force_right``,
    ``force_inner_i``; none at a free end), those within 1e-9 spacings of each other one jump (a force on a support:
    their sum), in the order of position."""
    L = scene.length
    parts = [
        (f"loads[{i}] (a point force at {ld.position:g})", ld.position, ld.value)
        for i, ld in enumerate(scene.loads)
        if isinstance(ld, PointForce) and ld.value
    ]
    parts += [
        (f"supports.inner[{i}] at {s.position:g}", s.position, float(reactions.get(f"force_inner_{i}", 0.0)))
        for i, s in enumerate(scene.supports.inner)
        if s.holds_deflection
    ]
    parts += [
        (f"the {side} end", at, float(reactions.get(f"force_{side}", 0.0)))
        for side, at in (("left", 0.0), ("right", L))
    ]
    out: list[tuple[str, float, float]] = []
    for name, at, J in sorted(parts, key=lambda p: p[1]):
        if out and abs(at - out[-1][1]) <= 1e-9 * dx:
            out[-1] = (f"{out[-1][0]} and {name}", out[-1][1], out[-1][2] + J)
        else:
            out.append((name, at, J))
    return out


def jump_estimates(constants: tuple[float, float], scene: Scene, rotation, info: dict) -> tuple:
    """(the jumps of :func:`shear_jumps`, each one's c, each one's c |J| h² / (EI max |rotation|)), c the first of
    ``constants`` inside the span and the second at an end; empty where nothing is estimated (no rotation, no
    spacing)."""
    top = float(np.abs(rotation).max()) if rotation is not None and len(rotation) else 0.0
    dx, delta = float(info.get("spacing", 0.0)), float(info.get("horizon", 0.0))
    if top == 0.0 or not dx:
        return [], np.zeros(0), np.zeros(0)
    h = max(dx, delta / 3.0)
    jumps = shear_jumps(scene, info.get("reactions", {}), dx)
    at = np.array([p for _, p, _ in jumps])
    end = (at <= 1e-9 * dx) | (at >= scene.length - 1e-9 * dx)
    c = np.where(end, constants[1], constants[0])
    return jumps, c, c * np.abs([J for _, _, J in jumps]) * h**2 / scene.stiffness_at(at)["EI"] / top


def jump_rotation_warning(constants: tuple[float, float], scene: Scene, rotation, info: dict) -> str:
    """The one-line warning where c |J| h² / EI passes :data:`TOLERANCE` of max |rotation| beside some jump J
    (:func:`jump_estimates`), naming the largest and the points that bring it to the tolerance; "" otherwise."""
    jumps, c, est = jump_estimates(constants, scene, rotation, info)
    # a support the model holds at first order only (its own line, e.g. pd-bond-pair's inner clamps and rotational
    # spring ends, gives the size): beside it the rotation's error is that support's, far above this second-order
    # estimate (docs/trust.md); the jumps there are left out, and a line for another gives only the jump's own part
    said = [w for w in info.get("warnings", []) if "first order in the spacing" in w]
    held = [(tag, pos) for tag, pos in support_tags(scene) if any(w.startswith(tag) for w in said)]
    beside = [any(abs(pos - at) < NEAR * scene.length for _, pos in held) for _, at, _ in jumps]
    est = np.where(beside, 0.0, est) if len(est) else est
    if not len(est) or est.max() <= TOLERANCE:
        return ""
    worst, dx = int(np.argmax(est)), float(info["spacing"])
    # equal jumps (a symmetric scene's two ends) are named together: which one rounding puts first is no fact of the
    # scene, and its mirror image would name the other
    ties = [jumps[i][0] for i in np.flatnonzero(est >= est[worst] * (1 - TIE))]
    points = int(np.ceil(MARGIN * scene.length / dx * np.sqrt(est[worst] / TOLERANCE))) + 1
    where = ", ".join(tag.strip() for tag, _ in held)
    # the first-order support's error is not confined to its neighbourhood: it turns the whole span (docs/trust.md),
    # so the jump's own part is all this line gives there, and no count of points brings the rotation to 1e-3
    tail = (
        f"; that is the jump's own part: the rotation everywhere also carries the first-order error of {where}, "
        "whose own line gives its size (more points reduce it at first order only)"
        if held
        else f"; second order: use at least {points} points for 1e-3"
    )
    return (
        f"rotation beside {' and '.join(ties)}: the shear jumps by {jumps[worst][2]:.3g} "
        f"{'there' if len(ties) == 1 else 'at each'}, and the rotation at the points next to it is off by about "
        f"{c[worst]:g} |J| h² / EI (h = max(spacing, horizon / 3)), here "
        f"{rounded_up(est[worst])} of max |rotation| (large where the rotation is small beside the shear: a point "
        f"force near a support, a clamp; docs/trust.md){tail}"
    )


def support_tags(scene: Scene) -> list[tuple[str, float]]:
    """(the prefix a support's warnings start with, its position) of every support."""
    tags = [(f"supports.inner[{i}] ", s.position) for i, s in enumerate(scene.supports.inner)]
    return tags + [("supports.left", 0.0), ("supports.right", scene.length)]
