"""Model ``pd-higher-order``: PD higher-order beam (Yang, Oterkus & Oterkus 2020, seed 002).

Kinematics (Eq. 2–3): u(x, z) = z theta + z^3 theta*, w(x, z) = w + z^2 w*; four DOFs per material
point, ordered (theta, theta*, w, w*) as in Eq. 16a. Node grid x_k = k dx, k = 0..n-1 (ends included).
A section given by area/inertia is treated as the equivalent rectangle of height ``Section.depth``
(h = sqrt(12 I / A)); all energies are per unit cross-section area (V_k = A dx cancels A).

Strain energy (Eq. 9 made peridynamic by the transformations Eq. 14a–f / A38a–f, assembled in Eq. 15).
Per bond k -> j, xi = x_j - x_k, five bond measures, each ~ (a derivative) * xi for smooth fields::

    a = theta_j - theta_k          s = 2 xi w*_k          c = theta*_j - theta*_k
    g = w_j - w_k + xi theta_k     e = w*_j - w*_k + 3 xi theta*_k

    W_k = 1/(2h) Σ_j omega_kj Q(a, s, c, g, e),   Q = m^T C m   (C: ``coefficients``)
    Q = E/(1-nu^2) [h^3/12 (a^2 + 2 nu a s + s^2) + h^5/40 c (a + nu s) + h^7/448 c^2]
        + G [h g^2 + h^5/80 e^2 + h^3/6 g e]

with omega_kj = V_j / (delta^2 A |xi|) in the paper (Eq. 14: (1/delta^2 A) Σ ... / |xi| V_j).
The static equations are the Euler–Lagrange equations of Eq. 20–21 without inertia:
dU/du_k = b_k V_k, i.e. K u = F with K = Σ_k V_k d^2 W_k / du^2 (``bond_block`` per bond). Eq. 22c–d
(legible) are rows of this K (checked symbolically in tests/test_pd_higher_order.py); Eq. 22a–b are
damaged in the source and are taken from the energy instead. Loads (Eq. 16b): b_z on w, b_theta on
theta; a point force P gives F_w = P, a ccw point moment C gives F_theta = -C (the paper's theta is
minus the counter-clockwise rotation: gamma = theta + w' vanishes for w' = ccw rotation).

Variants
--------
``paper`` (faithful): delta = (m + 0.015) dx, omega = 1/(delta^2 A |xi|) V_j (Eq. 14) for the members
j = 1..J each side. Family volumes (option ``volumes``): ``partial`` (default) is the authors' convention
(Oterkus/Madenci, reference [17] and the sister paper seed 000's "volume correction"): a member with
delta - dx/2 < xi < delta + dx/2 gets the volume fraction beta = (delta + dx/2 - xi)/dx, so at 3.015 dx the
third neighbour carries 0.515 and Σ_j omega xi^2 = 2 Σ beta_d d / (delta/dx)^2 = 9.09/9.090225, i.e. the
continuous integral of Eq. A30 (δ^2) to 2.5e-5; ``full`` gives every member inside delta a whole cell,
2 (1 + 2 + 3) / 3.015^2 = 12/9.090225 = 1.320: a uniformly 32 % stiffer operator (not the paper's).
Boundaries (Appendix B) by fictitious layers of J points mirrored (option ``mirror``): ``point`` (default)
about the end point, which is a material point and is held (clamped: w, w* symmetric and theta, theta*
antisymmetric, w = w* = 0 at the end point, Eq. B39–B40; simply supported: the opposite, Eq. B41, w and w*
held); read from the text: the conditions are "for the material point adjacent to the clamped end" (zero
w and rotation there; zero w and curvature for the simple support), which an image about that point gives,
and the sister paper mirrors "with respect to the first adjacent material point which is fixed".
``boundary``: cell-centred points x = (k + 1/2) dx, dx = L / points, images i' of the real points i = 1..J
about the boundary between 1 and 1' (Eq. B39–B41 with 1' a point of the fictitious layer), clamped
w(1) = w*(1) = 0 (theta(1) then not zero), pinned and guided nothing held. Guided, not in the paper: the
clamped mirror without w = 0. A free end has no fictitious layer (truncated families). The equations are
those of Eq. 22 at the real points, the fictitious DOFs substituted by their images (a non-symmetric
system). Loads on the mid-surface (Eq. 16b) while the plane-stress reference loads the top face: the
simply supported benchmarks differ from it by that, not by the operator (option ``loads = faces``).

``corrected`` (default), each change measured in tests/test_pd_higher_order.py:
1. micro-modulus calibrated on the discrete family of each point: omega_kj = beta_j / (|xi| S_k),
   S_k = Σ_j beta_j |xi_j| over the actual family (partial volume beta = 1/2 for the member at
   delta = m dx), so every W_k is exact for linear fields, also on truncated families near the ends
   (the same operator as the paper's partial volumes in the interior, exact also on truncated families);
2. shear measures along the bond (option ``shear = path``, :func:`path_measures`): g = w_j - w_k + the
   trapezoid of theta over the bond's nearest-neighbour segments, e likewise with 3 theta*. With theta_k
   alone (Eq. 14d-f, ``shear = point``) a pure bending field leaves g = -theta' xi^2 / 2, a spurious shear
   energy G h theta'^2 delta^2 / 8 next to E h^3 theta'^2 / 12, a stiffening of ~ (G/E) 1.5 (delta/h)^2;
   with the bond-mean rotations (theta_k + theta_j)/2 (``shear = centred``) that is gone, but the J bonds'
   measures cannot all vanish for a cubic w (trapezoid errors ~ xi^3 w'''/12 that differ bond by bond), a
   penalty ~ (G/E) xi^4 / (h L)^2 times the bending energy: shear locking once dx is many depths. Summed over
   the segments every bond's g is a sum of nearest-neighbour measures, which can all vanish together
   (no locking); for smooth fields g = xi (w' + theta) + O(xi dx^2) as before;
3. no fictitious points (option ``ends = truncated``): the discrete energy U = Σ_k V_k W_k with
   trapezoidal volumes (dx/2 at the ends) is minimised with the essential conditions on the end point
   (clamped theta = theta* = w = w* = 0: the whole end face fixed; guided theta = theta* = 0; pinned
   w + h^2/20 w* = 0, option ``pin = face``); natural conditions (free faces, moment-free pins) come out of
   the minimisation as in a finite-element model. The paper's mirror ghosts force w' = 0 at a clamped
   end (zero shear strain where the shear force is largest);
4. loads where the plane-stress reference applies them (option ``loads = faces``): distributed loads and
   interior forces on the top face (work on w + h^2/4 w*), end forces as a parabolic shear traction
   (w + h^2/20 w*), end moments as a linear normal traction (theta + 3 h^2/20 theta*).
Observed order at fixed m = 3: 1.0 (the per-point calibration leaves the bond weights V_k omega_kj
unsymmetric in the end layers: a linear field is not in equilibrium there, ghost forces as in
quasicontinuum coupling; ghost points extrapolated by polynomials, ``ends = taylor``, do the same). With
m = 1 the weights are symmetric and the order is 2.0. A linear-programming search for end-layer bond
weights with the patch test and trapezoidal volumes found none for m = 2, 3.

Cost: the operator is assembled straight into LAPACK's band layout (:meth:`PDHigherOrder.assemble_band`):
the translation-invariant interior as one 4x4 block stencil (Eq. 15's Hessian with the interior weights),
the rows of the ~2J points next to each end (truncated or ghost families, end volumes, Appendix B's images,
end conditions) from the exact sparse route on a small window, the end conditions as unit rows
(``Band.fix``); the band is factorised in place above 20,000 unknowns. ``pdverify bench`` (cantilever,
100,000 points, 400,000 DOFs): assembly 0.02 s, whole run 1.2x the bare banded solve of the same matrix
(was 7x: 0.6 s of sparse products and CSR bookkeeping). The assembled entries are the same bits as the
whole-grid sparse route (tests/test_pd_higher_order.py).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..band import Band
from ..errors import InputError
from ..linalg import solve_linear
from ..registry import Model, Option, Rule, System
from ..result import Result, Timer
from ..scene import Distributed, PointForce, PointMoment, Scene
from .pd_common import cell_integral, family

NF = 4  # DOFs per point: theta, theta*, w, w*
TH, TS, W, WS = range(NF)
MIRROR = {  # (sign of theta, theta*, w, w*) of the fictitious images, Appendix B
    "clamped": np.array([-1.0, -1.0, 1.0, 1.0]),
    "guided": np.array([-1.0, -1.0, 1.0, 1.0]),
    "pinned": np.array([1.0, 1.0, -1.0, -1.0]),
    "roller": np.array([1.0, 1.0, -1.0, -1.0]),  # no axial unknown: roller = pinned
}

# -- kernels (arrays in, arrays out) ---------------------------------------------------------


def coefficients(E: float, nu: float, G: float, h: float) -> np.ndarray:
    """C (5x5) of Q = m^T C m for the bond measures m = (a, s, c, g, e): Eq. 9 / Eq. 15."""
    Ep = E / (1.0 - nu * nu)
    C = np.zeros((5, 5))
    C[0, 0] = C[1, 1] = Ep * h**3 / 12
    C[0, 1] = C[1, 0] = Ep * h**3 / 12 * nu
    C[2, 0] = C[0, 2] = Ep * h**5 / 80
    C[2, 1] = C[1, 2] = Ep * h**5 / 80 * nu
    C[2, 2] = Ep * h**7 / 448
    C[3, 3] = G * h
    C[4, 4] = G * h**5 / 80
    C[3, 4] = C[4, 3] = G * h**3 / 12
    return C


def bond_measures(xi: float, centred: bool = False) -> np.ndarray:
    """M (5x8): m = M (u_k, u_j), u = (theta, theta*, w, w*) of the points k and j = k + xi.
    ``centred``: the shear measures take the bond-mean rotations, g = w_j - w_k + xi (theta_k + theta_j)/2,
    e = w*_j - w*_k + 3 xi (theta*_k + theta*_j)/2 (corrected variant: no shear locking)."""
    M = np.zeros((5, 8))
    M[0, [TH, NF + TH]] = -1.0, 1.0  # a
    M[1, WS] = 2.0 * xi  # s
    M[2, [TS, NF + TS]] = -1.0, 1.0  # c
    if centred:
        M[3, [TH, W, NF + TH, NF + W]] = xi / 2, -1.0, xi / 2, 1.0  # g
        M[4, [TS, WS, NF + TS, NF + WS]] = 1.5 * xi, -1.0, 1.5 * xi, 1.0  # e
    else:
        M[3, [TH, W, NF + W]] = xi, -1.0, 1.0  # g
        M[4, [TS, WS, NF + WS]] = 3.0 * xi, -1.0, 1.0  # e
    return M


def path_measures(off: int, dx: float) -> np.ndarray:
    """M (5 x 4(|off| + 1)): the bond measures of k -> k + off on the points k + sign(off) a, a = 0..|off|, with
    the shear measures summed over the bond's nearest-neighbour segments (``shear = path``):
    g = w_j - w_k + Σ_a c_a theta_a, e = w*_j - w*_k + 3 Σ_a c_a theta*_a, c_a = xi/|off| (1/2 at the ends), the
    trapezoid rule of the rotation along the bond; one bond (|off| = 1) is the centred measure. If every
    nearest-neighbour shear measure vanishes so do all: no over-constraint of the J bonds (no locking)."""
    d = abs(off)
    xi = off * dx
    c = np.full(d + 1, xi / d)
    c[[0, d]] /= 2
    M = np.zeros((5, NF * (d + 1)))
    j = NF * d
    M[0, [TH, j + TH]] = -1.0, 1.0  # a
    M[1, WS] = 2.0 * xi  # s
    M[2, [TS, j + TS]] = -1.0, 1.0  # c
    M[3, [W, j + W]] = -1.0, 1.0  # g
    M[3, NF * np.arange(d + 1) + TH] += c
    M[4, [WS, j + WS]] = -1.0, 1.0  # e
    M[4, NF * np.arange(d + 1) + TS] += 3 * c
    return M


def bond_block(C: np.ndarray, xi: float, centred: bool = False) -> np.ndarray:
    """Hessian (8x8) of Q(M u) / 2 = the stiffness of one bond for unit weight."""
    M = bond_measures(xi, centred)
    return M.T @ C @ M


def bond_weights(
    n: int,
    m: float,
    dx: float,
    variant: str,
    volumes: np.ndarray,
    calibrate: str = "point",
    points: np.ndarray | None = None,
    fractions: str = "partial",
) -> dict[int, np.ndarray]:
    """{offset d (+-1..+-J): per-point weight V_k omega_kd} for the bonds k -> k + d (zero where k + d
    is outside the grid). Paper: omega = dx / (delta^2 |xi|) (Eq. 14, V_j = A dx); corrected: calibrated
    on the discrete family so that Σ_j omega_kj xi^2 = 1, per point on its actual (possibly truncated)
    family (``calibrate = "point"``) or on the full family (``"family"``, grids with ghost points).
    ``points``: the indices k (of the n-point grid) whose weights are wanted, ``volumes`` given on them
    (default all points); each weight is computed point by point, so a subset gets the same bits.
    ``fractions``: the paper's family volumes (:func:`family`)."""
    d, beta = family(m, dx, variant, fractions)
    k = np.arange(n) if points is None else np.asarray(points, np.int64)
    raw = {}
    for sgn in (1, -1):
        for dd, bb in zip(d, beta):
            off = int(sgn * dd)
            inside = ((k + off) >= 0) & ((k + off) < n)
            raw[off] = np.where(inside, bb / (dd * dx), 0.0)  # beta / |xi| (volume dx factored out below)
    if variant == "paper":
        delta = (m + 0.015) * dx
        return {off: volumes * r * dx / delta**2 for off, r in raw.items()}
    if calibrate == "point":
        S = sum(r * (abs(off) * dx) ** 2 for off, r in raw.items())  # Σ beta |xi| over the actual family
    else:
        S = 2.0 * float(np.sum(beta * d * dx))
    return {off: volumes * r / S for off, r in raw.items()}


