"""The banded stiffness of ``pd-higher-order`` (Yang, Oterkus & Oterkus 2020, Eq. 15 with Appendix B's ends),
assembled straight into LAPACK's band layout (:class:`~pdverify.numerics.band.Band`).

Every row whose point, bonds and partners' bonds lie away from the ends is the same 4x4 block stencil (Eq. 15's
Hessian with the interior weights, :func:`~.bonds.uniform_blocks`), written diagonal by diagonal. The rows of the
few points near each end (truncated families and their calibration, end volumes, ghost layers folded onto their
images, the end conditions) and near the cut points are computed exactly on a small window of the extended grid,
by the sparse route of Eq. 15 + Appendix B (:meth:`Layout.window`), and overwrite those rows: the same bits as the
whole-grid sparse route.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...core.scene import PointForce, PointMoment, Scene
from ...numerics.band import Band
from ...theory.higher_order import NF
from .bonds import assemble_blocks, bond_weights, uniform_blocks
from .ends import constraint_map, end_conditions, extended_volumes, mirror_map, taylor_map


def put_rows(B: Band, r0: int, c0: int, D: np.ndarray) -> Band:
    """Overwrite the rows r0 .. r0 + len(D) - 1 of the band with the dense rows D (columns c0 ..): the
    rows are cleared, then D's nonzero entries written (``Band`` has no assignment of entries)."""
    B.clear_rows(np.arange(r0, r0 + D.shape[0]))
    i, j = np.nonzero(D)
    return B.add_entries(r0 + i, c0 + j, D[i, j])


def ghost_layers(ends: str, J: int, p: int, left: str, right: str, about: str, end_layer: str):
    """(G, calibrate, reach, info) of the end treatment ``ends``: ghost points per end G, the calibration of the
    bond weights (:func:`~.bonds.bond_weights`), the reach of the ghost map into the real points, and the
    description for the result's info. mirror: Appendix B's fictitious layers of J points (Eq. B39-B41), none at a
    free end; taylor: J ghosts per end extrapolated by a polynomial of degree p; truncated: no ghosts, per-point
    (``end_layer = point``) or patch-test (``patch``) calibration."""
    if ends == "mirror":
        G = (0 if left == "free" else J, 0 if right == "free" else J)
        info = {
            "boundary": f"fictitious mirror layers (Appendix B) about the "
            f"{'boundary' if about == 'boundary' else 'end point'}, free ends truncated",
            "ghosts_per_end": list(G),
        }
        return G, "family", J, info
    if ends == "taylor":
        info = {
            "boundary": f"ghosts extrapolated (degree {p}), energy of the real points, essential end conditions",
            "ghosts_per_end": [J, J],
        }
        return (J, J), "family", p, info
    return (0, 0), end_layer, 0, {"boundary": "truncated families (per-point calibration), essential end conditions"}


