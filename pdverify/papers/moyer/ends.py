"""The ends of the Moyer & Miraglia 2014 rod, Timoshenko beam and torsion bar: the ghost points beyond each
end as a map of the real points, w_ghost = R w_real + r0, for every support and variant.

``paper``: Taylor extrapolation of the real points (Eq. 20–21; first order at Dirichlet ends, second order with
one-sided differences at the others, Section 4, Eq. 53), on the node grid or the cell-centred grid of Section 4.
``corrected``: the rod (and torsion bar) takes mirror images at every end (:func:`rod_mirror_ghosts`), the beam
at its pinned (roller) and guided ends (:func:`mirror_ghosts`), with the Taylor terms of the end conditions and
loads the images lack; at clamped and free ends one cubic per field through the first four real points that
satisfies the support's conditions exactly (:func:`beam_ghosts`), and at free ends the ghost interval averages ψ̄
extrapolated from the real ones with the end shear imposed (:func:`shear_ghosts`). Why each choice: the
docstring of :mod:`.operator`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.scene import ROD_HELD, Distributed, Scene
from .kernels import average_ghosts, constrained_ghosts, taylor_rows, taylor_rows_cells
from .system import DIRICHLET

MIRRORED = ("pinned", "roller", "guided")  # corrected ends whose ghosts are mirror images (mirror_ghosts)
FIT_DEGREE, FIT_POINTS = 3, 4  # corrected ghosts: cubic per field through the first 4 real points
SHEAR_FIT_DEGREE, SHEAR_FIT_INTERVALS = 2, 4  # ψ̄ ghosts at free ends


def rod_ghosts(
    scene: Scene, side: int, sup: str, variant: str, grid: str, kind: str, G: int, dx: float, stiff: float, ends: dict
):
    """(R, r0, npts): the G ghosts of the rod's (``kind = "axial"``) or torsion bar's end ``side`` (0 left, 1
    right) with support ``sup`` from its first npts real points: Taylor rows (Eq. 20–21; ``grid = "cells"``:
    about the end face) in the paper variant, mirror images (:func:`rod_mirror_ghosts`) in the corrected one;
    ``stiff`` EA (GJ), ``ends[side][0]`` the end's force N̄ (torque T̄)."""
    fixed = sup in ROD_HELD[kind]
    if grid == "cells":
        return (taylor_rows_cells(G, 1 if fixed else 2, fixed), np.zeros(G), 4)
    if variant == "paper":
        return (taylor_rows(G, 1 if fixed else 2), np.zeros(G), 4)
    f = end_line_load(scene, side, "axial" if kind == "axial" else "torque")
    return rod_mirror_ghosts(fixed, G, ends[side][0], f, stiff, dx)


