"""The transient of ``fem-timoshenko`` (a finite-element reference for pd-timoshenko's transients): the element's
stiffness (its ``variant``), the consistent mass of linear w and θ (scikit-fem ElementLineP1 x ElementLineP1:
ρA w v + ρI θ φ, two Gauss points), damping as the PD beam applies it (mass-proportional, C = (c_d/ρ) M, on the
translations alone with the scene's ``damping_on = "translations"``; c_d/ρ given, or 2 ζ ω_1 with ω_1 this model's
first frequency), step loads from rest, :func:`~reference_fem.newmark.newmark` in time.
A probe is a node (inserted like a load position), so its history is a nodal value, unless it lies within
``PROBE_SNAP`` of its element's length from a node the scene already has (the grid's, a load's, a support's): then
it is read inside that element through the element's own w interpolation (:func:`probe_rows`), so that a probe
1e-7 from a node does not make a 1e-7 element, whose Courant step (and condition) would bring the run to a halt."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.sparse as sp

from pdverify.core.errors import InputError
from pdverify.core.result import Result, Timer, columns_csv
from pdverify.core.scene import Distributed, PointForce, Scene
from pdverify.numerics.steps import aligned_steps
from pdverify.numerics.timeint import MAX_STEPS, step_count

from .beam_elements import (
    add_springs,
    beam_nodes,
    constrained_dofs,
    element_properties,
    iie_shapes,
    merge_warnings,
    two_fields,
)
from .newmark import newmark

DEFAULT_SAMPLES = 2000  # samples over end_time when the scene gives no output_interval
# A probe nearer than this fraction of its element to a node is read inside the element, not made a node: the
# shortest element a probe makes is then PROBE_SNAP of the grid's, the default step at most 1/PROBE_SNAP times
# shorter. Read inside its element, a probe's history moves from the inserted node's by about PROBE_SNAP times the
# history's own error against exact-modal-timoshenko (beam_transient.toml, probe 1 + 0.099 h, dt 1e-5: iie 1.1e-4
# against 2.1e-3 at 21 nodes, 1.8e-6 against 1.8e-4 at 81; reduced 3.9e-4 against 4.2e-3 at 21).
PROBE_SNAP = 0.1


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


def inserted_probes(nodes: np.ndarray, probes) -> list[float]:
    """The probes to make nodes: those further than PROBE_SNAP of their element's length from every node of
    ``nodes`` (sorted) and from the probes inserted before them (left to right)."""
    x, out = np.asarray(nodes, float), []
    for p in sorted(set(float(p) for p in probes)):
        i = int(np.clip(np.searchsorted(x, p), 1, len(x) - 1))  # x[i - 1] <= p <= x[i]
        if min(p - x[i - 1], x[i] - p) > PROBE_SNAP * (x[i] - x[i - 1]):
            out.append(p)
            x = np.insert(x, i, p)
    return out


def probe_rows(scene: Scene, params: dict, nodes: np.ndarray, free: np.ndarray, probes) -> sp.csr_matrix:
    """Rows reading each probe's w from the free unknowns: its node's w, or inside its element the element's w
    interpolation (the IIE's shape functions for ``iie``, linear w for the linear elements) of the two nodes' w and
    θ. A held DOF is zero (the supports hold it): it drops out of the row."""
    probes = np.asarray(probes, float)
    tol = 1e-12 * scene.length  # beam_nodes' merging distance: a probe that near a node is that node
    i = np.clip(np.searchsorted(nodes, probes) - 1, 0, len(nodes) - 2)  # the element [x_i, x_{i+1}]
    l = nodes[i + 1] - nodes[i]
    xi = np.clip((probes - nodes[i]) / l, 0.0, 1.0)
    xi = np.where(np.abs(probes - nodes[i]) <= tol, 0.0, np.where(np.abs(nodes[i + 1] - probes) <= tol, 1.0, xi))
    if params.get("variant", "iie") == "iie":
        EI, kGA = element_properties(scene, nodes)
        N = iie_shapes(12 * EI / (kGA * np.diff(nodes) ** 2))(xi, l, i)
    else:
        N = np.array([1 - xi, 0 * xi, xi, 0 * xi])
    N = np.where(xi == 0.0, np.array([[1.0], [0.0], [0.0], [0.0]]), N)  # on a node: its w alone, exactly
    N = np.where(xi == 1.0, np.array([[0.0], [0.0], [1.0], [0.0]]), N)
    dofs = np.stack([2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3])  # (w_i, θ_i, w_i+1, θ_i+1)
    rows = np.broadcast_to(np.arange(len(probes)), dofs.shape)
    keep = (N != 0) & np.isin(dofs, free)
    at = np.searchsorted(free, dofs[keep])
    return sp.csr_matrix((N[keep], (rows[keep], at)), shape=(len(probes), len(free)))


def short_element(scene: Scene, nodes: np.ndarray, points: int, dt: float, end_time: float) -> None:
    """InputError naming the scene's position that made the shortest element when that element, far shorter than the
    grid's spacing, sets a default step past the step limit (a load 1e-7 from a node: a 1e-7 element); nothing when
    the grid's own spacing sets it (step_count's "use fewer points" then applies)."""
    k = int(np.argmin(np.diff(nodes)))
    a, b = nodes[k], nodes[k + 1]
    if b - a > 1e-3 * scene.length / (points - 1):
        return
    marks = [(f"supports.inner[{i}].position", s.position) for i, s in enumerate(scene.supports.inner)]
    for i, ld in enumerate(scene.loads):
        ends = scene.span(ld) if isinstance(ld, Distributed) else (ld.position,)
        marks += [(f"loads[{i}].{'position' if len(ends) == 1 else key}", v) for key, v in zip(("start", "end"), ends)]
    marks += [(f"segments[{i}].end", g.end) for i, g in enumerate(scene.segments[:-1])]
    grid = np.linspace(0.0, scene.length, points)
    name, v = min(marks, key=lambda m: min(abs(m[1] - a), abs(m[1] - b)), default=("a position", b))
    near = grid[np.argmin(np.abs(grid - v))]
    raise InputError(
        f"{name} = {v!r} lies {abs(v - near):.3g} from the grid's node at {near:.12g}: an element of {b - a:.3g} whose "
        f"default time step {dt:.3g} s asks for {end_time / dt:.3g} steps, more than the limit of {MAX_STEPS:.0e}; "
        f"give {name} = {near:.12g}, or dynamics.time_step (Newmark's step is stable at any length)"
    )


def transient(model, scene: Scene, params: dict) -> Result:
    """The model's transient on the scene (``model``: fem-timoshenko)."""
    timer = Timer()
    d, rho = scene.dynamics, scene.material.density
    probes = list(d.probes) or [scene.length / 2]
    with timer("assemble"):
        marks = inserted_probes(beam_nodes(scene, params["points"]), probes)
        K, M, F, free, nodes = free_system(model, scene, params, marks)
        translations = sp.diags((free % 2 == 0).astype(float))
        D = d.damping or 0.0
        if d.damping_ratio:
            from scipy.sparse.linalg import eigsh

            omega1 = float(np.sqrt(eigsh(K.tocsc(), k=1, M=M.tocsc(), sigma=0.0, which="LM")[0][0]))
            D = 2 * d.damping_ratio * omega1
        C = D * (M if d.damping_on == "all" else translations @ M @ translations)
        observe = probe_rows(scene, params, nodes, free, probes)
    sample = d.output_interval or d.end_time / DEFAULT_SAMPLES
    # default step: the sampling interval, or the time the fastest wave (sqrt(E/rho)) takes across the shortest
    # element if shorter (a Courant number of 1, which Newmark does not need for stability: the time error then
    # falls with the mesh)
    courant = float(np.diff(nodes).min()) / np.sqrt(scene.material.youngs_modulus / rho)
    dt = d.time_step or min(sample, courant)
    from_sampling = d.output_interval is not None and sample < courant
    source = "time_step" if d.time_step else ("output_interval" if from_sampling else "default")
    if source == "default" and d.end_time / dt > MAX_STEPS:
        short_element(scene, nodes, params["points"], dt, d.end_time)
    steps = step_count(d.end_time, dt, source)  # before any step (exit 2 above the limit)
    if source != "time_step" and (al := aligned_steps(d.end_time, dt, sample)):
        steps = al[0]  # a step that divides the sampling interval: every grid's samples on its multiples
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
    if near := step_beside_clamp(scene, params["points"]):
        info.setdefault("warnings", []).extend(near)
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


