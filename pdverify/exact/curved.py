"""Exact references of the curved Timoshenko–Ehrenfest beam (design note §4, RECONSTRUCTED there).

``exact-curved-cantilever``: any statically determinate curved cantilever (clamped at s = 0, free at s = L)
on an arc (or straight) axis, with point forces and moments anywhere and distributed loads (uniform | sine,
span, local | global frame). Statics gives the resultant on the section at s from the loads beyond it::

    F(s) = Σ_{a > s} P_a + ∫_s^L p dσ,   M(s) = Σ_{a > s} (C_a + (r_a - r(s)) × P_a) + ∫_s^L (r(σ) - r(s)) × p dσ

N = F·t, Q = F·n (so (N, Q, M) = (P·t, P·n, Mbar) at a loaded free end, the sign convention of pd-curved),
eps = N/EA, gamma = Q/kGA, phi(s) = ∫_0^s M/EI and the global displacement
u(s) = ∫_0^s (eps t + (gamma + phi) n) dσ; u_t = u·t, u_n = u·n.
Every integral is a composite 16-point Gauss–Legendre rule on >= 32 panels split at the load positions and
span edges (the integrands are smooth on each panel: trigonometric on an arc), so the values are exact to
round-off (tests: the Clapeyron energy balance and the closed-form thin-ring values). For the semicircle
this is the closed-form solution of the design note, evaluated by quadrature instead of by sympy.

``exact-curved-manufactured``: the chosen fields of pdverify/manufactured.py (the quintic example); the
loads that produce them are added by ``pd-curved --manufactured trig``.
"""

from __future__ import annotations

import numpy as np

from ..geometry import geometry
from ..registry import POINTS, Model
from ..result import Result, Timer
from ..scene import Distributed, PointForce, PointMoment, Scene

_GX, _GW = np.polynomial.legendre.leggauss(16)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


class _Cumulative:
    """∫_0^s f for vectorised f (values (m,) or (m, k)), composite Gauss on fixed panels."""

    def __init__(self, breaks: np.ndarray):
        self.a, self.b = breaks[:-1], breaks[1:]

    def __call__(self, f, s: np.ndarray) -> np.ndarray:
        a, b = self.a, self.b
        nodes = (a[:, None] + b[:, None]) / 2 + (b - a)[:, None] / 2 * _GX[None, :]
        k = np.searchsorted(b, s, side="left").clip(0, len(a) - 1)
        lo = a[k]
        part = lo[:, None] + (s - lo)[:, None] * (_GX[None, :] + 1) / 2
        vals = f(np.r_[nodes.ravel(), part.ravel()])
        npn = nodes.size
        vp = vals[:npn].reshape(nodes.shape + vals.shape[1:])
        vq = vals[npn:].reshape(part.shape + vals.shape[1:])
        w_p = ((b - a) / 2)[:, None] * _GW[None, :]
        w_q = ((s - lo) / 2)[:, None] * _GW[None, :]
        panel = np.einsum("pg,pg...->p...", w_p, vp)
        cum = np.concatenate([np.zeros((1,) + panel.shape[1:]), np.cumsum(panel, axis=0)])
        return cum[k] + np.einsum("ng,ng...->n...", w_q, vq)


