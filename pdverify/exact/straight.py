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

import numpy as np

from ..core.errors import SolveError
from ..core.scene import Distributed, PointForce, PointMoment, Scene, Spring, straight_mechanism
from ..numerics.error_bound import ENTRY_ROUNDING
from ..numerics.loads import bends_nothing


def _active(x: np.ndarray, a: float, length: float) -> np.ndarray:
    """A load at a acts on x > a; at the right end x = L every load with a <= L acts."""
    return (x > a) | ((x >= a) & (x >= length))


def _share(x: np.ndarray, a: float, length: float) -> np.ndarray:
    """The share of a point load at a in the fields at x: 1 past it, 0 before it, 1/2 within 64 eps L of it inside the
    span (the mean of its two sides, so that neither the rounding of a scaled scene's positions, a few eps, nor a
    mirror image decides a side); the end points their support's side (x = 0: no load acts yet; x = L: every load
    acts)."""
    tol = 64 * np.finfo(float).eps * length
    share = np.where(x > a + tol, 1.0, np.where(x < a - tol, 0.0, 0.5))
    share[x <= tol] = 0.0
    share[x >= length - tol] = 1.0
    return share


def particular(scene: Scene, x: np.ndarray, loads=None) -> tuple[np.ndarray, ...]:
    """(Mp, Mp', I1, I2, Mv) at x: the loads' particular moment (of ``loads``, default the scene's), its slope,
    two integrals from 0, and Mv = ∫Mp' (Mp without the steps of point moments)."""
    x = np.asarray(x, dtype=float)
    L = scene.length
    Mp, dMp, I1, I2 = (np.zeros_like(x) for _ in range(4))
    steps = np.zeros_like(x)
    for load in scene.loads if loads is None else loads:
        if isinstance(load, PointForce):
            a, P = load.position, load.value
            share = _share(x, a, L)
            t = np.where(share > 0, x - a, 0.0)
            Mp += P * t
            dMp += P * share
            I1 += P * t**2 / 2
            I2 += P * t**3 / 6
        elif isinstance(load, PointMoment):
            a, C = load.position, load.value
            share = _share(x, a, L)
            t = np.where(share > 0, x - a, 0.0)
            Mp += -C * share
            steps += -C * share
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


def _basis(scene: Scene, load, x: np.ndarray) -> np.ndarray:
    """(5, len(x)): M, V, I1 = ∫M, I2 = ∫∫M and Vi = ∫V (M without the steps of point moments) from 0, of
    one load (a scene load, or a unit reaction at an inner support) alone."""
    return np.stack(particular(scene, x, [load]))


def _condition_row(lin: dict, i: int, field: str, extra: dict, factor: float, col, divisor: float = 1.0):
    """(row, right-hand side) of boundary condition ``i``: ``field`` plus ``extra``'s coefficients times other fields,
    times ``factor``, plus the unknown ``col`` (a spring's reaction) where given; all divided by ``divisor`` (1: the
    condition as written, bit for bit)."""
    A, p = lin[field]
    f = factor / divisor
    row, r = f * A[i], -(f * p[i])
    for other, coef in extra.items():
        row += (f * coef) * lin[other][0][i]
        r -= (f * coef) * lin[other][1][i]
    if col is not None:
        row[col] += 1.0 / divisor
    return row, r


