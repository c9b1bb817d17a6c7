"""Model ``exact-modal-timoshenko``: the exact transient of the Timoshenko beam under the scene's step loads from
rest, a sum over its modes (the transient reference of ``pd-timoshenko``; Moyer & Miraglia Section 3 without
the horizon).

    ρA w_tt = kGA (w'' - γ') + q(x) H(t),   ρI γ_tt = EI γ'' + kGA (w' - γ) + μ(x) H(t),   w = γ = 0 at t = 0.

The modes (ω_k, w_k, γ_k) are those of :class:`pdverify.exact.vibration.TimoshenkoBeam`: ω_k the roots of the
characteristic determinant, (w_k, γ_k) its general solution with the null vector of the end conditions at ω_k,
scaled to unit modal mass ∫ ρA w_k² + ρI γ_k² dx = 1 (composite Gauss–Legendre, 8 points per panel, two panels
per mode up to the highest of its block). With the modal loads F_k = ∫ q w_k dx + Σ P w_k(a) + Σ C γ_k(a),

    w(x, t) = Σ_k p_k w_k(x) g_k(t),   p_k = F_k / ω_k²,   and γ alike,   g_k = 1 - cos ω_k t (undamped),

which at t -> ∞ on average is the static solution Σ p_k w_k (tested against exact-timoshenko). Damping as the
scene's ``damping_on = "all"`` asks (mass-proportional, D = c_d/ρ on ρA w_t and ρI γ_t, or 2 ζ ω_1): the modes
stay uncoupled and g_k is the damped step response of ``exact.modal.modal_sum``. A damping of the translations
alone (``damping_on = "translations"``) couples the modes: declined. Truncation as ``exact-modal-rod``: modes in
octaves (64, 128, ...) until the estimate of what the rest adds, 2 Σ_{k>N} |p_k| max|w_k| with the octave sums
extrapolated geometrically, is below ``tolerance`` x max |w_static|, at most :data:`MAX_MODES` in the sum
(``info["truncation_error"]``; a point force converges like 1/N in the shear range).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..core.contract import POINTS, Option
from ..core.errors import InputError
from ..core.result import Result, Timer
from ..core.scene import PointForce, PointMoment, Scene
from .modal import MAX_TOLERANCE, ModalReference, modal_result, modal_sum, scene_damping, tail_bound
from .vibration import TimoshenkoBeam, beam_end

MAX_MODES = 1024  # the sum's modes at most (their octave above them is computed for the estimate)
GAUSS = np.polynomial.legendre.leggauss(8)
BLOCK = 16  # modes evaluated together (a block's (modes x 4 x 4 x points) stays ~70 MB at 1024 modes)


class BeamModes:
    """The Timoshenko beam's modes and the scene's modal loads (see the module docstring)."""

    def __init__(self, scene: Scene):
        rho = scene.material.density
        if rho is None:
            raise InputError("material.density: needed for dynamics; add density to the scene")
        self.scene, self.L = scene, scene.length
        self._done = []  # per block of BLOCK modes: (coefficients, modal mass, modal load, max |w|)
        self.beam = TimoshenkoBeam(
            scene.EI,
            scene.kGA,
            rho * scene.section.A,
            rho * scene.section.I,
            scene.length,
            beam_end(scene.supports.left),
            beam_end(scene.supports.right),
        )

    def coefficients(self, omega: np.ndarray) -> np.ndarray:
        """(len(omega), 4): the general solution's coefficients at each ω_k (null vector of the end conditions,
        :meth:`TimoshenkoBeam.end_conditions`); NaN at the cut-off mode (w = 0, γ = const)."""
        M, scale = self.beam.end_conditions(omega)
        cutoff = np.isclose(omega, self.beam.cutoff, rtol=1e-9)
        M[cutoff] = np.eye(4)
        coef = np.linalg.svd(M)[2][:, -1, :] / scale
        coef[cutoff] = np.nan
        return coef

    def fields(self, omega: np.ndarray, coef: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """w_k(x), γ_k(x), each (len(omega), len(x)); the cut-off mode is w = 0, γ = 1."""
        C = self.beam._columns(omega, np.asarray(x, float), rows=(0, 2))  # (modes, [w, γ], 4, points)
        with np.errstate(invalid="ignore"):
            w = np.einsum("kfx,kf->kx", C[:, 0], coef)
            g = np.einsum("kfx,kf->kx", C[:, 1], coef)
        cut = np.isnan(coef[:, 0])
        w[cut], g[cut] = 0.0, 1.0
        return w, g

    def participations(self, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(ω_k, coefficients scaled to unit modal mass, p_k = F_k / ω_k², max |w_k|) of the first ``count``
        modes. Each block of :data:`BLOCK` modes is integrated on two panels per mode up to its highest one,
        and kept: the next octave computes its new modes only."""
        omega = self.beam.frequencies(count)
        for b0 in range(BLOCK * len(self._done), count, BLOCK):
            self._done.append(self._block(omega[b0 : b0 + BLOCK], b0 + BLOCK))
        coef, mass, force, peak = (np.concatenate(part)[:count] for part in zip(*self._done, strict=True))
        norm = 1 / np.sqrt(mass)
        return omega, coef * norm[:, None], force * norm / omega**2, peak * norm

    def _block(self, omega: np.ndarray, highest: int) -> tuple:
        """(coefficients, modal mass, modal load, max |w|) of the modes ``omega`` (unscaled), the integrals on
        2 ``highest`` + 16 panels over the beam (a mode k has fewer than k half-waves in either field)."""
        coef = self.coefficients(omega)
        panels = 2 * highest + 16
        xq, wq = _composite(np.linspace(0.0, self.L, panels + 1))
        w, g = self.fields(omega, coef, xq)
        F = np.zeros(len(omega))
        for ld in self.scene.loads:
            if isinstance(ld, (PointForce, PointMoment)):
                w1, g1 = self.fields(omega, coef, np.array([ld.position]))
                F += ld.value * (w1 if isinstance(ld, PointForce) else g1)[:, 0]
            else:
                a, b = self.scene.span(ld)
                xd, wd = _composite(np.linspace(a, b, max(2, int(np.ceil((b - a) / self.L * panels))) + 1))
                F += self.fields(omega, coef, xd)[0] @ (ld.value * self.scene.load_shape(ld, xd) * wd)
        return coef, (self.beam.rA * w * w + self.beam.rI * g * g) @ wq, F, np.abs(w).max(1)

    def truncated(self, tolerance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """(ω, coefficients, p, truncation error estimate relative to max |w_static|), the fewest octaves that
        meet it."""
        N, x = 64, np.linspace(0.0, self.L, 401)
        while True:
            omega, coef, p, peak = self.participations(4 * N)
            scale = np.abs(p[:N] @ self.fields(omega[:N], coef[:N], x)[0]).max()
            est = tail_bound(np.abs(p) * peak, N) / scale if scale > 0 else 0.0
            if est <= tolerance or 4 * N >= MAX_MODES:
                return omega[:N], coef[:N], p[:N], float(est)
            N *= 2


def _composite(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre points and weights of :data:`GAUSS` on each panel between ``edges``."""
    h, mid = np.diff(edges) / 2, (edges[1:] + edges[:-1]) / 2
    return (mid[:, None] + h[:, None] * GAUSS[0]).ravel(), (h[:, None] * GAUSS[1]).ravel()


@lru_cache(maxsize=16)
def _truncated(scene_json: str, tolerance: float) -> tuple:
    """The modes of a scene, kept: a study measures every case of a series against the same scene."""
    modes = BeamModes(Scene.model_validate_json(scene_json))
    return modes, *modes.truncated(tolerance)


def beam_response(scene: Scene, positions, times, tolerance: float = 1e-5) -> tuple:
    """w and γ at ``positions`` and ``times``, each (len(times), len(positions)), and info (modes, truncation,
    damping D = c_d/ρ in 1/s: the scene's damping, or 2 ζ ω_1 with this beam's ω_1)."""
    modes, omega, coef, p, est = _truncated(scene.model_dump_json(), tolerance)
    w, g = modes.fields(omega, coef, np.asarray(positions, float))
    damping = scene_damping(scene, omega[0])
    both = modal_sum(np.concatenate([w, g], 1) * p[:, None], omega, damping, times)
    n = len(positions)
    return both[:, :n], both[:, n:], {"modes": len(omega), "truncation_error": est, "damping": damping}


class ExactModalTimoshenko(ModalReference):
    name = "exact-modal-timoshenko"
    title = "exact transient of the Timoshenko beam from rest: sum of its modes (step loads, mass-proportional damping)"
    source = "modal superposition, modes from the characteristic determinant; the transient reference of pd-timoshenko"
    options = (
        POINTS,
        Option(
            "tolerance",
            float,
            1e-5,
            "truncation error estimate, relative to max |w_static|",
            minimum=1e-12,
            maximum=MAX_TOLERANCE,
        ),
    )
    theory = "timoshenko"
    load_types = frozenset({"point_force", "point_moment", "distributed"})

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        d = scene.dynamics
        if d is not None and (d.damping or d.damping_ratio) and d.damping_on == "translations":
            out.append(
                'dynamics: damping_on = "translations" couples the beam\'s modes (exact-modal-timoshenko sums '
                'uncoupled ones); use damping_on = "all" (mass-proportional) or drop damping / damping_ratio'
            )
        return out

    def history_at(self, scene: Scene, params: dict, probes, times) -> np.ndarray:
        """w at ``probes`` and ``times`` (len(times), len(probes)): the study runner's transient reference."""
        return beam_response(scene, probes, times, params["tolerance"])[0]

    def solve(self, scene: Scene, params: dict) -> Result:
        def response(positions, times):
            w, g, info = beam_response(scene, positions, times, params["tolerance"])
            return w, {"rotation": g}, info

        return modal_result(self, scene, params, Timer(), response, "w", "deflection")


MODELS = [ExactModalTimoshenko()]
