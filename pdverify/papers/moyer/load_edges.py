"""A distributed axial load or torque that ends inside a rod or a torsion bar (pd-rod, pd-torsion): its jump bends the
displacement's (twist's) slope there, which the horizon's bonds smooth over about a horizon, so the result is off by
about c Σ |p| h² / S (docs/trust.md, "A load that ends inside a rod or a bar"; benchmarks/member_edges.py)."""

from __future__ import annotations

import numpy as np

from ...core.scene import Distributed, Scene
from ...core.text import listed, rounded_down, rounded_up
from ...numerics.load_warnings import NEAR_TOLERANCE


def member_edge_warnings(
    scene: Scene,
    x: np.ndarray,
    field: np.ndarray,
    stiffness,
    component: str,
    constant: float,
    delta: float,
    fixed: bool = False,
) -> list[str]:
    """One line per distributed axial load or torque (``component``: "axial" or "torque") of a rod or a torsion bar
    whose edges inside the member make ``constant`` Σ |p| h² / S pass NEAR_TOLERANCE of the ``field``'s largest (u
    or the twist, the model's on ``x``; p the load's jump at an edge, S = ``stiffness(e)``, EA or GJ there, h =
    max(spacing, ``delta`` / 3)): the load's jump bends the field's slope, which the horizon's bonds smooth, second
    order (measured: benchmarks/member_edges.py, docs/trust.md). ``fixed``: the horizon is a given length, so more
    points do not take h below delta / 3 and the fix names a shorter horizon too."""
    dx, L = float(x[1] - x[0]), scene.length
    h = max(dx, delta / 3.0)
    top = float(np.max(np.abs(field))) if len(field) else 0.0
    if not (top > 0.0 and np.isfinite(top)):
        return []
    out = []
    for i, ld in enumerate(scene.loads):
        value = getattr(ld, component, None) if isinstance(ld, Distributed) else None
        if not value:
            continue
        edges = [e for e in scene.span(ld) if 1e-12 * L < e < L * (1 - 1e-12)]
        jumps = [abs(value * float(scene.load_shape(ld, e))) / stiffness(e) for e in edges]
        total = constant * sum(jumps) * h * h / top
        if not total > NEAR_TOLERANCE:
            continue
        target = h * np.sqrt(NEAR_TOLERANCE / total) / 1.05  # the h that brings it to 1e-3
        if fixed and delta / 3.0 > target:
            most = int(np.ceil(L / target)) + 1
            fix = f"a horizon_length of at most {rounded_down(3 * target)} and at least {most} points"
        else:
            fix = f"at least {int(np.ceil(L / (dx * target / h))) + 1} points"  # h in proportion to dx
        what = "an axial load" if component == "axial" else "a torque"
        out.append(
            f"loads[{i}] ({what}) ends inside the member at x = {listed(edges)}: its jump bends the slope there, which "
            f"the horizon smooths, and the result is off by up to about {constant:g} Σ |p| h² / S (p its jump, S = "
            f"{'EA' if component == 'axial' else 'GJ'}, h = max(spacing, horizon / 3)), here {rounded_up(total)} of "
            f"its largest (docs/trust.md); second order: use {fix} for 1e-3"
        )
    return out
