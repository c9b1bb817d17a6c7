"""Time integration apart from the operators: the energy ledger of an explicit transient, the blow-up test
it gives, and the largest eigenvalue of a banded operator that is a stencil away from its ends.

The semi-discrete system is M u_tt = b - K u - C u_t on the free DOFs, the supported DOFs following
their prescribed motions. With the full operator K (rows of supported DOFs included) the mechanical
energy E = T + U, T = ½ v_f·M v_f, U = ½ u·K u, changes as (K symmetric)

    dE/dt = b·v + v_p·(K u - b)_p - P_d

the power of the loads, of the support reactions (K u - b)_p on the prescribed motions, minus the
dissipated power P_d. The ledger records T, U, the load work b·u (loads are steps at t = 0, from rest),
the support work ∫ (K u - b)_p du_p (trapezoid per step), the dissipated work ∫ P_d dt of the damping
and of the stabilisation (trapezoid over the recorded samples: exact to O(dt²) when every step is
recorded, coarser with a coarser output interval) and the balance T + U + D - W_loads - W_supports, which
is zero up to the time discretisation error (and the non-symmetric part of K). With moving supports the
rows of K at the moving DOFs are replaced by their columns (the symmetric completion) in U and in the
reactions, so that the identity holds whenever the free block of K is symmetric. Every sum over points
weighs a point by its share of the length (``weights``: 1/2 at the two end points, the trapezoid).

The column ``scheme`` is the explicit scheme's own discrete energy at the half step j + 1/2,

    E = ½ v^{j+½}·M v^{j+½} + ½ u^j·K u^{j+1} - ½ b·(u^j + u^{j+1})   (weighted sums),

which the undamped leapfrog step conserves exactly (to round-off) when the weighted K is symmetric and no
support moves: M (u^{j+1} - 2u^j + u^{j-1}) = dt² (b - K u^j) gives E^{j+½} - E^{j-½} = 0 term by term. It differs
from T + U - W by O((ω dt)²) per mode; :meth:`EnergyLedger.scheme_drift` is its largest change over the run.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core.errors import InputError

MAX_STEPS = 10_000_000  # time steps a transient may ask for (hours of stepping on a fine grid); more is refused
BLOW_UP_RATIO = 1e6  # stored energy over the work put in at which a run counts as blown up (amplitudes ~1e6 x)
LEDGER_COLUMNS = ("kinetic", "strain", "load_work", "support_work", "damping", "stabilisation", "balance", "scheme")
"""Columns of the ledger: ``damping`` the work dissipated by the scene's damping (c_d per DOF),
``stabilisation`` that of the scheme's stiffness-proportional damping β K v (not in the paper), ``scheme`` the
scheme's discrete energy (module docstring; NaN at t = 0)."""


def step_count(end_time: float, dt: float, source: str = "default", limit: float | None = None) -> int:
    """ceil(end_time / dt), the steps of a run up to ``end_time``; InputError (one line naming the field and the fix)
    above :data:`MAX_STEPS`. ``source``: where dt comes from, the scene's ``time_step`` or ``output_interval``, or the
    model's ``default`` step; ``limit``: the largest stable step, named in the advice."""
    ratio = float(end_time) / float(dt) if dt > 0 else float("inf")
    if np.isfinite(ratio) and ratio <= MAX_STEPS:
        return int(np.ceil(ratio - 1e-9))
    if source == "default":
        field = f"dynamics.end_time = {end_time:.4g} s with the model's time step {dt:.4g} s"
        fix = "give a shorter dynamics.end_time or use fewer points (the stable step grows with the spacing)"
    else:
        field = f"dynamics.{source} = {dt:.4g} s with end_time = {end_time:.4g} s"
        longest = f" (up to the stable limit {limit:.4g} s)" if limit else ""
        fix = f"give a larger dynamics.{source}{longest} or a shorter dynamics.end_time"
    raise InputError(f"{field} asks for {ratio:.3g} steps, more than the limit of {MAX_STEPS:.0e}; {fix}")


