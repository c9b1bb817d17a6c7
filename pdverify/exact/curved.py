"""Model ``exact-curved-cantilever``: any statically determinate curved (or straight) cantilever, exact.

docs/design/formulas.md §4 (reconstructed): clamped at one end, free at the other; point forces (local or global
frame), point moments and distributed loads (uniform or sine, on any span, local or global frame).
Statics gives the internal force F(s) = N t + Q n and moment M(s) without solving anything::

    right end free:  F(s) = Σ_{a_i > s} P_i + ∫_s^L p,
                     M(s) = Σ_{a_i > s} [C_i + (r(a_i) - r(s)) × P_i] + ∫_s^L (r(σ) - r(s)) × p(σ) dσ
    left end free:   the same over [0, s) with a minus sign

(pd-curved's sign rules: F jumps by -P at a force, M by -C at a counter-clockwise couple; at a load
inside the beam the left limit is returned). Then ε = N/EA, γ = Q/kGA, χ = M/EI and, from the clamp
(left: s = 0)::

    φ(s) = ∫_0^s χ,    u(s) = ∫_0^s [ε t + γ n + χ e_z × (r(s) - r(σ))] dσ

(the rotation term ∫ φ n dσ integrated by parts, so every field is a single integral). Integrals: on
panels split at every load discontinuity, 24 Gauss–Legendre nodes each; the cumulative integrals at
the nodes by the spectral (Legendre) integration matrix, and at any s by barycentric interpolation in
its panel, so every field is round-off accurate on the exact axis geometry. For the semicircle the
same fields follow in closed form (sympy): tests/papers/curved/test_pd_curved.py checks this module against it and
against Clapeyron's theorem. ``evaluate`` gives u_t (``u``), u_n (``w``), φ (``rotation``), N, Q, M,
ux, uy at any s.
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.polynomial import legendre as leg

from ..core.contract import POINTS, Model
from ..core.errors import SolveError
from ..core.geometry import geometry, mechanism_message
from ..core.result import Result, Timer
from ..core.scene import HELD, Distributed, PointForce, PointMoment, Scene
from ..numerics.error_bound import ENTRY_ROUNDING, record_bound
from ..numerics.loads import axis_support_side, onto_end_points
from ..theory.curved_beam import coupling_warning, thick_ring_warning


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _ez(a: np.ndarray) -> np.ndarray:
    """e_z × a for planar vectors."""
    return np.stack([-a[..., 1], a[..., 0]], axis=-1)


def integration_matrix(x: np.ndarray) -> np.ndarray:
    """S with (S f)_i = ∫_{-1}^{x_i} p(t) dt, p the polynomial interpolating f at the nodes x."""
    n = len(x)
    Vinv = np.linalg.inv(leg.legvander(x, n - 1))
    lint = np.column_stack([leg.legint(np.eye(n)[k], lbnd=-1) for k in range(n)])  # (n + 1, n)
    return leg.legvander(x, n) @ lint @ Vinv


@functools.lru_cache(maxsize=8)
def _panel_rule(order: int) -> tuple[np.ndarray, np.ndarray]:
    """A panel's nodes (its ends and ``order`` Gauss-Legendre nodes) and their integration matrix, made once per
    order (every solution object of every scene uses the same)."""
    gx, _ = leg.leggauss(order)
    nodes = np.r_[-1.0, gx, 1.0]
    S = integration_matrix(nodes)
    nodes.flags.writeable = S.flags.writeable = False
    return nodes, S


def barycentric(nodes: np.ndarray, values: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """Interpolate values[k, j, ...] (panel k, node j) at reference points xi[k] in [-1, 1]."""
    w = 1.0 / np.prod(nodes[:, None] - nodes[None, :] + np.eye(len(nodes)), axis=1)
    d = xi[:, None] - nodes[None, :]
    hit = np.abs(d) < 1e-14
    d = np.where(hit, 1.0, d)
    c = np.where(hit.any(axis=1, keepdims=True), hit.astype(float), w[None, :] / d)
    c = c / c.sum(axis=1, keepdims=True)
    return np.einsum("kj,kj...->k...", c, values)


class Cantilever:
    """The statically determinate solution of one scene (clamped–free or free–clamped)."""

    ORDER = 24

    def __init__(self, scene: Scene, panels: int = 32):
        self.scene = scene
        self.geo = geometry(scene)
        L = scene.length
        self.free_right = scene.supports.right == "free"
        self.points = []  # (position, global force, couple)
        cuts = []
        for load in scene.loads:
            if isinstance(load, Distributed):
                cuts += list(scene.span(load))
                continue
            a = float(load.position)
            cuts.append(a)
            t, n = self.geo.frame(np.array([a]))
            if isinstance(load, PointMoment):
                self.points.append((a, np.zeros(2), load.value))
            elif load.frame == "global":
                self.points.append((a, np.array([load.axial, load.value]), 0.0))
            else:
                self.points.append((a, load.axial * t[0] + load.value * n[0], 0.0))
        edges = np.unique(np.concatenate([np.linspace(0, L, panels + 1), np.clip(cuts, 0, L)]))
        edges = edges[np.concatenate([[True], np.diff(edges) > 1e-12 * L])]
        edges[-1] = L
        self.edges = edges
        self.nodes, self.S = _panel_rule(self.ORDER)
        lo, hi = edges[:-1, None], edges[1:, None]
        self.half = (hi - lo)[:, 0] / 2
        sig = (lo + hi) / 2 + (hi - lo) / 2 * self.nodes[None, :]
        sig[:, 0], sig[:, -1] = edges[:-1], edges[1:]
        mid = ((lo + hi) / 2)[:, 0]
        # distributed loads: G1 = ∫_0^σ p, G2 = ∫_0^σ r × p at every node
        r = self.geo.position(sig)
        p = self._line_load(sig, np.broadcast_to(mid[:, None], sig.shape))
        self.G = self._cumulative(np.concatenate([p, _cross(r, p)[..., None]], axis=-1))  # (panels, nodes, 3)
        self.GL = self.G[-1, -1]
        N, Q, M, t, n, r = self.resultants(
            sig.ravel(), G=self.G.reshape(-1, 3), panel=np.broadcast_to(mid[:, None], sig.shape).ravel()
        )
        EA, kGA, EI = scene.EA, scene.kGA, scene.EI
        eps, gam, chi = N / EA, Q / kGA, M / EI
        f = np.column_stack([eps[:, None] * t + gam[:, None] * n, chi, chi[:, None] * r])
        self.I = self._cumulative(f.reshape(sig.shape + (5,)))  # (panels, nodes, 5)
        # round-off of u = I_01 + e_z x (I_2 r - I_34) (or the same of ∫_s^L): the quadrature's chains of sums, an
        # entry of ORDER nodes then up to one per panel, each of terms at most ∫ |f| (Higham, *Accuracy and
        # Stability*, 2nd ed., ch. 4), then the combination's own rounding
        size = np.abs(self._cumulative(np.abs(f).reshape(sig.shape + (5,)))[-1, -1])
        reach = float(np.hypot(*r.T).max())
        terms = size[0] + size[1] + size[2] * reach + size[3] + size[4]
        self.rounding = (ENTRY_ROUNDING + self.ORDER + len(edges)) * np.finfo(float).eps * terms
        self.sizes_at = edges  # where a state's size is read for the bound (its panels' ends: the sizes, not the sums)
        ends, re = self.I[:, -1], self.geo.position(edges[1:])  # the integrals at each panel's end
        if self.free_right:
            u = ends[:, 0:2] + _ez(ends[:, 2:3] * re - ends[:, 3:5])
        else:
            D = self.I[-1, -1][None, :] - ends
            u = -D[:, 0:2] + _ez(D[:, 3:5] - D[:, 2:3] * re)
        self.size = float(np.hypot(*u.T).max())  # its largest displacement at the panels' ends

    def _line_load(self, s: np.ndarray, inside: np.ndarray) -> np.ndarray:
        """Global line load vector at s (``inside``: a point of the same panel, to decide the spans)."""
        out = np.zeros(s.shape + (2,))
        t, n = self.geo.frame(s)
        for load in self.scene.loads:
            if not isinstance(load, Distributed):
                continue
            a, b = self.scene.span(load)
            on = (inside >= a) & (inside <= b)
            f = on * self.scene.load_shape(load, s)
            if load.frame == "global":
                out += f[..., None] * np.array([load.axial, load.value])
            else:
                out += f[..., None] * (load.axial * t + load.value * n)
        return out

    def _cumulative(self, f: np.ndarray) -> np.ndarray:
        """∫_0^σ f at every node of every panel, f given at the nodes (panels, nodes, c)."""
        within = np.einsum("ij,kjc->kic", self.S, f) * self.half[:, None, None]
        starts = np.concatenate([np.zeros((1, f.shape[-1])), np.cumsum(within[:, -1], axis=0)[:-1]])
        return within + starts[:, None, :]

    def _at(self, table: np.ndarray, s: np.ndarray) -> np.ndarray:
        j = np.clip(np.searchsorted(self.edges, s, side="right") - 1, 0, len(self.edges) - 2)
        xi = np.clip((s - self.edges[j]) / self.half[j] - 1.0, -1.0, 1.0)
        return barycentric(self.nodes, table[j], xi)

    def resultants(self, s: np.ndarray, G: np.ndarray | None = None, panel: np.ndarray | None = None):
        """(N, Q, M, t, n, r) at s: at a load inside the beam the left limit, at the ends the internal
        value (a load at the clamp goes into the reaction). ``panel``: a point inside the panel of each s
        (quadrature nodes on a panel end take the limit from inside the panel)."""
        s = np.asarray(s, float)
        r = self.geo.position(s)
        t, n = self.geo.frame(s)
        G = self._at(self.G, s) if G is None else G
        if self.free_right:
            dG = self.GL[None, :] - G  # ∫_s^L
            F = dG[:, :2].copy()
            M = dG[:, 2] - _cross(r, dG[:, :2])
        else:
            F = -G[:, :2]
            M = -(G[:, 2] - _cross(r, G[:, :2]))
        for a, P, C in self.points:
            ra = self.geo.position(np.array([a]))[0]
            if panel is not None:
                on = (a > panel) if self.free_right else (a < panel)
            else:
                on = ((a >= s) & (a > 0)) if self.free_right else ((a < s) | (a <= 0))
                # a point inside the span on the load: the mean of its two sides (as exact-eb's)
                tol = 64 * np.finfo(float).eps * self.geo.length
                on = np.where((np.abs(s - a) <= tol) & (s > tol) & (s < self.geo.length - tol), 0.5, on * 1.0)
            sg = 1.0 if self.free_right else -1.0
            F += sg * on[:, None] * P[None, :]
            M += sg * on * (C + _cross(ra[None, :] - r, np.broadcast_to(P, r.shape)))
        N = np.sum(F * t, axis=-1)
        Q = np.sum(F * n, axis=-1)
        return N, Q, M, t, n, r

    def fields(self, s) -> dict[str, np.ndarray]:
        s = np.atleast_1d(np.asarray(s, float))
        N, Q, M, t, n, r = self.resultants(s)
        I = self._at(self.I, s)
        if self.free_right:  # clamped at s = 0
            phi = I[:, 2]
            u = I[:, 0:2] + _ez(I[:, 2:3] * r - I[:, 3:5])
        else:  # clamped at s = L: u(s) = -∫_s^L (ε t + γ n) + ∫_s^L χ e_z × (r(τ) - r(s)) dτ
            D = self.I[-1, -1][None, :] - I
            phi = -D[:, 2]
            u = -D[:, 0:2] + _ez(D[:, 3:5] - D[:, 2:3] * r)
        ut = np.sum(u * t, axis=-1)
        un = np.sum(u * n, axis=-1)
        return {"u": ut, "w": un, "rotation": phi, "N": N, "Q": Q, "M": M, "ux": u[:, 0], "uy": u[:, 1]}


_KINEMATIC = HELD  # per slot (t, n, φ): held (kinematic) or loaded (resultant), as in pd-curved


class Indeterminate:
    """Any support pair (force method): the clamped–free solution of the loads plus the six load-free
    states (rigid translations a_x, a_y, rotation θ0 about r(0); unit end force F_x, F_y and couple C at
    s = L of the cantilever), their amplitudes fixed by the three conditions at each end (kinematic:
    u_t, u_n, φ = 0; resultant: N, Q, M equal to the end load, minus at s = 0)."""

    def __init__(self, scene: Scene):

        L = scene.length
        base = {"supports": scene.supports.model_copy(update={"left": "clamped", "right": "free"})}
        self.scene = scene
        self.geo = geometry(scene)
        self.part = Cantilever(scene.model_copy(update=base))
        units = [
            PointForce(type="point_force", position=L, value=0.0, axial=1.0, frame="global"),
            PointForce(type="point_force", position=L, value=1.0, axial=0.0, frame="global"),
            PointMoment(type="point_moment", position=L, value=1.0),
        ]
        self.units = [Cantilever(scene.model_copy(update=dict(base, loads=[u]))) for u in units]
        ends = [[], []]
        for load in scene.loads:
            # an end load is one the cantilever part takes at the end itself (Cantilever.resultants: a <= 0 on
            # the left, a >= L on the right); a load a hair inside is the part's, not the end condition's too
            if not isinstance(load, Distributed) and load.position <= 0.0:
                ends[0].append(load)
            elif not isinstance(load, Distributed) and load.position >= L:
                ends[1].append(load)
        r0 = self.geo.position(np.array([0.0]))[0]
        self.r0 = r0
        rows, rhs = [], []
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            s = np.array([0.0 if side == 0 else L])
            t, n = self.geo.frame(s)
            F = np.zeros(2)
            C = 0.0
            for load in ends[side]:
                if isinstance(load, PointMoment):
                    C += load.value
                elif load.frame == "global":
                    F += np.array([load.axial, load.value])
                else:
                    F += load.axial * t[0] + load.value * n[0]
            target = (-1.0 if side == 0 else 1.0) * np.array([F @ t[0], F @ n[0], C])
            basis = self._states(s)
            for c, kin in enumerate(_KINEMATIC[sup]):
                key = ("u", "w", "rotation")[c] if kin else ("N", "Q", "M")[c]
                rows.append([b[key][0] for b in basis[1:]])
                rhs.append((0.0 if kin else target[c]) - basis[0][key][0])
        # the conditions mix lengths, rotations, forces and moments, the amplitudes translations, a rotation, forces
        # and a couple: each row divided by its largest coefficient, then each column, so the system (and its
        # condition number, the fields' round-off is cond eps) is the same in any units
        A, rhs = np.array(rows), np.array(rhs)
        if not (np.all(np.isfinite(A)) and np.all(np.isfinite(rhs))):  # a radius or length near the float range's end
            raise SolveError(
                "exact-curved: the end conditions overflow a float64 at this size; give the scene in another length "
                "unit (e.g. km for m)"
            )
        row = np.abs(A).max(axis=1)
        col = np.abs(A / np.where(row > 0, row, 1.0)[:, None]).max(axis=0)
        if not (row.all() and col.all()):
            raise SolveError("exact-curved: the supports leave a rigid-body motion (a mechanism)")
        A = A / row[:, None] / col[None, :]
        self.cond = float(f"{np.linalg.cond(A):.3g}")
        try:
            self.c = np.linalg.solve(A, rhs / row) / col
        except np.linalg.LinAlgError:
            raise SolveError("exact-curved: the supports leave a rigid-body motion (a mechanism)") from None
        # round-off of the sum of the states: each cantilever state's own (times its amplitude), and the amplitudes'
        # from the conditions' entries, each a value rounded once (ENTRY_ROUNDING): Skeel's componentwise bound
        # |A^-1| (|A| |a| + |b|) c eps of the scaled system (Higham, *Accuracy and Stability*, eq. 7.31)
        self.sizes_at = self.part.sizes_at
        arm = float(np.hypot(*(self.geo.position(self.sizes_at) - r0[None, :]).T).max())  # the rigid rotation's
        size = np.array([1.0, 1.0, arm] + [u.size for u in self.units])
        own = np.array([0.0, 0.0, np.finfo(float).eps * arm] + [u.rounding for u in self.units])  # rigid: exact
        a = self.c * col  # the scaled system's solution
        entries = ENTRY_ROUNDING * np.finfo(float).eps
        da = np.abs(np.linalg.inv(A)) @ (np.abs(A) @ np.abs(a) + np.abs(rhs / row)) * entries
        self.rounding = self.part.rounding + float(np.sum(np.abs(self.c) * own + da / col * size))

    def _states(self, s: np.ndarray) -> list[dict]:
        """Fields of the particular solution and of the six load-free states at s."""
        t, n = self.geo.frame(s)
        r = self.geo.position(s)
        zero = np.zeros(len(s))
        out = [self.part.fields(s)]
        for v, th in ((np.array([1.0, 0.0]), 0.0), (np.array([0.0, 1.0]), 0.0), (np.zeros(2), 1.0)):
            u = v[None, :] + th * _ez(r - self.r0[None, :])
            out.append(
                {
                    "ux": u[:, 0],
                    "uy": u[:, 1],
                    "u": np.sum(u * t, axis=-1),
                    "w": np.sum(u * n, axis=-1),
                    "rotation": zero + th,
                    "N": zero,
                    "Q": zero,
                    "M": zero,
                }
            )
        out += [c.fields(s) for c in self.units]
        return out

    def fields(self, s) -> dict[str, np.ndarray]:
        s = np.atleast_1d(np.asarray(s, float))
        states = self._states(s)
        return {k: states[0][k] + sum(c * st[k] for c, st in zip(self.c, states[1:])) for k in states[0]}


def relative_rounding(sol, fields: dict) -> float:
    """The solution's round-off bound (its ``rounding``: an absolute displacement) relative to the largest
    displacement of ``fields`` (3 digits); relative to the rounding itself, eps, where nothing moves."""
    top = float(np.hypot(fields["ux"], fields["uy"]).max())
    if top == 0.0:
        return 0.0 if sol.rounding == 0.0 else float("inf")
    return float(f"{sol.rounding / top:.3g}")


class ExactCurved(Model):
    name = "exact-curved"
    title = "exact curved Timoshenko–Ehrenfest beam, any supports (statics + quadrature + force method)"
    source = (
        "docs/design/formulas.md §4 (statically determinate cantilever) extended by the force method to any "
        "support pair"
    )
    options = (POINTS,)
    curved = True
    axial = True
    theory = "timoshenko"
    reference = True

    solver = Indeterminate  # the exact solution object: .fields(s)

    def check(self, scene: Scene) -> list[str]:
        """The scene checks plus the rigid-body test on straight axes (e.g. two rollers slide along x)."""

        out = super().check(scene)
        why = mechanism_message(scene)
        return out + ([why] if why is not None else [])

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def evaluator(self, scene: Scene, params: dict):
        """The solution object built once, its fields at any x (the end points on their supports' side; a point
        load a few eps from an end is on it, :func:`~pdverify.numerics.loads.onto_end_points`), with its round-off
        bound (:func:`relative_rounding`) as ``error_bound``."""
        scene = onto_end_points(scene)
        sol = self.solver(scene)

        def fields(x):
            return axis_support_side(scene, x, sol.fields(x))

        fields.error_bound = relative_rounding(sol, sol.fields(sol.sizes_at))
        return fields

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            s = np.linspace(0.0, scene.length, params["points"])
            scene = onto_end_points(scene)
            sol = self.solver(scene)
            f = axis_support_side(scene, s, sol.fields(s))  # the solution's ends hold the beam's side
        info = {"cond": getattr(sol, "cond", 1.0)}  # a cantilever solves nothing: statics and quadrature only
        record_bound(info, relative_rounding(sol, f))
        for flag in (thick_ring_warning(scene), coupling_warning(scene, s, f["N"], f["M"])):
            if flag:
                info.setdefault("warnings", []).append(flag)
        return self.new_result(
            scene,
            params,
            s,
            f["w"],
            rotation=f["rotation"],
            fields={k: f[k] for k in ("u", "N", "Q", "M", "ux", "uy")},
            dofs=0,
            timings=timer.timings,
            info=info,
        )


class ExactCurvedCantilever(ExactCurved):
    name = "exact-curved-cantilever"
    title = "exact curved Timoshenko–Ehrenfest cantilever (statics + quadrature)"
    source = "docs/design/formulas.md §4: statically determinate curved cantilever (closed form for the semicircle)"
    solver = Cantilever

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = (scene.supports.kind("left"), scene.supports.kind("right"))
        if sorted(sup) != ["clamped", "free"]:
            out.append(
                f"supports = {sup[0]}-{sup[1]}: model {self.name} solves cantilevers only (one end clamped, the other "
                "free); use pd-curved or fem-plane-stress"
            )
        return out


MODELS = [ExactCurvedCantilever(), ExactCurved()]
