"""Model ``exact-eringen``: Eringen's differential nonlocal Euler–Bernoulli beam in closed form.

Eringen's constitutive law M - mu M'' = EI w'' (mu = (e0 a)^2) with equilibrium M'' = q gives EI w'''' = q - mu q''
(Reddy, Int. J. Eng. Sci. 45 (2007) 288–307, its Euler–Bernoulli case): the curvature is EI w'' = M - mu q, the
moment M a static field. Written as the local solution plus a correction (exact-eb's conventions: M sagging
positive, M'' = q, EI w'' = M):

    w = w_eb + u,   M = M_eb + c0 + c1 x,   EI u'' = c0 + c1 x - mu Q'',   Q = ∫∫ q (exact-eb's particular moment),

u holds the kinematic conditions homogeneously (a held deflection: u = 0; a held rotation: u' = 0) and the extra
moment c0 + c1 x the static ones (a free or pinned end: no moment; a free or guided end: no shear). Statically
determinate beams keep M = M_eb; a simply supported beam under a uniform load gets u = mu q (L x - x^2) / 2EI. A
clamped–clamped beam under a uniform load and a cantilever under a tip load get u = 0: the nonlocal effect vanishes
there (the paradox of the differential model: Peddieson, Buchanan & McNitt, Int. J. Eng. Sci. 41 (2003) 305–312;
Challamel & Wang, Nanotechnology 19 (2008) 345703). A point force inside the span kinks w (u' jumps by -mu P / EI);
a force at an end is a boundary condition and adds nothing; a couple inside the span would make w jump, and is
refused.
"""

from __future__ import annotations

import numpy as np

from ..core.contract import POINTS, Model, Option
from ..core.result import Result, Timer
from ..core.scene import HELD, PointForce, PointMoment, Scene
from .straight import particular, solve_straight


class ExactEringen(Model):
    name = "exact-eringen"
    title = "exact Eringen differential nonlocal Euler–Bernoulli beam"
    source = "Reddy 2007, Nonlocal theories for bending, buckling and vibration of beams: the Euler–Bernoulli case"
    options = (
        POINTS,
        Option("e0a", float, 0.0, "the nonlocal length e0 a (mu = (e0 a)^2), in the scene's length unit", minimum=0.0),
    )
    reference = True

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        L = scene.length
        for i, load in enumerate(scene.loads):
            if isinstance(load, PointMoment) and _interior(load.position, L):
                out.append(
                    f"loads[{i}]: a couple inside the span makes the deflection of Eringen's differential beam jump; "
                    "model exact-eringen takes couples at the ends only"
                )
        return out

    def evaluator(self, scene: Scene, params: dict):
        return eringen_fields(scene, params["e0a"] ** 2)

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            x = np.linspace(0.0, scene.length, params["points"])
            f = eringen_fields(scene, params["e0a"] ** 2)(x)
        return self.new_result(
            scene,
            params,
            x,
            f["w"],
            rotation=f["rotation"],
            fields={"M": f["M"], "V": f["V"]},
            dofs=4,
            timings=timer.timings,
            info={"mu": params["e0a"] ** 2},
        )


def _interior(position: float, L: float) -> bool:
    return 1e-12 * L < position < L * (1 - 1e-12)


def eringen_fields(scene: Scene, mu: float):
    """x -> {w, rotation, M, V} of Eringen's beam with mu = (e0 a)^2 (module docstring)."""
    local = solve_straight(scene, False)
    EI, L = scene.EI, scene.length
    inside = [q for q in scene.loads if not isinstance(q, (PointMoment, PointForce)) or _interior(q.position, L)]
    load = scene.model_copy(update={"loads": [q for q in inside if not isinstance(q, PointMoment)]})

    def basis(x):
        """Columns (c0, c1, a, b) of u and u', and their parts from the load."""
        x = np.asarray(x, float)
        Q, dQ, _, _, _ = particular(load, x)
        U = np.stack([x**2 / (2 * EI), x**3 / (6 * EI), np.ones_like(x), x], axis=-1)
        dU = np.stack([x / EI, x**2 / (2 * EI), np.zeros_like(x), np.ones_like(x)], axis=-1)
        return U, -mu * Q / EI, dU, -mu * dQ / EI

    rows, rhs = [], []
    for at, sup in ((0.0, scene.supports.left), (L, scene.supports.right)):
        U, u0, dU, du0 = (v[0] for v in basis(np.array([at])))
        holds_w, holds_rot = HELD[sup][1], HELD[sup][2]
        # u = 0 (a length), or no extra shear c1 (a force: times L^3/EI)
        rows.append(U if holds_w else np.array([0.0, L**3 / EI, 0.0, 0.0]))
        rhs.append(-u0 if holds_w else 0.0)
        # u' = 0 (times L), or no extra moment c0 + c1 at (times L^2/EI)
        rows.append(dU * L if holds_rot else np.array([L * L / EI, at * L * L / EI, 0.0, 0.0]))
        rhs.append(-du0 * L if holds_rot else 0.0)
    scale = np.array([EI / (L * L), EI / L**3, 1.0, 1.0 / L])  # unknowns in lengths: every entry of order one
    c = np.linalg.solve(np.array(rows) * scale, np.array(rhs)) * scale

    def fields(x):
        x = np.asarray(x, float)
        f = local.fields(x)
        U, u0, dU, du0 = basis(x)
        return {
            "w": f["w"] + U @ c + u0,
            "rotation": f["rotation"] + dU @ c + du0,
            "M": f["M"] + c[0] + c[1] * x,
            "V": f["V"] + c[1],
        }

    return fields


MODELS = [ExactEringen()]
