"""Variant ``energy`` of pd-timoshenko: the corrected beam (Moyer & Miraglia 2014, :mod:`.operator`) written as the
gradient of a discrete energy, so that its operator is symmetric and positive semi-definite in the points' volumes:
M⁻¹K has a real, non-negative spectrum for every support pair, horizon and slenderness, and the
leapfrog step conserves a discrete energy exactly. No ghost points.

    U = ½ (EI/Δ) Σ_bonds ω_ab (γ_b - γ_a)²  +  ½ kGA Δ Σ_intervals ψ̄²,      W = Σ_i (b_w,i w_i + b_γ,i γ_i)

Bending: the bonds of the rod kernel (Eq. 14–19, c_j = w_j / j), ω_j = 2 c_j / m²: the interior rows of
∂U/∂γ are Δ times the corrected variant's (2EI/δ²) J_i (Eq. 48). Within Z = 3m + 1 points of an end the weights of
the bonds that stay inside the beam, and the points' volumes V_r, are the smallest change (least squares) of the
interior ones that makes every row's bond sum exact for a quadratic γ, the end row carrying the end's flux:

    Σ_b ω_rb (b - r) = [r = 0],     Σ_b ω_rb (b - r)² = 2 V_r                     (:func:`end_bonds`)

The volumes have to move: for a symmetric bond set whose weights beyond the zone are the interior ones, summing
Σ_b ω_rb (b³ - r³) over the rows gives the end flux, which fixes Σ_r r V_r; the trapezoid's volumes miss it for
m ≥ 2. The γ rows' inertia and loads use these volumes.

Shear: ψ̄ on each interval as in the corrected variant (the interval average of ψ = w' - γ, Eq. 33: the w difference
minus the 13/24 average of γ, (9, 19, -5, 1)/24 on the end intervals, the same cubic's average), with the local
energy ½ kGA Δ Σ ψ̄². Its w rows are kGA (ψ̄_{i+1/2} - ψ̄_{i-1/2}), the PD integral I of Eq. 47 with horizon Δ:
the local ψ that Eq. 37 puts in the γ rows is the adjoint of this shear integral only. With the horizon δ = mΔ in the
w rows the γ rows would need ψ smoothed over the horizon, and that smoothing has no symmetric boundary rows that keep
second order. So the horizon acts on the bending only.

The rows are divided by the points' volumes (w: the trapezoid's; γ: V_r), which gives the per-length form of the
other variants (:class:`~.system.Discrete`, its ``weights`` the volumes in units of Δ).
"""

from __future__ import annotations

from functools import cache, lru_cache

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError
from ...core.scene import HELD, Distributed, PointMoment, Scene
from ...numerics.families import stencil_operator
from .couples import couple_column, shear_free
from .kernels import EndPatched, node_loads, rod_kernel, toeplitz
from .pieces import bond_stiffness
from .resultants import interval_averages, moment_steps, point_loads, shear_at_points
from .system import Discrete, beam_prescribed

ZONE = 3  # bonds are refitted within ZONE m + 1 points of each end
ENERGY_HORIZONS = 12  # the fitted bonds' energy is positive definite for m = 1..12, not from 13 on (definite)
AVERAGE = np.array([-1.0, 13.0, 13.0, -1.0]) / 24  # interval average of a cubic from its 4 nearest points
END_AVERAGE = np.array([9.0, 19.0, -5.0, 1.0]) / 24  # the same over the first interval, from the end's 4 points
GAMMA = sp.csr_matrix(([1.0], ([1], [1])), shape=(2, 2))  # the γ slot of a point's interleaved DOFs (w, γ)


def bond_kernel(m: int) -> np.ndarray:
    """ω_j, j = 1..m (units EI/Δ): the bond form of the corrected J sum (Eq. 48),
    (EI/Δ) Σ_b ω_ab (γ_b - γ_a) = Δ (2EI/δ²) J_a at an interior point."""
    return 2.0 * rod_kernel(m) / m**2


def zone(m: int) -> int:
    """Points at each end whose bonds and volumes are refitted."""
    return ZONE * m + 1


