"""The discrete operators of the micro-elastic PD rod, Timoshenko beam and torsion bar (Moyer & Miraglia 2014;
torsion: Section 5, Eq. 54–56, the rod kernel with GJ and twist θ): the PD sums over the real points
extended by the ghost closures of each support (:mod:`.ends`) and the load vector, as a
:class:`~.system.Discrete`.

Node grid x_i = i Δ, i = 0..n-1 (ends included), horizon δ = m Δ (integer m, option ``horizon``).

Rod (Section 2): ρ u_tt = ρ B I_i - c_d u_t + b with B = 2E/(δ² ρ) (Eq. 1–3) and the trapezoidal
peridynamic integral I_i = Σ_j c_j (u_{i+j} + u_{i-j} - 2u_i), c_j = w_j / j (Eq. 13–19;
w_j = 1, 1/2 at j = m; see ``kernels.rod_kernel``).

Timoshenko beam (Section 3), per unit length (w up, γ the cross-section rotation, ψ = w' - γ, Eq. 33):

    ρA w_tt = (kGA / 2δ) I_i + q                   I_i = PV∫ ψ(x_i + ε)/ε dε       (Eq. 34, 36, 47)
    ρI γ_tt = (2EI / δ²) J_i + (kGA / 2δ) K_i + μ   J_i = ∫ (γ(x_i+ε) - γ_i)/|ε| dε,  K_i = 2δ ψ_i (Eq. 35, 37, 48, 49)

i.e. C1 = kG/(2δρ), C2 = 2E/(ρδ²), C3 = AkG/(2ρδI) (Eq. 50); q is the line load, μ the line couple.
The static problem is the same discrete operator without inertia (rows: the real points; unknowns
interleaved w_0, γ_0, w_1, ...). It is assembled as written (sparse products of the ghost extension,
ψ and the PD sums) on a short grid of the same spacing only: away from the ends every row is the same
stencil, so the operator on any grid is that stencil plus the short grid's end rows
(:class:`~.kernels.EndPatched`, bit-identical to the whole-grid assembly). It is written
diagonal by diagonal into a :class:`~pdverify.numerics.band.Band`, the supported DOFs held by unit rows, and
solved by :func:`pdverify.numerics.linalg.solve_linear` (LU in place above 20,000 unknowns;
:func:`~.system.static_solution`). :func:`~.transient.integrate` integrates the same operator
in time with the damped leapfrog / velocity-Verlet scheme of Eq. 7–12 (38–44).

Variants
--------
``paper`` (as published): ψ at the nodes by central differences (Eq. 45–46), I by Eq. 47; ghost
points by Taylor extrapolation of w and γ (u) from the real points: first order (Eq. 20–21) at
Dirichlet ends (clamped; rod: clamped/pinned), second order with one-sided second-order differences
at the other ends (Section 4, Eq. 53); loads at an end as body force p/(AΔ) in the end cell.
Two printing errors had to be corrected to evaluate the sums at all: Eq. 16 gives l1 = 1 + k - m,
which runs over 2-m..0 (division by zero at k = m-1); the trapezoid of ∫_{-mΔ}^{-Δ} needs
l1 = k - m - 1 (as Eq. 47/48 index it), and Eq. 19's first sum then needs the minus sign of Eq. 15
(as Eq. 48 has it). Its weaknesses (tests/papers/moyer/test_pd_timoshenko.py): the pure extrapolation imposes
no traction condition at a free end (the mixed-boundary cantilever of Section 4 is singular with the
second-order extrapolation and wrong with the first-order one) and the central-difference ψ decouples
odd and even points (w' twice by central differences). Option ``grid = "cells"`` (paper variant,
static) is the literal Section 4 setup: n - 1 cells of Δ = L/(n - 1), points at the cell centres, ghost
cells by Taylor expansion about the end faces (a Dirichlet face anchored at zero): order 2 between Dirichlet ends,
and on Table 1 a tip deflection many times the exact one (docs/models/moyer.md gives the numbers).

``corrected`` (pd-rod's and pd-torsion's default; pd-timoshenko's is ``energy``, :mod:`.energy`):
1. ψ as interval averages: ψ̄_{i+1/2} = (w_{i+1} - w_i)/Δ - (-γ_{i-1} + 13γ_i + 13γ_{i+1} - γ_{i+2})/24
   (the exact average over [x_i, x_{i+1}] for a cubic γ), I by the midpoint rule on each unit interval
   (weights 1/(j - 1/2)), K_i = 2δ (ψ̄_{i-1/2} + ψ̄_{i+1/2})/2. Compact: no odd–even decoupling. With the
   plain mean (γ_i + γ_{i+1})/2 the shear force would carry an error kGA Δ² γ''/12 that grows like (Δ/h)²;
   with the 13/24 average the tip-loaded cantilever is exact to round-off.
2. ghost points at clamped and free ends from one polynomial per field (degree 3, fitted to the first 4
   real points) that satisfies the support's conditions exactly: clamped w = w_end, γ = γ_end; free
   EIγ' = M̄, kGA ψ = P̄ (end loads enter here); the end point's own equation holds where its value is not
   prescribed. The rod (and torsion bar) takes mirror images at every end (:func:`.ends.rod_mirror_ghosts`: odd
   where u is held, even where EA u' = N̄), so its operator times the end points' half cells is symmetric
   for every support pair and horizon. At the beam's pinned (roller) and guided ends the ghosts are mirror
   images (pinned: w odd, γ even; guided: w even, γ odd) plus the Taylor terms of the end conditions
   (pinned EIγ' = M̄, guided kGA ψ = P̄) and of the end's line load (:func:`.ends.mirror_ghosts`): the operator
   keeps the symmetry classes of the stencil, so between two such ends it has a real positive spectrum
   (cubic fits there would give it growing modes at every horizon).
3. at free ends the ghost ψ̄ are extrapolated from the real intervals' ψ̄ with ψ(end) =
   P̄/kGA imposed (quadratic, 4 intervals), not computed from the extrapolated w and γ, whose errors
   would enter the shear force multiplied by kGA/Δ, an error that grows with the slenderness.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.contract import missing_torsion_constant
from ...core.errors import InputError
from ...core.scene import ROD_HELD, Scene
from .ends import FIT_POINTS, beam_ghosts, rod_ghosts, shear_ghosts
from .energy import energy_beam_operator
from .kernels import EndPatched, node_loads, rod_kernel, shear_kernel, toeplitz
from .pieces import bond_stiffness, piece_stiffness
from .system import Discrete, beam_prescribed


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
            raise InputError(missing_torsion_constant(scene, "pd-torsion"))
        stiff, component, key = scene.material.G * J, "torque", "twist"
        inertia = scene.section.polar if scene.section.polar is not None else np.nan
    q, _, ends = node_loads(scene, x, component, ends_apart=(variant == "corrected"))
    prescribed = {}
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        if grid == "nodes" and sup in ROD_HELD[kind]:
            prescribed[0 if side == 0 else n - 1] = (key, side)
    # segments: the whole grid (each bond's own stiffness, no stencil away from the ends)
    Kc, bc = _rod_core(
        scene, n if not scene.uniform else min(n, _core_points(m)), dx, m, variant, stiff, ends, grid, kind
    )
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
    ends_stiff = (stiff, stiff)
    if not scene.uniform:  # each end's closure with its own segment's stiffness
        pieces = piece_stiffness(scene, "EA" if kind == "axial" else "GJ")
        ends_stiff = (pieces[0][2], pieces[-1][2])
    blocks = {
        side: rod_ghosts(scene, side, sup, variant, grid, kind, G, dx, ends_stiff[side], ends)
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right))
    }
    E, e0 = _extension(n, G, 1, blocks)
    c = rod_kernel(m)
    j = np.arange(1, m + 1)
    Iop = toeplitz(n, G, n + 2 * G, np.concatenate([[0], j, -j]), np.concatenate([[-2 * c.sum()], c, c]))
    if not scene.uniform:  # each bond's series stiffness over the reference (.pieces), the diagonal their sum
        x0 = 0.5 * dx if grid == "cells" else 0.0  # the first point: a cell's centre (Section 4) or the end
        Iop = _bonds_weighted(Iop, scene, n, G, dx, "EA" if kind == "axial" else "GJ", stiff, x0)
    B = 2.0 * stiff / delta**2  # ρA B = 2EA/δ² (Eq. 3): force per length per unit of I
    return (-B * (Iop @ E)).tocsr(), B * (Iop @ e0)


def _bonds_weighted(
    Iop: sp.csr_matrix, scene: Scene, n: int, G: int, dx: float, key: str, ref: float, x0: float = 0.0
) -> sp.csr_matrix:
    """The PD sum with each bond's series stiffness S_ab / ``ref`` (:func:`.pieces.bond_stiffness`; the extended
    grid's point e is at x = x0 + (e - G) Δ, ``x0`` the first real point), its diagonal minus the sum of the row's
    bonds."""
    C = Iop.tocoo()
    x_row = x0 + C.row * dx
    x_col = x0 + (C.col - G) * dx
    off = C.row + G != C.col
    vals = C.data.copy()
    vals[off] *= bond_stiffness(scene, x_row[off], x_col[off], key) / ref
    W = sp.csr_matrix((np.where(off, vals, 0.0), (C.row, C.col)), shape=Iop.shape)
    diag = sp.csr_matrix((-np.asarray(W.sum(axis=1)).ravel(), (np.arange(n), np.arange(n) + G)), shape=Iop.shape)
    return (W + diag).tocsr()


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


def segments_refusal(scene: Scene, variant: str) -> str:
    """The line refusing segments in pd-timoshenko's paper and corrected variants ("" where the variant takes them)."""
    if variant == "energy" or scene.uniform:
        return ""
    return (
        f"segments: variant {variant} of pd-timoshenko takes one section and one material (its ghost closures "
        "and shear sums are written for one); use variant energy (the default)"
    )


