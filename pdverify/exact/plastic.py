"""The classical elastic-perfectly plastic (and brittle) Euler-Bernoulli beam along a load path, on statically
determinate scenes (simply supported, cantilever, pinned-guided): ``exact-eb`` with ``[material] yield_stress``,
``failure_strain`` or ``[loading]``.

The moment is the statics' M = lambda M1(x) (M1 of the scene's loads, independent of the stiffness). Each section
follows the fibre law of :meth:`pdverify.core.section.Profile.fibre_moment` (plane sections, sigma = E clip(eps,
-eps_y, eps_y)) while it loads past its largest moment so far, and unloads elastically from it:

    kappa(x) = kappa_f(lambda_p M1(x)) + (lambda - lambda_p) M1(x) / EI,

lambda_p the factor of largest magnitude reached so far, kappa_f the fibre law inverted (Newton from the elastic
curvature, which lies below it: the law is concave, so the iterates rise monotonically to the root). A step that
would yield a fibre in reverse is refused (``fem-eb`` carries the fibre history). w'' = kappa is integrated in
closed form of its quadratures: w(x) = c0 + c1 x + x K1(x) - K2(x), K1 = ∫ kappa, K2 = ∫ s kappa from 0, by
Gauss-Legendre on the pieces between the loads and the points where the section's elastic core crosses a step of
its width (the curvature is analytic inside each piece), bisected where 10 and 20 points disagree (adaptive; the
estimate is kept in ``info``). The supports' two kinematic conditions fix c0, c1.

The collapse load factor is Mp / max |M1| (Mp = sigma_y Z, the hinge at the largest moment); a brittle section's
first fibre fails where the extreme fibre's strain reaches ``failure_strain`` at the largest moment: M_f = M(eps_f /
c). The path stops with one line at the step that passes either and keeps the steps so far.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.loading import Loading
from ..core.scene import HELD, Scene
from .straight import particular, solve_straight

GAUSS = [np.polynomial.legendre.leggauss(n) for n in (10, 20)]
QUAD_TOL = 1e-14  # per-piece tolerance of the adaptive quadrature, relative to the curvature's integral
LEVELS = 60  # bisections of a piece at most
TIE = 1e-12  # relative slack of the yield and reverse-yield tests (round-off of the fibre law)


def check(scene: Scene) -> None:
    """One line for a scene the determinate plastic path cannot take."""
    sup = scene.supports
    kinds = (sup.kind("left"), sup.kind("right"))
    if not sup.simple or "spring" in kinds:
        raise InputError(
            "supports: exact-eb follows a load path on statically determinate beams (end supports only); this one "
            "is indeterminate: use fem-eb (fibre sections, any supports)"
        )
    held = sum(HELD[k][1] + HELD[k][2] for k in kinds)
    if held != 2:
        raise InputError(
            f"supports = {kinds[0]}-{kinds[1]}: exact-eb follows a load path on statically determinate beams "
            "(simply supported, cantilever); use fem-eb (fibre sections, any supports)"
        )
    if scene.segments:
        raise InputError("segments: exact-eb's load path takes one section and material; use fem-eb")
    mat, prof = scene.material, scene.section.profile
    if (mat.yield_stress or mat.failure_strain) and (prof is None or not prof.symmetric):
        raise InputError(
            "section: a yield stress or failure strain needs a shape symmetric about its centroid (width and height, "
            'or shape = "I" or a symmetric "profile"): the fibre law bends it about the centroid'
        )


def inverse_fibre(prof, E: float, sy: float, M: np.ndarray) -> np.ndarray:
    """kappa with fibre_moment(kappa) = M (|M| < Mp): Newton from M / EI, monotone from below (the law is concave)."""
    M = np.asarray(M, float)
    m = np.abs(M)
    k = m / (E * prof.inertia)
    on = np.flatnonzero(m > sy * prof.elastic_modulus)  # the others are elastic: M / EI is the root
    for _ in range(200):
        if not len(on):
            break
        kk = k[on]
        dk = (m[on] - prof.fibre_moment(kk, E, sy)) / prof.fibre_stiffness(kk, E, sy)
        k[on] = kk + np.maximum(dk, 0.0)
        on = on[dk > 4e-16 * kk]
    else:
        raise SolveError("exact-eb: the fibre law's inverse did not converge (a moment too close to Mp)")
    return np.sign(M) * k


class PlasticBeam:
    """The determinate elastic-perfectly plastic beam of one scene: curvature, deflection and the path."""

    def __init__(self, scene: Scene):
        check(scene)
        self.scene, self.L = scene, scene.length
        self.unit = solve_straight(scene, False)
        mat, sec = scene.material, scene.section
        self.E, self.EI, self.sy, self.ef = mat.E, mat.E * sec.I, mat.yield_stress, mat.failure_strain
        self.prof = sec.profile
        self.kinds = (scene.supports.kind("left"), scene.supports.kind("right"))
        ends = np.array([0.0, self.L])  # M1 = c0 + c1 x + Mp(x): the line through the ends' statics
        self.line = np.polyfit(ends, self.unit.fields(ends)["M"] - particular(scene, ends)[0], 1)
        self.edges = self._load_edges()
        self._cache = {}
        self.peak_x, self.peak_M1 = self._peak()

    # -- statics ---------------------------------------------------------------------------------------------------
    def M1(self, x) -> np.ndarray:
        x = np.asarray(x, float)
        return particular(self.scene, x)[0] + np.polyval(self.line, x)

    def _load_edges(self) -> np.ndarray:
        pts = [0.0, self.L]
        for ld in self.scene.loads:
            if ld.type == "distributed":
                pts += list(self.scene.span(ld))
            elif hasattr(ld, "position"):
                pts.append(ld.position)
        return np.unique(np.clip(pts, 0.0, self.L))

    def _peak(self) -> tuple[float, float]:
        """(x, M1) where |M1| is largest: a fine sample, then the neighbours of its largest resampled (x 64 each)."""
        x = np.unique(np.r_[np.linspace(0.0, self.L, 20001), self.edges])
        i = int(np.argmax(np.abs(self.M1(x))))
        best, lo, hi = x[i], x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
        for _ in range(9):
            s = np.r_[np.linspace(lo, hi, 129), best]
            j = int(np.argmax(np.abs(self.M1(s))))
            best, step = s[j], (hi - lo) / 128
            lo, hi = max(best - step, lo), min(best + step, hi)
        return float(best), float(self.M1([best])[0])

    @property
    def plastic_moment(self) -> float:
        return self.sy * self.prof.plastic_modulus if self.sy else np.inf

    @property
    def yield_moment(self) -> float:
        return self.sy * self.prof.elastic_modulus if self.sy else np.inf

    def moment_of_curvature(self, kappa) -> np.ndarray:
        return self.prof.fibre_moment(kappa, self.E, self.sy) if self.sy else self.EI * np.asarray(kappa, float)

    @property
    def failure_moment(self) -> float:
        return float(self.moment_of_curvature(self.ef / self.prof.extreme_fibre)) if self.ef else np.inf

    # -- curvature -------------------------------------------------------------------------------------------------
    def curvature(self, s, lam: float, peak: float) -> np.ndarray:
        """kappa at s for the factor ``lam`` after the largest factor ``peak`` (module docstring)."""
        m1 = self.M1(s)
        kp = inverse_fibre(self.prof, self.E, self.sy, peak * m1) if self.sy else peak * m1 / self.EI
        return kp + (lam - peak) * m1 / self.EI

    def _kinks(self, peak: float) -> np.ndarray:
        """The x where the elastic core's edge crosses a step of the width or the extreme fibre (|M| at a level of
        the fibre law), by bisection on the sign changes of a fine sample between the load edges."""
        if not self.sy or peak == 0.0:
            return np.empty(0)
        c, yc = self.prof.extreme_fibre, self.prof.centroid
        depth = np.unique(np.abs(np.asarray(self.prof.y, float) - yc))
        depth = depth[depth > 1e-12 * c]
        return self._crossings(peak, self.moment_of_curvature(self.sy / self.E / depth))

    def _crossings(self, peak: float, levels: np.ndarray) -> np.ndarray:
        """The x where |peak M1(x)| crosses one of ``levels`` (kept per peak and levels)."""
        key = (peak, levels.tobytes())
        if key not in self._cache:
            self._cache[key] = self._find_crossings(peak, levels)
        return self._cache[key]

    def _find_crossings(self, peak: float, levels: np.ndarray) -> np.ndarray:
        s = np.unique(np.r_[[np.linspace(a, b, 2049) for a, b in zip(self.edges[:-1], self.edges[1:])]])
        g = np.abs(peak * self.M1(s))[:, None] - levels[None, :]
        i, j = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)
        lo, hi, lev = s[i], s[i + 1], levels[j]
        t = np.linspace(0.0, 1.0, 65)
        for _ in range(9):  # each round resamples the brackets at 65 points: 64^9 below round-off
            pts = lo[:, None] + (hi - lo)[:, None] * t[None, :]
            gp = np.abs(peak * self.M1(pts.ravel())).reshape(pts.shape) - lev[:, None]
            k = np.argmax(np.sign(gp[:, :-1]) * np.sign(gp[:, 1:]) <= 0, axis=1)
            r = np.arange(len(lo))
            lo, hi = pts[r, k], pts[r, k + 1]
        return 0.5 * (lo + hi)

    def quadratures(self, x, lam: float, peak: float):
        """(K1, K2, err) at the sorted points x: ∫_0^x kappa and ∫_0^x s kappa (adaptive Gauss-Legendre on pieces
        between the load edges, the kinks and x) and the estimate of their error."""
        xs = np.asarray(x, float)
        edges = np.unique(np.r_[self.edges, self._kinks(peak), np.clip(xs, 0.0, self.L)])
        a, b, owner = edges[:-1], edges[1:], np.arange(len(edges) - 1)
        I1, I2 = np.zeros(len(a)), np.zeros(len(a))
        err1, err2 = np.zeros(len(a)), np.zeros(len(a))
        scale = None
        for _ in range(LEVELS):
            h, mid = 0.5 * (b - a), 0.5 * (b + a)
            s = [mid[:, None] + h[:, None] * gx[None, :] for gx, _ in GAUSS]
            k = self.curvature(np.concatenate([v.ravel() for v in s]), lam, peak)
            ks = np.split(k, [s[0].size])
            est = [
                (
                    h * (kv.reshape(sv.shape) @ gw),
                    h * ((kv.reshape(sv.shape) * sv) @ gw),
                    h * (np.abs(kv.reshape(sv.shape)) @ gw),
                )
                for kv, sv, (_, gw) in zip(ks, s, GAUSS)
            ]
            (c1, c2, ak), (f1, f2, _) = est
            if scale is None:
                scale = max(ak.sum(), 1e-300)
            d1, d2 = np.abs(f1 - c1), np.abs(f2 - c2)
            ok = (d1 <= QUAD_TOL * scale) & (d2 <= QUAD_TOL * scale * self.L)
            np.add.at(I1, owner[ok], f1[ok])
            np.add.at(I2, owner[ok], f2[ok])
            np.add.at(err1, owner[ok], d1[ok])
            np.add.at(err2, owner[ok], d2[ok])
            if ok.all():
                break
            m = 0.5 * (a + b)
            a, b, owner = (
                np.r_[a[~ok], m[~ok]],
                np.r_[m[~ok], b[~ok]],
                np.r_[owner[~ok], owner[~ok]],
            )
        else:
            raise SolveError("exact-eb: the curvature's quadrature did not converge (a moment too close to Mp)")
        K1, K2 = np.r_[0.0, np.cumsum(I1)], np.r_[0.0, np.cumsum(I2)]
        idx = np.searchsorted(edges, xs)
        return K1[idx], K2[idx], float(err1.sum() * self.L + err2.sum())

    def deflection(self, x, lam: float, peak: float):
        """(w, rotation, err): w = c0 + c1 x + x K1 - K2 with the supports' two kinematic conditions."""
        xs = np.asarray(x, float)
        order = np.argsort(xs)
        pts = np.unique(np.r_[xs, 0.0, self.L])
        K1, K2, err = self.quadratures(pts, lam, peak)
        L = self.L
        rows, rhs = [], []
        for end, kind in ((0, self.kinds[0]), (-1, self.kinds[1])):
            X = pts[end]
            if HELD[kind][1]:
                rows.append([1.0, X / L])
                rhs.append(-(X * K1[end] - K2[end]))
            if HELD[kind][2]:
                rows.append([0.0, 1.0 / L])
                rhs.append(-K1[end])
        c0, c1 = np.linalg.solve(np.array(rows), np.array(rhs))
        c1 /= L
        j = np.searchsorted(pts, xs[order])
        w = np.empty_like(xs)
        rot = np.empty_like(xs)
        w[order] = c0 + c1 * pts[j] + pts[j] * K1[j] - K2[j]
        rot[order] = c1 + K1[j]
        return w, rot, err

    # -- state ------------------------------------------------------------------------------------------------------
    def section_state(self, x, lam: float, peak: float) -> dict:
        """The plastic zone (length where the section ever yielded), the health (the area fraction of each section
        never yielded) and the largest curvature, at the factor ``lam`` after ``peak``."""
        if not self.sy:
            return {"plastic_zone": 0.0, "health": np.ones(len(x)), "max_curvature": 0.0}
        xs = np.asarray(x, float)
        c, yc = self.prof.extreme_fibre, self.prof.centroid
        kp = np.abs(self.curvature(xs, peak, peak))
        with np.errstate(divide="ignore"):
            ye = np.where(kp > 0, np.minimum(self.sy / self.E / kp, c), c)
        core = self.prof.integral(0, yc - ye, yc + ye)
        cuts = np.unique(np.r_[self.edges, self._crossings(peak, np.array([self.yield_moment]))])
        mid = 0.5 * (cuts[:-1] + cuts[1:])
        zone = float(np.sum(np.diff(cuts)[np.abs(peak * self.M1(mid)) > self.yield_moment]))
        k = np.abs(self.curvature(np.r_[xs, self.peak_x], lam, peak))
        return {"plastic_zone": zone, "health": core / self.prof.area, "max_curvature": float(k.max())}

    def reverse_yield(self, lam: float, peak: float) -> bool:
        """True when unloading from ``peak`` to ``lam`` takes an extreme fibre past -sigma_y (or +sigma_y)."""
        if not self.sy:
            return False
        c = self.prof.extreme_fibre
        kp = self.curvature([self.peak_x], peak, peak)[0]
        dk = (lam - peak) * self.peak_M1 / self.EI
        s = self.E * np.clip(kp * c, -self.sy / self.E, self.sy / self.E) + self.E * c * dk
        return abs(s) > self.sy * (1 + TIE)


