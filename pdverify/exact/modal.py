"""Model ``exact-modal-rod``: the exact transient of the elastic rod under the scene's step loads from rest, a
sum over its modes (a transient reference for ``pd-rod``; Moyer & Miraglia Section 2 without the horizon).

ρA u_tt + ρA D u_t = EA u'' + f(x) H(t), u(x, 0) = u_t(x, 0) = 0, D = c_d/ρ (the scene's ``damping``, or
2 ζ ω_1 for ``damping_ratio``, as the PD integrator applies it: mass-proportional, so the modes stay
uncoupled). With the modes φ_k, ω_k of :func:`pdverify.exact.vibration.rod_frequencies` (sin or cos of
s_k x, ∫ φ_k² = L/2) and F_k = ∫ f φ_k (point forces P φ_k(a)):

    u(x, t) = Σ_k p_k φ_k(x) g_k(t),  p_k = F_k / (ρA (L/2) ω_k²),
    g_k(t) = 1 - e^{-Dt/2} (cos r_k t + (D/2r_k) sin r_k t),  r_k = sqrt(ω_k² - D²/4)

(undamped: g_k = 1 - cos ω_k t). Truncation: modes are taken in octaves (64, 128, ...) until the estimate
of what the rest adds, 2 Σ_{k>N} |p_k| (|φ_k| <= 1, |g_k| <= 2) with the octave sums extrapolated
geometrically, is below ``tolerance`` x max |u_static|; ``info["truncation_error"]`` holds that estimate.
A point force has p_k ~ k⁻² (the estimate falls like 1/N); distributed loads k⁻³ or faster.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core.contract import POINTS, Model, Option
from ..core.errors import InputError
from ..core.result import Result, Timer, columns_csv
from ..core.scene import HELD, Scene
from ..numerics.steps import sample_count
from .vibration import rod_frequencies

MAX_TOLERANCE = 0.01  # the largest truncation tolerance a reference takes (a percent of the static response)
MAX_MODES = 2**14  # 4096 modes in the sum (their octave above for the estimate): a point force ~1e-4


class RodModes:
    """The rod's modes and the scene's modal loads (see the module docstring)."""

    def __init__(self, scene: Scene):
        rho = scene.material.density
        if rho is None:
            raise InputError("material.density: needed for dynamics; add density to the scene")
        left, right = scene.supports.left, scene.supports.right
        self.held = (HELD[left][0], HELD[right][0])
        if not any(self.held):
            raise InputError(
                f"supports = {left}-{right}: neither end holds the axial displacement, so the rod has a rigid-body "
                "mode; make one end clamped or pinned"
            )
        self.scene, self.L = scene, scene.length
        self.rhoA = rho * scene.section.A
        self.c = np.sqrt(scene.EA / self.rhoA)

    def shapes(self, k: np.ndarray, x: np.ndarray) -> np.ndarray:
        """φ_k(x), (len(k), len(x)): sin s x from a held left end, cos s x from a free one."""
        s = rod_frequencies(self.L, 1.0, self.held, int(k.max()))[k - 1]  # s_k = ω_k / c
        arg = np.outer(s, x)
        return np.sin(arg) if self.held[0] else np.cos(arg)

    def _integral(self, k: np.ndarray, a: float, b: float, sine: bool) -> np.ndarray:
        """∫_a^b φ_k dx, or ∫_a^b sin(πx/L) φ_k dx (``sine``), in closed form (products to sums)."""
        s = rod_frequencies(self.L, 1.0, self.held, int(k.max()))[k - 1]
        trig = np.sin if self.held[0] else np.cos

        def prim(w, x):  # ∫ trig(w x) dx at x (w > 0, or w = 0)
            w0 = np.where(w == 0, 1.0, w)
            if trig is np.sin:
                return np.where(w == 0, 0.0, -np.cos(w0 * x) / w0)
            return np.where(w == 0, x, np.sin(w0 * x) / w0)

        if not sine:
            return prim(s, b) - prim(s, a)
        al = (
            np.pi / self.L
        )  # sin(αx) sin(sx) = (cos((s-α)x) - cos((s+α)x))/2; sin(αx) cos(sx) = (sin((s+α)x) - sin((s-α)x))/2
        d, p_ = np.abs(s - al), s + al
        sgn = np.sign(s - al)
        if trig is np.sin:
            c = lambda w, x: np.where(w == 0, x, np.sin(w * x) / np.where(w == 0, 1.0, w))  # noqa: E731
            return 0.5 * ((c(d, b) - c(d, a)) - (c(p_, b) - c(p_, a)))
        sn = lambda w, x: np.where(w == 0, 0.0, -np.cos(w * x) / np.where(w == 0, 1.0, w))  # noqa: E731
        return 0.5 * ((sn(p_, b) - sn(p_, a)) - sgn * (sn(d, b) - sn(d, a)))

    def participations(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        """(ω_k, p_k) of the first ``count`` modes."""
        k = np.arange(1, count + 1)
        omega = rod_frequencies(self.L, self.c, self.held, count)
        F = np.zeros(count)
        for load in self.scene.loads:
            if load.type == "point_force" and load.axial:
                F += load.axial * self.shapes(k, np.array([load.position]))[:, 0]
            elif load.type == "distributed" and load.axial:
                a = 0.0 if load.start is None else load.start
                b = self.L if load.end is None else load.end
                F += load.axial * self._integral(k, a, b, load.shape == "sine")
        return omega, F / (self.rhoA * self.L / 2 * omega**2)

    def truncated(self, tolerance: float) -> tuple[np.ndarray, np.ndarray, float]:
        """(ω, p, truncation error estimate relative to max |u_static|), the fewest octaves that meet it."""
        x = np.linspace(0.0, self.L, 401)
        N = 64
        while True:
            omega, p = self.participations(4 * N)
            k = np.arange(1, N + 1)
            scale = np.abs(p[:N] @ self.shapes(k, x)).max()
            est = tail_bound(np.abs(p), N) / scale if scale > 0 else 0.0  # |φ_k| <= 1
            if est <= tolerance or 4 * N >= MAX_MODES:
                return omega[:N], p[:N], float(est)
            N *= 2


def tail_bound(size: np.ndarray, N: int) -> float:
    """2 Σ_{k>N} size_k, what the modes beyond the first N add at most (``size``: a bound on each of the first 4N
    modes' contribution, |g_k| <= 2), from the sums over (N, 2N] and (2N, 4N] with the octave sums extrapolated
    geometrically."""
    s1, s2 = size[N : 2 * N].sum(), size[2 * N :].sum()
    ratio = min(s2 / s1, 0.99) if s1 > 0 else 0.0
    return 2 * s1 / (1 - ratio)


def scene_damping(scene: Scene, omega1: float) -> float:
    """D = c_d/ρ (1/s) of the scene's [dynamics]: its ``damping``, or 2 ζ ω_1 for ``damping_ratio`` with this
    reference's first frequency; 0 without either."""
    d = scene.dynamics
    return 0.0 if d is None else float(d.damping or 2 * (d.damping_ratio or 0.0) * omega1)


def rod_response(scene: Scene, positions, times, tolerance: float = 1e-6, damping: float | None = None) -> tuple:
    """u at ``positions`` and ``times``, (len(times), len(positions)), and info (modes, truncation error)."""
    modes = RodModes(scene)
    omega, p, est = modes.truncated(tolerance)
    if damping is None:
        damping = scene_damping(scene, omega[0])
    u = modal_sum(
        modes.shapes(np.arange(1, len(omega) + 1), np.asarray(positions, float)) * p[:, None], omega, damping, times
    )
    return u, {"modes": len(omega), "truncation_error": est, "damping": float(damping)}


def modal_sum(phi: np.ndarray, omega: np.ndarray, damping: float, times) -> np.ndarray:
    """Σ_k phi[k] g_k(t) for the step response g_k of the module docstring (under-, over- and critically damped
    modes apart, in real arithmetic), (len(times), phi.shape[1])."""
    a = damping / 2
    under, over = omega > a, omega < a
    r = np.sqrt(np.abs(omega**2 - a * a))
    out = np.zeros((len(times), phi.shape[1]))
    for i0 in range(0, len(times), 256):  # blocks of times: (times x modes) stays small
        t = np.asarray(times[i0 : i0 + 256], float)[:, None]
        e = np.exp(-a * t)
        g = np.empty((t.shape[0], len(omega)))
        ru = r[under]
        g[:, under] = 1 - e * (np.cos(ru * t) + (a / ru) * np.sin(ru * t))
        ro = r[over]
        g[:, over] = 1 - 0.5 * ((1 + a / ro) * np.exp(-(a - ro) * t) + (1 - a / ro) * np.exp(-(a + ro) * t))
        crit = ~(under | over)
        g[:, crit] = 1 - e * (1 + a * t)
        out[i0 : i0 + 256] = g @ phi
    return out


class ModalReference(Model):
    """A transient reference summed from modes: step loads from rest, no prescribed end motions; gives time
    histories at any probes and times (``history_at``), the study runner's transient reference."""

    histories = True
    analyses = frozenset({"dynamic"})
    reference = True

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if scene.material.density is None:
            out.append("material.density: needed for dynamics; add density to the scene")
        d = scene.dynamics
        if d is not None and any(em is not None for em in (d.left, d.right)):
            out.append(f"dynamics.left/right: {self.name} takes step loads only, no prescribed end motions")
        return out


class ExactModalRod(ModalReference):
    name = "exact-modal-rod"
    title = "exact transient of the elastic rod from rest: sum of its modes (step loads, mass-proportional damping)"
    source = "modal superposition (textbook); the transient reference of pd-rod"
    options = (
        POINTS,
        Option(
            "tolerance",
            float,
            1e-6,
            "truncation error estimate, relative to max |u_static|",
            minimum=1e-14,
            maximum=MAX_TOLERANCE,
        ),
    )
    axial = True
    bending = False
    theory = "axial"
    measures = "u"
    load_types = frozenset({"point_force", "distributed"})

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        d = scene.dynamics
        if d is not None and d.damping_ratio is not None and d.damping is not None:
            out.append("dynamics: give damping or damping_ratio, not both")
        return out

    def history_at(self, scene: Scene, params: dict, probes, times) -> np.ndarray:
        """u at ``probes`` and ``times`` (len(times), len(probes)): the study runner's transient reference."""
        return rod_response(scene, probes, times, params["tolerance"])[0]

    def solve(self, scene: Scene, params: dict) -> Result:
        def response(positions, times):
            u, info = rod_response(scene, positions, times, params["tolerance"])
            return u, {}, info

        return modal_result(self, scene, params, Timer(), response, "u", "axial displacement")


def modal_result(model: Model, scene: Scene, params: dict, timer: Timer, response, key: str, ylabel: str) -> Result:
    """The result of a modal reference on the scene's grid (``params["points"]``): ``response(positions, times)``
    gives (values, {other field: values}, info), each (len(times), len(positions)); the histories at the scene's
    probes (every ``output_interval``, else 2000 samples) and the values at ``end_time`` on the grid: ``w`` and
    ``rotation`` when ``key`` is "w", else the field ``key`` (w = 0)."""
    d = scene.dynamics
    x = np.linspace(0.0, scene.length, params["points"])
    probes = list(d.probes) or [scene.length / 2]
    n_out = sample_count(d.end_time, d.output_interval) if d.output_interval else 2000
    t = np.linspace(0.0, d.end_time, n_out + 1)
    with timer("solve"):
        values, more, info = response(np.concatenate([probes, x]), np.append(t, d.end_time))
    n = len(probes)
    final, hist = values[-1, n:], values[:-1, :n]
    info = dict(info, analysis="dynamic")
    if info["truncation_error"] > params["tolerance"]:
        info.setdefault("warnings", []).append(
            f"truncation error estimate {info['truncation_error']:.2g} above tolerance {params['tolerance']:g} "
            f"with {info['modes']} modes (a point force converges like 1/modes)"
        )
    series = {f"{key}(x={p_:g})": hist[:, k] for k, p_ in enumerate(probes)}
    info["history"] = {"t": t, "series": series, "ylabel": ylabel}
    beam = key == "w"
    return model.new_result(
        scene,
        params,
        x,
        final if beam else np.zeros_like(x),
        rotation=more["rotation"][-1, n:] if beam else None,
        fields={} if beam else {key: final},
        dofs=info["modes"],
        timings=timer.timings,
        info=info,
        writers={".csv": lambda path: Path(path).write_text(columns_csv({"t": t, **series}, fmt="%.12g"))},
    )


MODELS = [ExactModalRod()]
