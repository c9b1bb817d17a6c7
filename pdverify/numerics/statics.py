"""Support reactions of a straight beam closed by statics: a model gives a value for every reaction it can (its
multipliers, its end moments and shears); two of them are then taken from the two equilibrium equations, so the
reactions balance the loads to round-off whatever the model's discretisation error, and a statically determinate
beam's reactions are exact. Sign convention as exact-eb: force +z on the beam, moment counter-clockwise on the beam.
"""

from __future__ import annotations

import numpy as np

from ..core.reactions import load_resultants
from ..core.scene import HELD, Scene, Spring


def reaction_keys(scene: Scene) -> list[tuple[str, float, float]]:
    """(key, force coefficient, moment coefficient about x = 0) of every reaction the supports give: rigid end and
    inner forces, then springs' forces, then rigid moments, then springs' moments (the order statics picks from)."""
    L = scene.length
    rigid_f, spring_f, rigid_m, spring_m = [], [], [], []
    for side, at in (("left", 0.0), ("right", L)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            if sup.stiffness:
                spring_f.append((f"force_{side}", 1.0, at))
            if sup.rotational_stiffness:
                spring_m.append((f"moment_{side}", 0.0, 1.0))
            continue
        if HELD[sup][1]:
            rigid_f.append((f"force_{side}", 1.0, at))
        if HELD[sup][2]:
            rigid_m.append((f"moment_{side}", 0.0, 1.0))
    for i, s in enumerate(scene.supports.inner):
        spring = s.type == "spring"
        if s.holds_deflection:
            (spring_f if spring else rigid_f).append((f"force_inner_{i}", 1.0, s.position))
        if s.holds_rotation:
            (spring_m if spring else rigid_m).append((f"moment_inner_{i}", 0.0, 1.0))
    return rigid_f + spring_f + rigid_m + spring_m


def closed_reactions(scene: Scene, model: dict[str, float]) -> dict:
    """Every reaction of ``scene``'s supports (zero where the supports give none): the model's values ``model``
    (missing ones count as unknown), two of them replaced by statics (the first force, then the first reaction
    that makes the two equations independent); ``method`` says which."""
    keys = reaction_keys(scene)
    P, Mo = load_resultants(scene)
    L = scene.length
    first = next(k for k in keys if k[1] != 0.0)
    # independent of the first force: another force 1e-9 L away from it (the determinant a length), or a moment (1)
    scale = lambda k: max(L, 1e-300) if k[1] else 1.0  # noqa: E731
    second = next(k for k in keys if k is not first and abs(first[1] * k[2] - first[2] * k[1]) > 1e-9 * scale(k))
    out = {f"{kind}_{side}": 0.0 for side in ("left", "right") for kind in ("force", "moment")}
    out.update({k: float(model.get(k, 0.0)) for k, _, _ in keys})
    rest_f = P + sum(out[k] * cf for k, cf, _ in keys if k not in (first[0], second[0]))
    rest_m = Mo + sum(out[k] * cm for k, _, cm in keys if k not in (first[0], second[0]))
    A = np.array([[first[1], second[1]], [first[2], second[2]]])
    a, b = np.linalg.solve(A, -np.array([rest_f, rest_m]))
    out[first[0]], out[second[0]] = float(a), float(b)
    given = [k for k, _, _ in keys if k not in (first[0], second[0])]
    out["method"] = f"statics for {first[0]} and {second[0]}" + (
        f"; the model's own values for {', '.join(given)}" if given else " (statically determinate)"
    )
    return out
