"""The shear force V and the bending moment M of variant ``energy`` at the points, from its intervals' shear forces
(Moyer & Miraglia 2014, Eq. 33: V = -kGA ψ; :mod:`.energy`).

The beam's w rows say kGA (ψ̄_{i+½} - ψ̄_{i-½}) = -(the load at point i): the intervals' V̄ = -kGA ψ̄ step by each
point's load, as the exact V steps by the loads between the intervals' middles. For the distributed loads, whose
points take their cells' integrals, V̄ is then the exact V at the interval's middle, which :func:`interval_averages`
turns into V's average over the interval by the loads on its two halves (the middle's value differs from the average
by O(Δ q) where a load's edge falls inside the interval: a shear off by a few per cent that did not converge); a point
force split linearly between its two points gives the average already. The value at a point follows from the loads
on the interval before it,

    V(x_i) = V̄_{i-½} + (1/Δ) ∫_{x_{i-1}}^{x_i} (s - x_{i-1}) dV(s),    dV = q ds + point forces (reactions included),

or on the one after it, V̄_{i+½} - (1/Δ) ∫_{x_i}^{x_{i+1}} (x_{i+1} - s) dV(s): the mean of the two at an inner point (a
mirror scene gives the mirror shear), the one interval an end point has,

with exact-timoshenko's convention at a load on a point (a load at a acts on x > a; at x = L on x = L too). The mean of
the two intervals around a point would be wrong by O(Δ q') where q jumps and by up to half a point force next to
one between two points. The moment steps by Δ V̄ over each interval (∫ V exactly) and by -C at a couple, in the
interval that holds it; its constant is the energy's bond moment's (:func:`.energy.moment_field`).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import Distributed, PointForce, PointMoment, Scene

_GAUSS = np.polynomial.legendre.leggauss(8)


COMPONENT = {"transverse": "value", "axial": "axial", "torque": "torque"}


def interval_moments(scene: Scene, x: np.ndarray, component: str = "transverse") -> tuple[np.ndarray, np.ndarray]:
    """(A, B) per interval [x_i, x_{i+1}] of the distributed loads' line load q (``component``: transverse, axial or
    torque): A = ∫ q ds and B = ∫ (s - x_i) q ds (8-point Gauss on the part of each interval inside each load's
    span)."""
    lo, hi = x[:-1], x[1:]
    A, B = np.zeros(len(lo)), np.zeros(len(lo))
    g, gw = _GAUSS
    for load in scene.loads:
        v = getattr(load, COMPONENT[component], 0.0) if isinstance(load, Distributed) else 0.0
        if v == 0.0:
            continue
        a, b = scene.span(load)
        s0, s1 = np.clip(lo, a, b), np.clip(hi, a, b)
        half = (s1 - s0) / 2
        s = (s0 + s1)[:, None] / 2 + half[:, None] * g[None, :]
        q = v * scene.load_shape(load, s)
        A += (q * gw).sum(1) * half
        B += (q * (s - lo[:, None]) * gw).sum(1) * half
    return A, B


def interval_averages(
    mid: np.ndarray, x: np.ndarray, scene: Scene, component: str = "transverse", sign: float = 1.0
) -> np.ndarray:
    """The intervals' averages of V from their values at the intervals' middles ``mid`` (module docstring: the points'
    equations step V̄ by the cell integrals of the distributed loads, whose cells end at the middles):
    (1/Δ) ∫ V = V(m) - (1/Δ) ∫_{x_i}^{m} (s - x_i) dV(s) + (1/Δ) ∫_{m}^{x_{i+1}} (x_{i+1} - s) dV(s), dV = ``sign`` q ds
    (the distributed loads only: a point force's linear split already gives the average)."""
    dx = x[1] - x[0]
    halves = np.empty(2 * len(x) - 1)
    halves[0::2], halves[1::2] = x, (x[:-1] + x[1:]) / 2
    A, B = interval_moments(scene, halves, component)  # per half interval
    return mid + sign * (-B[0::2] + 0.5 * dx * A[1::2] - B[1::2]) / dx


def point_loads(scene: Scene, extra=()) -> tuple[list, list]:
    """([(position, force)], [(position, couple)]) of the scene's point loads and ``extra`` ones (the supports'
    reactions: (position, force, couple))."""
    forces = [(ld.position, ld.value) for ld in scene.loads if isinstance(ld, PointForce) and ld.value]
    couples = [(ld.position, ld.value) for ld in scene.loads if isinstance(ld, PointMoment) and ld.value]
    for at, f, c in extra:
        if f:
            forces.append((at, f))
        if c:
            couples.append((at, c))
    return forces, couples


def shear_at_points(
    Vbar: np.ndarray, x: np.ndarray, scene: Scene, forces: list, component: str = "transverse", sign: float = 1.0
) -> np.ndarray:
    """V at the points from the intervals' V̄ (module docstring): at an inner point the mean of the values from the
    interval before it and from the one after it, V̄_{i+½} - (1/Δ) ∫_{x_i}^{x_{i+1}} (x_{i+1} - s) dV(s) (so that a
    mirror scene gives the mirror shear), at an end from its own interval; a rod's N (``component`` axial) or a bar's
    T (torque) with ``sign`` = -1: N' = -p."""
    dx = x[1] - x[0]
    L = x[-1]
    n = len(x)
    A, B = interval_moments(scene, x, component)
    A, B = sign * A, sign * B
    forces = [(at, sign * P) for at, P in forces]
    before, after = np.empty(n), np.empty(n)
    before[1:] = Vbar + B / dx  # from the interval before each point
    after[:-1] = Vbar - (dx * A - B) / dx  # from the interval after it
    tol = 1e-9 * dx
    for at, P in forces:
        i = int(np.clip(np.ceil((at - x[0]) / dx - 1e-9), 1, n - 1))  # the interval (x_{i-1}, x_i] holding it
        if at < x[i] - tol or (i == n - 1 and at >= L - tol):  # on x_i: acts beyond it, except at x = L
            before[i] += P * (at - x[i - 1]) / dx
        k = int(np.clip(np.floor((at - x[0]) / dx + 1e-9), 0, n - 2))  # the interval [x_k, x_{k+1}) holding it
        on_inner_point = k > 0 and abs(at - x[k]) <= tol  # the value after x_k is past it already (x_0: the support's
        if at < L - tol and not on_inner_point:  # side); at x = L it acts on x = L, beyond every interval after a point
            after[k] -= P * (x[k + 1] - at) / dx
    V = before
    V[0] = after[0]
    V[1:-1] = 0.5 * (before[1:-1] + after[1:-1])
    return V


def moment_steps(Vbar: np.ndarray, x: np.ndarray, couples: list) -> np.ndarray:
    """M at the points up to a constant: M_0 = 0, M_{i+1} = M_i + Δ V̄_{i+½} - the couples in [x_i, x_{i+1})
    (at x = 0 beyond the end point, at x = L in the last interval: the ends carry their supports' side); a couple on
    a point inside the span half in the step before it and half in the one after, so that the point carries the mean
    of its two sides (docs/contract.md)."""
    dx = x[1] - x[0]
    steps = dx * np.asarray(Vbar, float).copy()
    tol = 1e-9 * dx
    for at, C in couples:
        i = int(np.clip(np.floor((at - x[0]) / dx + 1e-9), 0, len(x) - 2))
        if 0 < i and abs(at - x[i]) <= tol:
            steps[i - 1] -= 0.5 * C
            steps[i] -= 0.5 * C
        else:
            steps[i] -= C
    return np.concatenate([[0.0], np.cumsum(steps)])


def stepped(rows_force: np.ndarray, local: np.ndarray) -> np.ndarray:
    """The intervals' resultant from the forces each point's equation balances (``rows_force``, per point, in force
    units): stepped interval by interval, which is the discrete equilibrium whatever the model's sums reach, its
    constant the median of its difference from ``local`` (the intervals' resultant from the local strain: right away
    from loads and supports, where the median looks)."""
    steps = np.cumsum(rows_force[:-1])
    return steps + np.median(local - steps)