def extrapolation(G: int, p: int) -> np.ndarray:
    """X (G x (p+1)): values at s = -1..-G (spacings beyond the end) of the degree-p polynomial through
    the first p+1 real points s = 0..p (Lagrange extrapolation, the same for the four fields)."""
    s_real = np.arange(p + 1, dtype=float)
    s_g = -np.arange(1, G + 1, dtype=float)
    V = s_real[:, None] ** np.arange(p + 1)
    return (s_g[:, None] ** np.arange(p + 1)) @ np.linalg.inv(V)


def taylor_map(n: int, G: int | tuple[int, int], p: int) -> sp.csr_matrix:
    """E: extended DOFs (G ghosts, n real, G ghosts) <- real DOFs; ghosts by polynomial extrapolation.
    ``G = (G_left, G_right)`` gives each end its own number of ghosts (0: none, a window at the other end)."""
    G = (G, G) if np.isscalar(G) else tuple(G)
    rows = [NF * (G[0] + np.arange(n))[:, None] + np.arange(NF)]
    cols = [NF * np.arange(n)[:, None] + np.arange(NF)]
    vals = [np.ones((n, NF))]
    for side, g_n in ((0, G[0]), (1, G[1])):
        if g_n == 0:
            continue
        X = extrapolation(g_n, p)
        g = np.arange(1, g_n + 1)
        ghost = G[0] - g if side == 0 else G[0] + n - 1 + g
        real = np.arange(p + 1) if side == 0 else n - 1 - np.arange(p + 1)
        r = NF * ghost[:, None, None] + np.arange(NF)[None, None, :]
        c = NF * real[None, :, None] + np.arange(NF)[None, None, :]
        rows.append(np.broadcast_to(r, (g_n, p + 1, NF)))
        cols.append(np.broadcast_to(c, (g_n, p + 1, NF)))
        vals.append(np.broadcast_to(X[:, :, None], (g_n, p + 1, NF)))
    return sp.csr_matrix(
        (
            np.concatenate([v.ravel() for v in vals]),
            (np.concatenate([r.ravel() for r in rows]), np.concatenate([c.ravel() for c in cols])),
        ),
        shape=(NF * (n + G[0] + G[1]), NF * n),
    )