def solve_path(scene: Scene, x: np.ndarray):
    """(path, info, beam, last): one JSON-ready entry per step of the scene's ``[loading]`` (default [0, 1] in 10
    steps), the path's info (collapse and first-failure factors, stop line), the beam and the last (lam, peak)."""
    beam = PlasticBeam(scene)
    factors = (scene.loading or Loading()).path()
    M1 = beam.peak_M1
    lam_c = beam.plastic_moment / abs(M1) if M1 else np.inf
    lam_f = beam.failure_moment / abs(M1) if M1 else np.inf
    R1 = beam.unit.reactions()
    steps, stop, peak, err = [], None, 0.0, 0.0
    for lam in factors:
        new_peak = lam if abs(lam) >= abs(peak) and (peak == 0.0 or np.sign(lam) == np.sign(peak)) else peak
        if abs(new_peak) >= lam_f * (1 - TIE):
            stop = (
                f"the path stops at load factor {steps[-1]['factor'] if steps else 0.0:.6g}: the first fibre reaches "
                f"failure_strain at load factor {lam_f:.9g} at x = {beam.peak_x:.6g} (the hinge); exact-eb does not "
                "follow a broken section; the steps so far are kept"
            )
            break
        if abs(new_peak) >= lam_c * (1 - TIE):
            stop = (
                f"the path stops at load factor {steps[-1]['factor'] if steps else 0.0:.6g}: the collapse load factor "
                f"is {lam_c:.9g} (Mp = {beam.plastic_moment:.6g} at x = {beam.peak_x:.6g}: a hinge, a mechanism); the "
                "steps so far are kept"
            )
            break
        if new_peak == peak and beam.reverse_yield(lam, peak):
            stop = (
                f"the path stops at load factor {steps[-1]['factor']:.6g}: the step to {lam:.6g} yields fibres in "
                "reverse, which exact-eb does not follow (elastic unloading only): use fem-eb; the steps so far are "
                "kept"
            )
            break
        peak = new_peak
        w, _, e = beam.deflection(x, lam, peak)
        err = max(err, e)
        state = beam.section_state(x, lam, peak)
        steps.append(
            {
                "factor": float(lam),
                "w": w,
                "reactions": {k: float(lam * v) for k, v in R1.items()},
                "plastic_zone": state["plastic_zone"],
                "max_curvature": state["max_curvature"],
                "health": state["health"],
            }
        )
    if len(steps) < 2 and stop is not None:  # no step past the first corner: a failure, as in the other path models
        raise SolveError(f"exact-eb: {stop.replace('; the steps so far are kept', '')}")
    info = {
        "load_path": {
            "factors": [float(v) for v in (scene.loading or Loading()).factors],
            "steps": len(steps),
            "completed": stop is None,
            "last_factor": steps[-1]["factor"],
            "collapse_factor": _finite(lam_c),
            "first_failure_factor": _finite(lam_f),
            "peak_position": beam.peak_x,
            "first_yield_factor": _finite(beam.yield_moment / abs(M1) if M1 else np.inf),
            "quadrature_error": err,
        },
        "reactions": steps[-1]["reactions"],
    }
    if stop is not None:
        info.setdefault("warnings", []).append(stop)
    return steps, info, beam, (steps[-1]["factor"], peak)


def _finite(v: float) -> float | None:
    """v, or None (JSON null) when the law is absent (inf)."""
    return float(v) if np.isfinite(v) else None
