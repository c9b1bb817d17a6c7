"""The transient of ``fem-timoshenko`` (a finite-element reference for pd-timoshenko's transients): the element's
stiffness (its ``variant``), the consistent mass of linear w and θ (scikit-fem ElementLineP1 x ElementLineP1:
ρA w v + ρI θ φ, two Gauss points), damping as the PD beam applies it (mass-proportional, C = (c_d/ρ) M, on the
translations alone with the scene's ``damping_on = "translations"``; c_d/ρ given, or 2 ζ ω_1 with ω_1 this model's
first frequency), step loads from rest, :func:`~reference_fem.newmark.newmark` in time.
The probes are nodes (inserted like load positions), so their histories are nodal values."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.sparse as sp

from pdverify.core.errors import InputError
from pdverify.core.result import Result, Timer, columns_csv
from pdverify.core.scene import PointForce, Scene
from pdverify.numerics.timeint import step_count

from .beam_elements import add_springs, constrained_dofs, merge_warnings, two_fields
from .newmark import newmark

DEFAULT_SAMPLES = 2000  # samples over end_time when the scene gives no output_interval


def consistent_mass(nodes: np.ndarray, rhoA: float, rhoI: float) -> sp.csr_matrix:
    """ρA w v + ρI θ φ on ElementLineP1 x ElementLineP1 (two Gauss points: exact), DOFs (w_i, θ_i) interleaved."""

    def mass(w, theta, v, phi, _):
        return rhoA * w * v + rhoI * theta * phi

    return two_fields(mass, nodes, intorder=2)


def free_system(model, scene: Scene, params: dict, probes) -> tuple:
    """(K, M, F, free DOFs, nodes) of the model on the scene, the supported DOFs removed; ``probes`` inserted as
    nodes (as zero loads: beam_nodes puts every load position on a node)."""
    rho = scene.material.density
    if rho is None:
        raise InputError("material.density: needed for dynamics; add density to the scene")
    marks = [PointForce(type="point_force", position=p, value=0.0) for p in probes]
    K, F, nodes = model.assemble_band(scene.model_copy(update={"loads": [*scene.loads, *marks]}), params)
    add_springs(scene, K, nodes)
    M = consistent_mass(nodes, rho * scene.section.A, rho * scene.section.I)
    free = np.setdiff1d(np.arange(2 * len(nodes)), constrained_dofs(scene, nodes))
    return K.tocsr()[free][:, free], M[free][:, free], F[free], free, nodes


def transient(model, scene: Scene, params: dict) -> Result:
    """The model's transient on the scene (``model``: fem-timoshenko)."""
    timer = Timer()
    d, rho = scene.dynamics, scene.material.density
    probes = list(d.probes) or [scene.length / 2]
    with timer("assemble"):
        K, M, F, free, nodes = free_system(model, scene, params, probes)
        translations = sp.diags((free % 2 == 0).astype(float))
        D = d.damping or 0.0
        if d.damping_ratio:
            from scipy.sparse.linalg import eigsh

            omega1 = float(np.sqrt(eigsh(K.tocsc(), k=1, M=M.tocsc(), sigma=0.0, which="LM")[0][0]))
            D = 2 * d.damping_ratio * omega1
        C = D * (M if d.damping_on == "all" else translations @ M @ translations)
        dof = 2 * np.abs(nodes[:, None] - np.asarray(probes, float)).argmin(0)  # each probe's w
        held = ~np.isin(dof, free)  # a probe on a held deflection reads 0, its row empty
        at = np.searchsorted(free, dof[~held])
        observe = sp.csr_matrix((np.ones(len(at)), (np.arange(len(probes))[~held], at)), shape=(len(probes), len(free)))
    sample = d.output_interval or d.end_time / DEFAULT_SAMPLES
    # default step: the sampling interval, or the time the fastest wave (sqrt(E/rho)) takes across the shortest
    # element if shorter (a Courant number of 1, which Newmark does not need for stability: the time error then
    # falls with the mesh)
    courant = float(np.diff(nodes).min()) / np.sqrt(scene.material.youngs_modulus / rho)
    dt = d.time_step or min(sample, courant)
    from_sampling = d.output_interval is not None and sample < courant
    source = "time_step" if d.time_step else ("output_interval" if from_sampling else "default")
    steps = step_count(d.end_time, dt, source)  # before any step (exit 2 above the limit)
    with timer("solve"):
        t, hist, u = newmark(K, M, C, F, d.end_time / steps, steps, observe)
    every = max(1, int(round(sample / (d.end_time / steps))))
    kept = np.unique(np.r_[np.arange(0, len(t), every), len(t) - 1])  # the samples and the end time
    full = np.zeros(2 * len(nodes))
    full[free] = u
    series = {f"w(x={p:g})": hist[kept, k] for k, p in enumerate(probes)}
    info = {
        "analysis": "dynamic",
        "integrator": "Newmark average acceleration (beta = 1/4, gamma = 1/2)",
        "time_step": d.end_time / steps,
        "steps": steps,
        "damping": D,
        "history": {"t": t[kept], "series": series, "ylabel": "deflection"},
    }
    if merged := merge_warnings(scene, nodes):  # the static solve's: a load taken on a node within 1e-12 L of it
        info.setdefault("warnings", []).extend(merged)
    return model.new_result(
        scene,
        params,
        nodes,
        full[0::2],
        rotation=full[1::2],
        dofs=len(free),
        timings=timer.timings,
        info=info,
        writers={".csv": lambda path: Path(path).write_text(columns_csv({"t": t[kept], **series}, fmt="%.12g"))},
    )