@dataclass
class Layout:
    """The discrete operator of one grid: the real points x (n, spacing dx), horizon factor m, the variant's family
    volumes (``fractions``), the end treatment (``ends``: mirror, taylor or truncated; G ghosts per end, weights
    ``calibrate``d as :func:`~.bonds.bond_weights`, ghost extrapolation of degree p), the coefficients C of Eq. 9 and
    depth h, the shear measures (``centred``, ``path``), the supports and their options (``pin``, ``about``,
    ``clamp``), the points where the bonds are cut (``cuts``) and the stretch measure along the path (``stretch``).
    ``symmetric``: the energy's Hessian folded onto the real points (P^T K P); else (the paper's mirror layers)
    Eq. 22 at the real points with the images substituted (K P)."""

    x: np.ndarray
    m: float
    variant: str
    fractions: str
    ends: str
    G: tuple[int, int]
    calibrate: str
    reach: int
    p: int
    C: np.ndarray
    h: float
    centred: bool
    path: bool
    left: str
    right: str
    pin: str
    about: str
    clamp: str
    cuts: tuple[int, ...] = ()
    stretch: bool = False
    _extended: dict = field(default_factory=dict, init=False, repr=False, compare=False)  # (r0, r1) -> extended()

    @property
    def n(self) -> int:
        return len(self.x)

    @property
    def dx(self) -> float:
        return self.x[1] - self.x[0]

    @property
    def symmetric(self) -> bool:
        """False for the paper's mirror layers: Eq. 22 at the real points, the images substituted."""
        return not (self.ends == "mirror" and self.variant == "paper")

    @property
    def N(self) -> int:
        """Points of the extended grid (ghosts included)."""
        return self.n + self.G[0] + self.G[1]

    def weights(self, k: np.ndarray, cuts: tuple[int, ...] | None = None) -> dict[int, np.ndarray]:
        """V_k omega_kj of the extended points k (:func:`~.bonds.bond_weights` on the whole extended grid);
        ``cuts`` default: the layout's."""
        return bond_weights(
            self.N,
            self.m,
            self.dx,
            self.variant,
            extended_volumes(k, self.n, self.G, self.dx, self.ends, self.variant),
            self.calibrate,
            points=k,
            fractions=self.fractions,
            cuts=self.cuts if cuts is None else cuts,
        )

    def ghosts(self, r0: int, r1: int) -> tuple[int, int]:
        """The ghosts per end of the window of real points r0..r1-1: those of the ends it reaches."""
        return (self.G[0] if r0 == 0 else 0, self.G[1] if r1 == self.n else 0)

    def extended(self, r0: int, r1: int):
        """K of the extended points of the window r0..r1-1 (its ghosts included), Eq. 15 bond by bond
        (:func:`~.bonds.assemble_blocks`); made once per window of the layout (a window's rows with and without
        the end conditions share it)."""
        if (r0, r1) not in self._extended:
            g = self.ghosts(r0, r1)
            k = np.arange(self.G[0] + r0 - g[0], self.G[0] + r1 + g[1])
            K = assemble_blocks(len(k), self.dx, self.C, self.weights(k), self.h, self.centred, self.path, self.stretch)
            K.data.flags.writeable = False  # shared by the window's two readings
            self._extended[(r0, r1)] = K
        return self._extended[(r0, r1)]

    def fold(self, nw: int, g: tuple[int, int]):
        """The ghost map of a window of nw real points with g ghosts per end (None without ghosts)."""
        if self.ends == "mirror":
            return mirror_map(nw, g, self.left, self.right, self.about)
        if self.ends == "taylor":
            return taylor_map(nw, g, self.p)
        return None

    def window(self, r0: int, r1: int, constrained: bool = True) -> np.ndarray:
        """Dense K (end conditions included) of the real points r0..r1-1 with the ghosts of the ends the
        window reaches: exact in the rows whose bonds and ghost images lie in the window. ``constrained =
        False``: before the end conditions (the rows of the held DOFs kept: the reactions K u - b)."""
        n, g, nw = self.n, self.ghosts(r0, r1), r1 - r0
        Kx = self.extended(r0, r1)
        P = self.fold(nw, g)
        if P is None:
            K = Kx
        elif self.symmetric:
            K = (P.T @ Kx @ P).tocsr()
        else:
            K = (Kx[NF * g[0] : NF * (g[0] + nw)] @ P).tocsr()
        if not constrained:
            return K.toarray()
        left, right = (self.left if r0 == 0 else "free"), (self.right if r1 == n else "free")
        T = constraint_map(
            nw, left, right, self.variant, self.pin, self.h, numbering="points", about=self.about, clamp=self.clamp
        )
        if self.symmetric:
            return (T.T @ K @ T).toarray()
        D = (K @ T).toarray()
        D[end_conditions(nw, left, right, self.variant, self.pin, self.h, self.about, self.clamp)[0]] = 0.0
        return D


def load_cuts(scene: Scene, x: np.ndarray, J: int) -> tuple[int, ...]:
    """Interior grid points carrying a point force or moment, or a support inside the span, where the bonds are cut:
    loads and supports exactly on a point, at least 4J + 1 spacings from either end and from every other such point
    (a symmetric rule: mirror scenes cut alike)."""
    n, dx = len(x), x[1] - x[0]
    cand = set()
    spots = [ld.position for ld in scene.loads if isinstance(ld, (PointForce, PointMoment))]
    for pos in spots + [s.position for s in scene.supports.inner]:
        p = (pos - x[0]) / dx
        i = int(round(p))
        if abs(p - i) < 1e-9 and 0 < i < n - 1:
            cand.add(i)
    gap = 4 * J + 1
    return tuple(sorted(c for c in cand if min(c, n - 1 - c) >= gap and all(abs(c - o) >= gap for o in cand if o != c)))


