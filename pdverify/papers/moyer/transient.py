"""Transient runs of the Moyer & Miraglia 2014 rod / Timoshenko beam / torsion bar: the damped leapfrog /
velocity-Verlet scheme of Eq. 7–12 (38–44) from rest, its time histories (:class:`History`), the energy
ledger sampled along the run (:mod:`pdverify.numerics.timeint`) and the blow-up message.

Time stepping (both variants): the boundary closures make K non-symmetric and some modes have complex
(or, at pinned ends with m = 1, 2 and L/h = 100, negative) ω² (tests/papers/moyer/test_dynamics.py checks the
spectrum); a stiffness-proportional damping β K v with β = κ dt_ref, κ = 0.2, dt_ref = 0.9 x the stable
limit (``stabilisation``; the first mode gets ~2e-4 of critical) keeps the step map's spectral radius
<= 1 on the small grids of the paper (above 1 without it), not on every grid. Every transient carries an
energy ledger (:mod:`pdverify.numerics.timeint`: kinetic, strain, load and support work, the work of the damping
and of the stabilisation, balance) and is stopped when its stored energy outgrows the work put in.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError, SolveError
from ...core.result import columns_csv
from ...numerics.steps import aligned_steps, sample_count
from ...numerics.timeint import EnergyLedger, ledger_columns, step_count
from .kernels import motion_value
from .spectrum import first_frequency, mass_scaled, stable_time_step
from .steps import StencilStep, WholeStep
from .system import Discrete

STABILISATION = 0.2  # κ of the stiffness-proportional damping β = κ dt_ref of the time stepping (see integrate)
DEFAULT_SAFETY = 0.9  # default dt = this x the stable limit; dt_ref of the stabilisation


@dataclass
class History:
    """Time histories of a transient run: t (s), probe positions and their w (or u) and rotation."""

    t: np.ndarray
    probes: np.ndarray
    values: np.ndarray  # (len(t), len(probes)) translation at the probes
    rotations: np.ndarray | None
    final: np.ndarray  # all DOFs at the end time
    x: np.ndarray
    dt: float
    dt_limit: float
    steps: int
    damping: float  # c_d / rho (1/s)
    stabilisation: float
    omega1: float | None
    energy: dict = field(default_factory=dict)  # the ledger: "t" (a subset of t) and LEDGER_COLUMNS -> array
    energy_drift: float = 0.0  # max |balance| / max(stored energy, work put in)
    scheme_drift: float = 0.0  # max change of the scheme's discrete energy (dynamics.EnergyLedger.scheme_drift)

    def to_csv(self, series: dict) -> str:
        """The histories ``series`` (named as the result's ``info.history``) and the ledger in columns after ``t``."""
        return columns_csv({"t": self.t, **series, **ledger_columns(self.t, self.energy)}, fmt="%.12g")


def _interp_rows(x: np.ndarray, probes: np.ndarray) -> sp.csr_matrix:
    """Linear interpolation from the points to the probe positions (sparse rows)."""
    dx = x[1] - x[0]
    i = np.clip(np.floor(probes / dx).astype(int), 0, len(x) - 2)
    t = probes / dx - i
    rows = np.repeat(np.arange(len(probes)), 2)
    cols = np.stack([i, i + 1], 1).ravel()
    vals = np.stack([1 - t, t], 1).ravel()
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(probes), len(x)))


WHOLE_DOFS = 4000  # up to this many DOFs a step is one CSR product (fewer numpy calls per step); on larger
# grids the blockwise stencil (StencilStep) is the faster of the two
LEDGER_STRIDE = 200  # steps between ledger samples above WHOLE_DOFS (a sample costs ~12 steps there: <= 6 %)


def nf_n(disc: Discrete) -> int:
    return disc.nf * len(disc.x)


