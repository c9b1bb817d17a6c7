"""Dynamics of ``pd-eb`` (Diyaroglu et al. 2019, Eq. 3-7 and 15): natural frequencies (``eigenproblem``) and explicit
transients of the equation of motion rho w_tt = (the PD bending force, Eq. 15) + b.

Kinetic energy (Eq. 3): T = (1/2) Σ_k rho w_k'^2 V_k, so the Euler-Lagrange equations (Eq. 4-7) put rho w_tt beside
the static operator's rows, which are forces per unit volume (Eq. 15: rho w_tt + (EI/A) w'''' = b in the limit):
K w + rho w_tt = b on the free points, mass rho per point (lumped, as the paper's sum). K is the direct form's
operator with its ends eliminated (Taylor ghosts for the corrected variant, the fictitious layers and master-slave
conditions for the paper's), whose end rows make it non-symmetric: its low frequencies are real (measured), and
an undamped run's energy balance closes to the size of that non-symmetric part (the result says it). A transient
runs by central differences (:mod:`pdverify.numerics.explicit`); energies in joules (rows times A dx).
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import Scene
from ...numerics.explicit import ANALYSIS, dynamic, dynamic_info, integrate, probe_rows, updates_per_second


def operators(model, scene: Scene, params: dict):
    """(K, mass, b, free, x): the direct form's operator and loads on the free points and the lumped mass rho."""
    if not scene.supports.simple or scene.segments:
        raise InputError(
            "supports: pd-eb's dynamics take a uniform beam held at its ends (the direct form); springs, supports "
            "inside the span and segments are static (mixed form); drop [dynamics] or them"
        )
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density (kg/m^3) to the scene")
    system = model.assemble(scene, dict(params, form="direct"))
    K, b = system.reduced()
    x = model.grid(scene, params)
    return K.tocsr(), np.full(K.shape[0], scene.material.density), b, np.asarray(system.free), x


def eigenproblem(model, scene: Scene, params: dict) -> tuple:
    """(K, mass): K phi = omega^2 rho phi on the free points (Eq. 15 with its inertia)."""
    K, mass, *_ = operators(model, scene, params)
    return K, mass


def bench(model, scene: Scene, params: dict, steps: int = 200) -> float:
    K, mass, b, *_ = operators(model, scene, params)
    return updates_per_second(K, mass, b, params["points"], steps)


def transient(model, scene: Scene, params: dict) -> Result:
    """An explicit run of Eq. 15 from rest under the scene's loads (``[dynamics]``)."""
    timer = Timer()
    d = scene.dynamics
    with timer("assemble"):
        K, mass, b, free, x = operators(model, scene, params)
    rows, probes = probe_rows(x, d.probes)
    rows = rows[:, free].tocsr()
    with timer("solve"):
        run = integrate(
            K,
            mass,
            b,
            d.end_time,
            rows.__matmul__,
            dt=d.time_step,
            damping=d.damping or 0.0,
            damping_ratio=d.damping_ratio,
            output_interval=d.output_interval,
            context=f"supports {scene.supports.left}-{scene.supports.right}, points = {params['points']}",
            energy_scale=scene.section.A * (x[1] - x[0]),
        )
    info, writers = dynamic_info(run, probes)
    w = np.zeros(len(x))
    w[free] = run.final
    info.update(variant=params["variant"], spacing=x[1] - x[0], horizon_factor=params["horizon"])
    if flags := model.discretisation_warnings(scene, params, x):  # the static solve's operator and loads
        info.setdefault("warnings", []).extend(flags)
    return model.new_result(
        scene,
        params,
        x,
        w,
        rotation=np.gradient(w, x, edge_order=2),
        dofs=len(free),
        timings=timer.timings,
        info=info,
        writers=writers,
    )


__all__ = ["ANALYSIS", "dynamic", "eigenproblem", "bench", "transient", "operators"]