def window_parts(n: int, J: int, calibrate: str, reach: int, cuts: tuple[int, ...]):
    """(parts, span): the windows (r0, r1, a, b) whose rows a..b-1 (window numbering) are written into the band,
    one per end (beyond 2J points from an end the rows are the stencil's; the patch-test end layer changes the
    bonds of the first 2J + 1 points, which reach J further; one spare) and one per cut (its two end layers and
    their bonds); a small grid is one window. ``span``: the points of an end's window."""
    rows_end = max(2 * J + (J if calibrate == "patch" else 0), reach + 1) + 1
    span = rows_end + J  # window points: those rows and their partners
    if n < 2 * span:
        return [(0, n, 0, n)], span
    parts = [(0, span, 0, rows_end), (n - span, n, span - rows_end, span)]
    R = 3 * J + 2  # rows changed by a cut: its two end layers (2J + 1 points each side) and their bonds
    for c in cuts:
        r0, r1 = max(0, c - R - J), min(n, c + R + J + 1)
        parts.insert(-1, (r0, r1, c - R - r0, c + R + 1 - r0))
    return parts, span


def band_operator(lay: Layout, J: int):
    """(B, end_rows, span): the band of the constrained operator (end conditions as in :meth:`Layout.window`; the
    held DOFs not yet unit rows), the unconstrained rows of the two end points [(point, first column, rows)]
    (none for mirror layers, whose images carry part of the reaction), and the points of an end's window."""
    n = lay.n
    parts, span = window_parts(n, J, lay.calibrate, lay.reach, lay.cuts)
    dense = [(r0, a, lay.window(r0, r1)[NF * a : NF * b]) for r0, r1, a, b in parts]
    end_rows = []
    for k_end, (r0, r1, _, _) in ((0, parts[0]), (n - 1, parts[-1])) if lay.ends != "mirror" else ():
        D = lay.window(r0, r1, constrained=False)
        end_rows.append((k_end, NF * r0, D[NF * (k_end - r0) : NF * (k_end - r0 + 1)]))
    bw = NF * J + NF - 1
    for _r0, a, D in dense:
        i, j = np.nonzero(D)
        if len(i):
            bw = max(bw, int(np.abs(j - (i + NF * a)).max()))
    B = Band(NF * n, bw, bw)
    if len(parts) > 1:
        mid = lay.G[0] + n // 2
        interior = {off: float(wt[0]) for off, wt in lay.weights(np.array([mid]), cuts=()).items()}
        B.add_block_stencil(NF, uniform_blocks(lay.C, lay.dx, interior, lay.h, lay.centred, lay.path, lay.stretch))
    for r0, a, D in dense:
        put_rows(B, NF * (r0 + a), NF * r0, D)
    return B, end_rows, span


def held_system(B: Band, F: np.ndarray, drop: list, tie: list, symmetric: bool) -> np.ndarray:
    """b: the load vector F with the ties' slave loads on their masters (T^T F; the paper variant has no ties), the
    held DOFs ``drop`` made unit rows of B with cleared columns (``Band.fix``, which sets their b)."""
    b = F.copy()
    if symmetric:
        for slave, master, c in tie:
            b[master] += c * F[slave]
    B.fix(drop, b)
    return b


def stiffness_factor(J: int, m: float, dx: float, variant: str, fractions: str) -> float:
    """Σ_j V omega_j xi_j^2 / dx over an interior point's whole family: 1 for the calibrated weights; the paper's
    omega of Eq. 14 gives 9.09/9.090225 with partial volumes, 1.320 with full ones (at m = 3)."""
    wref = bond_weights(2 * J + 1, m, dx, variant, np.full(2 * J + 1, dx), calibrate="family", fractions=fractions)
    return float(sum(w[J] * (abs(o) * dx) ** 2 for o, w in wref.items()) / dx)