def integrate(
    disc: Discrete,
    motions: dict,
    t_end: float | None,
    dt: float | None = None,
    damping: float = 0.0,
    damping_ratio: float | None = None,
    safety: float = 0.9,
    probes=None,
    record_every: int | None = None,
    output_interval: float | None = None,
    damp_rotations: bool = False,
    stabilisation: float = STABILISATION,
    steps: int | None = None,
    context: str = "",
    ledger_every: int | None = None,
) -> History:
    """Damped leapfrog velocity-Verlet (Eq. 7–11 / 38–44) from rest, loads as steps at t = 0 (v^{-1/2} =
    -dt/2 a^0 so that v^0 = 0; Eq. 12 sets v^{-1/2} = 0, which is first order for a step load).

    Per step: a^j = (b - K u^j)/m (one product with K); v̂ = v^{j-1/2} + dt (a^j - D v^{j-1/2});
    û^{j+1} = u^j + dt v̂; v^j = (û^{j+1} - u^{j-1})/(2dt); v^{j+1/2} = v^{j-1/2} + dt (a^j - D v^j);
    u^{j+1} = u^j + dt v^{j+1/2}. D = c_d/ρ acts on the translations only (Eq. 36–37: γ undamped).
    Prescribed DOFs follow their motions.
    ``damp_rotations``: the same D on the rotations too (not in the paper; without it the high
    shear-rotation modes are damped only through their coupling to w and ring for long).
    ``stabilisation`` κ: stiffness-proportional damping β K v^{j-1/2} with β = κ dt_ref (not in the
    paper), dt_ref = DEFAULT_SAFETY x the limit: the same β at every step (dt = dt_ref: β = κ dt).
    The boundary closures make K non-symmetric: some high modes have complex ω² and grow without it
    (the step map's spectral radius passes 1 on the Table 1 cantilever); κ = 0.2
    gives the highest mode ~18 % of critical and the first ~1e-4 %, and costs no extra product
    (K (u + β v)). The stable limit becomes 2 / (ω_max sqrt(1 + 2κ)) (the step map is stable while
    ω²dt² + 2βω²dt < 4: with β = 0.9κ x the limit the threshold is 1.017 x the limit at
    κ = 0.2). ``steps``: run this many steps
    (instead of up to ``t_end``). ``output_interval`` (s) or ``record_every`` (steps): the sampling of
    the histories and of the energy ledger (:class:`pdverify.numerics.timeint.EnergyLedger`, v^j the mean of the
    half-step velocities around the sample; ``ledger_every``: at most every so many steps, default
    every sample up to ``WHOLE_DOFS`` unknowns, else every ``LEDGER_STRIDE`` steps). Raises SolveError
    when the stored energy outgrows the work put in (a growing mode;
    :meth:`~pdverify.numerics.timeint.EnergyLedger.blown_up`); ``context`` (supports, horizon) goes into that
    message.

    Implementation: with V = dt v^{j+1/2} the step is y = u + κ V, V <- α V + G (b - K y), u <- u + V
    with G = (1 - c/2) dt²/m per DOF (zero on prescribed DOFs); K y is one CSR product up to
    ``WHOLE_DOFS`` unknowns, else the operator's stencil applied block by block (:class:`StencilStep`)."""
    given = dt is not None
    dt, limit, kappa, damping, omega1 = time_step(disc, dt, damping, damping_ratio, safety, stabilisation)
    if steps is None:  # before any step: a run the machine cannot finish is refused (exit 2)
        beta = kappa * dt  # the stabilisation's β (s), the same whatever the step
        steps = step_count(t_end, dt, "time_step" if given else "default", limit)
        dt = t_end / steps  # whole steps that end at t_end (at most dt: as stable)
        if not given and (al := aligned_steps(t_end, dt, output_interval, limit)):
            steps, dt = al  # the samples on the multiples of output_interval
        kappa = beta / dt
    steps, record_every, ledger_every = sampling(disc, t_end, dt, steps, record_every, output_interval, ledger_every)
    clock = Clock(dt, limit, kappa, damping, omega1, steps, record_every, ledger_every)
    probes = np.atleast_1d(np.asarray(probes if probes is not None and len(probes) else [disc.x[-1] / 2], float))
    recorder = Recorder(disc, probes)
    gains = Gains(disc, clock.dt, clock.damping, damp_rotations)
    st, apply_K = step_engine(disc, gains, clock.kappa)
    supports = SupportWork(disc, motions)
    ledger = energy_ledger(disc, supports.ledger_K(apply_K), gains, clock.dt, clock.kappa)
    supports.start(st, clock.dt)
    # from rest: v^0 = 0 with the loads acting from t = 0, so v^{-1/2} = -dt/2 a^0 (second order; Eq. 12's
    # v^{-1/2} = 0 starts the step load with v^0 = dt/2 a^0, an O(dt) error of every later state)
    V0 = -0.5 * clock.dt * clock.dt * disc.b / disc.mass
    V0[gains.pres_dofs] = 0.0
    st.start(V0)
    ledger.sample(0.0, np.zeros(nf_n(disc)), np.zeros(nf_n(disc)))
    with np.errstate(over="ignore", invalid="ignore"):
        _step_loop(disc, clock, gains, st, apply_K, supports, ledger, recorder, stabilisation, context)
    return History(
        np.array(recorder.times),
        probes,
        np.array(recorder.vals),
        np.array(recorder.rots) if disc.nf == 2 else None,
        st.state(),
        disc.x,
        clock.dt,
        clock.limit,
        clock.steps,
        clock.damping,
        stabilisation,
        clock.omega1,
        ledger.arrays(disc.x[1] - disc.x[0]),
        ledger.drift(),
        ledger.scheme_drift(),
    )


