"""Models ``pd-rod``, ``pd-timoshenko``, ``pd-torsion``: micro-elastic PD rod, Timoshenko beam and
torsion (Moyer & Miraglia; torsion: Section 5, Eq. 54–56, the rod kernel with GJ and twist θ).

Node grid x_i = i Δ, i = 0..n-1 (ends included), horizon δ = m Δ (integer m, option ``horizon``).

Rod (Section 2): ρ u_tt = ρ B I_i - c_d u_t + b with B = 2E/(δ² ρ) (Eq. 1–3) and the trapezoidal
peridynamic integral I_i = Σ_j c_j (u_{i+j} + u_{i-j} - 2u_i), c_j = w_j / j (Eq. 13–19;
w_j = 1, 1/2 at j = m; see ``_moyer_kernels.rod_kernel``).

Timoshenko beam (Section 3), per unit length (w up, γ the cross-section rotation, ψ = w' - γ, Eq. 33):

    ρA w_tt = (kGA / 2δ) I_i + q                   I_i = PV∫ ψ(x_i + ε)/ε dε       (Eq. 34, 36, 47)
    ρI γ_tt = (2EI / δ²) J_i + (kGA / 2δ) K_i + μ   J_i = ∫ (γ(x_i+ε) - γ_i)/|ε| dε,  K_i = 2δ ψ_i (Eq. 35, 37, 48, 49)

i.e. C1 = kG/(2δρ), C2 = 2E/(ρδ²), C3 = AkG/(2ρδI) (Eq. 50); q is the line load, μ the line couple.
The static problem is the same discrete operator without inertia (rows: the real points; unknowns
interleaved w_0, γ_0, w_1, ...). It is assembled as written (sparse products of the ghost extension,
ψ and the PD sums) on a short grid of the same spacing only: away from the ends every row is the same
stencil, so the operator on any grid is that stencil plus the short grid's end rows
(:class:`~._moyer_kernels.EndPatched`, bit-identical to the whole-grid assembly). It is written
diagonal by diagonal into a :class:`~pdverify.band.Band`, the supported DOFs held by unit rows, and
solved by :func:`pdverify.linalg.solve_linear` (LU in place above 20,000 unknowns). :func:`simulate`
integrates the same operator in time with the damped leapfrog / velocity-Verlet scheme of Eq. 7–12
(38–44): one product with K per step (CSR on small grids, else the stencil applied block by block).

Variants
--------
``paper`` (as published): ψ at the nodes by central differences (Eq. 45–46), I by Eq. 47; ghost
points by Taylor extrapolation of w and γ (u) from the real points: first order (Eq. 20–21) at
Dirichlet ends (clamped; rod: clamped/pinned), second order with one-sided second-order differences
at the other ends (Section 4, Eq. 53); loads at an end as body force p/(AΔ) in the end cell.
Two printing errors had to be corrected to evaluate the sums at all: Eq. 16 gives l1 = 1 + k - m,
which runs over 2-m..0 (division by zero at k = m-1); the trapezoid of ∫_{-mΔ}^{-Δ} needs
l1 = k - m - 1 (as Eq. 47/48 index it), and Eq. 19's first sum then needs the minus sign of Eq. 15
(as Eq. 48 has it). Measured weaknesses (tests/test_pd_timoshenko.py): the pure extrapolation imposes
no traction condition at a free end (the mixed-boundary cantilever of Section 4 is singular with the
second-order extrapolation and wrong with the first-order one) and the central-difference ψ decouples
odd and even points (w' twice by central differences). Option ``grid = "cells"`` (paper variant,
static) is the literal Section 4 setup: n - 1 cells of Δ = L/(n - 1), points at the cell centres, ghost
cells by Taylor expansion about the end faces (a Dirichlet face anchored at zero); measured on Table 1:
19.6, 14.1 and 10.6 times the exact tip deflection for m = 2, 3, 4 (order 2 between Dirichlet ends).

``corrected`` (default; the "before" numbers were measured while developing it, the result is tested):
1. ψ as interval averages: ψ̄_{i+1/2} = (w_{i+1} - w_i)/Δ - (-γ_{i-1} + 13γ_i + 13γ_{i+1} - γ_{i+2})/24
   (the exact average over [x_i, x_{i+1}] for a cubic γ), I by the midpoint rule on each unit interval
   (weights 1/(j - 1/2)), K_i = 2δ (ψ̄_{i-1/2} + ψ̄_{i+1/2})/2. Compact: no odd–even decoupling. With the
   plain mean (γ_i + γ_{i+1})/2 the shear force carries an error kGA Δ² γ''/12 that grows like (Δ/h)²
   (measured 1.3 % on the Table 1 cantilever, 2.9 % at L/h = 100 with 201 points, clamped–free, mixed
   loads); with the 13/24 average the tip-loaded cantilever is exact (1e-11).
2. ghost points from one polynomial per field (degree 3, fitted to the first 4 real points) that
   satisfies the support's conditions exactly: clamped w = w_end, γ = γ_end; pinned w = w_end,
   EIγ' = M̄; free EIγ' = M̄, kGA ψ = P̄; guided γ = γ_end, kGA ψ = P̄ (end loads enter here);
   the end point's own equation holds where its value is not prescribed. Rod: u = u_end or EA u' = N̄.
3. at free and guided ends the ghost ψ̄ are extrapolated from the real intervals' ψ̄ with ψ(end) =
   P̄/kGA imposed (quadratic, 4 intervals), not computed from the extrapolated w and γ, whose errors
   would enter the shear force multiplied by kGA/Δ (uniformly loaded cantilever, 201 points: 27 % at
   L/h = 1000 and 2700 % at 1e4 before, 3e-8 and 3e-6 after).
Time stepping (both variants): the boundary closures make K non-symmetric and some modes have complex
(or, at pinned ends with m = 1, 2 and L/h = 100, negative) ω² (tests/test_dynamics.py measures the
spectrum); a stiffness-proportional damping β K v with β = κ dt_ref, κ = 0.2, dt_ref = 0.9 x the stable
limit (``stabilisation``; the first mode gets ~2e-4 of critical) keeps the step map's spectral radius
<= 1 on the small grids of the paper (1 + 2e-2 without), not on every grid. Every transient carries an
energy ledger (:mod:`pdverify.dynamics`: kinetic, strain, load and support work, the work of the damping
and of the stabilisation, balance) and is stopped when its stored energy outgrows the work put in.

Results: x, w, rotation = γ, fields M = EIγ', V = M' = -kGA ψ (the exact models' convention), psi;
rod: u, N = EA u'; torsion: twist, T = GJ θ'. A scene with a ``[dynamics]`` table is run in time by
``solve`` (option ``analysis``: auto | static | dynamic); the time histories are in info["history"]
and ``--out file.csv`` writes them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ..band import Band
from ..dynamics import LEDGER_COLUMNS, EnergyLedger, symbol_max
from ..errors import InputError, SolveError
from ..linalg import solve_linear
from ..registry import Model, Option, Rule, System
from ..result import Result, Timer, columns_csv
from ..scene import Scene
from ._moyer_kernels import (
    EndPatched,
    average_ghosts,
    constrained_ghosts,
    motion_final,
    motion_value,
    node_loads,
    rod_kernel,
    shear_kernel,
    stencil_ops,
    taylor_ghosts,
    taylor_ghosts_cells,
    toeplitz,
)
from .pd_common import boundary_layer_warnings

STABILISATION = 0.2  # κ of the stiffness-proportional damping β = κ dt_ref of the time stepping (see integrate)
DEFAULT_SAFETY = 0.9  # default dt = this x the stable limit; dt_ref of the stabilisation
FIT_DEGREE, FIT_POINTS = 3, 4  # corrected ghosts: cubic per field through the first 4 real points
SHEAR_FIT_DEGREE, SHEAR_FIT_INTERVALS = 2, 4  # ψ̄ ghosts at free/guided ends
# rod (torsion) ghosts at a traction end for m >= 2: quartic through 5 points. The cubic through 4 gives M⁻¹K
# complex eigenvalues at m = 2 (growth 3.4e-2 of ω_max, every slenderness); the quartic's spectrum is real for
# m = 2..10, the cubic's is at m = 1 (the quartic's is not: 4.8e-2); static results agree to the horizon's
# own error (they differ by 2e-11 at m = 2..4, clamped-free, mixed axial loads, 201 points)
ROD_TRACTION_FIT = (4, 5)


@dataclass
class Discrete:
    """The assembled operator on all real DOFs: rows r: mass_r u_tt = b_r - (K u)_r (free rows only).

    K is held as an :class:`~._moyer_kernels.EndPatched` operator ``op`` (the PD sums are one stencil
    away from the ends, explicit rows where a family reaches a ghost point): ``band()`` gives it in
    LAPACK's band layout for the direct solve, ``K`` as CSR (small grids, eigenvalues), and the time
    stepping applies the stencil matrix-free."""

    x: np.ndarray
    op: EndPatched  # all DOFs x all DOFs (rows of prescribed DOFs are ignored)
    b: np.ndarray
    field_mass: tuple  # per field: rho A for translations, rho I for rotations
    field_translational: tuple  # per field: damping acts on these
    prescribed: dict  # dof -> (field, side) of Dirichlet DOFs
    nf: int  # fields per point (1 rod, 2 beam)
    info: dict = field(default_factory=dict)
    psi: tuple | None = None  # (EndPatched op, constant): the shear strain at the points used by the operator

    @cached_property
    def K(self) -> sp.csr_matrix:
        return self.op.tocsr()

    def band(self) -> Band:
        return self.op.band()

    @property
    def mass(self) -> np.ndarray:
        return np.tile(np.asarray(self.field_mass, float), len(self.x))

    @property
    def translational(self) -> np.ndarray:
        return np.tile(np.asarray(self.field_translational, bool), len(self.x))

    @property
    def n_free(self) -> int:
        return len(self.b) - len(self.prescribed)

    @property
    def free(self) -> np.ndarray:
        keep = np.ones(len(self.b), bool)
        keep[list(self.prescribed)] = False
        return np.flatnonzero(keep)


def _core_points(m: int) -> int:
    """Points of the short grid on which an operator is assembled in full (EndPatched.from_core): a
    stretch of stencil rows between the two ends' ghost-influenced rows (about m + 4 each) wider than
    the family (m + 2 points each side). Grids up to this size are assembled in full."""
    return 12 * (m + 4)


def _end_data(n: int, side: int, npts: int) -> np.ndarray:
    """Real point indices from the end inward."""
    k = np.arange(npts)
    return k if side == 0 else n - 1 - k


def _ghost_index(n: int, G: int, side: int) -> np.ndarray:
    """Extended-grid indices of ghosts t = 1..G outside the end (extended index = real + G)."""
    t = np.arange(G)
    return G - 1 - t if side == 0 else G + n + t


DIRICHLET = {
    "clamped": (True, True),
    "pinned": (True, False),
    "roller": (True, False),
    "free": (False, False),
    "guided": (False, True),
}  # (w, γ) held; no axial unknown: roller = pinned
# ends whose axial displacement (pd-rod) or twist (pd-torsion) is held: a roller slides axially, but holds the
# twist as a pinned (fork) support does (docs/supports.md)
ROD_HELD = {"axial": ("clamped", "pinned"), "torsion": ("clamped", "pinned", "roller")}


def _extension(n: int, G: int, nf: int, blocks) -> tuple[sp.csr_matrix, np.ndarray]:
    """Sparse map real DOFs (interleaved, nf per point) -> extended field f values (stacked f-major):
    rows f*N + e. ``blocks``: per side, (R (nf G x nf npts), r0, npts) ghost maps, field-major."""
    N = n + 2 * G
    rows, cols, vals = [], [], []
    for f in range(nf):
        rows.append(f * N + G + np.arange(n)), cols.append(nf * np.arange(n) + f), vals.append(np.ones(n))
    e0 = np.zeros(nf * N)
    for side, (R, r0, npts) in blocks.items():
        real = _end_data(n, side, npts)
        ghost = _ghost_index(n, G, side)
        for f in range(nf):
            for g in range(nf):
                blk = R[f * G : (f + 1) * G, g * npts : (g + 1) * npts]
                rr = np.repeat(f * N + ghost, npts)
                cc = np.tile(nf * real + g, G)
                rows.append(rr), cols.append(cc), vals.append(blk.ravel())
            e0[f * N + ghost] = r0[f * G : (f + 1) * G]
    E = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nf * N, nf * n))
    return E, e0


def _check_grid(n: int, m: int, name: str):
    if n < max(2 * m + 2, FIT_POINTS + 1):
        raise InputError(
            f"points = {n}: model {name} with horizon = {m} needs at least {max(2 * m + 2, FIT_POINTS + 1)} "
            "points; use more points or a smaller horizon"
        )


# -- rod --------------------------------------------------------------------------------------


def rod_operator(scene: Scene, n: int, m: int, variant: str, kind: str = "axial", grid: str = "nodes") -> Discrete:
    """Static operator of the PD rod: K u = b with u the axial displacement (``kind = "axial"``: stiffness
        EA, mass ρA, loads.axial) or the twist θ (``kind = "torsion"``, Section 5 Eq. 54–56: the same
        kernel with GJ, mass ρ I_p, torques). Fixed ends: :data:`ROD_HELD` (clamped, pinned; pd-torsion: roller
    too); the others carry N̄ (T̄).
        Assembled in full on a short grid (:func:`_rod_core`) and extended by its stencil (Eq. 19)."""
    name = "pd-rod" if kind == "axial" else "pd-torsion"
    n, x = _grid(scene, n, grid, variant, name)
    _check_grid(n, m, name)
    dx = x[1] - x[0]
    delta = m * dx
    rho = scene.material.density or 0.0
    if kind == "axial":
        stiff, inertia, component, key = scene.EA, scene.section.A, "axial", "u"
    else:
        J = scene.section.J
        if J is None:
            raise InputError(
                "section.torsion_constant: pd-torsion needs the torsion constant J of a section given by "
                "area and inertia; add torsion_constant (or give width and height)"
            )
        stiff, component, key = scene.material.G * J, "torque", "twist"
        inertia = scene.section.polar if scene.section.polar is not None else np.nan
    q, _, ends = node_loads(scene, x, component, ends_apart=(variant == "corrected"))
    prescribed = {}
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        if grid == "nodes" and sup in ROD_HELD[kind]:
            prescribed[0 if side == 0 else n - 1] = (key, side)
    Kc, bc = _rod_core(scene, min(n, _core_points(m)), dx, m, variant, stiff, ends, grid, kind)
    op = EndPatched.from_core(Kc, 1, 1, n)
    b = EndPatched.add_ends(q, bc, 1)
    if variant == "paper":
        for side in (0, 1):
            b[0 if side == 0 else n - 1] += ends[side][0] / dx
    return Discrete(
        x, op, b, (rho * inertia,), (True,), prescribed, 1, {"ghosts_per_end": m, "spacing": dx, "horizon": delta}
    )


def _rod_core(
    scene: Scene, n: int, dx: float, m: int, variant: str, stiff: float, ends: dict, grid: str, kind: str = "axial"
) -> tuple[sp.csr_matrix, np.ndarray]:
    """(K, ghost part of b) of the rod on n points of spacing dx, assembled as written: K = -B I E with
    the extension E to G = m ghosts per end (Eq. 20–21 or the constrained polynomial) and the PD sum I
    (Eq. 19, c_j of ``rod_kernel``), B = 2 stiff/δ² (Eq. 3)."""
    delta = m * dx
    G = m
    blocks = {}
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        fixed = sup in ROD_HELD[kind]
        if grid == "cells":
            blocks[side] = (taylor_ghosts_cells(G, 1 if fixed else 2, fixed), np.zeros(G), 4)
            continue
        if variant == "paper":
            blocks[side] = (taylor_ghosts(G, 1 if fixed else 2), np.zeros(G), 4)
        else:
            if fixed:
                con = [({(0, 0): 1.0}, {(0, 0): 1.0}, 0.0)]
            else:  # EA u_s(0) = N̄ (outward force at this end); GJ θ_s(0) = T̄
                con = [({(0, 1): 1.0}, {}, dx * ends[side][0] / stiff)]
            deg, npts = (FIT_DEGREE, FIT_POINTS) if (fixed or m == 1) else ROD_TRACTION_FIT
            R, r0 = constrained_ghosts(1, deg, npts, G, con)
            blocks[side] = (R, r0, npts)
    E, e0 = _extension(n, G, 1, blocks)
    c = rod_kernel(m)
    j = np.arange(1, m + 1)
    Iop = toeplitz(n, G, n + 2 * G, np.concatenate([[0], j, -j]), np.concatenate([[-2 * c.sum()], c, c]))
    B = 2.0 * stiff / delta**2  # ρA B = 2EA/δ² (Eq. 3): force per length per unit of I
    return (-B * (Iop @ E)).tocsr(), B * (Iop @ e0)


# -- Timoshenko beam ----------------------------------------------------------------------------


def _grid(scene: Scene, n: int, grid: str, variant: str, name: str) -> tuple[int, np.ndarray]:
    """(points, x): ``nodes`` x_i = iΔ (ends included); ``cells`` (Section 4, paper variant only): n - 1
    cells of the same Δ = L/(n - 1), collocation points at their centres."""
    L = scene.length
    if grid == "nodes":
        return n, np.linspace(0.0, L, n)
    if variant != "paper":
        raise InputError(
            f"grid = 'cells': model {name} uses the cell-centred grid of Section 4 only in variant "
            "paper; use grid = nodes or variant = paper"
        )
    nc = n - 1
    return nc, (np.arange(nc) + 0.5) * (L / nc)


def beam_operator(scene: Scene, n: int, m: int, variant: str, grid: str = "nodes") -> Discrete:
    """Static operator of the PD Timoshenko beam on the interleaved DOFs (w_0, γ_0, w_1, γ_1, ...):
    assembled in full on a short grid (:func:`_beam_core`, Eq. 45–49 as written) and extended by its
    stencil (:class:`~._moyer_kernels.EndPatched`)."""
    n, x = _grid(scene, n, grid, variant, "pd-timoshenko")
    _check_grid(n, m, "pd-timoshenko")
    dx = x[1] - x[0]
    delta = m * dx
    kGA = scene.kGA
    rho = scene.material.density or 0.0
    q, mu, ends = node_loads(scene, x, "transverse", ends_apart=(variant == "corrected"))
    prescribed = {}
    if grid == "nodes":  # cells: the end faces are not points, Dirichlet values enter the ghost cells
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            end = 0 if side == 0 else n - 1
            fix_w, fix_g = DIRICHLET[sup]
            if fix_w:
                prescribed[2 * end] = ("w", side)
            if fix_g:
                prescribed[2 * end + 1] = ("rotation", side)
    Kc, bw_parts, bg_parts, Pc, p0c = _beam_core(scene, min(n, _core_points(m)), dx, m, variant, grid, ends)
    op = EndPatched.from_core(Kc, 2, 2, n)
    bw, bg = q, mu
    for v in bw_parts:
        bw = EndPatched.add_ends(bw, v, 1)
    for v in bg_parts:
        bg = EndPatched.add_ends(bg, v, 1)
    if variant == "paper":
        for side in (0, 1):
            end = 0 if side == 0 else n - 1
            bw[end] += ends[side][0] / dx
            bg[end] += ends[side][1] / dx
    b = np.empty(2 * n)
    b[0::2], b[1::2] = bw, bg
    psi_nodes = (EndPatched.from_core(Pc, 1, 2, n), EndPatched.add_ends(np.zeros(n), p0c, 1))
    info = {"ghosts_per_end": m + 1, "spacing": dx, "horizon": delta}
    if rho:  # the paper's constants (Eq. 50)
        info.update(
            C1=kGA / (2 * delta * rho * scene.section.A),
            C2=2 * scene.material.E / (rho * delta**2),
            C3=kGA / (2 * rho * delta * scene.section.I),
        )
    return Discrete(
        x, op, b, (rho * scene.section.A, rho * scene.section.I), (True, False), prescribed, 2, psi=psi_nodes, info=info
    )


def _beam_core(scene: Scene, n: int, dx: float, m: int, variant: str, grid: str, ends: dict):
    """The beam operator on n points of spacing dx, assembled as written: the extension E to G = m + 1
    ghosts per end, ψ from it (Eq. 45–46, or the interval averages of the corrected variant), the PD
    sums I (Eq. 47), J and K (Eq. 48–49) as sparse products. Returns (K (2n x 2n, interleaved), ghost
    parts of the w and γ loads (lists, added in this order), ψ at the points (n x 2n), its constant)."""
    delta = m * dx
    EI, kGA = scene.EI, scene.kGA
    G = m + 1
    N = n + 2 * G
    blocks = {}
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        sigma = -1.0 if side == 0 else 1.0
        fix_w, fix_g = DIRICHLET[sup]
        if grid == "cells":  # the end faces are not points: Dirichlet values enter the ghost cells
            order = 1 if (fix_w and fix_g) else 2
            R = np.zeros((2 * G, 8))
            R[:G, :4] = taylor_ghosts_cells(G, order, fix_w)
            R[G:, 4:] = taylor_ghosts_cells(G, order, fix_g)
            blocks[side] = (R, np.zeros(2 * G), 4)
            continue
        if variant == "paper":
            T = taylor_ghosts(G, 1 if (fix_w and fix_g) else 2)
            R = np.kron(np.eye(2), T)
            blocks[side] = (R, np.zeros(2 * G), 4)
            continue
        P, C = ends[side]
        con = []
        if fix_w:
            con.append(({(0, 0): 1.0}, {(0, 0): 1.0}, 0.0))
        if fix_g:
            con.append(({(1, 0): 1.0}, {(1, 0): 1.0}, 0.0))
        if not fix_g:  # moment: EI γ_s(0) = C̄ (both ends, s outward)
            con.append(({(1, 1): 1.0}, {}, dx * C / EI))
        if not fix_w:  # shear: kGA (w_s - σ γ) = P̄
            con.append(({(0, 1): 1.0, (1, 0): -sigma * dx}, {}, dx * P / kGA))
        R, r0 = constrained_ghosts(2, FIT_DEGREE, FIT_POINTS, G, con)
        blocks[side] = (R, r0, FIT_POINTS)
    E, e0 = _extension(n, G, 2, blocks)
    Ew, Eg = E[:N], E[N:]
    ew, eg = e0[:N], e0[N:]
    offs, a = shear_kernel(m, variant)
    c = rod_kernel(m)
    j = np.arange(1, m + 1)
    if variant == "paper":
        # nodal ψ on extended points 1..N-2 (index e - 1), ψ = (W_{e+1} - W_{e-1})/(2Δ) - Γ_e
        Dc = toeplitz(N - 2, 1, N, [-1, 1], [-0.5 / dx, 0.5 / dx])
        Sel = toeplitz(N - 2, 1, N, [0], [1.0])
        Pw, Pg = Dc, -Sel
        # I_i = Σ a_j (ψ_{e+j} - ψ_{e-j}) with e = i + G, ψ index e - 1
        Sop = toeplitz(n, G - 1, N - 2, np.concatenate([j, -j]), np.concatenate([a, -a]))
        Avg = toeplitz(n, G - 1, N - 2, [0], [1.0])
    else:
        # ψ̄ of the interval [e, e+1] (half point h = e + 1/2, rows h = 1..N-3, index h - 1): the interval
        # average of w' is (W_{e+1} - W_e)/Δ, that of γ (-Γ_{e-1} + 13Γ_e + 13Γ_{e+1} - Γ_{e+2})/24 (exact
        # for cubic γ; the plain mean (Γ_e + Γ_{e+1})/2 leaves kGA Δ² γ''/12, a shear-force error that
        # grows like (Δ/h)², see the module docstring)
        Pw = toeplitz(N - 3, 1, N, [0, 1], [-1.0 / dx, 1.0 / dx])
        Pg = toeplitz(N - 3, 1, N, [-1, 0, 1, 2], np.array([1.0, -13.0, -13.0, 1.0]) / 24)
        # I_i = Σ_j a_j (ψ_{e + j - 1/2} - ψ_{e - j + 1/2}): half points e + j - 1/2, e - j + 1/2
        Sop = toeplitz(n, G - 1, N - 3, np.concatenate([j - 1, -j]), np.concatenate([a, -a]))
        Avg = toeplitz(n, G - 1, N - 3, [-1, 0], [0.5, 0.5])
    Jop = toeplitz(n, G, N, np.concatenate([[0], j, -j]), np.concatenate([[-2 * c.sum()], c, c]))
    psi_u = Pw @ Ew + Pg @ Eg  # ψ (extended) from the real DOFs
    psi_0 = Pw @ ew + Pg @ eg
    if variant == "corrected":
        psi_u, psi_0 = _shear_ghosts(scene, psi_u, psi_0, n, G, m, ends, kGA)
    cw, cg = kGA / (2 * delta), 2 * EI / delta**2
    Kw = -(cw * (Sop @ psi_u))  # rows: w equations of the real points
    Kg = -(cg * (Jop @ Eg) + kGA * (Avg @ psi_u))
    bw_parts = [cw * (Sop @ psi_0)]
    bg_parts = [cg * (Jop @ eg), kGA * (Avg @ psi_0)]
    perm = np.empty(2 * n, dtype=np.int64)
    perm[0::2], perm[1::2] = np.arange(n), n + np.arange(n)
    K = sp.vstack([Kw, Kg]).tocsr()[perm]
    return K.tocsr(), bw_parts, bg_parts, (Avg @ psi_u).tocsr(), Avg @ psi_0


def _shear_ghosts(scene, psi_u, psi_0, n, G, m, ends, kGA):
    """At an end whose deflection is free (free, guided) the ghost ψ̄ are extrapolated from the ψ̄ of
    the real intervals with ψ(end) = the end shear P̄/kGA imposed, instead of being computed from
    extrapolated w and γ: an extrapolation error δ in w or γ would enter the shear force as kGA δ/Δ,
    which grows like (L/h)² (measured: 27 % at slenderness 1000 on a uniformly loaded cantilever)."""
    rows_all = psi_u.shape[0]
    rep_r, rep_c, rep_v = [], [], []
    c0 = np.zeros(rows_all)
    replaced = np.zeros(rows_all, bool)
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        if DIRICHLET[sup][0]:
            continue
        sigma = -1.0 if side == 0 else 1.0
        k = np.arange(SHEAR_FIT_INTERVALS)
        t = np.arange(m)
        # half index h of interval [h, h+1] on the extended grid; psi rows are h - 1
        if side == 1:
            real_h, ghost_h = n - 2 + G - k, n - 1 + G + t
        else:
            real_h, ghost_h = G + k, G - 1 - t
        R, r = average_ghosts(SHEAR_FIT_DEGREE, SHEAR_FIT_INTERVALS, m)
        for i, gh in enumerate(ghost_h):
            rep_r.append(np.full(len(real_h), gh - 1)), rep_c.append(real_h - 1), rep_v.append(R[i])
            c0[gh - 1] = r[i] * sigma * ends[side][0] / kGA
            replaced[gh - 1] = True
    if not replaced.any():
        return psi_u, psi_0
    keep = np.flatnonzero(~replaced)
    rep_r.append(keep), rep_c.append(keep), rep_v.append(np.ones(len(keep)))
    Rep = sp.csr_matrix(
        (np.concatenate(rep_v), (np.concatenate(rep_r), np.concatenate(rep_c))), shape=(rows_all, rows_all)
    )
    return (Rep @ psi_u).tocsr(), Rep @ psi_0 + c0


# -- prescribed values, static solve -----------------------------------------------------------

_MOTION_KEY = {"w": "displacement", "u": "axial", "rotation": "rotation", "twist": "twist"}


def prescribed_motions(scene: Scene, disc: Discrete) -> dict:
    """dof -> Motion (or None for a fixed zero value) from the scene's [dynamics] table."""
    out = {}
    d = scene.dynamics
    for dof, (fieldname, side) in disc.prescribed.items():
        em = None if d is None else getattr(d, "left" if side == 0 else "right")
        out[dof] = None if em is None else getattr(em, _MOTION_KEY[fieldname])
    return out


