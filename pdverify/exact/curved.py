"""Model ``exact-curved-cantilever``: any statically determinate curved (or straight) cantilever, exact.

Design note §4 (RECONSTRUCTED): clamped at one end, free at the other, point forces and moments
anywhere (scene ``point_force`` in the local or global frame, ``point_moment``). Statics gives the
internal force F(s) = N t + Q n and moment M(s) without solving anything::

    right end free:  F(s) =  Σ_{a_i > s} P_i,   M(s) =  Σ_{a_i > s} [C_i + (r(a_i) - r(s)) × P_i]
    left end free:   F(s) = -Σ_{a_i < s} P_i,   M(s) = -Σ_{a_i < s} [C_i + (r(a_i) - r(s)) × P_i]

(the sign rules of pd-curved: F jumps by -P at a force, M by -C at a counter-clockwise couple). Then
ε = N/EA, γ = Q/kGA, χ = M/EI and, from the clamped end (left: s = 0),

    φ(s) = ∫_0^s χ,    u(s) = ∫_0^s [ε t + γ n + χ e_z × (r(s) - r(σ))] dσ

(the rotation term ∫ φ n dσ integrated by parts, so every field is a single integral of a smooth
function). The integrals are composite Gauss–Legendre (24 nodes per panel, panels split at the loads)
on the exact axis geometry: round-off accurate. For the semicircle the same fields follow in closed
form from sympy; tests/test_pd_curved.py checks this module against that closed form.
``evaluate`` gives u_t (``u``), u_n (``w``), φ (``rotation``), N, Q, M, ux, uy at any s.
"""

from __future__ import annotations

import numpy as np

from ..geometry import geometry
from ..registry import POINTS, Model
from ..result import Result, Timer
from ..scene import PointForce, PointMoment, Scene


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _ez(a: np.ndarray) -> np.ndarray:
    """e_z × a for planar vectors."""
    return np.stack([-a[..., 1], a[..., 0]], axis=-1)