@dataclass
class Clock:
    """The time step of a run and its sampling: dt, the stable limit (with the stabilisation), ``kappa`` = β / dt
    (what the step uses), the damping c_d / ρ (from ``damping_ratio`` when given: 2 ζ ω1), ω1 (None unless
    asked for), the number of steps and the strides of the histories and of the ledger."""

    dt: float
    limit: float
    kappa: float
    damping: float
    omega1: float | None
    steps: int
    record_every: int
    ledger_every: int


def time_step(
    disc: Discrete, dt: float | None, damping: float, damping_ratio: float | None, safety: float, stabilisation: float
):
    """(dt, limit, kappa, damping, omega1) of a run: the stable limit 2 / (ω_max sqrt(1 + 2κ)) of the stabilised
    step (κ = ``stabilisation``), dt = ``safety`` x the limit unless given (at most 1 / damping: a given step
    past that is refused), β / dt of the stabilisation
    β = κ dt_ref with dt_ref = DEFAULT_SAFETY x the limit, the damping c_d / ρ (2 ζ ω1 from ``damping_ratio``
    when given) and ω1 (None unless needed for that)."""
    limit = stable_time_step(disc) / np.sqrt(1.0 + 2.0 * stabilisation)
    omega1 = None
    if damping_ratio is not None:
        omega1 = first_frequency(disc)
        damping = 2.0 * damping_ratio * omega1
    dt_ref = DEFAULT_SAFETY * limit
    if dt is not None and damping * float(dt) > 1.0:  # Gains: alpha = 1 - c + c^2/2, beta = 1 - c/2 with c = D dt
        raise InputError(
            f"dynamics.time_step = {float(dt):.4g} s with a damping of {damping:.4g} 1/s: the explicit step damps by "
            f"c = damping x dt = {damping * float(dt):.3g}, and needs c <= 1; give time_step <= {1.0 / damping:.4g} s "
            "or less damping"
        )
    dt = safety * limit if dt is None else float(dt)
    if damping * dt > 1.0:  # heavy damping: its term sets the step (a larger c grows, whatever the stiffness)
        dt = 1.0 / damping
    # β = κ dt_ref (seconds), the same for every step: with β = κ dt a smaller step damped the closures'
    # growing modes less (Table 1 cantilever: stable at 0.9 of the limit, blew up at 0.5 and 0.3) and the
    # scheme converged at order 1 in dt to a damping that vanishes. kappa: β / dt, what the step uses
    kappa = stabilisation if dt == dt_ref else stabilisation * dt_ref / dt
    return dt, limit, kappa, damping, omega1