def assemble_blocks(
    n: int,
    dx: float,
    C: np.ndarray,
    weights: dict[int, np.ndarray],
    h: float,
    centred: bool = False,
    path: bool = False,
) -> sp.csr_matrix:
    """K = Σ_bonds (weight / h) bond_block, as a block-banded matrix (4x4 blocks, point offsets -J..J),
    filled offset by offset with array slices (no loop over points or bonds), then BSR -> CSR.
    ``path``: the bond measures of :func:`path_measures` (a bond couples the points along it)."""
    J = max(abs(o) for o in weights)
    Kb = np.zeros((n, 2 * J + 1, NF, NF))
    for off, wt in weights.items():
        lo, hi = max(0, -off), min(n, n - off)
        t = wt[lo:hi, None, None]
        if path:
            M = path_measures(off, dx)
            B = M.T @ C @ M / h
            sg, d = (1 if off > 0 else -1), abs(off)
            for a in range(d + 1):
                for b in range(d + 1):
                    Kb[lo + sg * a : hi + sg * a, J + sg * (b - a)] += t * B[NF * a : NF * a + NF, NF * b : NF * b + NF]
            continue
        B = bond_block(C, off * dx, centred) / h
        Kb[lo:hi, J] += t * B[:NF, :NF]
        Kb[lo:hi, J + off] += t * B[:NF, NF:]
        Kb[lo + off : hi + off, J - off] += t * B[NF:, :NF]
        Kb[lo + off : hi + off, J] += t * B[NF:, NF:]
    cols = np.arange(n)[:, None] + np.arange(-J, J + 1)[None, :]
    ok = (cols >= 0) & (cols < n)
    indptr = np.r_[0, np.cumsum(ok.sum(axis=1))]
    K = sp.bsr_matrix((Kb[ok], cols[ok], indptr), shape=(NF * n, NF * n))
    return K.tocsr()