def beam_ghosts(scene: Scene, side: int, sup: str, variant: str, grid: str, G: int, dx: float, ends: dict):
    """(R (2G x 2 npts), r0, npts): the G ghosts of w and γ (field-major) beyond the beam's end ``side`` (0 left,
    1 right) with support ``sup`` from its first npts real points. Paper: Taylor rows per field (Eq. 20–21, first
    order at a Dirichlet end; ``grid = "cells"``: about the end face, Section 4); corrected: mirror images at
    pinned, roller and guided ends (:func:`mirror_ghosts`), else the cubic per field, fitted by least squares to w
    and L γ at FIT_POINTS real points, that satisfies the support's conditions: clamped w = w_end, γ = γ_end; free
    EI γ' = M̄ and kGA ψ = P̄ (``ends[side]`` = (P̄, C̄), s outward)."""
    EI, kGA = scene.EI, scene.kGA
    sigma = -1.0 if side == 0 else 1.0
    fix_w, fix_g = DIRICHLET[sup]
    if grid == "cells":  # the end faces are not points: Dirichlet values enter the ghost cells
        order = 1 if (fix_w and fix_g) else 2
        R = np.zeros((2 * G, 8))
        R[:G, :4] = taylor_rows_cells(G, order, fix_w)
        R[G:, 4:] = taylor_rows_cells(G, order, fix_g)
        return (R, np.zeros(2 * G), 4)
    if variant == "paper":
        T = taylor_rows(G, 1 if (fix_w and fix_g) else 2)
        R = np.kron(np.eye(2), T)
        return (R, np.zeros(2 * G), 4)
    P, C = ends[side]
    if sup in MIRRORED:
        return mirror_ghosts(sup, G, dx, sigma, P, C, end_line_load(scene, side), EI, kGA)
    # the fit is of w and L γ (both lengths, so that its least squares weighs them alike at any scale: of w and γ it
    # weighed metres against radians, and a scaled scene moved the ghosts by 1e-5 of themselves; with dx γ instead,
    # the clamped-free closures grew a mode the stabilisation does not hold at m = 2, 161 points)
    ell = scene.length
    con = []
    if fix_w:
        con.append(({(0, 0): 1.0}, {(0, 0): 1.0}, 0.0))
    if fix_g:
        con.append(({(1, 0): 1.0}, {(1, 0): 1.0}, 0.0))
    if not fix_g:  # moment: EI γ_s(0) = C̄ (both ends, s outward): (ell γ)_t = ell dx γ_s
        con.append(({(1, 1): 1.0}, {}, ell * dx * C / EI))
    if not fix_w:  # shear: kGA (w_s - σ γ) = P̄: w_t - σ (dx / ell) (ell γ) = dx P̄ / kGA
        con.append(({(0, 1): 1.0, (1, 0): -sigma * dx / ell}, {}, dx * P / kGA))
    R, r0 = constrained_ghosts(2, FIT_DEGREE, FIT_POINTS, G, con)
    ghost = np.r_[np.ones(G), np.full(G, 1.0 / ell)]  # the ghosts' ell γ back to γ
    data = np.r_[np.ones(FIT_POINTS), np.full(FIT_POINTS, ell)]  # the real points' γ as ell γ
    return (ghost[:, None] * R * data[None, :], ghost * r0, FIT_POINTS)


def end_line_load(scene: Scene, side: int, component: str = "transverse") -> float:
    """The line load of the distributed loads at the end point (0 outside their spans): ``component`` transverse
    (load.value), axial (load.axial) or torque (load.torque)."""
    xe = 0.0 if side == 0 else scene.length
    q = 0.0
    for load in scene.loads:
        if not isinstance(load, Distributed):
            continue
        v = {"transverse": load.value, "axial": load.axial, "torque": load.torque}[component]
        if v:
            a, b = scene.span(load)
            if a - 1e-12 * scene.length <= xe <= b + 1e-12 * scene.length:
                q += v * float(scene.load_shape(load, xe))
    return q


def rod_mirror_ghosts(held: bool, G: int, N: float, f: float, stiff: float, dx: float):
    """Ghosts of an end of the corrected rod (and torsion bar) as mirror images, (R, r0, G + 1): a held end is the
    centre of an odd deformation, a traction end (EA u_s = N̄, s outward) of an even one, the two classes the rod's
    stencil (Eq. 19) maps into themselves, so for every support pair and horizon the operator times the volumes
    (Δ/2 at an end point that moves) is symmetric, and its spectrum real. The end condition and the end's line
    load f enter r0 as the Taylor terms the image lacks (ξ runs into the rod; EA u_ξξ = -f):

    held:     u(-ξ) = -u(ξ) + 2 u_0 + ξ² u_ξξ,   u_ξξ = -f / EA;
    traction: u(-ξ) = u(ξ) - 2 ξ u_ξ,            u_ξ = -N̄ / EA.

    The first neglected terms (ξ⁴ u^(4) and ξ³ u^(3), from load gradients at the end) are O(Δ³) in the ghosts."""
    npts = G + 1
    t = np.arange(1, G + 1)
    xi = dx * t
    R, r0 = np.zeros((G, npts)), np.zeros(G)
    R[t - 1, t] = -1.0 if held else 1.0
    if held:
        R[:, 0] = 2.0
        r0[:] = -(xi**2) * f / stiff
    else:
        r0[:] = 2 * xi * N / stiff
    return R, r0, npts


