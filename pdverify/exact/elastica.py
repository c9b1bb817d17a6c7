"""Model ``exact-elastica``: the inextensible Euler elastica of a cantilever under one end load, exact.

Large rotations of a straight cantilever (clamped at one end, free at the other) loaded at the free end by

* a couple C: a circular arc of radius EI / C (curvature C / EI everywhere);
* a force P of fixed direction normal to the undeformed axis (a dead load): with theta the slope angle,
  EI theta'' + P cos theta = 0, theta(0) = 0, theta'(L) = 0. Substituting 1 + sin theta = 2 k² sin² phi
  (Bisshopp & Drucker 1945, "Large deflection of cantilever beams", Q. Appl. Math. 3, 272-275)::

      sqrt(alpha) = K(k) - F(phi_1, k),  alpha = P L² / EI,  k² = (1 + sin theta_0) / 2,  sin phi_1 = 1 / (k sqrt 2)

  and, with lambda = sqrt(P / EI), the material point at arc length s = (F(phi, k) - F(phi_1, k)) / lambda is at

      x(s) = 2 k (cos phi_1 - cos phi) / lambda,      z(s) = s - 2 (E(phi, k) - E(phi_1, k)) / lambda

  (tip: phi = pi / 2, z/L = 1 - 2 (E(k) - E(phi_1, k)) / sqrt(alpha), x/L = sqrt(2 sin theta_0 / alpha)).
  phi(s) is the Jacobi amplitude am(lambda s + F(phi_1, k), k²).

Fields are given at the material coordinate x (arc length from the left end), as the nonlinear models
report them: w = vertical displacement, u = axial displacement. Shear and stretching are neglected (EB).

``extensible = true``: the extensible elastica (Reissner 1972, "On one-dimensional finite-strain beam
theory", ZAMP 23, 795-804, without shear): the axis stretches by eps = N / EA, N the force along the
tangent, and with s the reference arc length::

    EI theta'' = -(1 + eps) P cos theta,   eps = P sin theta / EA,
    x' = (1 + eps) cos theta,   z' = (1 + eps) sin theta

with theta(0) = 0, theta'(L) = 0, solved by shooting on theta'(0) (no closed form; integration tolerance
1e-12). Under an end couple N = 0 and the circle is unchanged. This is the reference for a model that
carries axial stiffness (pd-bond-pair's nonlinear path): the inextensible tip differs from it by
~ alpha h² / (12 L²) of L for a rectangle.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipj, ellipk, ellipkinc

from ..core.contract import POINTS, Model, Option
from ..core.errors import InputError
from ..core.result import Result, Timer
from ..core.scene import PointForce, PointMoment, Scene


def tip_force_parameters(alpha: float) -> tuple[float, float, float]:
    """(k, phi_1, theta_0) of the cantilever elastica under a dead tip force, alpha = P L² / EI > 0."""

    def kphi(theta0):  # tan phi_1 = 1 / sqrt(sin theta_0): no cancellation near phi_1 = pi / 2
        return np.sqrt((1 + np.sin(theta0)) / 2), np.arctan2(1.0, np.sqrt(np.sin(theta0)))

    def mismatch(theta0):
        k, phi1 = kphi(theta0)
        return ellipk(k * k) - ellipkinc(phi1, k * k) - np.sqrt(alpha)

    theta0 = brentq(mismatch, 0.0, np.pi / 2 - 1e-15, xtol=1e-16, rtol=1e-15, maxiter=200)
    return (*kphi(theta0), theta0)


def tip_force_shape(s: np.ndarray, L: float, P: float, EI: float) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) of the material points at arc lengths ``s`` (clamp at the origin, axis along +x, the force
    of magnitude P > 0 pulling towards +z)."""
    s = np.asarray(s, float)
    lam = np.sqrt(P / EI)
    k, phi1, _ = tip_force_parameters(P * L * L / EI)
    m = k * k
    phi = ellipj(lam * s + ellipkinc(phi1, m), m)[3]
    x = 2 * k * (np.cos(phi1) - np.cos(phi)) / lam
    z = s - 2 * (ellipeinc(phi, m) - ellipeinc(phi1, m)) / lam
    return x, z