def beam_operator(scene: Scene, n: int, m: int, variant: str, grid: str = "nodes") -> Discrete:
    """Static operator of the PD Timoshenko beam on the interleaved DOFs (w_0, γ_0, w_1, γ_1, ...):
    assembled in full on a short grid (:func:`_beam_core`, Eq. 45–49 as written) and extended by its
    stencil (:class:`~.kernels.EndPatched`); variant ``energy``: :func:`.energy.energy_beam_operator`."""
    if variant == "energy":
        return energy_beam_operator(scene, n, m)
    if why := segments_refusal(scene, variant):
        raise InputError(why)
    n, x = _grid(scene, n, grid, variant, "pd-timoshenko")
    _check_grid(n, m, "pd-timoshenko")
    dx = x[1] - x[0]
    delta = m * dx
    kGA = scene.kGA
    rho = scene.material.density or 0.0
    q, mu, ends = node_loads(scene, x, "transverse", ends_apart=(variant == "corrected"))
    # cells: the end faces are not points, Dirichlet values enter the ghost cells
    prescribed = beam_prescribed(scene, n) if grid == "nodes" else {}
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
    blocks = {
        side: beam_ghosts(scene, side, sup, variant, grid, G, dx, ends)
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right))
    }
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
        psi_u, psi_0 = shear_ghosts(scene, psi_u, psi_0, n, G, m, ends, kGA)
    cw, cg = kGA / (2 * delta), 2 * EI / delta**2
    Kw = -(cw * (Sop @ psi_u))  # rows: w equations of the real points
    Kg = -(cg * (Jop @ Eg) + kGA * (Avg @ psi_u))
    bw_parts = [cw * (Sop @ psi_0)]
    bg_parts = [cg * (Jop @ eg), kGA * (Avg @ psi_0)]
    perm = np.empty(2 * n, dtype=np.int64)
    perm[0::2], perm[1::2] = np.arange(n), n + np.arange(n)
    K = sp.vstack([Kw, Kg]).tocsr()[perm]
    return K.tocsr(), bw_parts, bg_parts, (Avg @ psi_u).tocsr(), Avg @ psi_0