def energy(
    u: np.ndarray,
    x: np.ndarray,
    C: np.ndarray,
    weights: dict[int, np.ndarray],
    h: float,
    centred: bool = False,
    path: bool = False,
) -> float:
    """Strain energy U = Σ_k V_k W_k (Eq. 13, 15) evaluated directly from the bond measures (for the
    gradient checks: K must equal the Hessian of this function)."""
    u = np.asarray(u, float).reshape(-1, NF)
    n = len(x)
    dx = x[1] - x[0]
    U = 0.0
    for off, wt in weights.items():
        lo, hi = max(0, -off), min(n, n - off)
        uk, uj = u[lo:hi], u[lo + off : hi + off]
        xi = off * dx
        th = (uk[:, TH] + uj[:, TH]) / 2 if centred else uk[:, TH]
        ts = (uk[:, TS] + uj[:, TS]) / 2 if centred else uk[:, TS]
        if path:  # trapezoid of the rotations along the bond (path_measures), as a mean rotation
            d, sg = abs(off), (1 if off > 0 else -1)
            along = [u[lo + sg * a : hi + sg * a] for a in range(d + 1)]
            c = np.full(d + 1, 1.0 / d)
            c[[0, d]] /= 2
            th = sum(ca * ua[:, TH] for ca, ua in zip(c, along))
            ts = sum(ca * ua[:, TS] for ca, ua in zip(c, along))
        m = np.stack(
            [
                uj[:, TH] - uk[:, TH],
                2 * xi * uk[:, WS],
                uj[:, TS] - uk[:, TS],
                uj[:, W] - uk[:, W] + xi * th,
                uj[:, WS] - uk[:, WS] + 3 * xi * ts,
            ]
        )
        U += 0.5 / h * np.sum(wt[lo:hi] * np.einsum("pb,pq,qb->b", m, C, m))
    return U