def sampling(disc: Discrete, t_end, dt: float, steps, record_every, output_interval, ledger_every) -> tuple:
    """(steps, record_every, ledger_every): the steps up to ``t_end`` unless given, the histories every
    ``output_interval`` (s) or ``record_every`` steps (default: ~2000 samples), the ledger at most every
    ``ledger_every`` steps (default every sample up to ``WHOLE_DOFS`` unknowns, else every ``LEDGER_STRIDE``)."""
    if steps is None:
        steps = int(np.ceil(t_end / dt - 1e-9))
    if output_interval is not None:
        sample_count(t_end, output_interval)  # the limit of every model's histories (exit 2 past it)
        record_every = max(1, int(round(output_interval / dt)))
    record_every = record_every or max(1, steps // 2000)
    if ledger_every is None:  # a ledger sample costs ~3 products with K (on large grids ~4 steps each)
        ledger_every = record_every if nf_n(disc) <= WHOLE_DOFS else max(record_every, LEDGER_STRIDE)
    return steps, record_every, ledger_every


class Gains:
    """The per-DOF coefficients of the step in closed form (Eq. 7-11): u^j - u^{j-1} = dt v^{j-1/2}, so
    v^j = (v^{j-1/2} + v̂)/2 and v^{j+1/2} = alpha v^{j-1/2} + beta dt a^j with c = D dt, alpha = 1 - c + c²/2,
    beta = 1 - c/2. ``field_c``, ``alpha``, ``gd_field`` per field (c, alpha, G = beta dt²/m); ``gd``,
    ``alpha_dof`` per DOF (interleaved), G zero on the prescribed DOFs (``pres_dofs``: no acceleration, they
    follow their motions, so no index gathering per step); ``bG`` = G b."""

    def __init__(self, disc: Discrete, dt: float, damping: float, damp_rotations: bool):
        n = len(disc.x)
        self.field_c = [(damping if (tr or damp_rotations) else 0.0) * dt for tr in disc.field_translational]
        self.alpha = tuple(1.0 - c + c * c / 2 for c in self.field_c)
        self.gd_field = tuple((1.0 - c / 2) * dt * dt / mf for c, mf in zip(self.field_c, disc.field_mass))
        self.gd = np.tile(np.asarray(self.gd_field, float), n)
        self.pres_dofs = np.array(sorted(disc.prescribed), dtype=np.int64)
        self.gd[self.pres_dofs] = 0.0
        self.bG = self.gd * disc.b
        self.alpha_dof = np.tile(np.asarray(self.alpha), n)


def step_engine(disc: Discrete, gains: Gains, kappa: float):
    """(engine, K product): the whole DOF vector advanced by one CSR product up to ``WHOLE_DOFS`` unknowns
    (:class:`WholeStep`), else by the operator's stencil block by block (:class:`StencilStep`)."""
    if nf_n(disc) <= WHOLE_DOFS:
        return WholeStep(disc, gains.gd, gains.alpha_dof, kappa, gains.bG), disc.K.__matmul__
    return StencilStep(disc, gains.gd, gains.alpha, kappa, gains.bG, gains.gd_field), disc.op.matvec


MOTION_BLOCK = 4096  # steps whose prescribed motions are evaluated at once
DENSE_REACTION_ENTRIES = 1 << 16  # the moving rows' operator as a dense array up to this many entries


class SupportWork:
    """The prescribed motions of a run and the work of their supports, ∫ (K u - b)_p du_p (trapezoid per step,
    one small product per step); the ledger's K takes the rows of the moving DOFs as their columns (the
    symmetric completion, :func:`_columns`)."""

    def __init__(self, disc: Discrete, motions: dict):
        self.disc = disc
        self.pres = [(dof, mot) for dof, mot in motions.items() if mot is not None]
        self.moving = np.array([dof for dof, _ in self.pres], dtype=np.int64)
        self.w = point_weights(disc)
        self.Kcols = _columns(disc, self.moving, self.w) if len(self.moving) else None

    def ledger_K(self, apply_K):
        """u -> K u with the moving DOFs' rows replaced by the weighted columns divided by their own weight (apply_K
        itself when none moves): the ledger weighs every row by its point's share, so the moving rows of the
        symmetric weighted operator S (S_pj = w_j K_jp) count once in ½ uᵀ S u, as the free rows' entries do."""
        if not len(self.moving):
            return apply_K
        moving, Kcols, wp = self.moving, self.Kcols, self.w[self.moving]

        def ledger_K(u):
            y = apply_K(u)
            y[moving] = (Kcols @ u) / wp
            return y

        return ledger_K

    def start(self, st, dt: float) -> None:
        """The reactions and positions at rest, on the engine ``st``'s state; ``dt`` the step."""
        self.dt, self.block = dt, (0, np.zeros((0, len(self.pres))))
        if len(self.moving):
            self.Kp = st.on_state(self.Kcols)
            if self.Kp.shape[0] * self.Kp.shape[1] <= DENSE_REACTION_ENTRIES:  # one numpy product per step
                self.Kp = self.Kp.toarray()
            self.bp = (self.w * self.disc.b)[self.moving]
            self.react = self.Kp @ st.flat - self.bp
            self.up = np.zeros(len(self.moving))

    def _motions(self, s: int) -> np.ndarray:
        """The prescribed motions at step s (t = s dt), evaluated MOTION_BLOCK steps at a time."""
        first, values = self.block
        if not first <= s < first + len(values):
            t = np.arange(s, s + MOTION_BLOCK) * self.dt
            self.block = (s, np.column_stack([motion_value(mot, t) for _, mot in self.pres]))
            first = s
        return self.block[1][s - first]

    def advance(self, st, s: int, ledger: EnergyLedger) -> None:
        """Set the prescribed DOFs to their motions at step s (t = s dt) and add the step's support work to the
        ledger."""
        if not self.pres:
            return
        up_new = self._motions(s)
        for (dof, _), value in zip(self.pres, up_new):
            st.set(dof, value)
        if len(self.moving):
            r_new = self.Kp @ st.flat - self.bp
            ledger.add_support_step(0.5 * (self.react + r_new), up_new - self.up)
            self.react, self.up = r_new, up_new


def energy_ledger(disc: Discrete, ledger_K, gains: Gains, dt: float, kappa: float) -> EnergyLedger:
    """The run's :class:`~pdverify.numerics.timeint.EnergyLedger`: the free DOFs (not prescribed), damping c / dt
    per DOF, the stabilisation's β = kappa dt, the points' shares of the length (the operator's, else the
    trapezoid: 1/2 at the end points)."""
    nf, n = disc.nf, len(disc.x)
    free = np.ones(nf * n, bool)
    free[gains.pres_dofs] = False
    damping = np.tile(np.asarray(gains.field_c) / dt, n)
    return EnergyLedger(ledger_K, disc.mass, free, disc.b, damping, kappa * dt, point_weights(disc))


def point_weights(disc: Discrete) -> np.ndarray:
    """Per DOF, the point's share of the length in units of Δ: the operator's (``disc.weights``), else the
    trapezoid (1/2 at the end points)."""
    if disc.weights is not None:
        return np.asarray(disc.weights, float)
    nf, n = disc.nf, len(disc.x)
    weights = np.ones(nf * n)
    weights[:nf] = weights[-nf:] = 0.5  # the end points' half cells
    return weights


class Recorder:
    """The histories at the probes (linear interpolation from the points): t, the translation (field 0) and, for
    the beam, the rotation (field 1); zero at t = 0."""

    def __init__(self, disc: Discrete, probes: np.ndarray):
        self.P, self.nf = _interp_rows(disc.x, probes), disc.nf
        self.times, self.vals, self.rots = [0.0], [np.zeros(len(probes))], [np.zeros(len(probes))]

    def record(self, t: float, st) -> None:
        self.times.append(t)
        self.vals.append(self.P @ st.field(0))
        if self.nf == 2:
            self.rots.append(self.P @ st.field(1))


def _step_loop(disc, clock: Clock, gains: Gains, st, apply_K, supports, ledger, recorder, stabilisation, context):
    """The steps 1 .. clock.steps: a step of the engine, the prescribed motions and their work, and at every
    ``record_every``-th step (and the last) the histories, with a ledger sample at most every ``ledger_every``
    steps (the last always), in between only a check that the state is finite. Raises SolveError (the
    :func:`_blow_up_message`) when the stored energy outgrows the work put in."""
    dt, steps, kappa = clock.dt, clock.steps, clock.kappa
    last_ledger = 0
    for s in range(1, steps + 1):
        st.step()
        t = s * dt
        supports.advance(st, s, ledger)
        if s % clock.record_every == 0 or s == steps:
            if s - last_ledger >= clock.ledger_every or s == steps:
                last_ledger = s
                u, V = st.state(), st.velocity()
                Vn = gains.alpha_dof * V + gains.gd * (disc.b - apply_K(u + kappa * V))
                ratio = ledger.blown_up(ledger.sample(t, u, (V + Vn) / (2 * dt), u + Vn, Vn / dt))
            else:  # between ledger samples: only a non-finite state stops the run
                ratio = None if np.isfinite(st.amax()) else float("inf")
            if ratio is not None:
                raise SolveError(_blow_up_message(disc, dt, clock.limit, s, t, ratio, stabilisation, context))
            recorder.record(t, st)


def _columns(disc: Discrete, dofs: np.ndarray, weights: np.ndarray) -> sp.csr_matrix:
    """(W K)[:, dofs]ᵀ (len(dofs) x all DOFs), W the points' shares ``weights``: the rows of the symmetric weighted
    operator at the moving DOFs, from the rows of the points within the operator's reach, the diagonal entry set so
    that the row gives no force in the rigid mode of the DOF's field (the end row's own diagonal belongs to an
    equation the support replaces, not to an energy)."""
    nf, n, h = disc.nf, len(disc.x), disc.op.reach
    pts = np.unique(np.clip((dofs // nf)[:, None] + np.arange(-h, h + 1)[None, :], 0, n - 1))
    rows = disc.op.rows_csr(pts).tocsc()[:, dofs].T.tocsr()  # (len(dofs) x len(pts) nf)
    sel = (nf * pts[:, None] + np.arange(nf)[None, :]).ravel()
    C = rows.tocoo()
    cols = sel[C.col]
    out = sp.csr_matrix((C.data * weights[cols], (C.row, cols)), shape=(len(dofs), nf * n)).tolil()
    for i, d in enumerate(dofs):  # the diagonal: no energy in the rigid mode of the DOF's field
        r = np.zeros(nf * n)
        if d % nf == 0:  # translation (w, u, twist): a rigid translation
            r[0::nf] = 1.0
        else:  # rotation γ: w = (x - x_d) θ, γ = θ
            r[0::nf], r[1::nf] = disc.x - disc.x[d // nf], 1.0
        out[i, d] = 0.0
        out[i, d] = -float(out[i].toarray().ravel() @ r) / r[d]
    return out.tocsr()


def _blow_up_message(
    disc: Discrete, dt: float, limit: float, s: int, t: float, ratio: float, kappa: float, context: str
) -> str:
    """One line: the step, the limit, what grew and what to change."""
    head = (
        f"dt = {dt:.4g} s: the explicit integration blew up at step {s} (t = {t:.4g} s; stored energy "
        f"{ratio:.2g} x the work put in)"
    )
    where = f" ({context})" if context else ""
    if dt > limit * (1 + 1e-9):
        return f"{head}; the stable limit is {limit:.4g} s; use time_step <= {limit:.4g} s or leave time_step out"
    detail = ""
    if disc.n_free <= 1500:  # a dense eigenvalue solve of a few seconds at most
        lam = np.linalg.eigvals(mass_scaled(disc, disc.free).toarray())
        growth = np.abs(np.sqrt(lam.astype(complex)).imag)  # mode ~ exp(±i sqrt(λ) t)
        k = int(np.argmax(growth))
        if growth[k] > 0:
            detail = (
                f": M^-1 K has the eigenvalue {lam[k]:.3g} (the mode grows like exp({growth[k]:.3g} t), "
                "a real part below zero or an imaginary part)"
            )
    # a beam operator not written from an energy (pd-timoshenko paper, corrected): variant energy has no growing mode
    beam = disc.nf == 2 and disc.weights is None
    instead = ", or use variant = energy (its operator is symmetric: no growing mode)" if beam else ""
    return (
        f"{head}; dt is below the stable limit {limit:.4g} s, so a smaller step does not help: the operator's "
        f"boundary closures{where} have a growing mode{detail}; change the horizon or the number of points, "
        f"or damp more (damping_ratio){instead}"
    )