@cache
def end_bonds(m: int) -> tuple[np.ndarray, np.ndarray]:
    """(ω, V) at the left end: the bond weights among the first Z = :func:`zone` points (Z x Z, symmetric, units
    EI/Δ) and their volumes (units Δ), fitted as the module docstring says. m = 1: the interior weights and the
    trapezoid (already exact)."""
    Z = zone(m)
    wj = bond_kernel(m)
    a, b = np.triu_indices(Z, 1)
    keep = b - a <= m
    a, b = a[keep], b[keep]
    d = b - a
    V0 = np.ones(Z)
    V0[0] = 0.5
    x0 = np.concatenate([wj[d - 1], V0])
    nb = len(d)
    # rows r = 0..Z-1: first moments, then second moments minus 2 V_r; bonds leaving the zone keep their weight
    C = np.zeros((2 * Z, nb + Z))
    rhs = np.zeros(2 * Z)
    idx = np.arange(nb)
    for p, block in ((1, slice(0, Z)), (2, slice(Z, 2 * Z))):
        C[block][a, idx] = d**p
        C[block][b, idx] = (-d) ** p
    r = np.arange(Z)[:, None]
    j = np.arange(1, m + 1)[None, :]
    outside = (r + j >= Z) * wj[None, :]  # bonds r -> r + j beyond the zone
    rhs[:Z] = (r[:, 0] == 0) - (outside * j).sum(1)
    rhs[Z:] = -(outside * j**2).sum(1)
    C[Z:, nb:] = -2.0 * np.eye(Z)
    x = x0 + C.T @ np.linalg.lstsq(C @ C.T, rhs - C @ x0, rcond=None)[0]
    if np.abs(C @ x - rhs).max() > 1e-8 or x[nb:].min() <= 0:  # no exact fit with positive volumes (large m)
        raise InputError(
            f"horizon = {m}: variant energy finds no consistent end bonds at this horizon (horizons 1-12 are "
            "positive definite); use horizon <= 12 or variant corrected"
        )
    w = np.zeros((Z, Z))
    w[a, b] = w[b, a] = x[:nb]
    V = x[nb:].copy()
    w.setflags(write=False), V.setflags(write=False)  # cached: shared by every call
    return w, V


