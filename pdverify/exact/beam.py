"""Models ``exact-eb`` and ``exact-timoshenko``: closed-form deflection of any straight scene."""

from __future__ import annotations

import numpy as np

from ..core.contract import LOAD_TYPES, POINTS, Model
from ..core.result import Result, Timer
from ..core.scene import Scene
from ..numerics.error_bound import record_bound
from .brittle import BrittleDisplacement, displacement_load
from .plastic import solve_path
from .straight import solve_straight


def bound_grid(scene: Scene) -> np.ndarray:
    """Where the round-off bound of a closed form is taken, whatever points a solve asks for: 1001 points along the
    beam, its supports and its loads' positions and span ends."""
    marks = [s.position for s in scene.supports.inner]
    marks += [v for ld in scene.loads for v in ((ld.position,) if hasattr(ld, "position") else scene.span(ld))]
    return np.concatenate([np.linspace(0.0, scene.length, 1001), np.asarray(marks, float)])


def follows_path(scene: Scene) -> bool:
    """True when ``scene`` asks for a load path: a ``[loading]`` table, a yield stress or a failure strain."""
    mat = scene.material
    displaced = any(ld.type == "displacement" for ld in scene.loads)
    return scene.loading is not None or displaced or bool(mat.yield_stress or mat.failure_strain)


def _path(scene: Scene, x: np.ndarray):
    """(path, info, last-state fields at any x) of the scene's load path: a prescribed deflection on an elastic or
    brittle beam (:mod:`.brittle`), else the elastic-perfectly plastic or brittle beam under forces
    (:mod:`.plastic`)."""
    load = displacement_load(scene)
    if load is not None:
        beam = BrittleDisplacement(scene, load)
        path, info, (lam, failed) = beam.path(x)
        return path, info, lambda s: beam.fields(s, lam, failed)
    path, info, beam, (lam, peak) = solve_path(scene, x)

    def fields(s):
        s = np.asarray(s, float)
        w, rot, _ = beam.deflection(s, lam, peak)
        return {"w": w, "rotation": rot, "M": lam * beam.M1(s), "V": lam * beam.unit.fields(s)["V"]}

    return path, info, fields


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
        if not shear:  # the fibre law along a load path (pdverify.exact.plastic), statically determinate scenes
            self.materials = frozenset({"yield_stress", "failure_strain"})
            self.load_path = True
            self.load_types = LOAD_TYPES | {"displacement"}  # a prescribed deflection alone (pdverify.exact.brittle)

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def evaluator(self, scene: Scene, params: dict):
        if not self.shear and follows_path(scene):
            return self._path_evaluator(scene)
        sol = solve_straight(scene, self.shear)  # the constants once, then any x

        def fields(x):
            return sol.fields(x)

        fields.error_bound = sol.rounding(bound_grid(scene))  # a study's reference: its rows judge against it
        return fields

    def _path_evaluator(self, scene: Scene):
        """The last step's fields of the load path at any x."""
        return _path(scene, np.array([0.0]))[2]

    def solve(self, scene: Scene, params: dict) -> Result:
        if not self.shear and follows_path(scene):
            return self.solve_load_path(scene, params)
        timer = Timer()
        with timer("assemble"):
            x = np.linspace(0.0, scene.length, params["points"])
        with timer("solve"):
            sol = solve_straight(scene, self.shear)
            f = sol.fields(x)
        info = {"reactions": sol.reactions()}
        record_bound(info, sol.rounding(bound_grid(scene)))  # the evaluator's: a study's reference rows take it
        return self.new_result(
            scene,
            params,
            x,
            f["w"],
            rotation=f["rotation"],
            fields={"M": f["M"], "V": f["V"]},
            dofs=4,
            timings=timer.timings,
            info=info,
        )

    def solve_load_path(self, scene: Scene, params: dict) -> Result:
        """The elastic-perfectly plastic or brittle beam along the scene's load path (:mod:`.plastic`): the last
        step's fields, every step in ``Result.path``."""
        timer = Timer()
        with timer("solve"):
            x = np.linspace(0.0, scene.length, params["points"])
            path, info, fields = _path(scene, x)
            f = fields(x)
        return self.new_result(
            scene,
            params,
            x,
            f["w"],
            rotation=f["rotation"],
            fields={"M": f["M"], "health": path[-1]["health"]},
            dofs=4,
            timings=timer.timings,
            info=info,
            path=path,
        )


MODELS = [
    ExactBeam("exact-eb", False, "exact Euler–Bernoulli beam"),
    ExactBeam("exact-timoshenko", True, "exact Timoshenko beam"),
]
