"""Explicit transient of the pd-eb operator (Diyaroglu et al. Eq. 15 with damping): central differences
on the static operator the model assembles, from rest. Time integration apart from the model (model.py)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError, SolveError
from ...core.scene import Scene
from ...numerics.timeint import step_count
from .model import PDEulerBernoulli


def central_difference_limit(K: sp.spmatrix, density: float) -> float:
    """Central-difference limit dt = 2 / omega_max with omega_max² the largest eigenvalue of K / rho
    (ARPACK up to 5,000 unknowns; above, the Gershgorin bound max row sum |K|, which is safe)."""
    if K.shape[0] <= 5000:
        import scipy.sparse.linalg as spla

        lam = float(
            np.abs(spla.eigs(K.astype(float), k=1, which="LM", return_eigenvectors=False, v0=np.ones(K.shape[0]))[0])
        )  # fixed start: reproducible dt
    else:
        lam = float(np.abs(K).sum(axis=1).max())
    return 2.0 / np.sqrt(lam / density)


def simulate_eb(
    scene: Scene,
    params: dict,
    t_end: float,
    dt: float | None = None,
    damping: float = 0.0,
    safety: float = 0.9,
    record_every: int = 10,
):
    """Explicit central differences for rho w_tt + c w_t + K w = b (Eq. 15 with damping), from rest.

    Shares the static operator; returns (t, w history at the recorded steps, dt, dt_limit).
    Raises SolveError when a forced dt exceeds the stable limit and the response blows up."""
    model = PDEulerBernoulli()
    params = model.resolve(scene, params)
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density (kg/m^3) to the scene")
    rho = scene.material.density
    system = model.assemble(scene, dict(params, form="direct"))  # the fourth-order operator, eliminated
    Kf, bf = system.reduced()
    free = system.free
    n_all = params["points"]
    limit = central_difference_limit(Kf, rho)
    given = dt is not None
    dt = safety * limit if dt is None else float(dt)
    steps = step_count(t_end, dt, "time_step" if given else "default")
    w = np.zeros(len(free))
    w_old = np.zeros(len(free))
    hist, times = [], []
    scale = None
    c1 = damping * dt / (2 * rho)
    for s in range(1, steps + 1):
        acc = (bf - Kf @ w) * dt**2 / rho
        w_new = (2 * w - (1 - c1) * w_old + acc) / (1 + c1)
        w_old, w = w, w_new
        if s % record_every == 0 or s == steps:
            amp = np.abs(w).max()
            if scale is None and amp > 0:
                scale = amp
            if not np.isfinite(amp) or (scale and amp > 1e8 * scale):
                raise SolveError(
                    f"dt = {dt:.4g} s: the explicit integration blew up at step {s}; "
                    f"the stable limit is {limit:.4g} s (use dt below it)"
                )
            full = np.zeros(n_all)
            full[free] = w
            hist.append(full)
            times.append(s * dt)
    return np.array(times), np.array(hist), dt, limit
