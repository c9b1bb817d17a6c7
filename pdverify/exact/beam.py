"""Models ``exact-eb`` and ``exact-timoshenko``: closed-form deflection of any straight scene."""

from __future__ import annotations

import numpy as np

from ..core.contract import POINTS, Model
from ..core.result import Result, Timer
from ..core.scene import Scene
from .straight import solve_straight


class ExactBeam(Model):
    options = (POINTS,)
    source = "closed-form integration of the beam equations (textbook), piece by piece between supports and segments"

    reference = True
    springs = True
    inner_supports = True
    segments = True

    def __init__(self, name: str, shear: bool, title: str):
        self.name, self.shear, self.title = name, shear, title
        self.theory = "timoshenko" if shear else "euler-bernoulli"

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return solve_straight(scene, self.shear).fields(x)

    def evaluator(self, scene: Scene, params: dict):
        return solve_straight(scene, self.shear).fields  # the constants once, then any x

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("assemble"):
            x = np.linspace(0.0, scene.length, params["points"])
        with timer("solve"):
            sol = solve_straight(scene, self.shear)
            f = sol.fields(x)
        return self.new_result(
            scene,
            params,
            x,
            f["w"],
            rotation=f["rotation"],
            fields={"M": f["M"], "V": f["V"]},
            dofs=4,
            timings=timer.timings,
            info={"reactions": sol.reactions()},
        )


MODELS = [
    ExactBeam("exact-eb", False, "exact Euler–Bernoulli beam"),
    ExactBeam("exact-timoshenko", True, "exact Timoshenko beam"),
]