def mirror_ghosts(sup: str, G: int, dx: float, sigma: float, P: float, C: float, q: float, EI: float, kGA: float):
    """Ghosts of a pinned (roller) or guided end of the corrected beam as mirror images, (R, r0, G + 1).

    A pinned end is the centre of an antisymmetric deformation (w odd, γ even about it), a guided end of a
    symmetric one (w even, γ odd): the two classes the beam's stencil maps into themselves. With the ghosts
    their images, the operator between two such ends is the stencil of the periodic beam restricted to one
    class: its spectrum is the dispersion relation's, real and positive (no growing mode at any horizon or
    slenderness). The end conditions and loads enter only r0, as the Taylor terms the image lacks, from the
    static equations of the corrected operator (kGA ψ' = -q, EI γ'' = -kGA ψ, w' = γ + ψ) at the end; ξ runs
    into the beam, τ = -σ = dξ/dx:

    pinned: w(-ξ) = -w(ξ) + 2 w_0 + ξ² w_ξξ + ξ⁴ w_ξξξξ/12,  w_ξξ = -τ C̄/EI - q/kGA, w_ξξξξ = q/EI;
            γ(-ξ) = γ(ξ) - 2 ξ γ_ξ - ξ³ γ_ξξξ/3,           γ_ξ = -C̄/EI, γ_ξξξ = τ q/EI;
    guided: w(-ξ) = w(ξ) - 2 ξ w_ξ - ξ³ w_ξξξ/3,            w_ξ = τ γ_0 - P̄/kGA, w_ξξξ = P̄/EI;
            γ(-ξ) = -γ(ξ) + 2 γ_0 + ξ² γ_ξξ,               γ_ξξ = -σ P̄/EI.

    The first neglected terms (line couples and load gradients at the end, ξ⁵ γ^(5), ξ⁶ w^(6)) are
    O(Δ³) in the ghosts, like the cubic fits' errors. The ghost ψ̄ follow from the images (no
    :func:`shear_ghosts` extrapolation)."""
    npts = G + 1
    t = np.arange(1, G + 1)
    xi = dx * t
    tau = -sigma
    R, r0 = np.zeros((2 * G, 2 * npts)), np.zeros(2 * G)
    w, g = t - 1, G + t - 1  # rows of the w and γ ghosts; columns: w of real point k is k, γ is npts + k
    if sup in ("pinned", "roller"):
        R[w, t], R[w, 0] = -1.0, 2.0
        r0[:G] = xi**2 * (-tau * C / EI - q / kGA) + xi**4 / 12 * (q / EI)
        R[g, npts + t] = 1.0
        r0[G:] = -2 * xi * (-C / EI) - xi**3 / 3 * (tau * q / EI)
    else:
        R[w, t], R[w, npts] = 1.0, -2 * xi * tau
        r0[:G] = -2 * xi * (-P / kGA) - xi**3 / 3 * (P / EI)
        R[g, npts + t], R[g, npts] = -1.0, 2.0
        r0[G:] = xi**2 * (-sigma * P / EI)
    return R, r0, npts


def shear_ghosts(scene, psi_u, psi_0, n, G, m, ends, kGA):
    """(ψ̄ map, constant) with the ghost ψ̄ of every free end extrapolated from the ψ̄ of the real intervals (degree
    SHEAR_FIT_DEGREE through SHEAR_FIT_INTERVALS of them) with ψ(end) = the end shear P̄/kGA imposed, instead of
    computed from extrapolated w and γ: an extrapolation error δ in w or γ would enter the shear force as kGA δ/Δ,
    which grows like (L/h)² (the corrected variant's item 3 in :mod:`.operator`)."""
    rows_all = psi_u.shape[0]
    rep_r, rep_c, rep_v = [], [], []
    c0 = np.zeros(rows_all)
    replaced = np.zeros(rows_all, bool)
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        if DIRICHLET[sup][0] or sup in MIRRORED:
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
