"""Exact Euler–Bernoulli and Timoshenko solutions of any straight scene, in closed form.

Sign conventions (z up, x to the right, moments counter-clockwise positive):
bending moment M sagging-positive, shear V = dM/dx, d²M/dx² = q (q the load per length, +z).
A point force P at a makes dM/dx jump by +P; a counter-clockwise point moment C at a makes M jump by -C.

The moment is M(x) = c0 + c1 x + Mp(x), with Mp the Macaulay-type particular solution built from
the loads (zero left of each load). Then

* Euler–Bernoulli:  EI w'' = M, rotation = w';
* Timoshenko:       EI phi' = M, kGA (w' - phi) = -V = -M'  ->  w = ∫phi - M/kGA, rotation = phi;

so ``phi = (c0 x + c1 x²/2 + I1)/EI + c2`` and ``w = (c0 x²/2 + c1 x³/6 + I2)/EI + c2 x + c3 - r (c1 x + Mv)/EI``
with ``r = EI/kGA`` (0 for Euler–Bernoulli), I1 = ∫Mp, I2 = ∫∫Mp and Mv = ∫V the particular moment
without the steps of the point moments (a point moment makes M jump but not the shear force, so the
Timoshenko deflection stays continuous there). Two boundary conditions at each
end (clamped: w = phi = 0; pinned: w = M = 0; free: M = V = 0; guided: phi = V = 0) fix c0..c3.
Everything is integrated analytically: the answer is exact to round-off at any x.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import SolveError
from ..core.scene import Distributed, PointForce, PointMoment, Scene


def _active(x: np.ndarray, a: float, length: float) -> np.ndarray:
    """A load at a acts on x > a; at the right end x = L every load with a <= L acts."""
    return (x > a) | ((x >= a) & (x >= length))


def particular(scene: Scene, x: np.ndarray) -> tuple[np.ndarray, ...]:
    """(Mp, Mp', I1, I2, Mv) at x: the loads' particular moment, its slope, two integrals from 0,
    and Mv = ∫Mp' (Mp without the steps of point moments)."""
    x = np.asarray(x, dtype=float)
    L = scene.length
    Mp, dMp, I1, I2 = (np.zeros_like(x) for _ in range(4))
    steps = np.zeros_like(x)
    for load in scene.loads:
        if isinstance(load, PointForce):
            a, P = load.position, load.value
            on = _active(x, a, L)
            t = np.where(on, x - a, 0.0)
            Mp += P * t
            dMp += np.where(on, P, 0.0)
            I1 += P * t**2 / 2
            I2 += P * t**3 / 6
        elif isinstance(load, PointMoment):
            a, C = load.position, load.value
            on = _active(x, a, L)
            t = np.where(on, x - a, 0.0)
            Mp += np.where(on, -C, 0.0)
            steps += np.where(on, -C, 0.0)
            I1 += -C * t
            I2 += -C * t**2 / 2
        elif isinstance(load, Distributed):
            a, b = scene.span(load)
            terms = _distributed_terms(load, a, b, L, x)
            for acc, term in zip((Mp, dMp, I1, I2), terms):
                acc += term
    return Mp, dMp, I1, I2, Mp - steps


def _inside(load: Distributed, a: float, L: float, x: np.ndarray):
    """(Mp, Mp', I1, I2) of a load starting at a, for a <= x <= its end."""
    t = x - a
    v = load.value
    if load.shape == "uniform":
        return v * t**2 / 2, v * t, v * t**3 / 6, v * t**4 / 24
    k = np.pi / L
    ca, sa = np.cos(k * a), np.sin(k * a)
    # sin(kx) - sin(ka) and cos(kx) - cos(ka) written without cancellation
    ds = 2 * np.cos(k * (x + a) / 2) * np.sin(k * t / 2)
    dc = -2 * np.sin(k * (x + a) / 2) * np.sin(k * t / 2)
    Mp = v * (t * ca / k - ds / k**2)
    dMp = v * (-dc / k)
    I1 = v * (t**2 * ca / (2 * k) + dc / k**3 + t * sa / k**2)
    I2 = v * (t**3 * ca / (6 * k) + ds / k**4 - t * ca / k**3 + t**2 * sa / (2 * k**2))
    return Mp, dMp, I1, I2


def _distributed_terms(load: Distributed, a: float, b: float, L: float, x: np.ndarray):
    on = _active(x, a, L)
    inner = np.clip(x, a, b)
    Mp, dMp, I1, I2 = (np.asarray(v, float) for v in _inside(load, a, L, inner))
    s = np.maximum(x - b, 0.0)  # beyond the span the moment continues linearly
    Mb, dMb, I1b, I2b = Mp, dMp, I1, I2
    Mp_ = Mb + dMb * s
    I1_ = I1b + Mb * s + dMb * s**2 / 2
    I2_ = I2b + I1b * s + Mb * s**2 / 2 + dMb * s**3 / 6
    zero = np.zeros_like(x)
    return tuple(np.where(on, v, zero) for v in (Mp_, dMb, I1_, I2_))


@dataclass
class StraightSolution:
    """Closed-form solution; call :meth:`fields` at any x."""

    scene: Scene
    shear: bool  # True: Timoshenko, False: Euler–Bernoulli
    c: np.ndarray  # c0, c1 (moment), c2, c3 (rotation, deflection constants)

    @property
    def r(self) -> float:
        return self.scene.EI / self.scene.kGA if self.shear else 0.0

    def fields(self, x) -> dict[str, np.ndarray]:
        x = np.asarray(x, dtype=float)
        EI = self.scene.EI
        c0, c1, c2, c3 = self.c
        Mp, dMp, I1, I2, Mv = particular(self.scene, x)
        M = c0 + c1 * x + Mp
        V = c1 + dMp
        phi = (c0 * x + c1 * x**2 / 2 + I1) / EI + c2
        w = (c0 * x**2 / 2 + c1 * x**3 / 6 + I2) / EI + c2 * x + c3 - self.r * (c1 * x + Mv) / EI
        return {"w": w, "rotation": phi, "M": M, "V": V}

    def reactions(self) -> dict[str, float]:
        """Support reactions (force +z, moment counter-clockwise) at the left and right ends."""
        end = self.fields(np.array([self.scene.length]))
        return {
            "force_left": float(self.c[1]),
            "moment_left": float(-self.c[0]),
            "force_right": float(-end["V"][0]),
            "moment_right": float(end["M"][0]),
        }


def _rows(support: str, x: float, scene: Scene, r: float) -> list[tuple[np.ndarray, float]]:
    """Boundary-condition rows a·(c0/EI, c1/EI, c2, c3) = rhs at an end x."""
    EI = scene.EI
    Mp, dMp, I1, I2, Mv = (float(v[0]) for v in particular(scene, np.array([x])))
    w = (np.array([x**2 / 2, x**3 / 6 - r * x, x, 1.0]), -(I2 - r * Mv) / EI)
    phi = (np.array([x, x**2 / 2, 1.0, 0.0]), -I1 / EI)
    M = (np.array([1.0, x, 0.0, 0.0]), -Mp / EI)
    V = (np.array([0.0, 1.0, 0.0, 0.0]), -dMp / EI)
    return {"clamped": [w, phi], "pinned": [w, M], "roller": [w, M], "free": [M, V], "guided": [phi, V]}[support]


def solve_straight(scene: Scene, shear: bool) -> StraightSolution:
    """Integration constants from the four boundary conditions (Euler–Bernoulli or Timoshenko)."""
    r = scene.EI / scene.kGA if shear else 0.0
    rows = _rows(scene.supports.left, 0.0, scene, r) + _rows(scene.supports.right, scene.length, scene, r)
    A = np.array([row for row, _ in rows])
    b = np.array([rhs for _, rhs in rows])
    # scale x by the length (every unknown in deflection units) and each condition by its largest coefficient
    # (w, phi, M and V rows differ by powers of the length): the 4x4 system is then well conditioned at any size,
    # from a micrometre to kilometres, and its rank says whether the supports hold the beam
    L = scene.length
    S = np.diag([L**2, L**3, L, 1.0])  # S a: every unknown in deflection units
    As = A @ np.linalg.inv(S)
    row = np.abs(As).max(axis=1)
    As, b = As / row[:, None], b / row
    if np.linalg.matrix_rank(As, tol=1e-10) < 4:
        raise SolveError(
            f"supports = {scene.supports.left}-{scene.supports.right}: the beam is a mechanism; "
            "fix the deflection at one end and the rotation somewhere"
        )
    a = np.linalg.inv(S) @ np.linalg.solve(As, b)
    c = np.array([a[0] * scene.EI, a[1] * scene.EI, a[2], a[3]])
    return StraightSolution(scene, shear, c)