class StraightSolution:
    """The exact solution of a straight scene: end supports, springs, supports inside the span and segments of
    their own section and material. Call :meth:`fields` at any x.

    The moment is M = c0 + c1 x + Mp(x) + Σ R_i (x - a_i)+ - Σ C_i H(x - a_i): the loads' particular moment and
    the unknown force R_i and moment C_i of each inner support (force +z, moment counter-clockwise on the beam).
    On each segment [a_s, b_s] (EI_s, kGA_s) the rotation and deflection follow by integrating the moment piece by
    piece: phi = c2 + ∫ M / EI, w = c3 + ∫ phi - ∫ V / kGA (Euler–Bernoulli: no last term). The conditions of the
    ends and of each inner support give the unknowns (c0, c1, c2, c3, the R_i and C_i): one small dense system,
    scaled by the length and row by row so its rank says whether the supports hold the beam at any size."""

    def __init__(self, scene: Scene, shear: bool):
        self.scene, self.shear = scene, shear
        L = scene.length
        self.pieces = [(a, b, mat.E * sec.I, sec.k * mat.G * sec.A) for a, b, sec, mat in scene.pieces()]
        inner = scene.supports.inner
        self.forces = [s for s in inner if s.holds_deflection]
        self.moments = [s for s in inner if s.holds_rotation]
        units = [PointForce(type="point_force", position=s.position, value=1.0) for s in self.forces]
        units += [PointMoment(type="point_moment", position=s.position, value=1.0) for s in self.moments]
        self.units = units
        self.c = self._solve(L)

    # -- the fields as functions of the unknowns -----------------------------------------------------------------
    def _moment_basis(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(B, p): (5, n_moment_unknowns, len(x)) and (5, len(x)) of M, V, I1, I2, Vi for c0, c1 and the inner
        reactions (B) and for the scene's loads (p)."""
        one, zero = np.ones_like(x), np.zeros_like(x)
        cols = [np.stack([one, zero, x, x**2 / 2, zero]), np.stack([x, one, x**2 / 2, x**3 / 6, x])]
        cols += [_basis(self.scene, u, x) for u in self.units]
        p = np.stack(particular(self.scene, x)) if self.scene.loads else np.zeros((5, len(x)))
        return np.stack(cols, axis=1), p

    def _integrated(self, F, x: np.ndarray, size: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(Phi, W): ∫₀^x M / EI and ∫₀^x (∫ M / EI) - ∫₀^x V / kGA of moment functions F = (M, V, I1, I2, Vi)
        evaluated at the segments' ends and at x (F: callable x -> (5, ..., len(x))). ``size``: instead, the sums of
        the magnitudes of the terms they add and subtract, whose rounding they carry (a segment's increments are
        differences of the antiderivatives from 0 at its ends: on a segment short beside its position they cancel)."""
        d = (lambda u, v: np.abs(u) + np.abs(v)) if size else (lambda u, v: u - v)
        ends = np.array([a for a, _, _, _ in self.pieces] + [self.pieces[-1][1]])
        Fe = F(ends)  # (5, ..., pieces + 1): F at every segment's ends, once
        Phi = 0.0
        W = 0.0
        Phi_a = 0.0 * Fe[2][..., 0]  # ∫₀^a M / EI at the current segment's start
        for i, (a, b, EI, kGA) in enumerate(self.pieces):
            y = np.clip(x, a, b)
            Fy = F(y)
            Fa = Fe[..., i : i + 1]
            dy = y - a
            Phi = Phi + d(Fy[2], Fa[2]) / EI
            W = W + (np.abs(Phi_a[..., None]) if size else Phi_a[..., None]) * dy + d(d(Fy[3], Fa[3]), Fa[2] * dy) / EI
            if self.shear:  # minus the shear's part (its size: plus)
                W = W + (1.0 if size else -1.0) * d(Fy[4], Fa[4]) / kGA
            Phi_a = Phi_a + d(Fe[2][..., i + 1], Fe[2][..., i]) / EI
        return Phi, W

    def _linear(self, x: np.ndarray, size: bool = False) -> dict:
        """{field: (A, p)}: field(x) = A @ u + p for u = (c0, c1, reactions..., c2, c3); ``size``: the magnitudes of
        the terms that make each entry (:meth:`_integrated`), for the rounding."""
        x = np.asarray(x, float)
        k = 2 + len(self.units)

        def moment_part(y):
            B, p = self._moment_basis(y)
            return np.concatenate([B, p[:, None, :]], axis=1)  # (5, k + 1, len(y)): the unknowns' and the loads'

        Phi, W = self._integrated(moment_part, x, size)  # (k + 1, len(x)) each
        F = moment_part(x)
        n = len(x)
        out = {}
        for name, rows, c2, c3 in (
            ("M", F[0], 0.0, 0.0),
            ("V", F[1], 0.0, 0.0),
            ("rotation", Phi, 1.0, 0.0),
            ("w", W, x, 1.0),
        ):
            A = np.zeros((n, k + 2))
            A[:, :k] = np.asarray(rows)[:k].T
            A[:, k] = c2
            A[:, k + 1] = c3
            out[name] = (A, np.asarray(rows)[k] * np.ones(n))
        return out

    # -- the conditions --------------------------------------------------------------------------------------------
    def _solve(self, L: float) -> np.ndarray:
        sup = self.scene.supports
        conds = []  # (field, position, {other field: coefficient}, factor, column + 1 or 0): one row each

        def cond(field: str, at: float, extra: dict | None = None, factor: float = 1.0, col: int | None = None):
            conds.append((field, at, extra or {}, factor, col))

        k = 2 + len(self.units)
        for side, at in (("left", 0.0), ("right", L)):
            end = getattr(sup, side)
            sign = 1.0 if side == "left" else -1.0  # the support's force on the beam: V(0) at the left, -V(L) right
            if isinstance(end, Spring):
                if end.stiffness:
                    cond("V", at, {"w": sign * end.stiffness})  # force + k w = 0
                else:
                    cond("V", at)
                if end.rotational_stiffness:
                    cond("M", at, {"rotation": -sign * end.rotational_stiffness})  # moment + k_r phi = 0
                else:
                    cond("M", at)
                continue
            held = {
                "clamped": ("w", "rotation"),
                "pinned": ("w", "M"),
                "roller": ("w", "M"),
                "free": ("M", "V"),
                "guided": ("rotation", "V"),
            }[end]
            for field in held:
                cond(field, at)
        for j, s in enumerate(self.forces):  # w(a) = 0, or R + k w(a) = 0
            if s.type == "spring":
                cond("w", s.position, factor=s.stiffness, col=2 + j)
            else:
                cond("w", s.position)
        for j, s in enumerate(self.moments):  # phi(a) = 0, or C + k_r phi(a) = 0
            if s.type == "spring":
                cond("rotation", s.position, factor=s.rotational_stiffness, col=2 + len(self.forces) + j)
            else:
                cond("rotation", s.position)
        lin = self._linear(np.array([c[1] for c in conds]))  # every condition's point in one evaluation
        rows, rhs = [], []
        for i, (field, _, extra, factor, col) in enumerate(conds):
            row, r = _condition_row(lin, i, field, extra, factor, col)
            if not (np.all(np.isfinite(row)) and np.isfinite(r)):  # a spring so stiff that its terms overflow: the
                # same condition divided by its largest coefficient (k_r phi + M = 0 as phi + M / k_r = 0)
                row, r = _condition_row(
                    lin, i, field, extra, factor, col, max([abs(factor), *map(abs, extra.values())])
                )
            rows.append(row)
            rhs.append(r)
        A, b = np.array(rows), np.array(rhs)
        # every unknown in deflection units (x by L, moments by EI0 L^2, forces by EI0 L ...) and each condition by
        # its largest coefficient: the system is then well conditioned at any size, from a micrometre to kilometres,
        # and its rank says whether the supports hold the beam
        EI0 = self.pieces[0][2]
        scale = np.ones(k + 2)
        scale[0] = EI0 / L**2  # c0, a moment
        scale[1] = EI0 / L**3  # c1, a force
        for j in range(len(self.forces)):
            scale[2 + j] = EI0 / L**3
        for j in range(len(self.moments)):
            scale[2 + len(self.forces) + j] = EI0 / L**2
        scale[k] = 1.0 / L  # c2, a rotation
        As = A * scale
        row = np.abs(As).max(axis=1)
        As, b = As / row[:, None], b / row
        if np.linalg.matrix_rank(As, tol=1e-10) < As.shape[1]:
            if straight_mechanism(self.scene) is None:  # the supports hold it: their conditions are near-dependent
                many = len(sup.inner)
                raise SolveError(
                    f"supports = {sup.kind('left')}-{sup.kind('right')}: the supports' conditions are dependent at "
                    f"working precision (the boundary system's rank test at 1e-10, {As.shape[0]} conditions): a spring "
                    "far softer than the beam, or supports that nearly coincide"
                    + (f", or the {many} supports.inner too many for the closed form" if many else "")
                    + "; stiffen the spring, or give the supports as one (fem-eb and fem-timoshenko solve such scenes)"
                )
            raise SolveError(
                f"supports = {sup.kind('left')}-{sup.kind('right')}: the beam is a mechanism; "
                "fix the deflection at one end and the rotation somewhere"
            )
        self.cond = float(np.linalg.cond(As, 1))
        return np.linalg.solve(As, b) * scale

    # -- results ---------------------------------------------------------------------------------------------------
    def fields(self, x) -> dict[str, np.ndarray]:
        lin = self._linear(np.asarray(x, float))
        return {name: A @ self.c + p for name, (A, p) in lin.items() if name in ("w", "rotation", "M", "V")}

    def rounding(self, x) -> float:
        """Round-off bound of w and the rotation at the points x, each relative to its largest value there: a field
        is the sum A c + p of its terms (the unknowns' and the loads', each itself a sum over the segments of
        differences of antiderivatives: :meth:`_integrated`), which cancel where a load or support sits
        close to an end relative to the length (a cantilever's tip under a force at a: terms of P L^3 / EI for a
        result of P a^2 L / EI), so each rounds by about (ENTRY_ROUNDING + cond) eps of the sum of the terms'
        magnitudes (Higham, *Accuracy and Stability*, 2nd ed., ch. 4: a sum's error bound; cond: the scaled
        boundary system's 1-norm condition number, which carries c's own rounding). A scene whose loads all act on
        supports that hold them has w = 0: its bound is then relative to the terms' size."""
        lin = self._linear(np.asarray(x, float))  # a single piece starts at 0, where every antiderivative is 0
        mag = lin if len(self.pieces) == 1 else self._linear(np.asarray(x, float), size=True)
        c = (ENTRY_ROUNDING + self.cond) * np.finfo(float).eps
        if bends_nothing(self.scene):  # every load on a support that holds it: w = 0, its terms' rounding is all
            return float(f"{c:.3g}")  # there is (relative to the terms' size)
        out = 0.0
        for name in ("w", "rotation"):
            A, p = lin[name]
            Am, pm = mag[name]
            top = float(np.abs(A @ self.c + p).max())
            size = float((np.abs(Am) @ np.abs(self.c) + np.abs(pm)).max())
            if top > 0.0:
                out = max(out, c * size / top)
        return float(f"{out:.3g}")

    def reactions(self) -> dict[str, float]:
        """Support reactions (force +z, moment counter-clockwise on the beam): at the ends, and of each support
        inside the span in the order of ``supports.inner`` (``force_inner_<i>``, ``moment_inner_<i>``)."""
        L = self.scene.length
        start = self.fields(np.array([0.0]))
        end = self.fields(np.array([L]))
        out = {
            "force_left": float(start["V"][0]),
            "moment_left": float(-start["M"][0]),
            "force_right": float(-end["V"][0]),
            "moment_right": float(end["M"][0]),
        }
        inner = self.scene.supports.inner
        for j, s in enumerate(self.forces):
            out[f"force_inner_{inner.index(s)}"] = float(self.c[2 + j])
        for j, s in enumerate(self.moments):
            out[f"moment_inner_{inner.index(s)}"] = float(self.c[2 + len(self.forces) + j])
        return out


def solve_straight(scene: Scene, shear: bool) -> StraightSolution:
    """The exact Euler–Bernoulli (``shear = False``) or Timoshenko solution of a straight scene."""
    return StraightSolution(scene, shear)
