"""``pd-eb``'s corrected variant in its mixed form on any straight scene: the band of the two second-order
equations (Diyaroglu et al. Eq. 10a, 11a and 13-15 split in two), its right-hand side for any set of loads, and the
system with the supports inside the span and the springs' reactions as unknowns (:mod:`.scenes`).

Unknowns per position p = -J .. n - 1 + J (J ghosts each side), interleaved: k_p = dx² m_p / EI0 (the moment in
units of a curvature times dx², EI0 the left end's stiffness) and w_p. Rows::

    EI0 f_p k_p - dx² D1 w = (ghost and couple terms)     (the PD curvature, f the flexibility: 1/EI)
    dx² D2 k              = dx⁴ q / EI0                   (equilibrium of the moment)

Free and guided ends write their conditions over the kappa rows (:func:`.operator.mixed_end_rows`), clamped and
pinned ends extrapolate w by Taylor ghosts (:func:`.operator.ghost_map`); a spring end is a free end whose spring's
force and moment are end loads, unknowns of the system.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...core.scene import Distributed, PointForce, PointMoment, Scene, Spring
from ...numerics.band import Band
from ...numerics.loads import body_loads
from .operator import fixed_points, ghost_map, mixed_end_rows, mixed_ghost_coupling, mixed_matrix
from .scenes import (
    couple_kink,
    distributed_kink,
    flexibility,
    force_kink,
    measure_row,
    reaction_unknowns,
    spreads,
    unit_load,
)


@dataclass
class Layout:
    """The mixed form of one scene and grid: n points of spacing dx, curvature weights c (J = len(c)), the
    ends' support names (a spring end "free") and stiffnesses, EI0, the flexibility per position (EI0 f)."""

    scene: Scene
    n: int
    dx: float
    c: np.ndarray
    sups: tuple[str, str]
    EIs: tuple[float, float]
    EI0: float
    f: np.ndarray

    @property
    def J(self) -> int:
        return len(self.c)

    @property
    def st(self) -> np.ndarray:
        return np.concatenate([self.c[::-1], [-2.0 * self.c.sum()], self.c])

    @property
    def npos(self) -> int:
        return self.n + 2 * self.J

    def kdof(self, p) -> np.ndarray:
        return 2 * (np.asarray(p) + self.J)

    def wdof(self, p) -> np.ndarray:
        return 2 * (np.asarray(p) + self.J) + 1

    @property
    def held(self) -> np.ndarray:
        """w of the positions outside the beam and of the held end points."""
        J, n = self.J, self.n
        fixed = fixed_points(self.scene.model_copy(update={"supports": self._named()}), n)
        return np.r_[self.wdof(np.arange(-J, 0)), self.wdof(n + np.arange(J)), self.wdof(np.asarray(fixed, np.int64))]

    def _named(self):
        return self.scene.supports.model_copy(update={"left": self.sups[0], "right": self.sups[1], "inner": []})


def layout(scene: Scene, n: int, dx: float, c: np.ndarray, calibrated: bool = True) -> Layout:
    """The :class:`Layout` of ``scene`` on n points; ``calibrated``: the interfaces' flexibility
    (:func:`.scenes.flexibility`)."""
    sups = tuple("free" if isinstance(s, Spring) else s for s in (scene.supports.left, scene.supports.right))
    st = scene.stiffness_at(np.array([0.0, scene.length]))["EI"]
    EIs = (float(st[0]), float(st[1]))
    J = len(c)
    f = flexibility(scene, np.arange(-J, n + J, dtype=float), dx, c, EIs[0], calibrated)
    return Layout(scene, n, dx, c, sups, EIs, EIs[0], f)


def _end_rows(lay: Layout, q: np.ndarray, scene: Scene | None = None) -> list:
    """The free and guided ends' rows (:func:`mixed_end_rows`) with the k columns in this form's units (k = dx² m /
    EI0 instead of dx² kappa: times EI0 / EI_end)."""
    ends = mixed_end_rows(scene or lay.scene, lay.n, lay.dx, lay.c, q, lay.sups, lay.EIs)
    sides = [i for i, s in enumerate(lay.sups) if s in ("free", "guided")]
    out = []
    for (rows, cols, vals, rr, rv), side in zip(ends, sides):
        vals = np.where(cols % 2 == 0, vals * lay.EI0 / lay.EIs[side], vals)
        out.append((rows, cols, vals, rr, rv))
    return out


def band(lay: Layout) -> Band:
    """The mixed form's band with the held unknowns as unit rows (``Band.fix``)."""
    G = 2 * lay.J
    h2 = lay.dx * lay.dx
    g_rows, g_cols, g_vals, e0, _ = ghost_map(lay.scene, lay.n, lay.dx, G, True, lay.sups, lay.EIs)
    rows, cols, vals, _ = mixed_ghost_coupling(g_rows - G, g_cols, g_vals, e0, lay.n, lay.J, lay.st, h2)
    ends = _end_rows(lay, np.zeros(lay.n))
    M = mixed_matrix(lay.npos, lay.J, lay.st, h2, (rows, cols, vals), ends, diag=lay.f)
    return M.fix(lay.held)


