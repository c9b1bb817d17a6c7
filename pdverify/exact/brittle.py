"""The classical elastic-brittle Euler-Bernoulli beam under a prescribed deflection (the beam of O'Grady & Foster
2014, §3.3, Fig. 9; ``exact-eb`` with a ``displacement`` load): a statically determinate beam whose only load is the
deflection Δ = λ w̄ prescribed at x = a, λ the load factor of the scene's ``[loading]`` path.

Before the first failure the beam is elastic: the prescribed deflection is a point force F at a, F = Δ / w1(a) with
w1 the deflection under a unit force there, and M = F M1(x). The extreme fibre reaches ``failure_strain`` under the
largest moment at F_f = M_f / max |M1|, M_f = EI ε_f / c (:meth:`PlasticBeam.failure_moment`). A fibre strained
past ε_f carries nothing from then on, so the section softens; in the classical beam the softening localises in the
one section of largest moment, of zero length, and its moment falls to zero at once (the rotation there is a jump).
From that step on the beam is two rigid pieces hinged at the failed section x_p, moved by the prescribed deflection:
M = 0 and F = 0 everywhere, w linear on each piece, held by the supports' kinematic conditions, continuous at x_p,
w(a) = Δ. The failed section stays failed when the deflection is taken back.

A section fails when its strain passes ε_f: the step at exactly F_f is still elastic.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.loading import Loading
from ..core.scene import HELD, PointForce, Scene
from .plastic import TIE, PlasticBeam


def displacement_load(scene: Scene):
    """The scene's prescribed deflection, or None; InputError (one line) for what this module cannot take."""
    shown = [ld for ld in scene.loads if ld.type == "displacement"]
    if not shown:
        return None
    if len(scene.loads) > 1:
        raise InputError(
            f"loads: exact-eb takes a prescribed deflection as the scene's only load (this scene has {len(scene.loads)}"
            " loads); give the others a scene of their own or use pd-bond-pair"
        )
    if scene.material.yield_stress:
        raise InputError(
            "material.yield_stress: exact-eb takes a prescribed deflection on an elastic or brittle beam only (the "
            "plastic beam under a prescribed deflection is not in closed form here); drop yield_stress or the "
            "displacement load"
        )
    return shown[0]


class BrittleDisplacement:
    """The path of a determinate elastic-brittle beam under one prescribed deflection (module docstring)."""

    def __init__(self, scene: Scene, load):
        self.scene, self.L, self.a, self.target = scene, scene.length, float(load.position), float(load.value)
        unit = scene.model_copy(
            update={"loads": [PointForce(type="point_force", position=self.a, value=1.0)], "loading": None}
        )
        self.beam = PlasticBeam(unit)  # elastic (no yield stress): curvature M1 / EI
        self.w1a = float(self.beam.deflection(np.array([self.a]), 1.0, 1.0)[0][0])
        if self.w1a == 0.0:
            raise InputError(f"loads[0].position = {self.a:g}: a support holds the beam there; move the deflection")
        self.x_p = self.beam.peak_x
        m_peak = abs(self.beam.peak_M1)
        self.failure_factor = (
            self.beam.failure_moment * abs(self.w1a) / (m_peak * abs(self.target)) if m_peak > 0 else np.inf
        )
        self.R1 = self.beam.unit.reactions()

    def force(self, lam: float) -> float:
        """The force F at a that makes w(a) = lam w̄ on the elastic beam."""
        return lam * self.target / self.w1a

    def pieces(self, lam: float) -> np.ndarray:
        """(p0, p1, q0, q1): w = p0 + p1 x on [0, x_p], q0 + q1 x on [x_p, L] after failure."""
        L, xp, rows, rhs = self.L, self.x_p, [], []
        # unknowns (p0, L p1, q0, L q1): columns of one size
        for slot, X, cols in ((0, 0.0, (0, 1)), (1, L, (2, 3))):
            kind = self.scene.supports.kind(("left", "right")[slot])
            if HELD[kind][1]:
                rows.append(_row({cols[0]: 1.0, cols[1]: X / L}))
                rhs.append(0.0)
            if HELD[kind][2]:
                rows.append(_row({cols[1]: 1.0}))
                rhs.append(0.0)
        rows.append(_row({0: 1.0, 1: xp / L, 2: -1.0, 3: -xp / L}))
        rhs.append(0.0)
        rows.append(_row({0: 1.0, 1: self.a / L}) if self.a <= xp else _row({2: 1.0, 3: self.a / L}))
        rhs.append(lam * self.target)
        A = np.array(rows)
        if A.shape != (4, 4) or np.linalg.matrix_rank(A) < 4:
            raise SolveError(
                f"exact-eb: the beam hinged at its failed section x = {xp:.6g} is a mechanism the prescribed "
                "deflection does not hold"
            )
        return np.linalg.solve(A, np.array(rhs)) / np.array([1.0, L, 1.0, L])

    def health(self, x, failed: bool) -> np.ndarray:
        """The node health at x: 0 at the failed section, 1 elsewhere."""
        xs = np.asarray(x, float)
        return np.where(failed & (np.abs(xs - self.x_p) <= 1e-12 * self.L), 0.0, 1.0)

    def fields(self, x, lam: float, failed: bool) -> dict:
        """w, rotation, M and V at x for the factor ``lam``."""
        xs = np.asarray(x, float)
        if not failed:
            F = self.force(lam)
            w, rot, _ = self.beam.deflection(xs, 1.0, 1.0)
            V1 = self.beam.unit.fields(xs)["V"]
            return {"w": F * w, "rotation": F * rot, "M": F * self.beam.M1(xs), "V": F * V1}
        p0, p1, q0, q1 = self.pieces(lam)
        left = xs <= self.x_p
        return {
            "w": np.where(left, p0 + p1 * xs, q0 + q1 * xs),
            "rotation": np.where(left, p1, q1),
            "M": np.zeros(len(xs)),
            "V": np.zeros(len(xs)),
        }

    def reactions(self, lam: float, failed: bool) -> dict:
        F = 0.0 if failed else self.force(lam)
        return {**{k: float(F * v) for k, v in self.R1.items()}, "force_displacement_0": float(F)}

    def path(self, x):
        """(steps, info, (lam, failed)) along the scene's path (default [0, 1] in 10 steps), one entry per step."""
        loading = self.scene.loading or Loading()
        steps, failed = [], False
        for lam in loading.path():
            failed = failed or abs(lam) > self.failure_factor * (1 + TIE)
            f = self.fields(x, lam, failed)
            steps.append(
                {
                    "factor": float(lam),
                    "w": f["w"],
                    "reactions": self.reactions(lam, failed),
                    "broken": int(failed),
                    "health": self.health(x, failed),
                }
            )
        info = {
            "load_path": {
                "factors": [float(v) for v in loading.factors],
                "steps": len(steps),
                "completed": True,
                "last_factor": steps[-1]["factor"],
                "first_failure_factor": float(self.failure_factor) if np.isfinite(self.failure_factor) else None,
                "failure_force": float(abs(self.force(self.failure_factor)))
                if np.isfinite(self.failure_factor)
                else None,
                "peak_position": self.x_p,
                "failed": failed,
            },
            "reactions": steps[-1]["reactions"],
        }
        return steps, info, (steps[-1]["factor"], failed)


def _row(entries: dict) -> list[float]:
    r = [0.0] * 4
    for k, v in entries.items():
        r[k] = v
    return r