def static_system(scene: Scene, disc: Discrete) -> tuple[Band, np.ndarray, dict]:
    """(B, rhs, held) of the direct solve: the band of K with the prescribed DOFs held (Band.fix: unit
    row, cleared column) and their settled values ``held`` {dof: value} (zero for plain supports; the
    final value of a prescribed end motion) moved to the right-hand side."""
    end_time = scene.dynamics.end_time if scene.dynamics else 0.0
    held = {
        dof: 0.0 if mot is None else motion_final(mot, end_time) for dof, mot in prescribed_motions(scene, disc).items()
    }
    B = disc.band()
    rhs = disc.b.copy()
    moved = sorted(d for d, v in held.items() if v != 0.0)
    if moved:  # rhs = b - K u0: column d of K is column d of the band's data
        acc = np.zeros(len(rhs))
        o = B.offsets
        for d in moved:  # the few supported DOFs
            r = d - o
            ok = (r >= 0) & (r < B.n)
            acc[r[ok]] += B.data[B.upper - o[ok], d] * held[d]
        touched = np.flatnonzero(acc)
        rhs[touched] = disc.b[touched] - acc[touched]
    pres = np.array(sorted(disc.prescribed), dtype=np.int64)
    B.fix(pres, rhs)
    return B, rhs, held