def volumes(n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """(w volumes, γ volumes) of the n points in units of Δ: the trapezoid, and :func:`end_bonds`' at both ends."""
    vw = np.ones(n)
    vw[[0, -1]] = 0.5
    vg = vw.copy()
    _, V = end_bonds(m)
    Z = len(V)
    vg[:Z], vg[n - Z :] = V, V[::-1]
    return vw, vg


KEPT_POINTS = 20_000  # operators of grids up to this size are kept per (points, horizon): a study solves many loads


def bending_laplacian(n: int, m: int, bond=None) -> sp.csr_matrix:
    """Σ_b ω_ab (γ_a - γ_b) as an n x n matrix (units EI/Δ): the interior bonds, the fitted ones at both ends;
    ``bond``: (a, b) -> each bond's stiffness EI_ab (segments: :func:`.pieces.bond_stiffness`), then in units 1/Δ."""
    if bond is None and n <= KEPT_POINTS:
        return _plain_laplacian(n, m).copy()
    return _laplacian(n, m, bond)


@lru_cache(maxsize=32)
def _plain_laplacian(n: int, m: int) -> sp.csr_matrix:
    return _laplacian(n, m, None)


def _laplacian(n: int, m: int, bond) -> sp.csr_matrix:
    wj = bond_kernel(m)
    j = np.arange(1, m + 1)
    W = stencil_operator(n, 0, n, np.concatenate([j, -j]), np.concatenate([wj, wj]), truncate=True)
    w, _ = end_bonds(m)
    Z = len(w)
    r, c = np.nonzero(w)
    corners = sp.csr_matrix(
        (np.r_[w[r, c], w[r, c]], (np.r_[r, n - 1 - r], np.r_[c, n - 1 - c])), shape=(n, n)
    )  # the left end's fitted bonds and their mirror image at the right end
    inside = np.zeros(n, bool)
    inside[:Z] = inside[n - Z :] = True
    left = np.arange(n) < Z
    C = W.tocoo()
    same = (left[C.row] == left[C.col]) & inside[C.row] & inside[C.col]  # bonds within one end's zone
    W = sp.csr_matrix((C.data[~same], (C.row[~same], C.col[~same])), shape=(n, n)) + corners.tocsr()
    if bond is not None:
        C = W.tocoo()
        W = sp.csr_matrix((C.data * bond(C.row, C.col), (C.row, C.col)), shape=(n, n))
    return (sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W).tocsr()


def stiffnesses(scene: Scene, n: int, dx: float):
    """(kGA of the n - 1 intervals, the bonds' EI as a function of their points, for :func:`bending_laplacian`):
    the scene's own for a uniform beam (None for the bonds: the plain weights times EI), else the series stiffness
    of each interval and bond (:func:`.pieces.bond_stiffness`)."""
    if scene.uniform:
        return np.full(n - 1, scene.kGA), None
    x = np.arange(n) * dx
    return bond_stiffness(scene, x[:-1], x[1:], "kGA"), lambda a, b: bond_stiffness(scene, x[a], x[b], "EI")


def bond_moment(gamma: np.ndarray, m: int, EI: float, dx: float, bond=None) -> np.ndarray:
    """M = EIγ' at the points from the bond sums. For a quadratic γ the left end row's sum is M at the end of its
    cell, s_0 = V_0 Δ, and row r's (0 < r < n - 1) is M(s_r) - M(s_{r-1}), s_r = Σ_{k<=r} V_k Δ (the last row's is
    -M(s_{n-2})): M at the cells' ends s_0 .. s_{n-2} is the cumulative sum of the rows, interpolated linearly to the
    points and extrapolated to the end points."""
    n = len(gamma)
    rows = (
        -(EI / dx) * (bending_laplacian(n, m) @ gamma)
        if bond is None
        else -(bending_laplacian(n, m, bond) @ gamma) / dx
    )
    _, vg = volumes(n, m)
    s = np.cumsum(vg[:-1]) * dx
    Mf = np.cumsum(rows[:-1])
    x = np.arange(n) * dx
    M = np.interp(x, s, Mf)
    M[0] = Mf[0] - s[0] * (Mf[1] - Mf[0]) / (s[1] - s[0])
    M[-1] = Mf[-1] + (x[-1] - s[-1]) * (Mf[-1] - Mf[-2]) / (s[-1] - s[-2])
    return M


def moment_field(u: np.ndarray, scene: Scene, m: int, dx: float, reactions=(), kinks=()) -> np.ndarray:
    """The bending moment M = EIγ' at the points: M' = V = -kGA ψ integrated interval by interval (each interval's V̄
    is the average of V over it, so each step is exact to the solution's error), the couples (the scene's and the
    supports' ``reactions``, (position, force, couple)) as steps in the interval that holds them
    (:func:`.resultants.moment_steps`: a point on a couple carries the mean of its sides), and the constant from the
    bond sums' moment (:func:`bond_moment`): the median of their difference away from the ends' fitted zones (the bond
    sums smear a point couple over the horizon, which would bias a mean to first order). Why not the bond sums:
    near an end their cells (the fitted volumes) and the shear couple's (the columns of the cubic's interval
    averages) differ, so the discrete γ' is first order there. On a statically determinate beam (its steps are
    statics) with an end that holds no moment (pinned, roller, free, a spring without rotational stiffness) and takes
    no couple, M is zero there: the constant is statics instead (the median carries the bond sums' error, a few 1e-3 of
    max |M| on a coarse grid); on an indeterminate one the steps carry the reactions' error, which the median spreads
    and an anchor at one end would gather at the other."""
    n = len(u) // 2
    _, bond = stiffnesses(scene, n, dx)
    _, couples = point_loads(scene, reactions)
    M = moment_steps(interval_shear(u, scene, dx, kinks), np.arange(n) * dx, couples)
    if _reactions(scene) == 2:  # statically determinate: the reactions, and so the steps, are statics
        if _moment_free(scene, "left"):  # M_0 = 0 already
            return M
        if _moment_free(scene, "right"):
            return M - M[-1]
    flux = bond_moment(u[1::2], m, scene.EI, dx, bond)
    Z = 2 * zone(m)
    inner = slice(Z, n - Z) if n > 2 * Z + 2 else slice(None)
    return M + np.median(flux[inner] - M[inner])


def _reactions(scene: Scene) -> int:
    """The count of the beam's unknown reactions (forces and couples of the ends and of the supports inside): 2 for
    a statically determinate beam."""
    count = 0
    for sup in (scene.supports.left, scene.supports.right, *scene.supports.inner):
        kind = sup if isinstance(sup, str) else sup.type
        count += bool(sup.stiffness) + bool(sup.rotational_stiffness) if kind == "spring" else sum(HELD[kind][1:])
    return count


def _moment_free(scene: Scene, side: str) -> bool:
    """Whether the end ``side`` holds no moment and takes no couple: M is zero there."""
    end = getattr(scene.supports, side)
    free = end in ("pinned", "roller", "free") if isinstance(end, str) else not end.rotational_stiffness
    at = 0.0 if side == "left" else scene.length
    return free and not any(isinstance(ld, PointMoment) and ld.value and ld.position == at for ld in scene.loads)


def interval_shear(u: np.ndarray, scene: Scene, dx: float, kinks=()) -> np.ndarray:
    """V̄ of the n - 1 intervals: -kGA ψ̄ (segments: each interval's series kGA), the value at each interval's middle,
    as its average (:func:`.resultants.interval_averages`); ``kinks`` (position, couple C,
    singular part u_s) of the couples applied on their kink (:mod:`.couples`): their kink at the couple has no shear
    strain, so its intervals' ψ̄ (the 13/24 average of a kinked γ) are left out (:func:`.couples.shear_free`: the kink
    alone, not u_s's bends at the joints it crosses)."""
    n = len(u) // 2
    kga, _ = stiffnesses(scene, n, dx)
    x = np.arange(n) * dx
    for a, C, us in kinks:
        u = u - C * shear_free(scene, x, a, us)
    return interval_averages(-kga * (shear_strain(n, dx) @ u), x, scene)


def shear_strain(n: int, dx: float) -> sp.csr_matrix:
    """ψ̄ of the n - 1 intervals from the interleaved DOFs (w_0, γ_0, w_1, ...): (w_{i+1} - w_i)/Δ minus the cubic's
    interval average of γ."""
    D = toeplitz(n - 1, 0, n, [0, 1], [-1.0 / dx, 1.0 / dx])
    A = sp.vstack(
        [
            sp.csr_matrix((END_AVERAGE, ([0] * 4, np.arange(4))), shape=(1, n)),
            toeplitz(n - 3, 0, n, np.arange(4), AVERAGE),
            sp.csr_matrix((END_AVERAGE[::-1], ([0] * 4, np.arange(n - 4, n))), shape=(1, n)),
        ]
    )
    perm = np.column_stack((np.arange(n), n + np.arange(n))).ravel()  # (w_i, γ_i) interleaved
    return sp.hstack([D, -A]).tocsr()[:, perm]


def _core(scene: Scene, n: int, dx: float, m: int) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(K per length, ψ at the points) on n points: ∂U/∂u divided by the volumes, interleaved DOFs."""
    if scene.uniform:
        args = (float(scene.kGA), float(scene.EI), n, float(dx), m)
        if n > KEPT_POINTS:
            return _uniform_core(*args)
        K, P = _kept_uniform_core(*args)
        return K.copy(), P.copy()
    B = shear_strain(n, dx)  # segments: each interval's kGA and each bond's EI
    kga, bond = stiffnesses(scene, n, dx)
    Ke = B.T @ sp.diags(kga * dx) @ B + sp.kron(bending_laplacian(n, m, bond) / dx, GAMMA)
    return _per_volume(Ke, B, n, dx, m)


def _uniform_core(kGA: float, EI: float, n: int, dx: float, m: int) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """:func:`_core` of a uniform beam, which depends on its kGA and EI only."""
    B = shear_strain(n, dx)
    Ke = (kGA * dx) * (B.T @ B) + sp.kron(bending_laplacian(n, m) * (EI / dx), GAMMA)
    return _per_volume(Ke, B, n, dx, m)


_kept_uniform_core = lru_cache(maxsize=32)(_uniform_core)  # per grid and horizon: a study solves many loads


def _per_volume(Ke: sp.spmatrix, B: sp.spmatrix, n: int, dx: float, m: int) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(the energy's rows divided by the points' volumes, ψ at the points)."""
    vw, vg = volumes(n, m)
    K = sp.diags(1.0 / (np.column_stack((vw, vg)).ravel() * dx)) @ Ke
    return K.tocsr(), (to_points(n) @ B).tocsr()


def to_points(n: int) -> sp.csr_matrix:
    """Values at the n points from those of the n - 1 intervals: the mean of the two around a point, extrapolated
    linearly at the ends."""
    return sp.vstack(
        [
            sp.csr_matrix(([1.5, -0.5], ([0, 0], [0, 1])), shape=(1, n - 1)),
            toeplitz(n - 2, 0, n - 1, [0, 1], [0.5, 0.5]),
            sp.csr_matrix(([-0.5, 1.5], ([0, 0], [n - 3, n - 2])), shape=(1, n - 1)),
        ]
    ).tocsr()


def shear_force(u: np.ndarray, scene: Scene, dx: float, reactions=(), kinks=()) -> np.ndarray:
    """V = -kGA ψ at the points from the intervals' V̄ and the loads between them, the supports' ``reactions``
    ((position, force, couple)) included (:func:`.resultants.shear_at_points`)."""
    n = len(u) // 2
    forces, _ = point_loads(scene, reactions)
    return shear_at_points(interval_shear(u, scene, dx, kinks), np.arange(n) * dx, scene, forces)


@cache
def definite(m: int) -> float:
    """The lowest eigenvalue of the fitted bonds' Laplacian with one end held, over its largest (on 4 Z + 2m points,
    both ends' zones and the interior between them): positive when the bending energy is positive definite. It is
    for m = 1..12 and not from m = 13 on (an end mode of negative energy at each end,
    tests/papers/moyer/test_moyer_energy.py)."""
    n = 4 * zone(m) + 2 * m
    ev = np.linalg.eigvalsh(bending_laplacian(n, m).toarray()[1:, 1:])
    return float(ev[0] / ev[-1])


def energy_beam_operator(scene: Scene, n: int, m: int) -> Discrete:
    """The operator of variant ``energy`` on n points (x_i = iΔ, ends included), as a :class:`Discrete` whose rows
    are ∂U/∂u - b divided by the volumes: assembled in full on a short grid and extended by its stencil
    (:class:`~.kernels.EndPatched`), like the other variants."""
    if definite(m) <= 0:
        raise InputError(
            f"horizon = {m}: variant energy's fitted end bonds at this horizon have an end mode of negative bending "
            "energy (horizons 1-12 are positive definite); use horizon <= 12 or variant corrected"
        )
    need = max(2 * zone(m), 5)
    if n < need:
        raise InputError(
            f"points = {n}: model pd-timoshenko (variant energy) with horizon = {m} needs at least {need} points "
            "(its two ends' fitted bonds must not overlap); use more points or a smaller horizon"
        )
    x = np.linspace(0.0, scene.length, n)
    dx = x[1] - x[0]
    # both zones and stencil rows between; segments: the whole grid (no stencil away from the ends)
    Kc, Pc = _core(scene, n if not scene.uniform else min(n, 2 * zone(m) + 6 * m + 12), dx, m)
    vw, vg = volumes(n, m)
    op = EndPatched.from_core(Kc, 2, 2, n)
    weights = np.column_stack((vw, vg)).ravel()
    kinked, couples = [], np.zeros(2 * n)  # interior couples as the operator's action on their kink (.couples)
    for ld in scene.loads:
        if isinstance(ld, PointMoment) and 0.0 < ld.position < scene.length:
            got = couple_column(op, scene, x, m, weights, ld.position)
            if got is not None:
                kinked.append((ld, got[1]))
                couples += ld.value * got[0]
    rest = scene.model_copy(update={"loads": [ld for ld in scene.loads if not any(ld is k for k, _ in kinked)]})
    q, mu, ends = node_loads(rest, x, "transverse", ends_apart=True)
    spread = scene.model_copy(update={"loads": [ld for ld in scene.loads if isinstance(ld, Distributed)]})
    qd = node_loads(spread, x, "transverse", ends_apart=True)[0]
    bw = qd + (q - qd) / vw  # cell integrals of the line loads, point forces whole (their work)
    bg = mu / vg
    for side, end in ((0, 0), (1, n - 1)):
        bw[end] += ends[side][0] / (vw[end] * dx)
        bg[end] += ends[side][1] / (vg[end] * dx)
    prescribed = beam_prescribed(scene, n)
    rho = scene.material.density or 0.0
    info = {"ghosts_per_end": 0, "spacing": dx, "horizon": m * dx, "fitted_points_per_end": zone(m)}
    return Discrete(
        x,
        op,
        np.column_stack((bw, bg)).ravel() + couples,
        (rho * scene.section.A, rho * scene.section.I),
        (True, False),
        prescribed,
        2,
        info=info,
        psi=(EndPatched.from_core(Pc, 1, 2, n), np.zeros(n)),
        weights=weights,
        kinks=[(ld.position, ld.value, us) for ld, us in kinked],
    )
