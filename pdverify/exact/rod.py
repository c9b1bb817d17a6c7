"""Models ``exact-rod`` and ``exact-torsion``: the closed-form static axial displacement of an elastic rod and
twist of a torsion bar on any straight scene (the static references of ``pd-rod`` and ``pd-torsion``).

Both are one second-order equation, S f'' = -p (rod: f = u, S = EA, p the axial load per length, point forces
``axial``; bar: f = twist, S = GJ, p the torque per length, ``point_torque``). With F(x) the load acting on
[0, x] (a load at a acts on x > a, as in :mod:`.straight`) and G = ∫₀ˣ F, equilibrium of [0, x] gives the
resultant R(x) = R₀ - F(x) (N or T) and S f(x) = S f₀ + R₀ x - G(x). An end that holds the unknown
(``scene.ROD_HELD``) has f = 0, one that does not has R = 0:

* held-held: f₀ = 0, R₀ = G(L)/L;  held-free: f₀ = 0, R₀ = F(L);  free-held: R₀ = 0, S f₀ = G(L).

F and G of the distributed loads are the particular moment's first and second integrals of :mod:`.straight`
(Mp'' = q), so every load shape is integrated analytically: exact to round-off at any x.

Supports inside the span, springs and segments: each support that holds the unknown inside the span (rod: pinned,
clamped; bar: pinned, roller, clamped) and each spring inside (rod: its ``stiffness``; bar: its
``rotational_stiffness``) acts as an unknown point load Q_k at its place, F(x) gaining Q_k H(x - a_k); on the
segments S f' = R is integrated piece by piece, f(x) = f₀ + ∫₀ˣ R/S. The ends' conditions (f = 0 held; R = 0 free;
elastic: R(0) = k f(0), R(L) = -k f(L), R(L) after every load) and each support's (f(a_k) = 0, or Q_k = -k f(a_k))
give f₀, R₀ and the Q_k: one small system, scaled row by row.
"""

from __future__ import annotations

import numpy as np

from ..core.contract import POINTS, Model
from ..core.errors import SolveError
from ..core.result import Result, Timer
from ..core.scene import ROD_HELD, Distributed, PointForce, PointTorque, Scene, Spring
from ..numerics.error_bound import ENTRY_ROUNDING, record_bound
from .beam import bound_grid
from .straight import _distributed_terms, _share

_RIGID = {"axial": ("pinned", "clamped"), "torsion": ("pinned", "roller", "clamped")}
_SPRING = {"axial": "stiffness", "torsion": "rotational_stiffness"}


