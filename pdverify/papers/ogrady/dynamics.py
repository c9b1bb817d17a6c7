"""Dynamics of ``pd-bond-pair`` (O'Grady & Foster 2014): the PD equation of motion rho A w_tt = (the bond-pair
force per unit length) + q, for natural frequencies (``eigenproblem``) and explicit transients.

The paper states the peridynamic equation of motion, rho u_tt = (force state integral) + b, and solves statics; its
inertia is the point's mass. ``ends = taylor`` (default): the strong-form operator on w (rows per unit length,
EI w'''' in the limit) with its Taylor ghosts eliminated and the supported points held, mass rho A per point; its
ghost rows make it non-symmetric, with real eigenvalues (the transient's ledger is then the modal energy,
:mod:`pdverify.numerics.explicit`). ``ends = mirror``: the tangent stiffness of the bond-pair energy (u and w per
point, forces), symmetric, mass rho A times the point's share of the length (dx, half at the end points, as the
end points' energy is halved); its ledger is the physical energy. The direct Taylor form is used for dynamics
whatever ``form`` says (the mixed form's curvature unknowns carry no mass).
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError, SolveError
from ...core.result import Result, Timer
from ...core.scene import Scene
from ...numerics.explicit import ANALYSIS, dynamic, dynamic_info, integrate, probe_rows, updates_per_second


def operators(model, scene: Scene, params: dict):
    """(K, mass, b, free, x, w_index, energy scale): the operator and loads on the free DOFs, the lumped mass, where
    w sits among all DOFs, and what turns u.K u / 2 into joules."""
    if params.get("nonlinear"):
        raise InputError("nonlinear = true: dynamics follow the linear path; use nonlinear = false")
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density (kg/m^3) to the scene")
    n = params["points"]
    x = np.linspace(0.0, scene.length, n)
    dx = x[1] - x[0]
    rhoA = scene.material.density * scene.section.A
    if params["ends"] in ("mirror", "none"):
        s = model.assemble(scene, params)
        free = np.asarray(s.free)
        if s.info.get("form", "").startswith("pair form"):  # w alone per point (forces), the held points eliminated
            cell = np.full(n, dx)
            cell[[0, -1]] = dx / 2
            return s.matrix.tocsr(), rhoA * cell[free], np.asarray(s.rhs), free, x, np.arange(n), 1.0
        cell = np.full(2 * n, dx)
        cell[[0, 1, -2, -1]] = dx / 2
        return s.matrix.tocsr(), rhoA * cell[free], s.rhs, free, x, 2 * np.arange(n) + 1, 1.0
    s = model.assemble(scene, dict(params, form="direct"))  # the Taylor-ghost operator on w, supported rows held
    free = np.asarray(s.free)
    K = s.matrix.tocsr()[free][:, free]
    return K, np.full(len(free), rhoA), np.asarray(s.rhs)[free], free, x, np.arange(n), dx


def eigenproblem(model, scene: Scene, params: dict) -> tuple:
    """(K, mass) of the bending modes on the free DOFs: K phi = omega^2 M phi (lumped mass). With ``ends = mirror``
    the operator holds u and w per point, which do not couple at rest on a straight beam: the w block alone (the
    axial bonds' rod modes are not the beam's)."""
    K, mass, _, free, _, w_at, _ = operators(model, scene, params)
    if params["ends"] != "mirror":
        return K, mass
    bending = np.flatnonzero(np.isin(free, w_at))
    axial = np.setdiff1d(np.arange(len(free)), bending)
    if len(axial) and abs(K[bending][:, axial]).max() > 0:
        raise SolveError("pd-bond-pair: u and w couple at rest; its bending modes are not the w block")
    return K[bending][:, bending], mass[bending]


def bench(model, scene: Scene, params: dict, steps: int = 200) -> float:
    K, mass, b, *_ = operators(model, scene, params)
    return updates_per_second(K, mass, b, params["points"], steps)


def transient(model, scene: Scene, params: dict) -> Result:
    """An explicit run of the equation of motion from rest under the scene's loads (``[dynamics]``)."""
    timer = Timer()
    d = scene.dynamics
    with timer("assemble"):
        K, mass, b, free, x, w_at, scale = operators(model, scene, params)
    rows, probes = probe_rows(x, d.probes)
    total = 2 * len(x) if params["ends"] == "mirror" else len(x)

    def full(u):
        out = np.zeros(total)
        out[free] = u
        return out

    with timer("solve"):
        run = integrate(
            K,
            mass,
            b,
            d.end_time,
            lambda u: rows @ full(u)[w_at],
            dt=d.time_step,
            damping=d.damping or 0.0,
            damping_ratio=d.damping_ratio,
            output_interval=d.output_interval,
            context=f"supports {scene.supports.left}-{scene.supports.right}, points = {params['points']}",
            energy_scale=scale,
        )
    info, writers = dynamic_info(run, probes)
    u = full(run.final)
    w = u[w_at]
    fields = {"u": u[0::2]} if params["ends"] == "mirror" else {}
    info.update(variant=params["variant"], ends=params["ends"], spacing=x[1] - x[0], horizon_factor=params["horizon"])
    if flags := model.discretisation_warnings(scene, params, x):  # the static solve's operator and loads
        info.setdefault("warnings", []).extend(flags)
    return model.new_result(
        scene,
        params,
        x,
        w,
        fields=fields,
        rotation=np.gradient(w, x, edge_order=2),
        dofs=len(free),
        timings=timer.timings,
        info=info,
        writers=writers,
    )


__all__ = ["ANALYSIS", "dynamic", "eigenproblem", "bench", "transient", "operators"]