def static_solution(scene: Scene, disc: Discrete, what: str, system=None) -> tuple[np.ndarray, dict]:
    """Direct banded solve of :func:`static_system` (or the given ``system``, which is consumed: factorised
    in place above 20,000 unknowns); prescribed DOFs take their settled values. Raises SolveError when
    the system is singular to working precision (condition estimate > 1/eps: the paper variant's pure
    extrapolation at a free rod end, measured 1.6e18)."""
    B, rhs, held = static_system(scene, disc) if system is None else system
    u, info = solve_linear(B, rhs, what=what)
    cond = info.get("cond", 0.0)
    if np.isfinite(cond) and cond * np.finfo(float).eps > 1.0:
        hint = (
            (
                "variant paper leaves an end's free unknowns (the deflection at a free end, the rotation at "
                "a pinned or free one) without a traction condition (Section 4 as published); use variant "
                "corrected"
            )
            if "paper" in what
            else "use fewer points"
        )
        raise SolveError(f"{what}: the system is singular to working precision (condition estimate {cond:.2g}); {hint}")
    for dof, value in held.items():  # their unit rows gave zero
        u[dof] = value
    return u, info


# -- dynamics ---------------------------------------------------------------------------------


@dataclass
class History:
    """Time histories of a transient run: t (s), probe positions and their w (or u) and rotation."""

    t: np.ndarray
    probes: np.ndarray
    values: np.ndarray  # (len(t), len(probes)) translation at the probes
    rotations: np.ndarray | None
    final: np.ndarray  # all DOFs at the end time
    x: np.ndarray
    dt: float
    dt_limit: float
    steps: int
    damping: float  # c_d / rho (1/s)
    stabilisation: float
    omega1: float | None
    energy: dict = field(default_factory=dict)  # the ledger: "t" (a subset of t) and LEDGER_COLUMNS -> array
    energy_drift: float = 0.0  # max |balance| / max(stored energy, work put in)

    def to_csv(self) -> str:
        cols = {"t": self.t, **{f"x={p:g}": self.values[:, k] for k, p in enumerate(self.probes)}}
        if self.energy:  # the ledger's samples are a subset of the rows (NaN elsewhere)
            rows = np.searchsorted(self.t, self.energy["t"])
            for k in LEDGER_COLUMNS:
                col = np.full(len(self.t), np.nan)
                col[rows] = self.energy[k]
                cols[f"energy_{k}"] = col
        return columns_csv(cols, fmt="%.12g")