@dataclass
class EnergyLedger:
    """Energy of a transient at its recorded steps (see the module docstring); one entry per sample.

    ``apply_K``: u -> K u on the whole DOF vector (interleaved); ``mass`` per DOF; ``free`` mask;
    ``b`` the load vector; ``damping`` c_d/ρ per DOF (1/s); ``beta``: the stiffness-proportional
    damping coefficient (s) of the scheme (force -β K v on the free rows); ``weights`` per DOF (the point's
    share of the length: 1/2 at the end points; default 1)."""

    apply_K: object
    mass: np.ndarray
    free: np.ndarray
    b: np.ndarray
    damping: np.ndarray
    beta: float
    weights: np.ndarray | None = None
    t: list = field(default_factory=list)
    cols: dict = field(default_factory=lambda: {k: [] for k in LEDGER_COLUMNS})
    support_work: float = 0.0
    _power: np.ndarray = field(default_factory=lambda: np.zeros(2))
    _work_in: float = 0.0  # largest |work put in| so far

    def __post_init__(self):
        self._free = np.asarray(self.free, float)
        self._w = np.ones(len(self.mass)) if self.weights is None else np.asarray(self.weights, float)
        self._wm, self._wb = self._w * self.mass, self._w * self.b

    def add_support_step(self, reaction_mid: np.ndarray, du_p: np.ndarray):
        """One step of ∫ (K u - b)_p du_p: the reaction at mid step (trapezoid) times the motion's increment."""
        self.support_work += float(reaction_mid @ du_p)

    def sample(self, t: float, u: np.ndarray, v: np.ndarray, u_next=None, v_half=None) -> dict:
        """Record the energy at time t for displacements u (all DOFs) and velocities v (free DOFs;
        others ignored); ``u_next``, ``v_half``: u^{j+1} and v^{j+½} for the scheme's energy (else NaN).
        Returns the new row."""
        w = self._w
        vf = v * self._free
        Ku = self.apply_K(u)
        mv2 = self._wm * vf * vf
        T = 0.5 * float(mv2.sum())
        U = 0.5 * float(u @ (w * Ku))
        W = float(self._wb @ u)
        P = np.array([float(self.damping @ mv2), self.beta * float(vf @ (w * self.apply_K(vf))) if self.beta else 0.0])
        scheme = float("nan")
        if u_next is not None:
            vh = v_half * self._free
            scheme = (
                0.5 * float(self._wm @ (vh * vh))
                + 0.5 * float(u_next @ (w * Ku))
                - 0.5 * float(self._wb @ (u + u_next))
            )
        if self.t:  # trapezoid over the samples
            D = np.array([self.cols["damping"][-1], self.cols["stabilisation"][-1]])
            D += 0.5 * (self._power + P) * (t - self.t[-1])
        else:
            D = np.zeros(2)
        self._power = P
        row = {
            "kinetic": T,
            "strain": U,
            "load_work": W,
            "support_work": self.support_work,
            "damping": float(D[0]),
            "stabilisation": float(D[1]),
            "balance": T + U + float(D.sum()) - W - self.support_work,
            "scheme": scheme,
        }
        self.t.append(t)
        for k, val in row.items():
            self.cols[k].append(val)
        self._work_in = max(self._work_in, abs(W) + abs(self.support_work))
        return row

    def blown_up(self, row: dict) -> float | None:
        """The ratio (stored energy) / (largest work put in so far) when it exceeds BLOW_UP_RATIO or is not
        finite, else None (nothing put in yet: only a non-finite state counts). A stable passive system
        stores at most what was put in; a growing mode's energy grows with the square of its amplitude, the
        work of the loads on it only linearly."""
        stored = max(row["kinetic"], abs(row["strain"]))
        if not (np.isfinite(stored) and np.isfinite(row["load_work"]) and np.isfinite(row["support_work"])):
            return float("inf")
        if self._work_in > 0 and stored > BLOW_UP_RATIO * self._work_in:
            return stored / self._work_in
        return None

    def arrays(self, length: float = 1.0) -> dict:
        """The samples; the energies times ``length``: the operators' rows are equations per unit length at each
        point, so the sums over points (the end points weighted 1/2: the trapezoid) become energies (J) when
        multiplied by the spacing; drifts are ratios and do not depend on it."""
        return {"t": np.asarray(self.t, float), **{k: length * np.asarray(v, float) for k, v in self.cols.items()}}

    def _scale(self) -> float:
        a = {k: np.asarray(self.cols[k], float) for k in ("kinetic", "strain")}
        return max(np.abs(a["kinetic"]).max(initial=0.0) + np.abs(a["strain"]).max(initial=0.0), self._work_in)

    def drift(self) -> float:
        """max |balance| over the run relative to the largest of the stored energy and the work put in."""
        scale = self._scale()
        return float(np.abs(np.asarray(self.cols["balance"], float)).max(initial=0.0) / scale) if scale > 0 else 0.0

    def scheme_drift(self) -> float:
        """max |E - E_first| of the scheme's discrete energy over the samples that have it, relative to the
        largest of the stored energy and the work put in (round-off for an undamped run with a symmetric K)."""
        e = np.asarray(self.cols["scheme"], float)
        e = e[np.isfinite(e)]
        scale = self._scale()
        return float(np.abs(e - e[0]).max() / scale) if len(e) and scale > 0 else 0.0


def ledger_columns(t: np.ndarray, energy: dict) -> dict:
    """The ledger as columns beside the histories' times ``t``: ``energy_<column>`` with NaN where the ledger
    took no sample (its times ``energy["t"]`` are a subset of ``t``)."""
    if not energy:
        return {}
    rows = np.searchsorted(t, energy["t"])
    out = {}
    for k in LEDGER_COLUMNS:
        col = np.full(len(t), np.nan)
        col[rows] = energy[k]
        out[f"energy_{k}"] = col
    return out


def symbol_max(blocks: dict, inv_mass: np.ndarray, samples: int = 4097) -> float:
    """max over wavenumbers k in [0, π] of |eigenvalues| of the stencil's symbol Σ_o M⁻¹ C_o e^{iko}: the
    top of the interior spectrum of an operator on an unbounded grid."""
    k = np.linspace(0.0, np.pi, samples)
    nf = len(inv_mass)
    S = np.zeros((samples, nf, nf), complex)
    for o, C in blocks.items():
        S += np.exp(1j * k * o)[:, None, None] * (inv_mass[:, None] * C)[None]
    return float(np.abs(np.linalg.eigvals(S)).max())
