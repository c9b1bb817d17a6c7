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
``paper`` (faithful): delta = (m + 0.015) dx, full volumes V_j = A dx, omega = 1/(delta^2 A |xi|) V_j
for j = 1..floor(delta/dx) each side; clamped and simply supported ends by fictitious layers of
floor(delta/dx) points mirrored about the end point (Appendix B: clamped w, w* symmetric and theta,
theta* antisymmetric, w = w* = 0 at the end point, Eq. B39–B40; simply supported the opposite,
Eq. B41; guided, not in the paper: the clamped mirror without w = 0); a free end has no fictitious
layer (truncated families). The equations are those of Eq. 22 at the real points, the fictitious
DOFs substituted by their images (a non-symmetric system).
Measured defect: with full volumes Σ_j omega xi^2 = 2 dx^2 (1 + 2 + 3) / (3.015 dx)^2 = 1.320, not 1
(the continuous integral of Eq. A30 is δ^2 but the volumes of the outer members reach 3.5 dx): the
model is 32 % too stiff everywhere and does not converge under refinement at fixed m.

``corrected`` (default), each change measured in tests/test_pd_higher_order.py:
1. micro-modulus calibrated on the discrete family of each point: omega_kj = beta_j / (|xi| S_k),
   S_k = Σ_j beta_j |xi_j| over the actual family (partial volume beta = 1/2 for the member at
   delta = m dx), so every W_k is exact for linear fields, also on truncated families near the ends
   (removes the paper's factor 1.32: -24 % -> within 0.22 % of converged plane stress at dx = 1 mm);
2. bond-centred shear measures g = w_j - w_k + xi (theta_k + theta_j)/2, e = w*_j - w*_k +
   3 xi (theta*_k + theta*_j)/2 (option ``shear``): with theta_k alone a pure bending field leaves
   g = -theta' xi^2 / 2, a spurious shear energy G h theta'^2 delta^2 / 8 next to E h^3 theta'^2 / 12, i.e.
   a stiffening of ~ (G/E) 1.5 (delta/h)^2 (measured 5 % at dx = h/10, m = 3: a locking-like defect);
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

Cost: block-banded assembly (4x4 blocks per point offset, filled offset by offset with array slices),
banded LU: 100,001 points (400,000 DOFs) in ~1.9 s.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..errors import InputError
from ..linalg import solve_linear
from ..registry import Model, Option
from ..result import Result, Timer
from ..scene import Distributed, PointForce, PointMoment, Scene
from .pd_eb import _cell_integral, partial_volumes

NF = 4  # DOFs per point: theta, theta*, w, w*
TH, TS, W, WS = range(NF)
MIRROR = {  # (sign of theta, theta*, w, w*) of the fictitious images, Appendix B
    "clamped": np.array([-1.0, -1.0, 1.0, 1.0]),
    "guided": np.array([-1.0, -1.0, 1.0, 1.0]),
    "pinned": np.array([1.0, 1.0, -1.0, -1.0]),
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


def bond_block(C: np.ndarray, xi: float, centred: bool = False) -> np.ndarray:
    """Hessian (8x8) of Q(M u) / 2 = the stiffness of one bond for unit weight."""
    M = bond_measures(xi, centred)
    return M.T @ C @ M


def family(m: float, dx: float, variant: str) -> tuple[np.ndarray, np.ndarray]:
    """Offsets d = 1..J and their volume fractions beta_d (paper: full volumes inside (m + 0.015) dx)."""
    if variant == "paper":
        J = int(np.floor(m + 0.015 + 1e-12))
        return np.arange(1, J + 1), np.ones(J)
    return partial_volumes(m)


def bond_weights(n: int, m: float, dx: float, variant: str, volumes: np.ndarray,
                 calibrate: str = "point") -> dict[int, np.ndarray]:
    """{offset d (+-1..+-J): per-point weight V_k omega_kd} for the bonds k -> k + d (zero where k + d
    is outside the grid). Paper: omega = dx / (delta^2 |xi|) (Eq. 14, V_j = A dx); corrected: calibrated
    on the discrete family so that Σ_j omega_kj xi^2 = 1, per point on its actual (possibly truncated)
    family (``calibrate = "point"``) or on the full family (``"family"``, grids with ghost points)."""
    d, beta = family(m, dx, variant)
    k = np.arange(n)
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


def taylor_map(n: int, G: int, p: int) -> sp.csr_matrix:
    """E: extended DOFs (G ghosts, n real, G ghosts) <- real DOFs; ghosts by polynomial extrapolation."""
    X = extrapolation(G, p)
    rows = [NF * (G + np.arange(n))[:, None] + np.arange(NF)]
    cols = [NF * np.arange(n)[:, None] + np.arange(NF)]
    vals = [np.ones((n, NF))]
    for side in (0, 1):
        g = np.arange(1, G + 1)
        ghost = G - g if side == 0 else G + n - 1 + g
        real = np.arange(p + 1) if side == 0 else n - 1 - np.arange(p + 1)
        r = NF * ghost[:, None, None] + np.arange(NF)[None, None, :]
        c = NF * real[None, :, None] + np.arange(NF)[None, None, :]
        rows.append(np.broadcast_to(r, (G, p + 1, NF)))
        cols.append(np.broadcast_to(c, (G, p + 1, NF)))
        vals.append(np.broadcast_to(X[:, :, None], (G, p + 1, NF)))
    return sp.csr_matrix((np.concatenate([v.ravel() for v in vals]),
                          (np.concatenate([r.ravel() for r in rows]), np.concatenate([c.ravel() for c in cols]))),
                         shape=(NF * (n + 2 * G), NF * n))


def assemble_blocks(n: int, dx: float, C: np.ndarray, weights: dict[int, np.ndarray], h: float,
                    centred: bool = False) -> sp.csr_matrix:
    """K = Σ_bonds (weight / h) bond_block, as a block-banded matrix (4x4 blocks, point offsets -J..J),
    filled offset by offset with array slices (no loop over points or bonds), then BSR -> CSR."""
    J = max(abs(o) for o in weights)
    Kb = np.zeros((n, 2 * J + 1, NF, NF))
    for off, wt in weights.items():
        B = bond_block(C, off * dx, centred) / h
        lo, hi = max(0, -off), min(n, n - off)
        t = wt[lo:hi, None, None]
        Kb[lo:hi, J] += t * B[:NF, :NF]
        Kb[lo:hi, J + off] += t * B[:NF, NF:]
        Kb[lo + off:hi + off, J - off] += t * B[NF:, :NF]
        Kb[lo + off:hi + off, J] += t * B[NF:, NF:]
    cols = np.arange(n)[:, None] + np.arange(-J, J + 1)[None, :]
    ok = (cols >= 0) & (cols < n)
    indptr = np.r_[0, np.cumsum(ok.sum(axis=1))]
    K = sp.bsr_matrix((Kb[ok], cols[ok], indptr), shape=(NF * n, NF * n))
    return K.tocsr()


def energy(u: np.ndarray, x: np.ndarray, C: np.ndarray, weights: dict[int, np.ndarray], h: float,
           centred: bool = False) -> float:
    """Strain energy U = Σ_k V_k W_k (Eq. 13, 15) evaluated directly from the bond measures (for the
    gradient checks: K must equal the Hessian of this function)."""
    u = np.asarray(u, float).reshape(-1, NF)
    n = len(x)
    dx = x[1] - x[0]
    U = 0.0
    for off, wt in weights.items():
        lo, hi = max(0, -off), min(n, n - off)
        uk, uj = u[lo:hi], u[lo + off:hi + off]
        xi = off * dx
        th = (uk[:, TH] + uj[:, TH]) / 2 if centred else uk[:, TH]
        ts = (uk[:, TS] + uj[:, TS]) / 2 if centred else uk[:, TS]
        m = np.stack([uj[:, TH] - uk[:, TH], 2 * xi * uk[:, WS], uj[:, TS] - uk[:, TS],
                      uj[:, W] - uk[:, W] + xi * th, uj[:, WS] - uk[:, WS] + 3 * xi * ts])
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
            q = _cell_integral(load, scene, lo, hi)
            F[:, W] += q
            if faces:
                F[:, WS] += q * h * h / 4
            continue
        pos = load.position / dx
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


def constraint_map(n: int, left: str, right: str, variant: str, pin: str, h: float) -> sp.csr_matrix:
    """T (4n x unknowns): u = T z with the end conditions built in. clamped: theta = theta* = w = w* = 0
    (the end face fixed); guided: theta = theta* = 0; pinned: w = 0 and, in the paper, w* = 0 (Eq. B41's
    antisymmetric w*); ``pin = face``: w = -h^2/20 w* instead (zero parabola-weighted mean deflection
    of the end face); free: nothing."""
    drop, tie = [], []
    for sup, k in ((left, 0), (right, n - 1)):
        if sup == "clamped":
            drop += [NF * k + f for f in (TH, TS, W, WS)]
        elif sup == "guided":
            drop += [NF * k + f for f in (TH, TS)]
        elif sup == "pinned":
            if variant == "paper":
                drop += [NF * k + W, NF * k + WS]
            elif pin == "face":
                tie.append((NF * k + W, NF * k + WS))
                drop.append(NF * k + W)
            else:
                drop.append(NF * k + W)
    keep = np.ones(NF * n, bool)
    keep[drop] = False
    free = np.flatnonzero(keep)
    col = np.full(NF * n, -1)
    col[free] = np.arange(len(free))
    rows, cols, vals = list(free), list(col[free]), [1.0] * len(free)
    for slave, master in tie:
        rows.append(slave), cols.append(col[master]), vals.append(-h * h / 20)
    return sp.csr_matrix((vals, (rows, cols)), shape=(NF * n, len(free)))


def mirror_map(n: int, G: tuple[int, int], left: str, right: str) -> sp.csr_matrix:
    """P: extended DOFs (G[0] ghosts, n real, G[1] ghosts) <- real DOFs; ghost i' = sign * real i
    (mirror about the end point, Appendix B)."""
    N = G[0] + n + G[1]
    rows = [NF * (G[0] + np.arange(n))[:, None] + np.arange(NF)]
    cols = [NF * np.arange(n)[:, None] + np.arange(NF)]
    vals = [np.ones((n, NF))]
    for side, sup, g in ((0, left, G[0]), (1, right, G[1])):
        if g == 0:
            continue
        j = np.arange(1, g + 1)
        ghost = G[0] - j if side == 0 else G[0] + n - 1 + j
        real = j if side == 0 else n - 1 - j
        rows.append(NF * ghost[:, None] + np.arange(NF))
        cols.append(NF * real[:, None] + np.arange(NF))
        vals.append(np.broadcast_to(MIRROR[sup], (g, NF)))
    return sp.csr_matrix((np.concatenate([v.ravel() for v in vals]),
                          (np.concatenate([r.ravel() for r in rows]), np.concatenate([c.ravel() for c in cols]))),
                         shape=(NF * N, NF * n))


# -- the model -------------------------------------------------------------------------------


class PDHigherOrder(Model):
    name = "pd-higher-order"
    title = "PD higher-order beam (theta, theta*, w, w* per point)"
    source = "Yang, Oterkus & Oterkus 2020, Peridynamic higher-order beam formulation (seed 002)"
    theory = "higher-order"
    options = (
        Option("points", int, 201, "material points along the beam, ends included (paper: 1001 for dx = 1 mm)", minimum=5),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing (3 = the paper's 3.015 dx)", minimum=1.0),
        Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
        Option("ends", str, "auto", "auto (mirror for paper, taylor for corrected) | mirror (Appendix B fictitious "
               "layers) | truncated (no ghosts, per-point calibration) | taylor (ghosts extrapolated by a polynomial "
               "of the real points, energy of the real points only)", choices=("auto", "mirror", "truncated", "taylor")),
        Option("ghost_degree", int, 3, "degree of the ghost extrapolation (ends = taylor)", minimum=1, maximum=6),
        Option("pin", str, "auto", "pinned end: auto (mid for paper, face for corrected) | mid (w = 0 on the axis) | face (parabola-weighted mean of "
               "w + z^2 w* over the end face = 0: w + h^2/20 w* = 0, as fem-plane-stress pin = face)",
               choices=("auto", "mid", "face")),
        Option("shear", str, "auto", "auto (point for paper, centred for corrected) | point (Eq. 14d-f: theta_k xi) | "
               "centred (bond-mean rotations (theta_k + theta_j)/2 xi: no spurious G h theta'^2 delta^2 energy)",
               choices=("auto", "point", "centred")),
        Option("loads", str, "auto", "auto (mid for paper, faces for corrected) | mid (Eq. 16b: b_z on w, b_theta on theta) | faces (where the plane-stress "
               "reference puts them: top face, parabolic end shear, linear end traction)", choices=("auto", "mid", "faces")),
    )

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        return np.linspace(0.0, scene.length, params["points"])

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

    def assemble(self, scene: Scene, params: dict):
        """(K, F, T, info): K z = F with u = T z; u interleaved (theta, theta*, w, w*) per real point,
        z the unknowns left by the end conditions."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        m, variant, ends = params["horizon"], params["variant"], self.ends(params)
        d, _ = family(m, dx, variant)
        J = int(d.max())
        if 2 * J + 1 > n or (ends == "taylor" and params["ghost_degree"] + 1 > n):
            raise InputError(f"horizon = {m:g}: the family ({J} points each side) does not fit in {n} points; "
                             "use more points or a smaller horizon")
        C, h = self.constants(scene)
        left, right = scene.supports.left, scene.supports.right
        info = {"depth": h, "ends": ends, "section": "rectangle" if scene.section.height is not None else
                f"equivalent rectangle h = sqrt(12 I / A) = {h:.6g} m"}
        symmetric = True
        centred = params.get("shear", "auto") == "centred" or (params.get("shear", "auto") == "auto"
                                                               and variant != "paper")
        info["shear"] = "centred" if centred else "point"
        if ends == "mirror":
            G = (0 if left == "free" else J, 0 if right == "free" else J)
            N = n + G[0] + G[1]
            V = np.full(N, dx)
            if variant != "paper":
                V[:G[0]] = 0.0
                V[N - G[1]:] = 0.0
                V[[G[0], G[0] + n - 1]] = dx / 2
            wts = bond_weights(N, m, dx, variant, V, calibrate="family")
            Kx = assemble_blocks(N, dx, C, wts, h, centred)
            P = mirror_map(n, G, left, right)
            real = slice(NF * G[0], NF * (G[0] + n))
            if variant == "paper":  # Eq. 22 at the real points, images substituted
                K = (Kx[real] @ P).tocsr()
                symmetric = False
            else:
                K = (P.T @ Kx @ P).tocsr()
            info.update(boundary="fictitious mirror layers (Appendix B), free ends truncated", ghosts_per_end=list(G))
        elif ends == "taylor":
            G = J
            N = n + 2 * G
            V = np.zeros(N)
            V[G:G + n] = dx
            V[[G, G + n - 1]] = dx / 2
            Kx = assemble_blocks(N, dx, C, bond_weights(N, m, dx, variant, V, calibrate="family"), h, centred)
            E = taylor_map(n, G, params["ghost_degree"])
            K = (E.T @ Kx @ E).tocsr()
            info.update(boundary=f"ghosts extrapolated (degree {params['ghost_degree']}), energy of the real points, "
                        "essential end conditions", ghosts_per_end=[G, G])
        else:
            V = np.full(n, dx)
            V[[0, -1]] = dx / 2
            K = assemble_blocks(n, dx, C, bond_weights(n, m, dx, variant, V, calibrate="point"), h, centred)
            info.update(boundary="truncated families (per-point calibration), essential end conditions")
        wref = bond_weights(2 * J + 1, m, dx, variant, np.full(2 * J + 1, dx), calibrate="family")
        info["stiffness_factor"] = float(sum(w[J] * (abs(o) * dx) ** 2 for o, w in wref.items()) / dx)
        F = load_vector(scene, x, self.choice(params, "loads") == "faces").ravel()
        T = constraint_map(n, left, right, variant, self.choice(params, "pin"), h)
        info.update(pin=self.choice(params, "pin"), loads=self.choice(params, "loads"))
        if symmetric:
            return (T.T @ K @ T).tocsr(), T.T @ F, T, info
        rows = np.flatnonzero(np.asarray(abs(T).sum(axis=1)).ravel() > 0)
        return (K[rows] @ T).tocsr(), F[rows], T, info

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("assemble"):
            K, F, T, binfo = self.assemble(scene, params)
        with timer("solve"):
            z, info = solve_linear(K, F, what=f"pd-higher-order ({params['variant']})")
        n = params["points"]
        u = (T @ z).reshape(n, NF)
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        fields = {"theta": u[:, TH], "theta_star": u[:, TS], "w_star": u[:, WS]}
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=x, w=u[:, W].copy(),
                      rotation=-u[:, TH], fields=fields, dofs=T.shape[1], timings=timer.timings, info=info)


MODELS = [PDHigherOrder()]