def point_load_terms(scene: Scene, n: int, dx: float, st: np.ndarray, skip: dict) -> tuple[np.ndarray, np.ndarray]:
    """(q, curv): the line load on the n points (every load as the divergence of its particular moment where its
    kinks lie 2J spacings from the ends, :func:`.scenes.force_kink`, :func:`.scenes.couple_kink`,
    :func:`.scenes.distributed_kink`; else distributed loads by cell averages and point loads split as Eq. 25; the
    end loads in ``skip`` left to the ends) and the couples' part of the PD curvature on the positions
    -J .. n - 1 + J (divided by EI)."""
    J = len(st) // 2
    kinked = [ld for ld in scene.loads if isinstance(ld, (PointForce, PointMoment)) and spreads(ld, scene, n, dx, J)]
    q = np.zeros(n)
    spread = list(kinked)
    for ld in scene.loads:
        if (
            isinstance(ld, Distributed)
            and ld.value != 0.0
            and (qd := distributed_kink(ld, scene, n, dx, st)) is not None
        ):
            spread.append(ld)
            q += qd
    rest = [ld for ld in scene.loads if not any(ld is k for k in spread)]
    x = np.arange(n) * dx
    if rest:
        q += body_loads(scene.model_copy(update={"loads": rest}), x, skip_ends=skip)
    curv = np.zeros(n + 2 * J)
    for ld in kinked:
        t0 = ld.position / dx
        if isinstance(ld, PointForce):
            p, qk = force_kink(t0, dx, st)
        else:
            p, qk, kk = couple_kink(t0, dx, st)
            curv[p + J] += ld.value * kk * couple_compliance(scene, ld.position)
        q[p] += ld.value * qk
    return q, curv


def couple_compliance(scene: Scene, at: float) -> float:
    """1 / EI where a couple's kink sits: its segment's, or on a segment joint (within 1e-9 of the length) the mean of
    the two sides' 1 / EI, so that the mirror image takes the same (either side's alone: mirror images 8.9e-4 of max
    |w| apart at 41 points, docs/models/diyaroglu.md)."""
    tol = 1e-9 * scene.length
    sides = [mat.E * sec.I for a, b, sec, mat in scene.pieces() if abs(a - at) <= tol or abs(b - at) <= tol]
    if len(sides) == 2 and 0.0 < at < scene.length:
        return float(np.mean([1.0 / v for v in sides]))
    return 1.0 / float(scene.stiffness_at(np.array([at]))["EI"][0])


def rhs(lay: Layout, loads: list) -> np.ndarray:
    """The right-hand side of ``loads`` (a list of scene loads): the ghosts' and the end rows' end loads, the line
    loads on the w rows and the couples' curvature terms (:func:`point_load_terms`)."""
    sc = lay.scene.model_copy(update={"loads": list(loads)})
    n, dx, J = lay.n, lay.dx, lay.J
    G, h2 = 2 * J, dx * dx
    g_rows, g_cols, g_vals, e0, skip = ghost_map(sc, n, dx, G, True, lay.sups, lay.EIs)
    _, _, _, r = mixed_ghost_coupling(g_rows - G, g_cols, g_vals, e0, n, J, lay.st, h2)
    q, curv = point_load_terms(sc, n, dx, lay.st, skip)
    r[lay.wdof(np.arange(n))] = q * h2 * h2 / lay.EI0
    r[lay.kdof(np.arange(-J, n + J))] += h2 * curv
    for _, _, _, rr, rv in _end_rows(lay, q, sc):
        r[rr] = rv
    r[lay.held] = 0.0
    return r


@dataclass
class Augmented:
    """The system the mixed form solves: ``matrix`` (the band, or with the reactions' rows and columns appended a
    sparse matrix), ``rhs``, the reaction unknowns (:func:`.scenes.reaction_unknowns`) and their column scales."""

    matrix: object
    rhs: np.ndarray
    unknowns: list
    scales: list
    n_band: int


def system(lay: Layout) -> Augmented:
    """The mixed form's system, the reactions of the springs and of the supports inside the span as unknowns when
    the scene has any: each a Lagrange multiplier of its measure of w (:mod:`.scenes`), entering as a point load of
    its kind (the right-hand side of a unit reaction: its column), with the row k s measure + lam = 0 (spring) or
    measure = 0 (rigid), lam = R s and s the column's largest entry (columns and rows of order one)."""
    M = band(lay)
    b = rhs(lay, lay.scene.loads)
    unknowns = reaction_unknowns(lay.scene)
    if not unknowns:
        return Augmented(M, b, [], [], M.n)
    N = M.n
    cols, scales, rows, diag = [], [], [], []
    for r in unknowns:
        col = rhs(lay, [unit_load(r)])
        s = float(np.abs(col).max()) or 1.0
        cols.append(-col / s)
        scales.append(s)
        pts, wts = measure_row(r, lay.n, lay.dx)
        k = r["stiffness"]
        row = (k * s * wts) if k is not None else wts
        d = 1.0 if k is not None else 0.0
        norm = max(float(np.abs(row).max()), d)
        rows.append((lay.wdof(pts), row / norm))
        diag.append(d / norm)
    R = len(unknowns)
    rr = np.concatenate([np.full(len(i), j) for j, (i, _) in enumerate(rows)])
    Rm = sp.csr_matrix((np.concatenate([v for _, v in rows]), (rr, np.concatenate([i for i, _ in rows]))), shape=(R, N))
    A = sp.bmat([[M.tocsr(), sp.csr_matrix(np.column_stack(cols))], [Rm, sp.diags(diag)]], format="csr")
    return Augmented(A, np.r_[b, np.zeros(R)], unknowns, scales, N)


def unpack(lay: Layout, aug: Augmented, z: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict]:
    """(w, m, reactions) of a solution z of :func:`system`: w and the moment m (sagging) on the n points, and the
    reactions that were unknowns (force +z, moment counter-clockwise on the beam) by key."""
    pts = np.arange(lay.n)
    w = z[lay.wdof(pts)]
    m = lay.EI0 * z[lay.kdof(pts)] / (lay.dx * lay.dx)
    lam = z[aug.n_band :]
    return w, m, {r["key"]: float(lam[j] / aug.scales[j]) for j, r in enumerate(aug.unknowns)}
