"""Models ``exact-rod`` and ``exact-torsion``: the closed-form static axial displacement of an elastic rod and
twist of a torsion bar on any straight scene (the static references of ``pd-rod`` and ``pd-torsion``).

Both are one second-order equation, S f'' = -p (rod: f = u, S = EA, p the axial load per length, point forces
``axial``; bar: f = twist, S = GJ, p the torque per length, ``point_torque``). With F(x) the load acting on
[0, x] (a load at a acts on x > a, as in :mod:`.straight`) and G = ∫₀ˣ F, equilibrium of [0, x] gives the
resultant R(x) = R₀ - F(x) (N or T) and S f(x) = S f₀ + R₀ x - G(x). An end that holds the unknown
(``scene.ROD_HELD``) has f = 0, one that does not has R = 0:

* held-held: f₀ = 0, R₀ = G(L)/L;  held-free: f₀ = 0, R₀ = F(L);  free-held: R₀ = 0, S f₀ = G(L).

F and G of the distributed loads are the particular moment's first and second integrals of :mod:`.straight`
(Mp'' = q), so every load shape is integrated analytically: exact to round-off at any x.
"""

from __future__ import annotations

import numpy as np

from ..core.contract import POINTS, Model
from ..core.result import Result, Timer
from ..core.scene import ROD_HELD, Distributed, PointForce, PointTorque, Scene
from .straight import _active, _distributed_terms


def load_integrals(scene: Scene, x, kind: str) -> tuple[np.ndarray, np.ndarray]:
    """(F, G) at x: the axial load (``kind = "axial"``) or the torque (``"torsion"``) on [0, x], and its integral."""
    x = np.asarray(x, dtype=float)
    L = scene.length
    F, G = np.zeros_like(x), np.zeros_like(x)
    for load in scene.loads:
        if isinstance(load, Distributed):
            v = load.axial if kind == "axial" else load.torque
            if v != 0.0:
                a, b = scene.span(load)
                g, f = _distributed_terms(load.model_copy(update={"value": v}), a, b, L, x)[:2]
                F, G = F + f, G + g
            continue
        if kind == "axial" and isinstance(load, PointForce):
            v = load.axial
        elif kind == "torsion" and isinstance(load, PointTorque):
            v = load.value
        else:
            continue
        on = _active(x, load.position, L)
        F += np.where(on, v, 0.0)
        G += np.where(on, v * (x - load.position), 0.0)
    return F, G


class ExactRod(Model):
    """The exact static rod (``theory = "axial"``) or torsion bar (``"torsion"``); see the module docstring."""

    options = (POINTS,)
    source = "closed-form integration of the rod / torsion-bar equation (textbook)"
    reference = True
    bending = False

    def __init__(self, theory: str):
        axial = theory == "axial"
        self.name = "exact-rod" if axial else "exact-torsion"
        self.title = "exact elastic rod (axial displacement)" if axial else "exact torsion bar (twist)"
        self.theory = theory
        self.axial, self.torsion = axial, not axial
        self.measures, self.resultant = ("u", "N") if axial else ("twist", "T")
        self.load_types = frozenset({"point_force", "distributed"} if axial else {"point_torque", "distributed"})

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = (scene.supports.left, scene.supports.right)
        if not set(sup) & set(ROD_HELD[self.theory]):
            what = "axial displacement" if self.theory == "axial" else "twist"
            out.append(
                f"supports = {sup[0]}-{sup[1]}: neither end holds the {what}, so the bar is a mechanism; make one "
                f"end {' or '.join(ROD_HELD[self.theory])}"
            )
        return out

    def stiffness(self, scene: Scene) -> float:
        return scene.EA if self.theory == "axial" else scene.material.G * scene.section.J

    def evaluator(self, scene: Scene, params: dict):
        """x -> {measures: f, resultant: R}, the constants f₀, R₀ found once (module docstring)."""
        L, S = scene.length, self.stiffness(scene)
        held = [s in ROD_HELD[self.theory] for s in (scene.supports.left, scene.supports.right)]
        FL, GL = (float(v[0]) for v in load_integrals(scene, [L], self.theory))
        f0, R0 = (0.0, GL / L) if all(held) else (0.0, FL) if held[0] else (GL / S, 0.0)

        def fields(x):
            F, G = load_integrals(scene, x, self.theory)
            return {self.measures: f0 + (R0 * np.asarray(x, float) - G) / S, self.resultant: R0 - F}

        return fields

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            x = np.linspace(0.0, scene.length, params["points"])
            f = self.evaluator(scene, params)(x)
        key = "axial" if self.theory == "axial" else "torque"
        return self.new_result(
            scene,
            params,
            x,
            np.zeros_like(x),
            fields=f,
            dofs=2,
            timings=timer.timings,
            # the supports' reactions on the bar (+x, or right-handed about +x): -R(0) at the left, R(L) at the right
            info={
                "reactions": {f"{key}_left": float(-f[self.resultant][0]), f"{key}_right": float(f[self.resultant][-1])}
            },
        )


MODELS = [ExactRod("axial"), ExactRod("torsion")]