class Cantilever:
    """The statically determinate solution of one scene (point loads, clamped–free or free–clamped)."""

    def __init__(self, scene: Scene, panels: int = 32, order: int = 24):
        self.scene = scene
        self.geo = geometry(scene)
        L = scene.length
        self.free_right = scene.supports.right == "free"
        loads = []
        for load in scene.loads:
            a = float(load.position)
            t, n = self.geo.frame(np.array([a]))
            if isinstance(load, PointMoment):
                loads.append((a, np.zeros(2), load.value))
            elif load.frame == "global":
                loads.append((a, np.array([load.axial, load.value]), 0.0))
            else:
                loads.append((a, load.axial * t[0] + load.value * n[0], 0.0))
        self.loads = loads
        edges = np.unique(np.concatenate([np.linspace(0, L, panels + 1),
                                          [a for a, _, _ in loads if 0 < a < L]]))
        self.edges = edges
        gx, gw = np.polynomial.legendre.leggauss(order)
        self.gx, self.gw = gx, gw
        lo, hi = edges[:-1, None], edges[1:, None]
        sig = (lo + hi) / 2 + (hi - lo) / 2 * gx[None, :]
        f = self._integrands(sig.ravel())
        w = ((hi - lo) / 2 * gw[None, :]).ravel()
        # cumulative integrals over whole panels, from s = 0
        per_panel = (f * w[:, None]).reshape(len(edges) - 1, order, -1).sum(axis=1)
        self.cum = np.vstack([np.zeros((1, f.shape[1])), np.cumsum(per_panel, axis=0)])

    def resultants(self, s: np.ndarray):
        """(N, Q, M, t, n, r) at s: at a load inside the beam the left limit, at the ends the internal
        value (a load at the clamp goes into the reaction)."""
        s = np.asarray(s, float)
        r = self.geo.position(s)
        t, n = self.geo.frame(s)
        F = np.zeros(s.shape + (2,))
        M = np.zeros(s.shape)
        for a, P, C in self.loads:
            ra = self.geo.position(np.array([a]))[0]
            # left limits (pd-curved's convention at a load inside the beam); internal values at the ends
            on = ((a >= s) & (a > 0)) if self.free_right else ((a < s) | (a <= 0))
            sg = 1.0 if self.free_right else -1.0
            F += sg * on[:, None] * P[None, :]
            M += sg * on * (C + _cross(ra[None, :] - r, np.broadcast_to(P, r.shape)))
        N = np.sum(F * t, axis=-1)
        Q = np.sum(F * n, axis=-1)
        return N, Q, M, t, n, r

    def _integrands(self, sig: np.ndarray) -> np.ndarray:
        """columns: (ε t + γ n) x, y; χ; χ r x, y."""
        sc = self.scene
        N, Q, M, t, n, r = self.resultants(sig)
        eps, gam, chi = N / sc.EA, Q / sc.kGA, M / sc.EI
        f1 = eps[:, None] * t + gam[:, None] * n
        return np.column_stack([f1, chi, chi[:, None] * r])

    def integrals(self, s: np.ndarray) -> np.ndarray:
        """∫_0^s of the integrand columns at each s."""
        s = np.asarray(s, float)
        j = np.clip(np.searchsorted(self.edges, s, side="right") - 1, 0, len(self.edges) - 2)
        lo = self.edges[j]
        sig = (lo[:, None] + s[:, None]) / 2 + (s[:, None] - lo[:, None]) / 2 * self.gx[None, :]
        f = self._integrands(sig.ravel()).reshape(len(s), len(self.gx), -1)
        part = np.einsum("nqc,q->nc", f, self.gw) * ((s - lo) / 2)[:, None]
        return self.cum[j] + part

    def fields(self, s) -> dict[str, np.ndarray]:
        s = np.atleast_1d(np.asarray(s, float))
        N, Q, M, t, n, r = self.resultants(s)
        I = self.integrals(s)
        if self.free_right:  # clamped at s = 0
            phi = I[:, 2]
            u = I[:, 0:2] + _ez(I[:, 2:3] * r - I[:, 3:5])
        else:  # clamped at s = L: u(s) = -∫_s^L (ε t + γ n) + ∫_s^L χ e_z × (r(τ) - r(s)) dτ
            IL = self.integrals(np.array([self.scene.length]))[0]
            D = IL[None, :] - I
            phi = -D[:, 2]
            u = -D[:, 0:2] + _ez(D[:, 3:5] - D[:, 2:3] * r)
        ut = np.sum(u * t, axis=-1)
        un = np.sum(u * n, axis=-1)
        return {"u": ut, "w": un, "rotation": phi, "N": N, "Q": Q, "M": M, "ux": u[:, 0], "uy": u[:, 1]}


class ExactCurvedCantilever(Model):
    name = "exact-curved-cantilever"
    title = "exact curved Timoshenko–Ehrenfest cantilever (statics + quadrature)"
    source = "design note §4: statically determinate curved cantilever (closed form for the semicircle)"
    options = (POINTS,)
    curved = True
    axial = True
    theory = "timoshenko"
    reference = True

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = (scene.supports.left, scene.supports.right)
        if sorted(sup) != ["clamped", "free"]:
            out.append(f"supports = {sup}: model {self.name} solves cantilevers only (one end clamped, the other "
                       "free); use pd-curved or fem-plane-stress")
        for i, load in enumerate(scene.loads):
            if not isinstance(load, (PointForce, PointMoment)):
                out.append(f"loads[{i}].type = {load.type!r}: model {self.name} takes point forces and moments only")
        return out

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return Cantilever(scene).fields(x)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            s = np.linspace(0.0, scene.length, params["points"])
            f = Cantilever(scene).fields(s)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=s, w=f["w"],
                      rotation=f["rotation"], fields={k: f[k] for k in ("u", "N", "Q", "M", "ux", "uy")},
                      dofs=0, timings=timer.timings, info={})


MODELS = [ExactCurvedCantilever()]