class CantileverSolution:
    """Fields of a curved cantilever (clamped at s = 0) at any arc lengths."""

    def __init__(self, scene: Scene):
        self.scene = scene
        self.geo = geometry(scene)
        L = scene.length
        tol = 1e-12 * L
        breaks = [np.linspace(0.0, L, 33)]
        self.points = []  # (position, global force (2,), moment)
        self.dist = []
        for load in scene.loads:
            if isinstance(load, Distributed):
                a, b = scene.span(load)
                breaks.append([a, b])
                self.dist.append(load)
            elif isinstance(load, (PointForce, PointMoment)):
                breaks.append([load.position])
                if load.position <= tol:
                    continue  # at the clamp: a reaction
                if isinstance(load, PointForce):
                    t, n = (v[0] for v in self.geo.frame(np.array([load.position])))
                    F = np.array([load.axial, load.value]) if load.frame == "global" else load.axial * t + load.value * n
                    self.points.append((load.position, F, 0.0))
                else:
                    self.points.append((load.position, np.zeros(2), load.value))
        br = np.unique(np.clip(np.concatenate(breaks), 0.0, L))
        br = br[np.r_[True, np.diff(br) > tol]]
        br[-1] = L
        self.cum = _Cumulative(br)
        self.L = L

    def _p(self, s: np.ndarray) -> np.ndarray:
        """Distributed load (global vector per length) at s."""
        out = np.zeros((len(s), 2))
        if not self.dist:
            return out
        t, n = self.geo.frame(s)
        for load in self.dist:
            a, b = self.scene.span(load)
            sh = np.ones_like(s) if load.shape == "uniform" else np.sin(np.pi * s / self.L)
            sh = np.where((s >= a) & (s <= b), sh, 0.0)
            vec = np.array([load.axial, load.value])[None, :] if load.frame == "global" else load.axial * t + load.value * n
            out += sh[:, None] * vec
        return out

    def resultants(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Global force F (n, 2) and moment M (n,) on the section at s from the part beyond it."""
        s = np.asarray(s, float)
        r = self.geo.position(s)
        F = np.zeros((len(s), 2))
        M = np.zeros(len(s))
        for a, P, C in self.points:
            on = (a > s) | (a >= self.L * (1 - 1e-12))
            F += on[:, None] * P
            M += on * (C + _cross(self.geo.position(np.array([a]))[0] - r, P[None, :]))
        if self.dist:
            def g(sig):
                p = self._p(sig)
                return np.column_stack([p, _cross(self.geo.position(sig), p)])

            tot = self.cum(g, np.array([self.L]))[0]
            G = tot[None, :] - self.cum(g, s)
            F += G[:, :2]
            M += G[:, 2] - _cross(r, G[:, :2])
        return F, M

    def fields(self, s) -> dict[str, np.ndarray]:
        sc = self.scene
        s = np.asarray(s, float)
        EA, kGA, EI = sc.EA, sc.kGA, sc.EI

        def phi(sig):
            return self.cum(lambda q: self.resultants(q)[1] / EI, sig)

        def du(sig):
            F, _ = self.resultants(sig)
            t, n = self.geo.frame(sig)
            N, Q = np.einsum("ij,ij->i", F, t), np.einsum("ij,ij->i", F, n)
            return (N / EA)[:, None] * t + (Q / kGA + phi(sig))[:, None] * n

        F, M = self.resultants(s)
        t, n = self.geo.frame(s)
        U = self.cum(du, s)
        return {"w": np.einsum("ij,ij->i", U, n), "u": np.einsum("ij,ij->i", U, t), "rotation": phi(s),
                "ux": U[:, 0], "uy": U[:, 1], "N": np.einsum("ij,ij->i", F, t), "Q": np.einsum("ij,ij->i", F, n), "M": M}


class _ExactCurved(Model):
    options = (POINTS,)
    theory = "timoshenko"
    curved = True
    axial = True
    reference = True

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("assemble"):
            s = np.linspace(0.0, scene.length, params["points"])
        with timer("solve"):
            f = self.evaluate(scene, params, s)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=s, w=f["w"],
                      rotation=f["rotation"], fields={k: v for k, v in f.items() if k not in ("w", "rotation")},
                      dofs=0, timings=timer.timings, info={})


class ExactCurvedCantilever(_ExactCurved):
    name = "exact-curved-cantilever"
    title = "exact curved Timoshenko–Ehrenfest cantilever (statics + quadrature), arc axis"
    source = "design note formulas-bondpair-curved.md §4 (statically determinate curved cantilever)"

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if scene.axis.type != "arc":
            out.append(f"axis.type = {scene.axis.type!r}: {self.name} is written for arc axes; straight beams: "
                       "use exact-timoshenko")
        if (scene.supports.left, scene.supports.right) != ("clamped", "free"):
            out.append(f"supports = {scene.supports.left}-{scene.supports.right}: {self.name} needs left = clamped, "
                       "right = free (statically determinate)")
        out += [f"loads[{i}]: a torque: {self.name} has no twist" for i, l in enumerate(scene.loads)
                if l.type == "point_torque" or getattr(l, "torque", 0.0)]
        return out

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return CantileverSolution(scene).fields(x)


class ExactCurvedManufactured(_ExactCurved):
    name = "exact-curved-manufactured"
    title = "manufactured solution of the curved Timoshenko–Ehrenfest beam (pdverify/manufactured.py)"
    source = "chosen fields; loads by sympy (pd-curved --manufactured trig)"

    def check(self, scene: Scene) -> list[str]:
        out = []
        if scene.axis.type != "polynomial":
            out.append(f"axis.type = {scene.axis.type!r}: the manufactured solution is written for a polynomial axis")
        if (scene.supports.left, scene.supports.right) != ("clamped", "clamped"):
            out.append(f"supports = {scene.supports.left}-{scene.supports.right}: the manufactured fields vanish at "
                       "both ends; use clamped-clamped")
        if scene.loads:
            out.append("loads: the manufactured solution has no scene loads (pd-curved --manufactured trig adds them); "
                       "remove the [[loads]]")
        return out

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        from ..manufactured import fields

        f = fields(scene, x)
        t, n = geometry(scene).frame(np.asarray(x, float))
        U = f["u_t"][:, None] * t + f["u_n"][:, None] * n
        return {"w": f["u_n"], "u": f["u_t"], "rotation": f["phi"], "ux": U[:, 0], "uy": U[:, 1],
                "N": f["N"], "Q": f["Q"], "M": f["M"]}


MODELS = [ExactCurvedCantilever(), ExactCurvedManufactured()]
