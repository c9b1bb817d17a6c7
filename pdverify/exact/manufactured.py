"""Model ``exact-curved-manufactured``: the chosen fields of the manufactured curved-beam solution
(:mod:`pdverify.theory.curved_manufactured`, the quintic example). The loads that produce them are not scene
loads: ``pd-curved-mms`` adds them. The scene must be clamped at both ends and carry no [[loads]]."""

from __future__ import annotations

import numpy as np

from ..core.contract import POINTS, Model
from ..core.geometry import geometry
from ..core.result import Result, Timer
from ..core.scene import Scene
from ..theory.curved_manufactured import FIELDS, fields, manufactured_checks


class ExactCurvedManufactured(Model):
    name = "exact-curved-manufactured"
    title = "manufactured solution of the curved Timoshenko–Ehrenfest beam (chosen fields)"
    source = (
        "pdverify.theory.curved_manufactured: u_t = U sin(pi x), u_n = U sin(2 pi x), phi = (U/L) sin(pi x)(1 - x) "
        "(fields = trig) or a beam-like bending field (fields = bending)"
    )
    options = (POINTS, FIELDS)
    theory = "timoshenko"
    curved = True
    axial = True
    reference = True

    def check(self, scene: Scene) -> list[str]:
        return super().check(scene) + manufactured_checks(scene)

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        x = np.asarray(x, float)
        f = fields(scene, x, kind=params.get("fields", "trig"))
        t, n = geometry(scene).frame(x)
        U = f["u_t"][:, None] * t + f["u_n"][:, None] * n
        return {
            "w": f["u_n"],
            "rotation": f["phi"],
            "u": f["u_t"],
            "ux": U[:, 0],
            "uy": U[:, 1],
            "N": f["N"],
            "Q": f["Q"],
            "M": f["M"],
        }

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            s = np.linspace(0.0, scene.length, params["points"])
            f = self.evaluate(scene, params, s)
        return self.new_result(
            scene,
            params,
            s,
            f["w"],
            rotation=f["rotation"],
            fields={k: v for k, v in f.items() if k not in ("w", "rotation")},
            dofs=0,
            timings=timer.timings,
            info={},
        )


MODELS = [ExactCurvedManufactured()]