def _mass_scaled(disc: Discrete, free: np.ndarray) -> sp.csr_matrix:
    return sp.diags(1.0 / disc.mass[free]) @ disc.K[free][:, free]


EIG_DOFS = 1000  # up to this many free DOFs the largest eigenvalue is computed on the whole operator (ARPACK,
# k = 4: 0.44 s at 1,000 DOFs, 3.9 s at 5,000), above on the operator shortened to this size and the symbol


def stable_time_step(disc: Discrete) -> float:
    """dt_limit = 2 / ω_max, ω_max² the largest |eigenvalue| of M⁻¹K on the free DOFs
    (:func:`largest_eigenvalue`)."""
    return 2.0 / np.sqrt(largest_eigenvalue(disc))


def _eig_max(disc: Discrete) -> float:
    import scipy.sparse.linalg as spla

    A = _mass_scaled(disc, disc.free)
    if A.shape[0] < 20:
        return float(np.abs(np.linalg.eigvals(A.toarray())).max())
    # fixed start vector: ARPACK's default is random, which made dt (and every transient) differ
    # between runs in the 11th digit. Not the ones vector, and k = 4: with v0 = ones and k = 1 ARPACK
    # missed an end mode of the rod's traction closure (m = 2, 61 points: 5.72e10 for 7.49e10)
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])
    return float(
        np.abs(spla.eigs(A, k=min(4, A.shape[0] - 2), which="LM", return_eigenvectors=False, tol=1e-6, v0=v0)).max()
    )