def load_integrals(scene: Scene, x, kind: str, size: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(F, G) at x: the axial load (``kind = "axial"``) or the torque (``"torsion"``) on [0, x], and its integral;
    ``size``: the sums of the loads' magnitudes instead (what their rounding is relative to)."""
    x = np.asarray(x, dtype=float)
    mag = np.abs if size else (lambda v: v)
    L = scene.length
    F, G = np.zeros_like(x), np.zeros_like(x)
    for load in scene.loads:
        if isinstance(load, Distributed):
            v = load.axial if kind == "axial" else load.torque
            if v != 0.0:
                a, b = scene.span(load)
                g, f = _distributed_terms(load.model_copy(update={"value": v}), a, b, L, x)[:2]
                F, G = F + mag(f), G + mag(g)
            continue
        if kind == "axial" and isinstance(load, PointForce):
            v = load.axial
        elif kind == "torsion" and isinstance(load, PointTorque):
            v = load.value
        else:
            continue
        share = _share(x, load.position, L)
        F += mag(v * share)
        G += mag(np.where(share > 0, v * (x - load.position), 0.0))
    return F, G


class ExactRod(Model):
    """The exact static rod (``theory = "axial"``) or torsion bar (``"torsion"``); see the module docstring."""

    options = (POINTS,)
    source = "closed-form integration of the rod / torsion-bar equation (textbook)"
    reference = True
    bending = False
    springs = True
    inner_supports = True
    segments = True

    def __init__(self, theory: str):
        axial = theory == "axial"
        self.name = "exact-rod" if axial else "exact-torsion"
        self.title = "exact elastic rod (axial displacement)" if axial else "exact torsion bar (twist)"
        self.theory = theory
        self.axial, self.torsion = axial, not axial
        self.measures, self.resultant = ("u", "N") if axial else ("twist", "T")
        self.load_types = frozenset({"point_force", "distributed"} if axial else {"point_torque", "distributed"})

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = scene.supports
        held = [s in ROD_HELD[self.theory] for s in (sup.left, sup.right) if isinstance(s, str)]
        springs = [end_spring(scene, side, self.theory) for side in ("left", "right")]
        if not any(held) and not any(springs) and not holds(scene, self.theory):
            what = "axial displacement" if self.theory == "axial" else "twist"
            out.append(
                f"supports = {sup.kind('left')}-{sup.kind('right')}: neither end holds the {what}, nor does a support "
                f"inside the span or a spring, so the bar is a mechanism; make one end "
                f"{' or '.join(ROD_HELD[self.theory])}"
            )
        return out

    def stiffness(self, scene: Scene) -> float:
        return scene.EA if self.theory == "axial" else scene.material.G * scene.section.J

    def evaluator(self, scene: Scene, params: dict):
        """x -> {measures: f, resultant: R}, the constants f₀, R₀ (and the supports' Q_k) found once (module
        docstring); its ``error_bound`` (:meth:`rounding`) for a study's reference rows."""
        fields = self._evaluator(scene)
        fields.error_bound = self.rounding(scene, fields)
        return fields

    def _evaluator(self, scene: Scene):
        if scene.supports.simple and scene.uniform:
            L, S = scene.length, self.stiffness(scene)
            held = [s in ROD_HELD[self.theory] for s in (scene.supports.left, scene.supports.right)]
            FL, GL = (float(v[0]) for v in load_integrals(scene, [L], self.theory))
            f0, R0 = (0.0, GL / L) if all(held) else (0.0, FL) if held[0] else (GL / S, 0.0)

            def fields(x):
                F, G = load_integrals(scene, x, self.theory)
                return {self.measures: f0 + (R0 * np.asarray(x, float) - G) / S, self.resultant: R0 - F}

            def size(x):
                return (
                    abs(f0) + (np.abs(R0 * np.asarray(x, float)) + load_integrals(scene, x, self.theory, True)[1]) / S
                )

            fields.reactions = {"left": -R0, "right": R0 - FL}
            fields.size, fields.cond = size, 1.0
            return fields
        return _general(scene, self.theory, self.measures, self.resultant, self.stiffness(scene))

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def rounding(self, scene: Scene, fields) -> float:
        """Round-off bound of the unknown (u or the twist) relative to its largest value, over :func:`bound_grid`:
        each value is a sum of terms (the constants' and the loads' integrals, on segments differences of them),
        which rounds by about (ENTRY_ROUNDING + cond) eps of the sum of the terms' magnitudes (Higham, *Accuracy
        and Stability*, 2nd ed., ch. 4; cond: the scaled constants' system's 1-norm condition number, 1 where the
        constants are explicit). Relative to the terms' size where nothing moves."""
        x = bound_grid(scene)
        c = (ENTRY_ROUNDING + fields.cond) * np.finfo(float).eps
        top = float(np.abs(fields(x)[self.measures]).max())
        return float(f"{c * float(fields.size(x).max()) / top:.3g}") if top > 0.0 else float(f"{c:.3g}")

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            x = np.linspace(0.0, scene.length, params["points"])
            ev = self.evaluator(scene, params)
            f = ev(x)
        key = "axial" if self.theory == "axial" else "torque"
        # the supports' reactions on the bar (+x, or right-handed about +x): -R(0) at the left, R(L) at the right
        info = {"reactions": {f"{key}_{k}": float(v) for k, v in ev.reactions.items()}}
        record_bound(info, ev.error_bound)
        return self.new_result(scene, params, x, np.zeros_like(x), fields=f, dofs=2, timings=timer.timings, info=info)


def end_spring(scene: Scene, side: str, theory: str) -> float:
    """The stiffness of an elastic end on the unknown (0 for a named support or a spring that does not hold it)."""
    end = getattr(scene.supports, side)
    return float(getattr(end, _SPRING[theory])) if isinstance(end, Spring) else 0.0


def holds(scene: Scene, theory: str) -> list[tuple[str, float, float | None]]:
    """(label, position, stiffness or None for rigid) of the inner supports that hold the unknown."""
    out = []
    for i, s in enumerate(scene.supports.inner):
        if s.type in _RIGID[theory]:
            out.append((f"inner_{i}", s.position, None))
        elif s.type == "spring" and getattr(s, _SPRING[theory]):
            out.append((f"inner_{i}", s.position, float(getattr(s, _SPRING[theory]))))
    return out


def _pieces(scene: Scene, theory: str) -> list[tuple[float, float, float]]:
    out = []
    for a, b, sec, mat in scene.pieces():
        out.append((a, b, mat.E * sec.A if theory == "axial" else mat.G * (sec.J or np.nan)))
    return out


def _general(scene: Scene, theory: str, measures: str, resultant: str, S0: float):
    """The evaluator of a bar with segments, springs or supports inside the span (module docstring)."""
    L = scene.length
    hs = holds(scene, theory)
    pieces = _pieces(scene, theory)
    nq = len(hs)

    def parts(x, size: bool = False):
        """(f, R) at x as (len(x), 2 + nq) coefficient rows for (f0, R0, Q...) and the loads' (len(x),) part;
        ``size``: f's terms' magnitudes (each segment's increment a difference of two integrals from 0)."""
        x = np.asarray(x, float)
        mag = np.abs if size else (lambda v: v)
        F, G = load_integrals(scene, x, theory)
        Rc = np.zeros((len(x), 2 + nq))
        Rc[:, 1] = 1.0
        Rp = -F
        Ic = np.zeros((len(x), 2 + nq))  # ∫₀ˣ R / S
        Ip = np.zeros(len(x))
        for k, (_, at, _) in enumerate(hs):
            Rc[:, 2 + k] = -_share(x, at, L)
        for a, b, S in pieces:
            y = np.clip(x, a, b)
            Fa, Ga = load_integrals(scene, np.full(len(x), a), theory, size)
            Fy, Gy = load_integrals(scene, y, theory, size)
            Ic[:, 1] += (mag(y) + mag(a)) / S if size else (y - a) / S
            Ip += (Gy + Ga) / S if size else -(Gy - Ga) / S
            for k, (_, at, _) in enumerate(hs):
                ya, aa = np.maximum(y - at, 0.0), np.maximum(a - at, 0.0)
                Ic[:, 2 + k] += (ya + aa) / S if size else -(ya - aa) / S
        fc = Ic.copy()
        fc[:, 0] = 1.0
        return fc, Ip, Rc, Rp

    rows, rhs = [], []
    sup = scene.supports
    for side, at in (("left", 0.0), ("right", L)):
        end = getattr(sup, side)
        fc, fp, Rc, Rp = parts(np.array([at]))
        k = end_spring(scene, side, theory)
        if isinstance(end, str) and end in ROD_HELD[theory]:
            rows.append(fc[0] * S0 / L), rhs.append(-fp[0] * S0 / L)
        else:  # free, or elastic: the end's resultant is the spring's force, R(0) = k f(0), R(L) = -k f(L)
            sign = -1.0 if side == "left" else 1.0
            rows.append(Rc[0] + sign * k * fc[0]), rhs.append(-Rp[0] - sign * k * fp[0])
    for k, (_, at, stiff) in enumerate(hs):
        fc, fp, _, _ = parts(np.array([at]))
        if stiff is None:
            rows.append(fc[0] * S0 / L), rhs.append(-fp[0] * S0 / L)
        else:  # Q + k f(a) = 0
            row = fc[0] * stiff
            row[2 + k] += 1.0
            rows.append(row), rhs.append(-fp[0] * stiff)
    A, b = np.array(rows), np.array(rhs)
    scale = np.ones(2 + nq)
    scale[0] = L * 1.0 / S0  # f0 in units of a force's stretch
    As = A * scale
    norm = np.abs(As).max(axis=1)
    As, b = As / norm[:, None], b / norm
    if np.linalg.matrix_rank(As, tol=1e-10) < As.shape[1]:
        raise SolveError(f"supports = {sup.kind('left')}-{sup.kind('right')}: the bar is a mechanism along its axis")
    c = np.linalg.solve(As, b) * scale

    def fields(x):
        fc, fp, Rc, Rp = parts(x)
        return {measures: fc @ c + fp, resultant: Rc @ c + Rp}

    def size(x):
        fc, fp, _, _ = parts(x, size=True)
        return np.abs(fc) @ np.abs(c) + fp

    fields.size, fields.cond = size, float(np.linalg.cond(As, 1))

    R_end = fields(np.array([0.0, L]))[resultant]
    out = {"left": -float(c[1]), "right": float(R_end[1])}  # zero at a free end
    for k, (label, _, _) in enumerate(hs):
        out[label] = float(c[2 + k])
    fields.reactions = out
    return fields


MODELS = [ExactRod("axial"), ExactRod("torsion")]