NEAR_CLAMP = 10  # spacings from a clamp within which a step force's history is off by more than ~1 % (measured below)


def step_beside_clamp(scene: Scene, points: int) -> list[str]:
    """Point forces (steps at t = 0) within :data:`NEAR_CLAMP` spacings of a clamp, at an end or inside the span: the
    modes such a force excites grow in share as it nears the clamp, and the mesh resolves them at about first order
    in spacing over distance (a roller-clamped timber strip, L/h = 100, a step force 3 depths from the clamp: 2.4 %,
    1.25 %, 0.44 % of the largest deflection off exact-modal-timoshenko at 161, 321, 641 points, the same at a
    quarter of the time step; 1.7 % and 0.73 % at 8 and 16 spacings; 5.3e-4 at mid-span)."""
    dx = scene.length / (points - 1)
    clamps = [(0.0, "the left end")] * (scene.supports.kind("left") == "clamped")
    clamps += [(scene.length, "the right end")] * (scene.supports.kind("right") == "clamped")
    clamps += [(s.position, f"supports.inner[{i}]") for i, s in enumerate(scene.supports.inner) if s.type == "clamped"]
    out = []
    for i, ld in enumerate(scene.loads):
        if not isinstance(ld, PointForce) or ld.value == 0.0 or not clamps:
            continue
        at, name = min(clamps, key=lambda c: abs(c[0] - ld.position))
        d = abs(at - ld.position)
        if 1e-12 * scene.length < d < NEAR_CLAMP * dx:
            out.append(
                f"loads[{i}], a step force {d / dx:.2g} spacings from the clamp at {name}: the modes it excites there "
                "are resolved at about first order (measured 2.4 %, 1.25 %, 0.44 % of max |w| at 161, 321, 641 points "
                f"3 depths from a clamp); use at least {int(np.floor(NEAR_CLAMP * scene.length / d)) + 2} points"
            )
    return out