def largest_eigenvalue(disc: Discrete) -> float:
    """The largest |eigenvalue| of M⁻¹K on the free DOFs. Above ``EIG_DOFS`` free DOFs the operator is a
    stencil away from its end rows: its spectrum is the end modes, which are those of the same operator
    shortened to ``EIG_DOFS`` DOFs (same end rows and stencil; ARPACK), and the interior modes, bounded by
    the maximum of the stencil's symbol over the wavenumbers (:func:`pdverify.dynamics.symbol_max`).
    (The Gershgorin row-sum bound used before above 5,000 DOFs gave a dt 1.13x (m = 2) and 1.32x (m = 3)
    too small on a clamped–clamped beam of 3,001 points.) The beam's top modes are end modes (~2x the
    symbol's maximum at m = 3), so the short grid carries the estimate."""
    if disc.n_free <= EIG_DOFS:
        return _eig_max(disc)
    nf, n = disc.nf, len(disc.x)
    ns = EIG_DOFS // nf
    op = disc.op.shortened(ns)
    shift = nf * (n - ns)
    pres = {(d if d < nf * n // 2 else d - shift): v for d, v in disc.prescribed.items()}
    short = Discrete(disc.x[:ns], op, np.zeros(nf * ns), disc.field_mass, disc.field_translational, pres, nf)
    return max(_eig_max(short), symbol_max(op.blocks, 1.0 / np.asarray(disc.field_mass, float)))


def first_frequency(disc: Discrete) -> float:
    """ω_1 (rad/s): the smallest |eigenvalue| of M⁻¹K on the free DOFs, square-rooted (shift-invert)."""
    import scipy.sparse.linalg as spla

    free = disc.free
    A = _mass_scaled(disc, free).tocsc()
    if A.shape[0] < 40:
        lam = np.linalg.eigvals(A.toarray())
        return float(np.sqrt(np.abs(lam).min()))
    lam = spla.eigs(A, k=1, sigma=0.0, which="LM", return_eigenvectors=False, v0=np.ones(A.shape[0]))
    return float(np.sqrt(np.abs(lam[0])))


def _interp_rows(x: np.ndarray, probes: np.ndarray) -> sp.csr_matrix:
    """Linear interpolation from the points to the probe positions (sparse rows)."""
    dx = x[1] - x[0]
    i = np.clip(np.floor(probes / dx).astype(int), 0, len(x) - 2)
    t = probes / dx - i
    rows = np.repeat(np.arange(len(probes)), 2)
    cols = np.stack([i, i + 1], 1).ravel()
    vals = np.stack([1 - t, t], 1).ravel()
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(probes), len(x)))


LEDGER_STRIDE = 200  # steps between ledger samples above WHOLE_DOFS (a sample costs ~12 steps there: <= 6 %)


def nf_n(disc: Discrete) -> int:
    return disc.nf * len(disc.x)


CHUNK = 16384  # points per block of the matrix-free time step (its arrays stay in the CPU cache)
WHOLE_DOFS = 4000  # up to this many DOFs a step is one CSR product: fewer numpy calls per step (measured
# crossover with the blockwise stencil at 2,000-5,000 points; at 1e5 points the stencil is 1.7x faster)


class _WholeStep:
    """One step of :func:`integrate`'s scheme on the whole DOF vector (interleaved), K y as one CSR
    product with the gains folded into its rows: r = G b - (G K) y, V = α V + r, u = u + V."""

    def __init__(self, disc: Discrete, gd: np.ndarray, alpha: np.ndarray, kappa: float, bG: np.ndarray):
        K = disc.K
        rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
        self.KG = sp.csr_matrix((K.data * gd[rows], K.indices, K.indptr), shape=K.shape)
        self.nf, self.kappa, self.bG = disc.nf, kappa, bG
        self.alpha = None if np.all(alpha == 1.0) else alpha
        n = len(bG)
        self.u, self.V, self.y = np.zeros(n), np.zeros(n), np.empty(n)

    def step(self):
        np.multiply(self.V, self.kappa, out=self.y)
        self.y += self.u
        r = self.KG @ self.y
        np.subtract(self.bG, r, out=r)
        if self.alpha is not None:
            self.V *= self.alpha
        self.V += r
        self.u += self.V

    def field(self, f: int) -> np.ndarray:
        return self.u[f :: self.nf]

    @property
    def flat(self) -> np.ndarray:
        return self.u

    def on_state(self, M: sp.csr_matrix) -> sp.csr_matrix:
        """M (columns: interleaved DOFs) acting on ``flat``."""
        return sp.csr_matrix(M)

    def velocity(self) -> np.ndarray:
        """V = dt v^{j-1/2} (interleaved)."""
        return self.V.copy()

    def start(self, V0: np.ndarray):
        self.V[:] = V0

    def set(self, dof: int, value: float):
        self.u[dof] = value

    def amax(self) -> float:
        return float(np.abs(self.u).max())

    def state(self) -> np.ndarray:
        return self.u.copy()