def load_vector(scene: Scene, x: np.ndarray, faces: bool) -> np.ndarray:
    """F (n x 4): generalised forces (per unit area) on (theta, theta*, w, w*) of the real points.
    Distributed loads: cell integrals (cells [x_k -+ dx/2] within the beam); point forces and moments
    split linearly between the two nearest points (any position); Eq. 16b: F_w = b_z V, F_theta = b_theta V."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    h = scene.section.depth
    A = scene.section.A
    F = np.zeros((n, NF))
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    for load in scene.loads:
        if isinstance(load, Distributed):
            q = cell_integral(load, scene, lo, hi)
            F[:, W] += q
            if faces:
                F[:, WS] += q * h * h / 4
            continue
        pos = float(np.clip((load.position - x[0]) / dx, 0.0, n - 1))  # cell-centred grids: beyond the end points
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1:
            t = 0.0
        at_end = t == 0.0 and i in (0, n - 1)
        for node, wgt in ((i, 1.0 - t), (i + 1, t)):
            if wgt == 0.0:
                continue
            if isinstance(load, PointForce):
                F[node, W] += wgt * load.value
                if faces:
                    F[node, WS] += wgt * load.value * h * h * (1 / 20 if at_end else 1 / 4)
            elif isinstance(load, PointMoment):
                F[node, TH] -= wgt * load.value
                if faces and at_end:
                    F[node, TS] -= wgt * load.value * 3 * h * h / 20
    return F / A


def end_conditions(
    n: int, left: str, right: str, variant: str, pin: str, h: float, about: str = "point"
) -> tuple[list, list]:
    """(drop, tie): the DOFs held at zero and the ties (slave, master, c), u_slave = c u_master, of the end
    conditions. clamped: theta = theta* = w = w* = 0 (the end face fixed); guided: theta = theta* = 0;
    pinned: w = 0 and, in the paper, w* = 0 (Eq. B41's antisymmetric w*); ``pin = face``: w = -h^2/20 w*
    instead (zero parabola-weighted mean deflection of the end face); free: nothing. Paper mirrored about the
    boundary (``about = "boundary"``): clamped w(1) = w*(1) = 0 on the first point (Eq. B39; theta, theta*
    follow from the antisymmetric images, Eq. B40), pinned and guided nothing (the images carry them)."""
    drop, tie = [], []
    for sup, k in ((left, 0), (right, n - 1)):
        if variant == "paper" and about == "boundary":
            if sup == "clamped":
                drop += [NF * k + W, NF * k + WS]
            continue
        if sup == "clamped":
            drop += [NF * k + f for f in (TH, TS, W, WS)]
        elif sup == "guided":
            drop += [NF * k + f for f in (TH, TS)]
        elif sup in ("pinned", "roller"):  # no axial unknown: roller = pinned
            if variant == "paper":
                drop += [NF * k + W, NF * k + WS]
            elif pin == "face":
                tie.append((NF * k + W, NF * k + WS, -h * h / 20))
                drop.append(NF * k + W)
            else:
                drop.append(NF * k + W)
    return drop, tie


def constraint_map(
    n: int, left: str, right: str, variant: str, pin: str, h: float, numbering: str = "unknowns", about: str = "point"
) -> sp.csr_matrix:
    """T: u = T z with the end conditions built in (:func:`end_conditions`). ``numbering = "unknowns"``:
    T is 4n x unknowns (the held DOFs eliminated); ``"points"``: 4n x 4n, the numbering of u kept and the
    columns of the held DOFs zero (the band's form: unit rows added by ``Band.fix``)."""
    drop, tie = end_conditions(n, left, right, variant, pin, h, about)
    keep = np.ones(NF * n, bool)
    keep[drop] = False
    free = np.flatnonzero(keep)
    col = np.full(NF * n, -1)
    col[free] = free if numbering == "points" else np.arange(len(free))
    rows, cols, vals = list(free), list(col[free]), [1.0] * len(free)
    for slave, master, c in tie:
        rows.append(slave), cols.append(col[master]), vals.append(c)
    return sp.csr_matrix((vals, (rows, cols)), shape=(NF * n, NF * n if numbering == "points" else len(free)))


def mirror_map(n: int, G: tuple[int, int], left: str, right: str, about: str = "point") -> sp.csr_matrix:
    """P: extended DOFs (G[0] ghosts, n real, G[1] ghosts) <- real DOFs; ghost i' = sign * real i
    (Appendix B, Eq. B39-B41). ``about = "point"``: mirror about the end point (ghost j spacings out is the
    image of real point j spacings in); ``"boundary"``: mirror about the boundary half a spacing beyond the
    first point (cell-centred points: ghost i' at -(i - 1/2) dx is the image of real i at (i - 1/2) dx)."""
    shift = 1 if about == "boundary" else 0
    N = G[0] + n + G[1]
    rows = [NF * (G[0] + np.arange(n))[:, None] + np.arange(NF)]
    cols = [NF * np.arange(n)[:, None] + np.arange(NF)]
    vals = [np.ones((n, NF))]
    for side, sup, g in ((0, left, G[0]), (1, right, G[1])):
        if g == 0:
            continue
        j = np.arange(1, g + 1)
        ghost = G[0] - j if side == 0 else G[0] + n - 1 + j
        real = j - shift if side == 0 else n - 1 - j + shift
        rows.append(NF * ghost[:, None] + np.arange(NF))
        cols.append(NF * real[:, None] + np.arange(NF))
        vals.append(np.broadcast_to(MIRROR[sup], (g, NF)))
    return sp.csr_matrix(
        (
            np.concatenate([v.ravel() for v in vals]),
            (np.concatenate([r.ravel() for r in rows]), np.concatenate([c.ravel() for c in cols])),
        ),
        shape=(NF * N, NF * n),
    )


def uniform_blocks(
    C: np.ndarray, dx: float, weights: dict[int, float], h: float, centred: bool = False, path: bool = False
) -> dict[int, np.ndarray]:
    """{point offset o: 4x4 block K[p, p + o]} of a row p whose own bonds and whose partners' bonds all
    carry the interior weights ``weights`` (offset -> V omega): Eq. 15's Hessian summed bond by bond in
    the order of :func:`assemble_blocks` (the same bits as its interior rows)."""
    J = max(abs(o) for o in weights)
    blocks = {o: np.zeros((NF, NF)) for o in range(-J, J + 1)}
    for off, wt in weights.items():
        if path:
            M = path_measures(off, dx)
            B = M.T @ C @ M / h
            sg, d = (1 if off > 0 else -1), abs(off)
            for a in range(d + 1):
                for b in range(d + 1):
                    blocks[sg * (b - a)] += wt * B[NF * a : NF * a + NF, NF * b : NF * b + NF]
            continue
        B = bond_block(C, off * dx, centred) / h
        blocks[0] += wt * B[:NF, :NF]
        blocks[off] += wt * B[:NF, NF:]
        blocks[-off] += wt * B[NF:, :NF]
        blocks[0] += wt * B[NF:, NF:]
    return blocks


def extended_volumes(k: np.ndarray, n: int, G: tuple[int, int], dx: float, ends: str, variant: str) -> np.ndarray:
    """V_k / A of the extended points k (G[0] ghosts, the n real points, G[1] ghosts): the paper's mirror
    layers carry full volumes (Appendix B); otherwise ghosts carry none and the two end points dx/2."""
    k = np.asarray(k)
    if ends == "mirror" and variant == "paper":
        return np.full(k.shape, dx)
    real = (k >= G[0]) & (k < G[0] + n)
    end = (k == G[0]) | (k == G[0] + n - 1)
    return np.where(real, np.where(end, dx / 2, dx), 0.0)


def put_rows(B: Band, r0: int, c0: int, D: np.ndarray) -> Band:
    """Overwrite the rows r0 .. r0 + len(D) - 1 of the band with the dense rows D (columns c0 ..): the
    rows are cleared, then D's nonzero entries written (``Band`` has no assignment of entries)."""
    B.clear_rows(np.arange(r0, r0 + D.shape[0]))
    i, j = np.nonzero(D)
    return B.add_entries(r0 + i, c0 + j, D[i, j])


# -- the model -------------------------------------------------------------------------------


class PDHigherOrder(Model):
    name = "pd-higher-order"
    title = "PD higher-order beam (theta, theta*, w, w* per point)"
    source = "Yang, Oterkus & Oterkus 2020, Peridynamic higher-order beam formulation (seed 002)"
    theory = "higher-order"
    options = (
        Option(
            "points", int, 201, "material points along the beam, ends included (paper: 1001 for dx = 1 mm)", minimum=5
        ),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing (3 = the paper's 3.015 dx)", minimum=1.0),
        Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
        Option(
            "ends",
            str,
            "auto",
            "auto (mirror for paper, truncated for corrected) | mirror (Appendix B fictitious "
            "layers) | truncated (no ghosts, per-point calibration) | taylor (ghosts extrapolated by a polynomial "
            "of the real points, energy of the real points only)",
            choices=("auto", "mirror", "truncated", "taylor"),
        ),
        Option("ghost_degree", int, 3, "degree of the ghost extrapolation (ends = taylor)", minimum=1, maximum=6),
        Option(
            "pin",
            str,
            "auto",
            "pinned end: auto (mid for paper, face for corrected) | mid (w = 0 on the axis) | "
            "face (parabola-weighted mean of "
            "w + z^2 w* over the end face = 0: w + h^2/20 w* = 0, as fem-plane-stress pin = face)",
            choices=("auto", "mid", "face"),
        ),
        Option(
            "shear",
            str,
            "auto",
            "auto (point for paper, path for corrected) | point (Eq. 14d-f: theta_k xi) | "
            "centred (bond-mean rotations (theta_k + theta_j)/2 xi: no spurious G h theta'^2 delta^2 energy) | path "
            "(the rotations' trapezoid along the bond's segments: no shear locking of slender beams)",
            choices=("auto", "point", "centred", "path"),
        ),
        Option(
            "loads",
            str,
            "auto",
            "auto (mid for paper, faces for corrected) | mid (Eq. 16b: b_z on w, b_theta on theta) | "
            "faces (where the plane-stress "
            "reference puts them: top face, parabolic end shear, linear end traction)",
            choices=("auto", "mid", "faces"),
        ),
        Option(
            "volumes",
            str,
            "partial",
            "paper variant's family volumes: partial (the authors' convention: the "
            "member at 3 dx inside delta = 3.015 dx gets (delta + dx/2 - xi)/dx = 0.515) | full (whole cells "
            "inside delta)",
            choices=("partial", "full"),
        ),
        Option(
            "mirror",
            str,
            "point",
            "paper variant's fictitious layers (ends = mirror): point (points at the ends, "
            "images about the end point, which is held: the material point at the support, as in Appendix B's text "
            "and seed 000) | boundary (cell-centred points, images about the boundary half a spacing beyond "
            "point 1, clamped w(1) = w*(1) = 0, Eq. B39-B41 read with 1' distinct from 1)",
            choices=("boundary", "point"),
        ),
    )

    assembles = True
    _PAPER = (("variant", "paper"),)
    variant_rules = (
        Rule(
            _PAPER,
            "horizon",
            "Eq. 14: delta = (m + 0.015) dx, full volumes over whole families of m points; "
            "use variant = corrected for a fractional horizon",
            whole=True,
        ),
        Rule(
            _PAPER,
            "ends",
            "Appendix B: fictitious mirror layers (Eq. B39-B41), free ends truncated",
            allowed=("auto", "mirror"),
        ),
        Rule(
            _PAPER,
            "pin",
            "Eq. B41: a simply supported end holds w = w* = 0 at the end point (mid)",
            allowed=("auto", "mid"),
        ),
        Rule(_PAPER, "shear", "Eq. 14d-f: the shear measures use theta_k xi (point)", allowed=("auto", "point")),
        Rule(_PAPER, "loads", "Eq. 16b: b_z on w, b_theta on theta (mid)", allowed=("auto", "mid")),
    )

    def about(self, params: dict) -> str:
        """The mirror of the paper's fictitious layers: "boundary" or "point" (every other variant/end: "point")."""
        if params["variant"] == "paper" and self.ends(params) == "mirror":
            return params.get("mirror", "point")
        return "point"

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        """x_k = k dx, ends included; mirrored about the boundary: cell centres (k + 1/2) dx, dx = L / points."""
        n = params["points"]
        if self.about(params) == "boundary":
            return (np.arange(n) + 0.5) * (scene.length / n)
        return np.linspace(0.0, scene.length, n)

    def constants(self, scene: Scene):
        mat = scene.material
        h = scene.section.depth
        return coefficients(mat.E, mat.poissons_ratio, mat.G, h), h

    @staticmethod
    def choice(params: dict, key: str) -> str:
        """An option's value with ``auto`` resolved (paper: Appendix B and Eq. 16b; corrected: see the docstring)."""
        auto = {"ends": ("mirror", "truncated"), "pin": ("mid", "face"), "loads": ("mid", "faces")}[key]
        v = params.get(key, "auto")
        return auto[params["variant"] != "paper"] if v == "auto" else v

    def ends(self, params: dict) -> str:
        return self.choice(params, "ends")

    def assemble_band(self, scene: Scene, params: dict):
        """(B, b, (drop, tie), info): B u = b on the real points' interleaved DOFs u = (theta, theta*, w, w*)
        per point, assembled straight into a :class:`~pdverify.band.Band` (the matrix ``solve`` factorises).

        Every row whose point, bonds and partners' bonds lie away from the ends is the same 4x4 block
        stencil (Eq. 15's Hessian with the interior weights, :func:`uniform_blocks`), written diagonal by
        diagonal. The rows of the few points near each end (truncated families and their calibration,
        end volumes, ghost layers folded onto their images, the end conditions) are computed exactly on a
        small window of the extended grid, by the sparse route of Eq. 15 + Appendix B
        (:func:`assemble_blocks`, :func:`mirror_map` / :func:`taylor_map`, :func:`constraint_map`), and
        overwrite those rows. The ties of ``pin = face`` are folded in (u_slave = c u_master) and the held
        DOFs (``drop``, and the slaves) are unit rows with cleared columns (``Band.fix``): the numbering of
        u is kept, u_slave is restored after the solve."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        m, variant, ends = params["horizon"], params["variant"], self.ends(params)
        fractions, about = params.get("volumes", "partial"), self.about(params)
        d, _ = family(m, dx, variant, fractions)
        J = int(d.max())
        p = params["ghost_degree"]
        if 2 * J + 1 > n or (ends == "taylor" and p + 1 > n):
            raise InputError(
                f"horizon = {m:g}: the family ({J} points each side) does not fit in {n} points; "
                "use more points or a smaller horizon"
            )
        C, h = self.constants(scene)
        left, right = scene.supports.left, scene.supports.right
        pin = self.choice(params, "pin")
        info = {
            "depth": h,
            "ends": ends,
            "section": "rectangle"
            if scene.section.height is not None
            else f"equivalent rectangle h = sqrt(12 I / A) = {h:.6g} m",
        }
        shear = params.get("shear", "auto")
        path = shear == "path" or (shear == "auto" and variant != "paper")
        centred = shear == "centred"
        info["shear"] = "path" if path else "centred" if centred else "point"
        symmetric = not (
            ends == "mirror" and variant == "paper"
        )  # paper: Eq. 22 at the real points, images substituted
        if ends == "mirror":
            G, calibrate, reach = (0 if left == "free" else J, 0 if right == "free" else J), "family", J
            fold = lambda nw, Gw: mirror_map(nw, Gw, left, right, about)  # noqa: E731
            info.update(
                boundary=f"fictitious mirror layers (Appendix B) about the "
                f"{'boundary' if about == 'boundary' else 'end point'}, free ends truncated",
                ghosts_per_end=list(G),
            )
        elif ends == "taylor":
            G, calibrate, reach = (J, J), "family", p
            fold = lambda nw, Gw: taylor_map(nw, Gw, p)  # noqa: E731
            info.update(
                boundary=f"ghosts extrapolated (degree {p}), energy of the real points, essential end conditions",
                ghosts_per_end=[J, J],
            )
        else:
            G, calibrate, reach, fold = (0, 0), "point", 0, None
            info.update(boundary="truncated families (per-point calibration), essential end conditions")
        N = n + G[0] + G[1]

        def weights(k):  # V_k omega_kj of the extended points k (bond_weights on the whole extended grid)
            return bond_weights(
                N,
                m,
                dx,
                variant,
                extended_volumes(k, n, G, dx, ends, variant),
                calibrate,
                points=k,
                fractions=fractions,
            )

        def window(r0: int, r1: int) -> np.ndarray:
            """Dense K (end conditions included) of the real points r0..r1-1 with the ghosts of the ends the
            window reaches: exact in the rows whose bonds and ghost images lie in the window."""
            g = (G[0] if r0 == 0 else 0, G[1] if r1 == n else 0)
            nw = r1 - r0
            k = np.arange(G[0] + r0 - g[0], G[0] + r1 + g[1])
            Kx = assemble_blocks(len(k), dx, C, weights(k), h, centred, path)
            if fold is None:
                K = Kx
            elif symmetric:
                P = fold(nw, g)
                K = (P.T @ Kx @ P).tocsr()
            else:
                K = (Kx[NF * g[0] : NF * (g[0] + nw)] @ fold(nw, g)).tocsr()
            T = constraint_map(
                nw,
                left if r0 == 0 else "free",
                right if r1 == n else "free",
                variant,
                pin,
                h,
                numbering="points",
                about=about,
            )
            if symmetric:
                return (T.T @ K @ T).toarray()
            D = (K @ T).toarray()
            D[
                end_conditions(nw, left if r0 == 0 else "free", right if r1 == n else "free", variant, pin, h, about)[0]
            ] = 0.0
            return D

        rows_end = max(2 * J, reach + 1) + 1  # rows of each end from its window (beyond 2J: uniform; one spare)
        span = rows_end + J  # window points: those rows and their partners
        if n >= 2 * span:
            parts = [(0, span, 0, rows_end), (n - span, n, span - rows_end, span)]
        else:  # a small grid: one window is the whole matrix
            parts = [(0, n, 0, n)]
        dense = [(r0, a, window(r0, r1)[NF * a : NF * b]) for r0, r1, a, b in parts]
        bw = NF * J + NF - 1
        for _r0, a, D in dense:
            i, j = np.nonzero(D)
            if len(i):
                bw = max(bw, int(np.abs(j - (i + NF * a)).max()))
        B = Band(NF * n, bw, bw)
        if len(parts) > 1:
            mid = G[0] + n // 2
            interior = {off: float(wt[0]) for off, wt in weights(np.array([mid])).items()}
            B.add_block_stencil(NF, uniform_blocks(C, dx, interior, h, centred, path))
        for r0, a, D in dense:
            put_rows(B, NF * (r0 + a), NF * r0, D)
        drop, tie = end_conditions(n, left, right, variant, pin, h, about)
        F = load_vector(scene, x, self.choice(params, "loads") == "faces").ravel()
        b = F.copy()
        if symmetric:  # T^T F: the slave's load acts on its master (the paper variant has no ties)
            for slave, master, c in tie:
                b[master] += c * F[slave]
        B.fix(drop, b)
        wref = bond_weights(2 * J + 1, m, dx, variant, np.full(2 * J + 1, dx), calibrate="family", fractions=fractions)
        info["stiffness_factor"] = float(sum(w[J] * (abs(o) * dx) ** 2 for o, w in wref.items()) / dx)
        info.update(pin=pin, loads=self.choice(params, "loads"))
        if variant == "paper":
            info.update(volumes=fractions, mirror=about)
        return B, b, (drop, tie), info

    def assemble(self, scene: Scene, params: dict) -> System:
        """The band of :meth:`assemble_band` (the system ``solve`` factorises): u interleaved (theta, theta*,
        w, w*) per real point, free = the DOFs not held; ``info["ties"]``: the (slave, master, c) of
        ``pin = face`` (u_slave = c u_master, restored after the solve)."""
        B, b, (drop, tie), info = self.assemble_band(scene, params)
        return System(B, b, np.delete(np.arange(B.n), drop), dict(info, ties=tie))

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("assemble"):
            system = self.assemble(scene, params)
            binfo = dict(system.info)
            tie = binfo.pop("ties")
        with timer("solve"):
            u, info = solve_linear(system.matrix, system.rhs, what=f"pd-higher-order ({params['variant']})")
            for slave, master, c in tie:
                u[slave] = c * u[master]
        n = params["points"]
        u = u.reshape(n, NF)
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        fields = {"theta": u[:, TH], "theta_star": u[:, TS], "w_star": u[:, WS]}
        return Result(
            scene=scene.name,
            model=self.name,
            parameters=dict(params),
            x=x,
            w=u[:, W].copy(),
            rotation=-u[:, TH],
            fields=fields,
            dofs=system.unknowns,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDHigherOrder()]
