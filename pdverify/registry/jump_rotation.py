"""The warning of a rotation that is small beside a jump of the shear: a point force or a support's reaction inside
the span makes V jump by J, and the PD models' w (or rotation unknown) carries an error of about c |J| h² / EI in the
rotation at the points next to it (h = max(spacing, horizon / 3), c the model's ``jump_rotation``): second order, but
large beside max |rotation| where the rotation is small and the shear large, as between a point force and a support
close to it (docs/trust.md, "The rotation beside a jump of the shear")."""

from __future__ import annotations

import numpy as np

from ..core.scene import PointForce, Scene

TOLERANCE = 1e-3  # the estimated error (of max |rotation|) above which it is a warning
MARGIN = 1.1  # on the points the warning asks for: the estimate divides by the model's max |rotation|, off by its error


def shear_jumps(scene: Scene, reactions: dict) -> list[tuple[str, float, float]]:
    """(name, position, J) of every jump of the shear inside the span: the point forces and the reactions of the
    supports inside that hold the deflection (``reactions``: the result's, ``force_inner_i``)."""
    L = scene.length
    out = [
        (f"loads[{i}] (a point force at {ld.position:g})", ld.position, ld.value)
        for i, ld in enumerate(scene.loads)
        if isinstance(ld, PointForce) and ld.value and 0.0 < ld.position < L
    ]
    out += [
        (f"supports.inner[{i}] at {s.position:g}", s.position, float(reactions.get(f"force_inner_{i}", 0.0)))
        for i, s in enumerate(scene.supports.inner)
        if s.holds_deflection
    ]
    return out


def jump_rotation_warning(constant: float, scene: Scene, rotation: np.ndarray, info: dict) -> str:
    """The one-line warning where ``constant`` |J| h² / EI passes :data:`TOLERANCE` of max |rotation| beside some jump
    J (:func:`shear_jumps`), naming the largest and the points that bring it to the tolerance; "" otherwise."""
    top = float(np.abs(rotation).max()) if rotation is not None and len(rotation) else 0.0
    dx, delta = float(info.get("spacing", 0.0)), float(info.get("horizon", 0.0))
    if not constant or top == 0.0 or not dx:
        return ""
    h = max(dx, delta / 3.0)
    jumps = shear_jumps(scene, info.get("reactions", {}))
    if not jumps:
        return ""
    EI = scene.stiffness_at([p for _, p, _ in jumps])["EI"]
    est = constant * np.abs([J for _, _, J in jumps]) * h**2 / EI / top
    worst = int(np.argmax(est))
    if est[worst] <= TOLERANCE:
        return ""
    points = int(np.ceil(MARGIN * scene.length / dx * np.sqrt(est[worst] / TOLERANCE))) + 1
    return (
        f"rotation beside {jumps[worst][0]}: the shear jumps by {jumps[worst][2]:.3g} there, and the rotation at the "
        f"points next to it is off by about {constant:g} |J| h² / EI (h = max(spacing, horizon / 3)), here "
        f"{est[worst]:.2g} of max |rotation| (large where the rotation is small beside the shear: a point force near "
        f"a support inside; docs/trust.md); second order: use at least {points} points for 1e-3"
    )