def extensible_tip_force_shape(
    s: np.ndarray, L: float, P: float, EI: float, EA: float
) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) of the extensible elastica (module docstring) at reference arc lengths ``s``, force P > 0
    towards +z, by shooting on theta'(0) in units of L (alpha = P L² / EI, stretch number P / EA)."""
    alpha, e = P * L * L / EI, P / EA

    def rhs(_, y):
        th, dth = y[0], y[1]
        st = 1 + e * np.sin(th)
        return [dth, -alpha * st * np.cos(th), st * np.cos(th), st * np.sin(th)]

    def shoot(q, dense=False):
        return solve_ivp(rhs, [0, 1], [0.0, q, 0.0, 0.0], rtol=1e-12, atol=1e-14, dense_output=dense)

    q = brentq(lambda q: shoot(q).y[1, -1], 0.0, alpha * (1 + e) * 1.01, xtol=1e-15, rtol=1e-15, maxiter=200)
    y = shoot(q, dense=True).sol(np.asarray(s, float) / L)
    return L * y[2], L * y[3]


def tip_force_tip(alpha: float) -> tuple[float, float, float]:
    """(x_tip / L, z_tip / L, theta_0) for alpha = P L² / EI (the columns of Bisshopp & Drucker's table)."""
    if alpha == 0:
        return 1.0, 0.0, 0.0
    k, phi1, theta0 = tip_force_parameters(alpha)
    m = k * k
    return np.sqrt(2 * np.sin(theta0) / alpha), 1 - 2 * (ellipe(m) - ellipeinc(phi1, m)) / np.sqrt(alpha), theta0


def tip_moment_shape(s: np.ndarray, C: float, EI: float) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) of the circular arc of curvature C / EI (C > 0 counter-clockwise: bends towards +z)."""
    s = np.asarray(s, float)
    kappa = C / EI
    if kappa == 0:
        return s, 0 * s
    return np.sin(kappa * s) / kappa, (1 - np.cos(kappa * s)) / kappa


class ExactElastica(Model):
    name = "exact-elastica"
    title = "exact large-rotation cantilever (Euler elastica) under one end force or couple"
    source = "Bisshopp & Drucker 1945 (tip force, elliptic integrals); circular arc (tip couple)"
    options = (
        POINTS,
        Option(
            "extensible",
            bool,
            False,
            "include the axial strain N / EA (Reissner's extensible elastica; tip force by shooting)",
        ),
    )
    reference = True
    axial = True

    def reasons(self, scene: Scene) -> list[str]:
        """Why this reference cannot solve ``scene`` (empty when it can)."""
        sup = (scene.supports.kind("left"), scene.supports.kind("right"))  # (a spring end: "spring")
        if not scene.is_straight or sorted(sup) != ["clamped", "free"]:
            return [
                (
                    f"supports = {sup[0]}-{sup[1]}: exact-elastica solves a straight cantilever (clamped-free or "
                    "free-clamped); use exact-eb for other supports"
                )
            ]
        end = 0.0 if sup[0] == "free" else scene.length
        loads = list(scene.loads)
        ok = (
            len(loads) == 1
            and isinstance(loads[0], (PointForce, PointMoment))
            and abs(loads[0].position - end) <= 1e-12 * scene.length
            and getattr(loads[0], "axial", 0.0) == 0.0
        )
        if not ok:
            return [
                (
                    "loads: exact-elastica takes one transverse point force or one point moment at the free end; "
                    "use a numerical reference for other loads"
                )
            ]
        return []

    def check(self, scene: Scene) -> list[str]:
        return super().check(scene) + self.reasons(scene)

    def case(self, scene: Scene) -> tuple[int, object]:
        """(side, load): the free end (0 left, 1 right) and its single end load, or InputError."""
        why = self.reasons(scene)
        if why:
            raise InputError(why[0])
        return (0 if scene.supports.left == "free" else 1), scene.loads[0]

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        side, load = self.case(scene)
        L, EI = scene.length, scene.EI
        s = np.asarray(x, float) if side == 1 else scene.length - np.asarray(x, float)
        if isinstance(load, PointMoment):
            # a ccw couple at the right end bends towards +z; at the left end (mirror image) towards -z
            X, Z = tip_moment_shape(s, load.value if side == 1 else -load.value, EI)
        else:
            if not load.value:
                X, Z = s, 0 * s
            elif params.get("extensible"):
                X, Z = extensible_tip_force_shape(s, L, abs(load.value), EI, scene.EA)
            else:
                X, Z = tip_force_shape(s, L, abs(load.value), EI)
            Z = np.sign(load.value) * Z
        u = X - s
        return {"w": Z, "u": u if side == 1 else -u}

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            x = np.linspace(0.0, scene.length, params["points"])
            f = self.evaluate(scene, params, x)
        return self.new_result(
            scene,
            params,
            x,
            f["w"],
            fields={"u": f["u"]},
            dofs=1,
            timings=timer.timings,
            info={
                "theory": ("extensible (Reissner)" if params.get("extensible") else "inextensible Euler")
                + " elastica (large rotations)"
            },
        )


MODELS = [ExactElastica()]
