"""Dynamics of ``pd-higher-order`` (Yang, Oterkus & Oterkus 2020, Eq. 17-22): the mass of the kinetic energy and the
static operator, for natural frequencies (``eigenproblem``) and explicit transients.

Kinetic energy (Eq. 17-19): u = z theta + z^3 theta*, w = w + z^2 w* integrated through the depth gives per point
T_k = (1/2) (rho / h) [h^3/12 theta'^2 + h^5/40 theta' theta*' + h^7/448 theta*'^2 + h w'^2 + h^3/6 w' w*' +
h^5/80 w*'^2] V_k (dots as primes), so the mass couples theta with theta* and w with w* (Eq. 22's left-hand sides:
rho (h^2/12 theta'' + h^4/80 theta*''), rho (w'' + h^2/12 w*''), ...). The static operator K of the model is the
Hessian of the discrete energy per unit cross-section area (the load vector is a cell's force over A,
:func:`.ends.load_vector`), so the mass per point is that 4 x 4 block over A: (rho / h) times the depth integrals
times the point's cell (dx; dx/2 at the end points of the truncated ends, as the loads' cells). Held DOFs are
dropped and ``pin = face``'s ties (u_slave = c u_master) folded in: M_r = T^T M T, as the operator's. Eq. 22 with
its inertia terms is then K u + M u_tt = F, and a transient integrates it by central differences
(:mod:`pdverify.numerics.explicit`; in q = R^T u, M = R R^T per 2 x 2 block). The energy form makes K symmetric:
real frequencies, and the undamped scheme conserves its discrete energy to round-off.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import Scene
from ...numerics.explicit import ANALYSIS, dynamic, dynamic_info, integrate, probe_rows, updates_per_second
from ...theory.higher_order import NF, TH, TS, WS, W


def point_mass(rho: float, h: float) -> np.ndarray:
    """The 4 x 4 mass per unit cell length and unit area on (theta, theta*, w, w*) (Eq. 19 over h)."""
    m = np.zeros((NF, NF))
    m[np.ix_([TH, TS], [TH, TS])] = [[h**3 / 12, h**5 / 80], [h**5 / 80, h**7 / 448]]
    m[np.ix_([W, WS], [W, WS])] = [[h, h**3 / 12], [h**3 / 12, h**5 / 80]]
    return rho / h * m


def operators(model, scene: Scene, params: dict):
    """(K, M, F, free, T, x, info): the operator and the mass on the free DOFs, the load vector there, the free DOFs,
    the map T (all DOFs x free) that restores every DOF (ties included) from the free ones, the points and the
    assembly's info."""
    if not scene.supports.simple:
        raise InputError(
            "supports: pd-higher-order's dynamics hold the beam at its ends only; springs and supports inside the "
            "span are static (their reactions are multipliers); drop [dynamics] or the inner supports and springs"
        )
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density (kg/m^3) to the scene")
    B, b, (drop, tie), info = model.assemble_band(scene, params)
    n = params["points"]
    x = model.grid(scene, params)
    dx = x[1] - x[0]
    cells = np.full(n, dx)
    if info.get("ends") == "truncated":
        cells[[0, -1]] = dx / 2
    Mfull = sp.kron(sp.diags(cells), sp.csr_matrix(point_mass(scene.material.density, info["depth"]))).tocsr()
    slaves = [s for s, _, _ in tie]
    free = np.setdiff1d(np.arange(NF * n), np.r_[np.asarray(drop, np.int64), np.asarray(slaves, np.int64)])
    T = sp.lil_matrix((NF * n, len(free)))
    T[free, np.arange(len(free))] = 1.0
    col = {int(d): k for k, d in enumerate(free)}
    for s, m, c in tie:
        T[s, col[int(m)]] = c
    T = T.tocsr()
    K = B.tocsr()[free][:, free]
    M = (T.T @ Mfull @ T).tocsr()
    return K, M, b[free], free, T, x, info


def eigenproblem(model, scene: Scene, params: dict) -> tuple:
    """(K, M) on the free DOFs: K phi = omega^2 M phi (M the consistent 2 x 2-block mass of Eq. 19)."""
    K, M, *_ = operators(model, scene, params)
    return K, M


def bench(model, scene: Scene, params: dict, steps: int = 200) -> float:
    """Point-updates per second of the explicit integration (``pdverify bench``)."""
    K, M, F, *_ = operators(model, scene, params)
    return updates_per_second(K, M, F, params["points"], steps)


def transient(model, scene: Scene, params: dict) -> Result:
    """An explicit run of Eq. 22 with its inertia from rest under the scene's loads (``[dynamics]``)."""
    timer = Timer()
    d = scene.dynamics
    with timer("assemble"):
        K, M, F, free, T, x, binfo = operators(model, scene, params)
    rows, probes = probe_rows(x, d.probes)
    n = len(x)
    w_of = (sp.csr_matrix((np.ones(n), (np.arange(n), NF * np.arange(n) + W)), shape=(n, NF * n)) @ T).tocsr()
    observe_rows = (rows @ w_of).tocsr()
    damped = None
    if d.damping_on == "translations":
        damped = np.isin(free % NF, [W, WS])
    with timer("solve"):
        run = integrate(
            K,
            M,
            F,
            d.end_time,
            observe_rows.__matmul__,
            dt=d.time_step,
            damping=d.damping or 0.0,
            damping_ratio=d.damping_ratio,
            output_interval=d.output_interval,
            context=f"supports {scene.supports.left}-{scene.supports.right}, points = {params['points']}",
            damped=damped,
            energy_scale=scene.section.A,
        )
    info, writers = dynamic_info(run, probes)
    u = (T @ run.final).reshape(n, NF)
    info.update(variant=params["variant"], spacing=x[1] - x[0], horizon_factor=params["horizon"])
    if flags := model.discretisation_warnings(scene, params, x, binfo):  # the static solve's operator and loads
        info.setdefault("warnings", []).extend(flags)
    return model.new_result(
        scene,
        params,
        x,
        u[:, W].copy(),
        rotation=-u[:, TH],
        fields={"theta": u[:, TH], "theta_star": u[:, TS], "w_star": u[:, WS]},
        dofs=len(free),
        timings=timer.timings,
        info=info,
        writers=writers,
    )


__all__ = ["ANALYSIS", "dynamic", "eigenproblem", "bench", "transient", "point_mass", "operators"]