class _StencilStep:
    """One step of :func:`integrate`'s scheme with K applied matrix-free: fields stored apart (padded by
    the family's reach), the interior rows by the operator's stencil with the gains folded into its
    coefficients, the few end rows by small dense products, block by block of ``chunk`` points so that
    y = u + κV, the PD sums and the update of u and V run on data in cache (one pass over memory per
    step instead of one per operation and the matrix's ~25 values per point). The y of a block are
    formed one block ahead, before the update of u and V reaches the points they depend on."""

    def __init__(
        self,
        disc: Discrete,
        gd: np.ndarray,
        alpha: tuple,
        kappa: float,
        bG: np.ndarray,
        gd_field: tuple,
        chunk: int = CHUNK,
    ):
        op, nf = disc.op, disc.nf
        n, h = op.n, op.reach
        self.n, self.nf, self.h = n, nf, h
        U, V, Y = (np.zeros((nf, n + 2 * h)) for _ in range(3))
        self.U, self.V = U, V
        BG = bG.reshape(n, nf).T.copy()
        need = max(op.L, op.R) + 2 * h + 1
        P = max(chunk, need)
        starts = list(range(0, n, P))
        if len(starts) > 1 and n - starts[-1] < need:
            starts.pop()
        bounds = list(zip(starts, starts[1:] + [n]))
        width = max(p1 - p0 for p0, p1 in bounds)
        R, T = np.empty((nf, width)), np.empty(width)
        # end rows: dense blocks, rows and columns field-major, scaled by -gd of the row
        patches = []
        if op.L or op.R:
            rp = op.rows // nf
            for side, sel in ((0, rp < op.L), (1, rp >= n - op.R)):
                if not sel.any():
                    continue
                r, c, v = op.rows[sel], op.cols[sel], op.vals[sel]
                pr0 = 0 if side == 0 else n - op.R
                npr = op.L if side == 0 else op.R
                pc0 = 0 if side == 0 else int(c.min()) // nf
                npc = (int(c.max()) // nf + 1) - pc0
                Dm = np.zeros((nf * npr, nf * npc))
                np.add.at(Dm, ((r % nf) * npr + r // nf - pr0, (c % nf) * npc + c // nf - pc0), -gd[r] * v)
                patches.append((side, pr0, npr, pc0, npc, Dm))
        self._patches = patches

        def y_ops(p0, p1):
            out = []
            for f in range(nf):
                out.append((np.multiply, (V[f, h + p0 : h + p1], kappa, Y[f, h + p0 : h + p1])))
                out.append((np.add, (Y[f, h + p0 : h + p1], U[f, h + p0 : h + p1], Y[f, h + p0 : h + p1])))
            return out

        def patch_op(pr0, npr, pc0, npc, Dm, Rv):
            def run():
                Rv[...] = (Dm @ Y[:, h + pc0 : h + pc0 + npc].ravel()).reshape(nf, npr)

            return run, ()

        ops = y_ops(*bounds[0])
        for k, (p0, p1) in enumerate(bounds):
            if k + 1 < len(bounds):
                ops += y_ops(*bounds[k + 1])
            w = p1 - p0
            for a in range(nf):
                first = True
                for b in range(nf):
                    first = stencil_ops(
                        ops, R[a, :w], Y[b], h + p0, h + p1, op.stencil(a, b, -gd_field[a]), T[:w], first
                    )
                if first:
                    ops.append((R[a, :w].fill, (0.0,)))
            for _side, pr0, npr, pc0, npc, Dm in patches:
                if p0 <= pr0 and pr0 + npr <= p1:
                    ops.append(patch_op(pr0, npr, pc0, npc, Dm, R[:, pr0 - p0 : pr0 - p0 + npr]))
            for f in range(nf):
                Rf, Vf, Uf = R[f, :w], V[f, h + p0 : h + p1], U[f, h + p0 : h + p1]
                if np.any(BG[f, p0:p1]):
                    ops.append((np.add, (Rf, BG[f, p0:p1], Rf)))
                if alpha[f] != 1.0:
                    ops.append((np.multiply, (Vf, alpha[f], Vf)))
                ops.append((np.add, (Vf, Rf, Vf)))
                ops.append((np.add, (Uf, Vf, Uf)))
        self.ops = ops

    def step(self):
        for f, args in self.ops:
            f(*args)

    def field(self, f: int) -> np.ndarray:
        return self.U[f, self.h : self.h + self.n]

    @property
    def flat(self) -> np.ndarray:
        return self.U.reshape(-1)

    def on_state(self, M: sp.csr_matrix) -> sp.csr_matrix:
        """M (columns: interleaved DOFs) acting on ``flat`` (fields apart, padded by the reach)."""
        M = sp.csr_matrix(M)
        c = M.indices
        cols = (c % self.nf) * (self.n + 2 * self.h) + self.h + c // self.nf
        return sp.csr_matrix((M.data, cols, M.indptr), shape=(M.shape[0], self.U.size))

    def start(self, V0: np.ndarray):
        self.V[:, self.h : self.h + self.n] = V0.reshape(self.n, self.nf).T

    def velocity(self) -> np.ndarray:
        """V = dt v^{j-1/2} (interleaved)."""
        out = np.empty(self.nf * self.n)
        out.reshape(self.n, self.nf)[...] = self.V[:, self.h : self.h + self.n].T
        return out

    def set(self, dof: int, value: float):
        self.U[dof % self.nf, self.h + dof // self.nf] = value

    def amax(self) -> float:
        return float(np.abs(self.U).max())

    def state(self) -> np.ndarray:
        out = np.empty(self.nf * self.n)
        out.reshape(self.n, self.nf)[...] = self.U[:, self.h : self.h + self.n].T
        return out


def integrate(
    disc: Discrete,
    motions: dict,
    t_end: float | None,
    dt: float | None = None,
    damping: float = 0.0,
    damping_ratio: float | None = None,
    safety: float = 0.9,
    probes=None,
    record_every: int | None = None,
    output_interval: float | None = None,
    damp_rotations: bool = False,
    stabilisation: float = STABILISATION,
    steps: int | None = None,
    context: str = "",
    ledger_every: int | None = None,
) -> History:
    """Damped leapfrog velocity-Verlet (Eq. 7–11 / 38–44) from rest, loads as steps at t = 0 (v^{-1/2} =
    -dt/2 a^0 so that v^0 = 0; Eq. 12 sets v^{-1/2} = 0, which is first order for a step load).

    Per step: a^j = (b - K u^j)/m (one product with K); v̂ = v^{j-1/2} + dt (a^j - D v^{j-1/2});
    û^{j+1} = u^j + dt v̂; v^j = (û^{j+1} - u^{j-1})/(2dt); v^{j+1/2} = v^{j-1/2} + dt (a^j - D v^j);
    u^{j+1} = u^j + dt v^{j+1/2}. D = c_d/ρ acts on the translations only (Eq. 36–37: γ undamped).
    Prescribed DOFs follow their motions.
    ``damp_rotations``: the same D on the rotations too (not in the paper; without it the high
    shear-rotation modes are damped only through their coupling to w and ring for long).
    ``stabilisation`` κ: stiffness-proportional damping β K v^{j-1/2} with β = κ dt_ref (not in the
    paper), dt_ref = DEFAULT_SAFETY x the limit: the same β at every step (dt = dt_ref: β = κ dt).
    The boundary closures make K non-symmetric: some high modes have complex ω² and grow without it
    (measured step-map spectral radius 1 + 2e-2 on the Table 1 cantilever, 101 points, m = 3); κ = 0.2
    gives the highest mode ~18 % of critical and the first ~1e-4 %, and costs no extra product
    (K (u + β v)). The stable limit becomes 2 / (ω_max sqrt(1 + 2κ)) (the step map is stable while
    ω²dt² + 2βω²dt < 4: with β = 0.9κ x the limit the threshold is 1.017 x the limit at
    κ = 0.2). ``steps``: run this many steps
    (instead of up to ``t_end``). ``output_interval`` (s) or ``record_every`` (steps): the sampling of
    the histories and of the energy ledger (:class:`pdverify.dynamics.EnergyLedger`, v^j the mean of the
    half-step velocities around the sample; ``ledger_every``: at most every so many steps, default
    every sample up to ``WHOLE_DOFS`` unknowns, else every ``LEDGER_STRIDE`` steps). Raises SolveError
    when the stored energy outgrows the work put in (a growing mode;
    :meth:`~pdverify.dynamics.EnergyLedger.blown_up`); ``context`` (supports, horizon) goes into that
    message.

    Implementation: with V = dt v^{j+1/2} the step is y = u + κ V, V <- α V + G (b - K y), u <- u + V
    with G = (1 - c/2) dt²/m per DOF (zero on prescribed DOFs); K y is one CSR product up to
    ``WHOLE_DOFS`` unknowns, else the operator's stencil applied block by block (:class:`_StencilStep`)."""
    limit = stable_time_step(disc) / np.sqrt(1.0 + 2.0 * stabilisation)
    omega1 = None
    if damping_ratio is not None:
        omega1 = first_frequency(disc)
        damping = 2.0 * damping_ratio * omega1
    dt_ref = DEFAULT_SAFETY * limit
    dt = safety * limit if dt is None else float(dt)
    # β = κ dt_ref (seconds), the same for every step: with β = κ dt a smaller step damped the closures'
    # growing modes less (Table 1 cantilever: stable at 0.9 of the limit, blew up at 0.5 and 0.3) and the
    # scheme converged at order 1 in dt to a damping that vanishes. kappa: β / dt, what the step uses
    kappa = stabilisation if dt == dt_ref else stabilisation * dt_ref / dt
    if steps is None:
        steps = int(np.ceil(t_end / dt - 1e-9))
    if output_interval is not None:
        record_every = max(1, int(round(output_interval / dt)))
    record_every = record_every or max(1, steps // 2000)
    if ledger_every is None:  # a ledger sample costs ~3 products with K (on large grids ~4 steps each)
        ledger_every = record_every if nf_n(disc) <= WHOLE_DOFS else max(record_every, LEDGER_STRIDE)
    last_ledger = 0
    nf = disc.nf
    probes = np.atleast_1d(np.asarray(probes if probes is not None and len(probes) else [disc.x[-1] / 2], float))
    Pm = _interp_rows(disc.x, probes)
    # the whole DOF vector is advanced; prescribed DOFs have 1/m = 0 (no acceleration) and are
    # overwritten by their motions, so no index gathering per step
    # Eq. 7-11 in closed form: u^j - u^{j-1} = dt v^{j-1/2}, so v^j = (v^{j-1/2} + v̂)/2 and
    # v^{j+1/2} = alpha v^{j-1/2} + beta dt a^j with c = D dt, alpha = 1 - c + c²/2, beta = 1 - c/2
    field_c = [(damping if (tr or damp_rotations) else 0.0) * dt for tr in disc.field_translational]
    alpha = tuple(1.0 - c + c * c / 2 for c in field_c)
    gd_field = tuple((1.0 - c / 2) * dt * dt / mf for c, mf in zip(field_c, disc.field_mass))
    n = len(disc.x)
    gd = np.tile(np.asarray(gd_field, float), n)
    pres_dofs = np.array(sorted(disc.prescribed), dtype=np.int64)
    gd[pres_dofs] = 0.0
    bG = gd * disc.b
    alpha_dof = np.tile(np.asarray(alpha), n)
    if nf * n <= WHOLE_DOFS:
        st = _WholeStep(disc, gd, alpha_dof, kappa, bG)
        apply_K = disc.K.__matmul__
    else:
        st = _StencilStep(disc, gd, alpha, kappa, bG, gd_field)
        apply_K = disc.op.matvec
    free = np.ones(nf * n, bool)
    free[pres_dofs] = False
    pres = [(dof, mot) for dof, mot in motions.items() if mot is not None]
    moving = np.array([dof for dof, _ in pres], dtype=np.int64)
    ledger_K = apply_K
    if len(moving):  # the ledger's K: rows of the moving DOFs are their columns (symmetric completion)
        Kcols = _columns(disc, moving)

        def ledger_K(u):
            y = apply_K(u)
            y[moving] = Kcols @ u
            return y

    ledger = EnergyLedger(ledger_K, disc.mass, free, disc.b, np.tile(np.asarray(field_c) / dt, n), kappa * dt)
    if len(moving):  # the support work ∫ (K u - b)_p du_p, one small product per step
        Kp = st.on_state(Kcols)
        bp = disc.b[moving]
        react = Kp @ st.flat - bp
        up = np.zeros(len(moving))
    # from rest: v^0 = 0 with the loads acting from t = 0, so v^{-1/2} = -dt/2 a^0 (second order; Eq. 12's
    # v^{-1/2} = 0 starts the step load with v^0 = dt/2 a^0, an O(dt) error of every later state:
    # measured 2.5e-3 at 0.1 of the step on a clamped rod, first order in dt)
    V0 = -0.5 * dt * dt * disc.b / disc.mass
    V0[pres_dofs] = 0.0
    st.start(V0)
    times, vals, rots = [0.0], [np.zeros(len(probes))], [np.zeros(len(probes))]
    ledger.sample(0.0, np.zeros(nf * n), np.zeros(nf * n))
    with np.errstate(over="ignore", invalid="ignore"):
        for s in range(1, steps + 1):
            st.step()
            t = s * dt
            up_new = [float(motion_value(mot, t)) for _, mot in pres]
            for (dof, _), value in zip(pres, up_new):
                st.set(dof, value)
            if len(moving):
                r_new = Kp @ st.flat - bp
                up_new = np.array(up_new)
                ledger.add_support_step(0.5 * (react + r_new), up_new - up)
                react, up = r_new, up_new
            if s % record_every == 0 or s == steps:
                if s - last_ledger >= ledger_every or s == steps:
                    last_ledger = s
                    u, V = st.state(), st.velocity()
                    Vn = alpha_dof * V + gd * (disc.b - apply_K(u + kappa * V))
                    ratio = ledger.blown_up(ledger.sample(t, u, (V + Vn) / (2 * dt)))
                else:  # between ledger samples: only a non-finite state stops the run
                    ratio = None if np.isfinite(st.amax()) else float("inf")
                if ratio is not None:
                    raise SolveError(_blow_up_message(disc, dt, limit, s, t, ratio, stabilisation, context))
                times.append(t)
                vals.append(Pm @ st.field(0))
                if nf == 2:
                    rots.append(Pm @ st.field(1))
    return History(
        np.array(times),
        probes,
        np.array(vals),
        np.array(rots) if nf == 2 else None,
        st.state(),
        disc.x,
        dt,
        limit,
        steps,
        damping,
        stabilisation,
        omega1,
        ledger.arrays(),
        ledger.drift(),
    )


def _columns(disc: Discrete, dofs: np.ndarray) -> sp.csr_matrix:
    """K[:, dofs]ᵀ (len(dofs) x all DOFs) from the rows of the points within the operator's reach, the
    diagonal entry set so that the row gives no force in the rigid mode of the DOF's field (the end row's
    own diagonal belongs to an equation the support replaces, not to an energy)."""
    nf, n, h = disc.nf, len(disc.x), disc.op.reach
    pts = np.unique(np.clip((dofs // nf)[:, None] + np.arange(-h, h + 1)[None, :], 0, n - 1))
    rows = disc.op.rows_csr(pts).tocsc()[:, dofs].T.tocsr()  # (len(dofs) x len(pts) nf)
    sel = (nf * pts[:, None] + np.arange(nf)[None, :]).ravel()
    C = rows.tocoo()
    out = sp.csr_matrix((C.data, (C.row, sel[C.col])), shape=(len(dofs), nf * n)).tolil()
    for i, d in enumerate(dofs):  # the diagonal: no energy in the rigid mode of the DOF's field
        r = np.zeros(nf * n)
        if d % nf == 0:  # translation (w, u, twist): a rigid translation
            r[0::nf] = 1.0
        else:  # rotation γ: w = (x - x_d) θ, γ = θ
            r[0::nf], r[1::nf] = disc.x - disc.x[d // nf], 1.0
        out[i, d] = 0.0
        out[i, d] = -float(out[i].toarray().ravel() @ r) / r[d]
    return out.tocsr()


def _blow_up_message(
    disc: Discrete, dt: float, limit: float, s: int, t: float, ratio: float, kappa: float, context: str
) -> str:
    """One line: the step, the limit, what grew and what to change."""
    head = (
        f"dt = {dt:.4g} s: the explicit integration blew up at step {s} (t = {t:.4g} s; stored energy "
        f"{ratio:.2g} x the work put in)"
    )
    where = f" ({context})" if context else ""
    if dt > limit * (1 + 1e-9):
        return f"{head}; the stable limit is {limit:.4g} s; use time_step <= {limit:.4g} s or leave time_step out"
    detail = ""
    if disc.n_free <= 1500:  # a dense eigenvalue solve of a few seconds at most
        lam = np.linalg.eigvals(_mass_scaled(disc, disc.free).toarray())
        growth = np.abs(np.sqrt(lam.astype(complex)).imag)  # mode ~ exp(±i sqrt(λ) t)
        k = int(np.argmax(growth))
        if growth[k] > 0:
            detail = (
                f": M^-1 K has the eigenvalue {lam[k]:.3g} (the mode grows like exp({growth[k]:.3g} t), "
                "a real part below zero or an imaginary part)"
            )
    return (
        f"{head}; dt is below the stable limit {limit:.4g} s, so a smaller step does not help: the operator's "
        f"boundary closures{where} have a growing mode{detail}; change the horizon or the number of points, "
        f"or damp more (damping_ratio)"
    )


# -- the models -------------------------------------------------------------------------------

_OPTIONS = (
    Option(
        "points", int, 101, "material points along the beam, ends included (grid = cells: points - 1 cells)", minimum=6
    ),
    Option("horizon", int, 3, "horizon delta = m dx, m an integer (1 = nearest neighbours)", minimum=1),
    Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
    Option(
        "analysis",
        str,
        "auto",
        "auto (dynamic when the scene has [dynamics]) | static | dynamic",
        choices=("auto", "static", "dynamic"),
    ),
    Option(
        "grid",
        str,
        "nodes",
        "nodes (ends included) | cells (Section 4 cell centres; variant paper, static)",
        choices=("nodes", "cells"),
    ),
)


class _MoyerModel(Model):
    source = "Moyer & Miraglia, Peridynamic solutions for Timoshenko beams (seed 001)"
    options = _OPTIONS
    analyses = frozenset({"static", "dynamic"})  # the damped leapfrog-Verlet integrator (Eq. 7-11)
    end_motions = True  # prescribed end motions of [dynamics] (Example 2); the static part: their final value
    assembles = True
    variant_rules = (
        Rule(
            (("variant", "corrected"),),
            "grid",
            "the corrections are written for the node grid; grid = cells "
            "is the paper's Section 4 setup (variant = paper)",
            allowed=("nodes",),
        ),
    )

    def operator(self, scene: Scene, params: dict) -> Discrete:  # pragma: no cover - interface
        raise NotImplementedError

    def assemble(self, scene: Scene, params: dict) -> System:
        """The static system ``solve`` factorises (:func:`static_system`): the operator's band with the
        prescribed DOFs held (unit rows; a settled end motion moved to the right-hand side)."""
        disc = self.operator(scene, params)
        B, rhs, _ = static_system(scene, disc)
        return System(B, rhs, np.asarray(disc.free), dict(disc.info))

    def _dynamic(self, scene: Scene, params: dict) -> bool:
        if params["analysis"] == "dynamic" and scene.dynamics is None:
            raise InputError(
                "analysis = 'dynamic': the scene has no [dynamics] table; add one (end_time, ...) "
                "or use analysis = static"
            )
        dyn = params["analysis"] == "dynamic" or (params["analysis"] == "auto" and scene.dynamics is not None)
        moving = scene.dynamics is not None and any(
            getattr(em, k) is not None
            for em in (scene.dynamics.left, scene.dynamics.right)
            if em is not None
            for k in ("displacement", "axial", "rotation", "twist")
        )
        if params.get("grid") == "cells" and (dyn or moving):
            raise InputError(
                "grid = 'cells': the cell-centred grid takes no dynamics or prescribed end motions here "
                "(its end faces carry no points); use grid = nodes"
            )
        return dyn

    def bench_dynamics(self, scene: Scene, params: dict, steps: int = 200) -> float:
        """Point-updates per second of the explicit integration (``pdverify bench``)."""
        import time

        disc = self.operator(scene, params)
        t0 = time.perf_counter()
        h = integrate(disc, {}, t_end=None, steps=steps, record_every=steps)  # dt = 0.9 of the stable limit
        return len(disc.x) * h.steps / (time.perf_counter() - t0)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        if self._dynamic(scene, params) and scene.material.density is None:
            raise InputError("material.density: needed for dynamics; add density to the scene")
        with timer("assemble"):
            disc = self.operator(scene, params)
        m = params["horizon"]
        info = dict(disc.info, horizon_factor=m, variant=params["variant"])
        fields = {}
        writers = {}
        if self._dynamic(scene, params):
            d = scene.dynamics
            with timer("solve"):
                h = integrate(
                    disc,
                    prescribed_motions(scene, disc),
                    d.end_time,
                    dt=d.time_step,
                    damping=d.damping or 0.0,
                    damping_ratio=d.damping_ratio,
                    probes=d.probes,
                    output_interval=d.output_interval,
                    context=_context(scene, params),
                )
            u = h.final
            label = "w" if self.bending else ("u" if self.axial else "twist")
            series = {f"{label}(x={p:g})": h.values[:, k] for k, p in enumerate(h.probes)}
            if h.rotations is not None:
                series.update({f"rotation(x={p:g})": h.rotations[:, k] for k, p in enumerate(h.probes)})
            info.update(
                analysis="dynamic",
                dt=h.dt,
                dt_limit=h.dt_limit,
                steps=h.steps,
                damping=h.damping,
                omega1=h.omega1,
                stabilisation=h.stabilisation,
                energy_drift=h.energy_drift,
                history={
                    "t": h.t,
                    "series": series,
                    "energy": h.energy,
                    "ylabel": {"u": "axial displacement", "w": "deflection", "twist": "twist (rad)"}[label],
                },
            )
            writers[".csv"] = lambda path, h=h: Path(path).write_text(h.to_csv())
        else:
            with timer("assemble"):  # the band of K and the supports
                system = static_system(scene, disc)
            with timer("solve"):
                u, sinfo = static_solution(scene, disc, f"{self.name} ({params['variant']})", system)
            info.update(sinfo, analysis="static")
            flags = boundary_layer_warnings(scene, disc.x, FIT_POINTS + m)
            if flags:
                info.setdefault("warnings", []).extend(flags)
        return self.result(scene, params, disc, u, fields, info, timer, writers)


class PDRod(_MoyerModel):
    name = "pd-rod"
    title = "micro-elastic PD rod (axial), trapezoidal kernel"
    axial = True
    bending = False
    theory = "axial"
    load_types = frozenset({"point_force", "distributed"})  # their axial components

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = (scene.supports.left, scene.supports.right)
        if not set(sup) & set(ROD_HELD["axial"]):
            out.append(
                f"supports = {sup[0]}-{sup[1]}: neither end holds the axial displacement (a roller or guided "
                "end slides along the axis), so the rod is a mechanism; make one end clamped or pinned"
            )
        return out

    def operator(self, scene, params):
        return rod_operator(
            scene, params["points"], params["horizon"], params["variant"], kind="axial", grid=params["grid"]
        )

    def result(self, scene, params, disc, u, fields, info, timer, writers):
        x = disc.x
        N = scene.EA * np.gradient(u, x[1] - x[0], edge_order=2)
        fields = dict(fields, u=u, N=N)
        return Result(
            scene=scene.name,
            model=self.name,
            parameters=dict(params),
            x=x,
            w=np.zeros_like(x),
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings,
            info=info,
            writers=writers,
        )


class PDTorsion(_MoyerModel):
    name = "pd-torsion"
    title = "micro-elastic PD torsion (twist), the rod kernel with GJ (Section 5)"
    bending = False
    torsion = True
    theory = "torsion"
    load_types = frozenset({"point_torque", "distributed"})  # distributed: its torque component

    def operator(self, scene, params):
        disc = rod_operator(
            scene, params["points"], params["horizon"], params["variant"], kind="torsion", grid=params["grid"]
        )
        if self._dynamic(scene, params) and not np.all(np.isfinite(disc.mass)):
            raise InputError(
                "section: pd-torsion dynamics needs the polar moment of a rectangle; give width and height"
            )
        return disc

    def result(self, scene, params, disc, u, fields, info, timer, writers):
        x = disc.x
        T = scene.material.G * scene.section.J * np.gradient(u, x[1] - x[0], edge_order=2)
        fields = dict(fields, twist=u, T=T)
        return Result(
            scene=scene.name,
            model=self.name,
            parameters=dict(params),
            x=x,
            w=np.zeros_like(x),
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings,
            info=info,
            writers=writers,
        )


class PDTimoshenko(_MoyerModel):
    name = "pd-timoshenko"
    title = "micro-elastic PD Timoshenko beam (w, rotation)"
    theory = "timoshenko"

    def operator(self, scene, params):
        return beam_operator(scene, params["points"], params["horizon"], params["variant"], grid=params["grid"])

    def result(self, scene, params, disc, u, fields, info, timer, writers):
        x = disc.x
        dx = x[1] - x[0]
        w, g = u[0::2], u[1::2]
        M = scene.EI * np.gradient(g, dx, edge_order=2)
        # ψ as the operator sees it (interval averages at the point; paper: central differences):
        # np.gradient(w) - γ would carry the O(Δ²) error of w' multiplied by kGA
        psi = disc.psi[0] @ u + disc.psi[1]
        fields = dict(fields, M=M, V=-scene.kGA * psi, psi=psi)
        return Result(
            scene=scene.name,
            model=self.name,
            parameters=dict(params),
            x=x,
            w=w,
            rotation=g,
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings,
            info=info,
            writers=writers,
        )


def simulate(
    scene: Scene,
    params: dict | None = None,
    t_end: float | None = None,
    dt: float | None = None,
    damping: float | None = None,
    damping_ratio: float | None = None,
    safety: float = 0.9,
    probes=None,
    record_every: int | None = None,
    model: str = "pd-timoshenko",
    damp_rotations: bool = False,
    stabilisation: float = STABILISATION,
) -> History:
    """Transient run of ``pd-timoshenko`` (or ``model = "pd-rod"`` / ``"pd-torsion"``) on ``scene``: the scene's
    [dynamics] table gives the defaults (end time, damping, probes, prescribed end motions); the
    arguments override them (``record_every`` overrides the table's output_interval). Returns a :class:`History`."""
    m = {"pd-timoshenko": PDTimoshenko(), "pd-rod": PDRod(), "pd-torsion": PDTorsion()}[model]
    params = m.resolve(scene, params or {})
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density to the scene")
    d = scene.dynamics
    if t_end is None:
        if d is None:
            raise InputError("t_end: give the end time (the scene has no [dynamics] table)")
        t_end = d.end_time
    if d is not None:
        dt = d.time_step if dt is None else dt
        if damping is None and damping_ratio is None:
            damping, damping_ratio = d.damping, d.damping_ratio
        probes = d.probes if probes is None else probes
    output_interval = d.output_interval if (d is not None and record_every is None) else None
    disc = m.operator(scene, params)
    return integrate(
        disc,
        prescribed_motions(scene, disc),
        t_end,
        dt=dt,
        damping=damping or 0.0,
        damping_ratio=damping_ratio,
        safety=safety,
        probes=probes,
        record_every=record_every,
        output_interval=output_interval,
        damp_rotations=damp_rotations,
        stabilisation=stabilisation,
        context=_context(scene, params),
    )


def _context(scene: Scene, params: dict) -> str:
    """Where a growing mode comes from, for the blow-up message."""
    return (
        f"supports {scene.supports.left}-{scene.supports.right}, horizon = {params['horizon']}, "
        f"points = {params['points']}, variant {params['variant']}"
    )


MODELS = [PDRod(), PDTimoshenko(), PDTorsion()]
