"""Explicit transient of a linear operator with a lumped or block-diagonal mass, from rest: the damped leapfrog
(central differences) of M u_tt + c M u_t + K u = b on the free unknowns, loads as steps at t = 0.

The mass is factored M = R R^T (a vector: R = diag(sqrt m); a block-diagonal matrix, e.g. the 2 x 2 blocks of a
higher-order beam's coupled inertia: Cholesky per block) and the run is made in q = R^T u, where the mass is the
identity: q_tt + c q_t + K~ q = b~ with K~ = R^-1 K R^-T, b~ = R^-1 b. The step (v at half steps)::

    v^{j+1/2} = ((1 - c dt/2) v^{j-1/2} + dt (b~ - K~ q^j)) / (1 + c dt/2),   q^{j+1} = q^j + dt v^{j+1/2}

from rest: v^{-1/2} = -dt/2 a^0 (v^0 = 0, second order). Stable for dt below 2 / omega_max, omega_max^2 the
largest eigenvalue of K~ (ARPACK, fixed start vector: the same dt on every run); dt defaults to ``safety`` times
that limit. ``damping_ratio`` zeta gives c = 2 zeta omega_1 (mass-proportional: every mode decays at c/2).

The energy ledger (:class:`pdverify.numerics.timeint.EnergyLedger`, unit mass in q) records kinetic and strain
energy, the load work and the damping's work at every sample; with a symmetric K the undamped scheme conserves
its discrete energy (the ledger's column ``scheme``) to round-off, and T + U - W changes by O((omega dt)^2) of the
stored energy. A non-symmetric K~ (boundary closures by ghost points) conserves no energy of the form
u.K u / 2; when its eigenvalues are real (a diagonalisable K~ = S Lambda S^-1, S of unit columns) the run is made
in p = S^-1 q, where the step is the same linear map and decouples per mode: the ledger is then the modal energy
(1/2) Σ (p_t^2 + lambda p^2), the energy of the inner product that makes K~ symmetric (``Run.ledger = "modal"``),
conserved by the undamped scheme to round-off; it equals the physical energy when K is symmetric, and lies within a
factor cond(S)^2 of it (cond(S) ~ 2 to 5 for the PD beams' ghost closures). Up to MODAL_DOFS unknowns (a dense
eigensolve); above, the physical ledger, whose balance then carries the non-symmetric part.
A run whose stored energy outgrows the work put in (``blown_up``) stops with a SolveError naming
the step and the limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import connected_components

from ..core.contract import Option
from ..core.errors import InputError, SolveError
from ..core.result import columns_csv
from .steps import aligned_steps, sample_count
from .timeint import EnergyLedger, ledger_columns, step_count

ANALYSIS = Option(
    "analysis",
    str,
    "auto",
    "auto (dynamic when the scene has [dynamics]) | static | dynamic",
    choices=("auto", "static", "dynamic"),
)
DEFAULT_SAFETY = 0.9
SAMPLES = 2000  # default number of recorded samples of a run
OMEGA1_DOFS = 20000  # omega_1 is computed (and reported) up to this many unknowns, or when a damping ratio needs it
MODAL_DOFS = 4000  # a non-symmetric operator up to this size is run in its eigenbasis (a dense eigensolve)


def symmetric(K: sp.spmatrix) -> bool:
    """Whether K equals its transpose to round-off (1e-12 of its largest entry)."""
    K = sp.csr_matrix(K)
    return bool(abs(K - K.T).max() <= 1e-12 * abs(K).max()) if K.nnz else True


def dynamic(scene, params: dict) -> bool:
    """Whether a run is a transient (option ``analysis``: auto = when the scene has a [dynamics] table); one line
    when it cannot be."""
    a = params.get("analysis", "auto")
    if a == "dynamic" and scene.dynamics is None:
        raise InputError("analysis = 'dynamic': the scene has no [dynamics] table; add one or use analysis = static")
    return a == "dynamic" or (a == "auto" and scene.dynamics is not None)


def mass_factor(mass) -> sp.csr_matrix:
    """R^-1 (sparse) with M = R R^T: 1/sqrt(m) for a lumped mass vector, the inverse Cholesky factor of each
    diagonal block of a block-diagonal symmetric positive definite matrix (blocks grouped by size: vectorised)."""
    if not sp.issparse(mass):
        return sp.diags(1.0 / np.sqrt(np.asarray(mass, float))).tocsr()
    M = sp.csr_matrix(mass)
    count, label = connected_components(M != 0, directed=False)
    order = np.argsort(label, kind="stable")
    sizes = np.bincount(label, minlength=count)
    rows, cols, vals = [], [], []
    starts = np.r_[0, np.cumsum(sizes)]
    for s in np.unique(sizes):
        blocks = np.flatnonzero(sizes == s)
        idx = np.stack([order[starts[b] : starts[b] + s] for b in blocks])  # (k, s) unknowns of each block
        r, cc = np.repeat(idx, s, axis=1), np.tile(idx, (1, s))  # (k, s * s): row-major entries of each block
        D = np.asarray(M[r.ravel(), cc.ravel()]).reshape(len(blocks), s, s)
        Rinv = np.linalg.inv(np.linalg.cholesky(D))
        rows.append(r.ravel())
        cols.append(cc.ravel())
        vals.append(Rinv.reshape(len(blocks), s * s).ravel())
    n = M.shape[0]
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))


def extreme_eigenvalue(A: sp.spmatrix, smallest: bool = False) -> float:
    """|lambda| of A largest (or smallest, shift-invert about 0) in modulus; fixed start vector."""
    n = A.shape[0]
    if n <= 300:
        lam = np.abs(np.linalg.eigvals(A.toarray()))
        return float(lam.min() if smallest else lam.max())
    v0 = np.ones(n)
    if smallest:
        return float(np.abs(spla.eigs(A.tocsc(), k=1, sigma=0.0, which="LM", v0=v0, return_eigenvectors=False))[0])
    return float(np.abs(spla.eigs(A, k=1, which="LM", v0=v0, return_eigenvectors=False))[0])


@dataclass
class Run:
    """A transient's samples: t (s), the observed values (one row per sample), the final u, the step, the stable
    limit, the damping c (1/s), omega_1 (the lowest frequency; None on large grids without a damping ratio) and the
    ledger."""

    t: np.ndarray
    values: np.ndarray
    final: np.ndarray
    dt: float
    dt_limit: float
    steps: int
    damping: float
    omega1: float | None
    energy: dict = field(default_factory=dict)
    energy_drift: float = 0.0
    scheme_drift: float = 0.0
    ledger: str = "physical"  # or "modal": the energy in the eigenbasis of a non-symmetric operator


def integrate(
    K: sp.spmatrix,
    mass,
    b: np.ndarray,
    t_end: float,
    observe,
    dt: float | None = None,
    damping: float = 0.0,
    damping_ratio: float | None = None,
    output_interval: float | None = None,
    safety: float = DEFAULT_SAFETY,
    context: str = "",
    damped: np.ndarray | None = None,
    steps: int | None = None,
    energy_scale: float = 1.0,
) -> Run:
    """The damped leapfrog from rest (module docstring). ``K`` (n x n, free unknowns), ``mass`` (vector or sparse
    block-diagonal), ``b`` (n); ``observe``: u -> 1-D array recorded per sample; ``output_interval`` (s) between
    samples (default: about SAMPLES over the run); ``damped``: the unknowns the damping acts on (default all; the
    mass's blocks must not mix damped and undamped ones); ``steps``: run this many steps instead of up to t_end;
    ``energy_scale``: what turns u.K u / 2 into joules (the operator's rows per unit area or volume: the area, or
    the area times the spacing)."""
    Ri = mass_factor(mass)
    Kt = (Ri @ sp.csr_matrix(K) @ Ri.T).tocsr()
    bt = Ri @ np.asarray(b, float)
    back, modal = Ri.T, symmetric(Kt) is False and Kt.shape[0] <= MODAL_DOFS
    if modal:  # the run in the eigenbasis of K~ (module docstring)
        lam, S = np.linalg.eig(Kt.toarray())
        if np.abs(lam.imag).max() > 1e-9 * np.abs(lam).max() or damped is not None:
            modal = False
        else:
            S = S.real
            Kt, bt, back = sp.diags(lam.real).tocsr(), np.linalg.solve(S, bt), Ri.T @ S
    limit = 2.0 / np.sqrt(extreme_eigenvalue(Kt))
    omega1 = None  # the damping ratio's scale; in info up to OMEGA1_DOFS unknowns (a shift-invert solve)
    if damping_ratio is not None or Kt.shape[0] <= OMEGA1_DOFS:
        omega1 = float(np.sqrt(extreme_eigenvalue(Kt, smallest=True)))
    if damping_ratio is not None:
        damping = 2.0 * damping_ratio * omega1
    source = "default" if dt is None else "time_step"
    dt = safety * limit if dt is None else float(dt)
    if steps is None:  # whole steps that end at t_end (each at most dt: as stable); exit 2 past the limit
        steps = step_count(t_end, dt, source, limit)
        dt = t_end / steps
        if source == "default" and (al := aligned_steps(t_end, dt, output_interval, limit)):
            steps, dt = al  # the samples on the multiples of output_interval
    steps = int(steps)
    if output_interval:
        sample_count(t_end, output_interval)  # the limit of every model's histories (exit 2 past it)
    every = max(1, int(round(output_interval / dt))) if output_interval else max(1, steps // SAMPLES)
    n = Kt.shape[0]
    cd = damping * (np.ones(n) if damped is None else np.asarray(damped, float))
    c = cd * dt / 2
    ledger = EnergyLedger(Kt.__matmul__, np.ones(n), np.ones(n, bool), bt, cd, 0.0)
    q = np.zeros(n)
    v = -0.5 * dt * bt  # v^{-1/2}
    t, vals = [0.0], [observe(np.zeros(n))]
    ledger.sample(0.0, q, np.zeros(n))
    with np.errstate(over="ignore", invalid="ignore"):
        for j in range(steps):
            v_new = ((1.0 - c) * v + dt * (bt - Kt @ q)) / (1.0 + c)
            q_new = q + dt * v_new
            if j and j % every == 0:  # step j: v^j the mean of its half steps, the scheme's energy at j + 1/2
                row = ledger.sample(j * dt, q, 0.5 * (v + v_new), q_new, v_new)
                if ledger.blown_up(row):
                    raise SolveError(
                        f"dynamics.time_step = {dt:.4g} s: the explicit run blew up at step {j}"
                        f"{' (' + context + ')' if context else ''}; the stable limit is {limit:.4g} s: use a "
                        "step below it"
                    )
                t.append(j * dt)
                vals.append(observe(back @ q))
            q, v = q_new, v_new
    t.append(steps * dt)
    vals.append(observe(back @ q))
    return Run(
        np.array(t),
        np.array(vals),
        back @ q,
        dt,
        limit,
        steps,
        damping,
        omega1,
        ledger.arrays(energy_scale),
        ledger.drift(),
        ledger.scheme_drift(),
        "modal" if modal else "physical",
    )


def step_warnings(dt: float, limit: float) -> list[str]:
    """The warning of a given time step above the explicit scheme's stable limit: the run is unstable, and one short
    enough to end before its growth shows is wrong by as much without blowing up."""
    if not dt > limit * (1 + 1e-9):
        return []
    digits = next((d for d in range(4, 17) if f"{dt:.{d}g}" != f"{limit:.{d}g}"), 17)  # enough to tell them apart
    unit = 10.0 ** (math.floor(math.log10(limit)) - digits + 1)
    safe = math.floor(limit / unit) * unit  # the advice rounded down: never above the limit
    ratio = dt / limit
    shown = next((f"{ratio:.{d}g}" for d in range(3, 17) if f"{ratio:.{d}g}" != "1"), f"{ratio:.17g}")
    return [
        f"time_step = {dt:.{digits}g} s is {shown} x the stable limit {limit:.{digits}g} s of the "
        f"explicit scheme: the run is unstable and its history wrong even where it has not blown up yet; use "
        f"time_step <= {safe:.{digits}g} s or leave time_step out"
    ]


def dynamic_info(run: Run, probes: np.ndarray, label: str = "w") -> tuple[dict, dict]:
    """(info, writers) of a transient result, as the other dynamic models give them: analysis, dt, dt_limit, steps,
    damping, omega1, energy_drift, scheme_drift and the history (t, one series per probe, the ledger); the
    writer ``.csv`` puts the histories and the ledger in columns."""
    series = {f"{label}(x={p:g})": run.values[:, k] for k, p in enumerate(probes)}
    info = {
        "analysis": "dynamic",
        "dt": run.dt,
        "dt_limit": run.dt_limit,
        "steps": run.steps,
        "damping": run.damping,
        "omega1": run.omega1,
        "energy_drift": run.energy_drift,
        "scheme_drift": run.scheme_drift,
        "energy_ledger": run.ledger,
        "history": {"t": run.t, "series": series, "energy": run.energy, "ylabel": "deflection"},
    }
    if flags := step_warnings(run.dt, run.dt_limit):
        info.setdefault("warnings", []).extend(flags)
    text = columns_csv({"t": run.t, **series, **ledger_columns(run.t, run.energy)}, fmt="%.12g")
    return info, {".csv": lambda path: Path(path).write_text(text)}


def probe_rows(x: np.ndarray, probes) -> tuple[sp.csr_matrix, np.ndarray]:
    """Linear interpolation from the points x (uniform) to the probe positions (sparse rows); no probes: mid-span."""
    probes = np.atleast_1d(np.asarray(probes if probes is not None and len(probes) else [(x[0] + x[-1]) / 2], float))
    dx = x[1] - x[0]
    pos = np.clip((probes - x[0]) / dx, 0.0, len(x) - 1)
    i = np.minimum(np.floor(pos).astype(np.int64), len(x) - 2)
    t = pos - i
    k = np.arange(len(probes))
    rows = sp.csr_matrix((np.r_[1 - t, t], (np.r_[k, k], np.r_[i, i + 1])), shape=(len(probes), len(x)))
    return rows, probes


def updates_per_second(K, mass, b, points: int, steps: int = 200) -> float:
    """Point-updates per second of :func:`integrate` on this operator (``pdverify bench``)."""
    import time  # a benchmark's clock, only here

    t0 = time.perf_counter()
    integrate(K, mass, b, 0.0, lambda u: u[:1], steps=steps)
    return points * steps / (time.perf_counter() - t0)
