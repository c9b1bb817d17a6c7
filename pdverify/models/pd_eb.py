"""Model ``pd-eb``: ordinary state-based PD Euler–Bernoulli beam (Diyaroglu, Oterkus & Oterkus).

One transverse DOF per material point, points x_k = k dx (ends included).

Curvature (Eq. 11a) of point k with family j = 1..J on each side::

    kappa_k = d Σ_j (w_{k+j} + w_{k-j} - 2 w_k) V_j / xi_j²  =  Σ_j c_j (w_{k+j} + w_{k-j} - 2 w_k)

strain energy density W_k = a kappa_k² / 2 (Eq. 10a) with a = EI/A (Eq. 33); the force densities of
Eq. 13–15 are the gradient of U = Σ_k W_k V_k (Eq. 2, 6), so the static equation is
``a D^T D w = b`` (paper, energy form) or ``a D (D w) = b`` (corrected, strong form), with
b = p/A per unit volume (Eq. 25) and point loads as b = P/(A dx) on the loaded point.

Variants
--------
``paper`` (as published): delta = (m + 0.015) dx, full volumes V = A dx, d = 1/(A delta) (Eq. 32);
clamped = support point fixed + mirror image of the real points (w_{-j} = w_j), simply supported =
support point fixed + negative mirror image (w_{-j} = -w_j), both eliminated by the master–slave
transformation U = T Û, K̂ = T^T K T (Eq. 39–42); free end = no fictitious points, the first point
uses the one-sided curvature of Eq. A1 with d1 = 1/(A dx) (A6), the p-th point (p = 1..m-1) the reduced
horizon delta_p = (p + 0.015) dx with d_p = 1/(A delta_p) (A7–A12). Point moments enter as
b = -dm/dx (Eq. 25): a force couple on the two neighbouring points.

The horizon factor: ``--horizon 3`` means the papers' delta = 3.015 dx in ``paper`` (the 0.015 keeps
the third neighbour inside despite round-off, and enters d as published); in ``corrected`` the
horizon is exactly m dx and the last member's partial volume is used.

``corrected``: three changes, each measured in tests/test_pd_eb.py.
1. d calibrated on the DISCRETE family: c_j = beta_j / (j² dx² Σ beta), so kappa is exact for any
   quadratic (the paper's continuous d makes kappa too small by m / (m + 0.015) and K by its square).
2. partial volume of the last member: beta_j = clip(m - (j - 1/2), 0, 1) (beta_3 = 1/2 for m = 3).
3. boundaries by Taylor ghost points (design note §1): a degree-4 polynomial satisfying the support's
   conditions (clamped w = w' = 0; pinned w = 0, EI w'' = M̄; free EI w'' = M̄, EI w''' = -V̄; guided
   w' = 0, EI w''' = -V̄) is fitted to the first four real points and evaluated at 2J ghosts per end;
   end loads enter through M̄, V̄ (not as body forces), the support point's equation is w = 0.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from ..band import Band
from ..errors import InputError, SolveError
from ..linalg import eliminate, solve_linear
from ..registry import Model, Option
from ..result import Result, Timer
from ..scene import Distributed, PointForce, PointMoment, Scene

# -- kernels (arrays in, arrays out) ---------------------------------------------------------


def partial_volumes(m: float) -> tuple[np.ndarray, np.ndarray]:
    """Family offsets j and volume fractions beta_j of the cells [j - 1/2, j + 1/2] dx inside m dx."""
    J = int(np.ceil(m + 0.5 - 1e-12))
    j = np.arange(1, J + 1)
    beta = np.clip(m - (j - 0.5), 0.0, 1.0)
    return j[beta > 0], beta[beta > 0]


def curvature_weights(m: float, dx: float, variant: str) -> np.ndarray:
    """c_j, j = 1..J, of kappa_k = Σ_j c_j (w_{k+j} + w_{k-j} - 2 w_k) (Eq. 11a with Eq. 32 or discrete)."""
    if variant == "paper":
        delta = (m + 0.015) * dx
        J = int(np.floor(delta / dx + 1e-12))
        j = np.arange(1, J + 1)
        return dx / (delta * j**2 * dx**2)  # d V / xi² with d = 1/(A delta), V = A dx
    j, beta = partial_volumes(m)
    return beta / (j**2 * dx**2 * beta.sum())


def stencil_operator(n_rows: int, row0: int, n_cols: int, offsets: np.ndarray, coefs: np.ndarray,
                     truncate: bool = False) -> sp.csr_matrix:
    """Sparse Toeplitz operator: row r holds ``coefs`` at columns r + row0 + ``offsets`` (repeated
    offsets add up). Built diagonal by diagonal (``scipy.sparse.diags``, C speed: 25x faster than COO
    triplets at 10^6 points). ``truncate``: drop entries outside the grid instead of raising."""
    offsets = np.asarray(offsets, dtype=np.int64) + row0
    coefs = np.asarray(coefs, dtype=float)
    u, inv = np.unique(offsets, return_inverse=True)
    vals = np.bincount(inv.ravel(), weights=coefs, minlength=len(u))
    if not truncate and (u.min() < 0 or n_rows - 1 + u.max() > n_cols - 1):
        raise ValueError("stencil leaves the grid")
    return sp.diags(list(vals), list(u), shape=(n_rows, n_cols), format="csr")


def curvature_operator(n_rows: int, row0: int, n_cols: int, c: np.ndarray) -> sp.csr_matrix:
    """Sparse D: rows are points row0 .. row0 + n_rows - 1 of a column grid of n_cols points."""
    J = len(c)
    j = np.arange(1, J + 1)
    offsets = np.concatenate([[0], -j, j])
    return stencil_operator(n_rows, row0, n_cols, offsets, np.concatenate([[-2.0 * c.sum()], c, c]))


def ghost_stencil_system(offsets, coefs, G: int, n: int, g_rows, g_cols, g_vals, e0) -> tuple[Band, np.ndarray]:
    """(K, r): the Toeplitz operator whose row i (real point i) holds ``coefs`` at extended columns
    i + G + ``offsets`` (extended grid: G ghosts, n real points, G ghosts), with the ghosts eliminated by
    w_ext = E w + e0 (E: identity on the real points, ghost rows (g_rows, g_cols, g_vals) in extended
    numbering). K = K_ext E as a :class:`~pdverify.band.Band` (the truncated Toeplitz part by diagonals
    plus the few ghost entries of the boundary rows), r = K_ext e0."""
    offsets = np.asarray(offsets, dtype=np.int64)
    coefs = np.asarray(coefs, dtype=float)
    g_rows, g_cols, g_vals = (np.asarray(v) for v in (g_rows, g_cols, g_vals))
    band = np.unique(np.r_[0:min(n, G), max(0, n - G):n])  # rows whose family reaches a ghost
    cols = band[:, None] + G + offsets[None, :]
    ghost = (cols < G) | (cols >= G + n)
    rr = np.broadcast_to(band[:, None], cols.shape)[ghost]
    cc = cols[ghost]
    vv = np.broadcast_to(coefs[None, :], cols.shape)[ghost]
    r = np.zeros(n)
    np.add.at(r, rr, vv * np.asarray(e0, float)[cc])
    # the ghost columns through E's ghost rows onto the real columns: a product of two small matrices
    N = n + 2 * G
    Cg = sp.csr_matrix((vv, (np.searchsorted(band, rr), cc)), shape=(len(band), N))
    P = (Cg @ sp.csr_matrix((g_vals, (g_rows, g_cols)), shape=(N, n))).tocoo()
    rows, cols_r, vals = band[P.row], P.col.astype(np.int64), P.data
    reach = int(max(np.abs(offsets).max(), np.abs(cols_r - rows).max() if len(rows) else 0))
    K = Band(n, reach, reach).add_stencil(offsets, coefs)
    K.add_entries(rows, cols_r, vals)
    return K, r


def fixed_points(scene: Scene, n: int) -> list[int]:
    """End points held at w = 0 (clamped and pinned supports) of a grid of n points."""
    held = ("clamped", "pinned", "roller")  # no axial unknown: roller = pinned
    return [i for i, sup in ((0, scene.supports.left), (n - 1, scene.supports.right)) if sup in held]


# -- loads -----------------------------------------------------------------------------------


def _cell_integral(load: Distributed, scene: Scene, lo: np.ndarray, hi: np.ndarray,
                   value: float | None = None) -> np.ndarray:
    """∫ over [lo, hi] ∩ span of the load's shape times ``value`` (default: the transverse
    ``load.value``; pass ``load.axial`` or ``load.torque`` for the other components)."""
    v = load.value if value is None else value
    a, b = scene.span(load)
    lo, hi = np.clip(lo, a, b), np.clip(hi, a, b)
    if load.shape == "uniform":
        return v * (hi - lo)
    k = np.pi / scene.length
    return v * (np.cos(k * lo) - np.cos(k * hi)) / k


def body_loads(scene: Scene, x: np.ndarray, skip_ends: dict | None = None) -> np.ndarray:
    """Line load q_k (N/m) on the points: cell averages of distributed loads, P/dx for point forces
    (split linearly between the two nearest points), -dm/dx couples for point moments (Eq. 25).
    ``skip_ends``: {0 or n-1: set of load types} handled elsewhere (by ghost points or reactions)."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    q = np.zeros(n)
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    skip_ends = skip_ends or {}
    for load in scene.loads:
        if isinstance(load, Distributed):
            q += _cell_integral(load, scene, lo, hi) / (hi - lo)
            continue
        pos = load.position / dx
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1:
            t = 0.0
        node = i if t < 1e-9 else None
        if node is not None and load.type in skip_ends.get(node, ()):
            continue
        if isinstance(load, PointForce):
            q[i] += load.value * (1 - t) / dx
            if t > 0:
                q[i + 1] += load.value * t / dx
        elif isinstance(load, PointMoment):
            # ccw couple C: q = -C delta'(x - a), with the delta split linearly between the two nearest
            # points (weights 1 - t, t) and each point's delta' a central dipole (-C/(2dx²) left, +C/(2dx²) right)
            C = load.value
            for node, wgt in ((i, 1.0 - t), (i + 1, t)):
                if wgt == 0.0:
                    continue
                left, right = node - 1, node + 1
                if left < 0:
                    left, right = 0, 1
                if right > n - 1:
                    left, right = n - 2, n - 1
                arm = (right - left) * dx
                q[left] -= wgt * C / (arm * dx)
                q[right] += wgt * C / (arm * dx)
    return q


def end_loads(scene: Scene) -> tuple[dict, dict]:
    """Point force and moment applied exactly at the left (x = 0) and right (x = L) ends."""
    P = {0: 0.0, 1: 0.0}
    C = {0: 0.0, 1: 0.0}
    for load in scene.loads:
        if isinstance(load, (PointForce, PointMoment)):
            for side, xe in ((0, 0.0), (1, scene.length)):
                if abs(load.position - xe) <= 1e-12 * scene.length:
                    (P if isinstance(load, PointForce) else C)[side] += load.value
    return P, C


def boundary_layer_warnings(scene: Scene, x: np.ndarray, reach: int) -> list[str]:
    """Point loads (force, moment, torque) strictly inside the first ``reach`` spacings of an end: the
    ghost polynomial fitted there assumes a smooth solution, so such a load is under-resolved (measured:
    pd-eb 85-300 % error for a force one spacing from the support at 101 points, 1e-4 at 1601;
    pd-timoshenko, 201 points, L/h = 20: 59 % one spacing from a pinned end, 2 % from a clamped one,
    0.2 % at five spacings). Flag it instead of hiding it. Positions in the scene's length unit."""
    dx = x[1] - x[0]
    out = []
    for i, load in enumerate(scene.loads):
        if hasattr(load, "position"):
            d = min(load.position, scene.length - load.position)
            if 1e-12 * scene.length < d < reach * dx:
                out.append(f"loads[{i}] at {load.position:g} is {d / dx:.3g} spacings from an end, inside the "
                           f"boundary layer of {reach} spacings: expect large errors; use at least "
                           f"{int(np.ceil(reach * scene.length / d)) + 1} points")
    return out


# -- Taylor ghost points (corrected variant) -------------------------------------------------

# roller = pinned: no axial unknown
_FIXED = {"clamped": (0, 1), "pinned": (0, 2), "roller": (0, 2), "free": (2, 3), "guided": (1, 3)}


def _solve_exact(A: list[list[Fraction]], B: list[list[Fraction]]) -> list[list[Fraction]]:
    """X with A X = B, A square and regular, by Gauss–Jordan elimination in exact rationals."""
    n = len(A)
    M = [list(A[i]) + list(B[i]) for i in range(n)]
    for k in range(n):
        piv = next(i for i in range(k, n) if M[i][k] != 0)
        M[k], M[piv] = M[piv], M[k]
        M[k] = [v / M[k][k] for v in M[k]]
        for i in range(n):
            if i != k and M[i][k] != 0:
                f = M[i][k]
                M[i] = [a - f * b for a, b in zip(M[i], M[k])]
    return [row[n:] for row in M]


@lru_cache(maxsize=None)
def ghost_maps(support: str, n_ghost: int, p: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """(G, C): ghost values w(t) at t = 1..n_ghost spacings outside the end, for a degree-4 polynomial
    in t = s/dx with the support's coefficients fixed (``_FIXED``), fitted by least squares to the
    first ``p`` real points (t = 0, -1, ..., -(p-1)): w_ghost = G w_real[:p] + C c_fixed.

    Computed in exact rational arithmetic and rounded once: the matrices hold small integers, and a
    LAPACK pseudo-inverse rounds differently from one CPU's kernels to another's. The discrete
    cantilever is so sensitive to these coefficients (its constant-curvature mode is pinned by the
    free-end ghosts only) that the last bit of G moved the 6,401-point mixed-form solution from
    5.5e-7 to 1.6e-5 between OpenBLAS's Haswell and SkylakeX kernels; with G exact both give 3.6e-6."""
    fixed = _FIXED[support]
    free = [q for q in range(5) if q not in fixed]
    Vr = [[Fraction(-i) ** q for q in range(5)] for i in range(p)]
    Vg = [[Fraction(t) ** q for q in range(5)] for t in range(1, n_ghost + 1)]
    A = [[row[q] for q in free] for row in Vr]  # p x k
    At = [list(col) for col in zip(*A)]  # k x p
    N = [[sum(a * b for a, b in zip(r1, r2)) for r2 in At] for r1 in At]  # A^T A
    X = _solve_exact(N, At)  # (A^T A)^-1 A^T, k x p
    G = [[sum(row[q] * X[a][i] for a, q in enumerate(free)) for i in range(p)] for row in Vg]
    C = [[row[f] - sum(G[g][i] * Vr[i][f] for i in range(p)) for f in fixed] for g, row in enumerate(Vg)]
    Gf, Cf = np.array(G, dtype=float), np.array(C, dtype=float)
    Gf.flags.writeable = Cf.flags.writeable = False
    return Gf, Cf


def taylor_ghosts(support: str, n_ghost: int, dx: float, M_end: float, V_coef: float, EI: float,
                  p: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Ghost values as an affine map of the first p real points: w_g = G w_real[:p] + g0.

    s is the distance from the end into the ghost region (ghost i at s = i dx, real point i at
    s = -i dx). w(s) = Σ_{q<=4} c_q s^q with the support's coefficients fixed: c0 = 0 (w = 0),
    c1 = 0 (w' = 0), c2 = M_end / (2 EI), c3 = V_coef / (6 EI) (the third s-derivative, see caller).
    The fit is made in t = s/dx (:func:`ghost_maps`, exact).
    """
    fixed = _FIXED[support]
    values = {0: 0.0, 1: 0.0, 2: M_end / (2 * EI), 3: V_coef / (6 * EI)}
    G, C = ghost_maps(support, n_ghost, p)
    fvals = np.array([values[q] * dx**q for q in fixed])
    return G, C @ fvals


# -- the model -------------------------------------------------------------------------------


class PDEulerBernoulli(Model):
    name = "pd-eb"
    title = "ordinary state-based PD Euler–Bernoulli beam"
    source = "Diyaroglu, Oterkus & Oterkus, PD Euler–Bernoulli beam (seed 000)"
    options = (
        Option("points", int, 101, "material points along the beam, ends included", minimum=5),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing (3 = the paper's 3.015 dx)", minimum=1.0),
        Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
        Option("form", str, "auto", "auto (mixed for corrected, direct for paper) | direct (one fourth-order system) | "
               "mixed (two second-order equations: round-off floor ~N^2 eps instead of ~N^4 eps; corrected only)",
               choices=("auto", "direct", "mixed")),
    )

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        return np.linspace(0.0, scene.length, params["points"])

    def assemble(self, scene: Scene, params: dict):
        """(K, b, free, info): the system K w_free = b after the supports (master–slave elimination of
        the fixed points, Eq. 39–42), K sparse; ``free`` are the indices of the unknown points."""
        K, b, fixed, info = self.assemble_full(scene, params)
        Kf, bf, free = self.reduced(K.tocsr(), b, fixed)
        return Kf, bf, free, info

    def assemble_full(self, scene: Scene, params: dict):
        """(K, b, fixed, info): K w = b on all real points (per unit volume), K a
        :class:`~pdverify.band.Band`; the points ``fixed`` are held at w = 0 (unit rows, ``Band.fix``)."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        m, variant = params["horizon"], params["variant"]
        c = curvature_weights(m, dx, variant)
        J = len(c)
        if 2 * J + 1 > n:
            raise InputError(f"horizon = {m:g}: the family ({J} points each side) does not fit in {n} points; "
                             "use more points or a smaller horizon")
        a = scene.EI / scene.section.A
        A = scene.section.A
        left, right = scene.supports.left, scene.supports.right
        assemble = self._assemble_paper if variant == "paper" else self._assemble_corrected
        K, b, fixed, info = assemble(scene, x, c, a, A, left, right)
        K.fix(fixed, b)  # master–slave elimination of the supported points (Eq. 39–42): w = 0 there
        return K, b, fixed, info

    # paper: energy form with mirror ghosts and Appendix free ends -------------------------
    def _assemble_paper(self, scene, x, c, a, A, left, right):
        n, dx, J = len(x), x[1] - x[0], len(c)
        G = J
        D = curvature_operator(n, G, n + 2 * G, c).tocoo()
        keep = np.ones(D.nnz, bool)
        rr, cc, vv = [D.row], [D.col], [D.data]
        for side, sup in ((0, left), (1, right)):
            if sup != "free":
                continue
            o = 1 if side == 0 else -1
            for pnt in range(min(J, n)):
                k = pnt if side == 0 else n - 1 - pnt
                keep &= D.row != k
                e = k + G
                if pnt == 0:  # Eq. A1 with d1 = 1/(A dx): one-sided second difference
                    cols, vals = [e, e + o, e + 2 * o], [1 / dx**2, -2 / dx**2, 1 / dx**2]
                else:  # Eq. A7/A10: reduced horizon (p + 0.015) dx, d_p = 1/(A delta_p)
                    cp = curvature_weights(float(pnt), dx, "paper")
                    cols = [e] + [e + j for j in range(1, len(cp) + 1)] + [e - j for j in range(1, len(cp) + 1)]
                    vals = [-2 * cp.sum()] + list(cp) + list(cp)
                rr.append(np.full(len(cols), k))
                cc.append(np.array(cols))
                vv.append(np.array(vals))
        rr[0], cc[0], vv[0] = D.row[keep], D.col[keep], D.data[keep]
        D = sp.csr_matrix((np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=D.shape)
        # master–slave map T: extended (ghost + real) <- real (Eq. 39–41)
        tr, tc, tv = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
        for side, sup in ((0, left), (1, right)):
            sign = {"clamped": 1.0, "guided": 1.0, "pinned": -1.0, "roller": -1.0, "free": 0.0}[sup]
            if sign == 0.0:
                continue
            j = np.arange(1, G + 1)
            g = G - j if side == 0 else G + n - 1 + j
            r = j if side == 0 else n - 1 - j
            ok = (r >= 0) & (r < n)
            tr.append(g[ok]), tc.append(r[ok]), tv.append(np.full(ok.sum(), sign))
        T = sp.csr_matrix((np.concatenate(tv), (np.concatenate(tr), np.concatenate(tc))), shape=(n + 2 * G, n))
        DT = D @ T
        K = Band.from_sparse(a * (DT.T @ DT))
        b = body_loads(scene, x) / A
        fixed = fixed_points(scene, n)
        return K, b, fixed, {"ghosts_per_end": G, "boundary": "mirror images, Appendix free ends"}

    # corrected: strong form with Taylor ghosts -----------------------------------------------
    def _assemble_corrected(self, scene, x, c, a, A, left, right):
        n, dx, J = len(x), x[1] - x[0], len(c)
        G = 2 * J
        # K_ext = a D2 D1 (D1: kappa on the real points and J ghosts each side; D2: on the real points),
        # a Toeplitz operator whose stencil is the self-convolution of the curvature stencil
        st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])
        g_rows, g_cols, g_vals, e0, skip = self.ghosts(scene, n, dx, G)
        K, r = ghost_stencil_system(np.arange(-G, G + 1), a * np.convolve(st, st), G, n, g_rows, g_cols, g_vals, e0)
        b = body_loads(scene, x, skip_ends=skip) / A - r
        fixed = fixed_points(scene, n)
        return K, b, fixed, {"ghosts_per_end": G, "boundary": "Taylor ghost points (degree 4, 4 real points)"}

    @staticmethod
    def form(params: dict) -> str:
        f = params.get("form", "auto")
        return ("mixed" if params["variant"] == "corrected" else "direct") if f == "auto" else f

    def limit_system(self, scene: Scene, params: dict):
        """(matrix, rhs) of the linear system ``solve`` factorises (for ``pdverify bench``'s limit)."""
        if self.form(params) == "mixed":
            M, rhs, *_ = self.assemble_mixed(scene, params)
            return M, rhs
        K, b, *_ = self.assemble_full(scene, params)
        return K, b

    def ghosts(self, scene: Scene, n: int, dx: float, G: int):
        """Taylor ghost points of both ends (design note §1): w_ghost = Gm w_real + g0.
        Returns (rows, cols, values) of the ghost rows of E in extended numbering (G ghosts, n real,
        G ghosts), the constant part e0 (length n + 2G) and the end loads handled by the ghosts."""
        P, C = end_loads(scene)
        EI = scene.EI
        p = min(4, n)
        er, ec, ev = [], [], []
        e0 = np.zeros(n + 2 * G)
        skip = {0: set(), n - 1: set()}
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            # internal moment and the third s-derivative coefficient EI d3w/ds3 at the end
            if side == 0:
                M_end, V3 = -C[0], -P[0]  # M(0+) = -C0, EI w'''(0) = P0 -> d3/ds3 = -w'''
            else:
                M_end, V3 = C[1], -P[1]  # M(L-) = C1, EI w'''(L) = -P1
            Gm, g0 = taylor_ghosts(sup, G, dx, M_end, V3, EI, p)
            real = np.arange(p) if side == 0 else n - 1 - np.arange(p)
            ghost = G - 1 - np.arange(G) if side == 0 else G + n + np.arange(G)
            er.append(np.repeat(ghost, p)), ec.append(np.tile(real, G)), ev.append(Gm.ravel())
            e0[ghost] = g0
            skip[0 if side == 0 else n - 1] = {"point_force", "point_moment"}  # end loads: in the ghosts or reactions
        return np.concatenate(er), np.concatenate(ec), np.concatenate(ev), e0, skip

    def assemble_mixed(self, scene: Scene, params: dict):
        """The corrected operator split in two second-order equations (``form = mixed``)::

            h² kappa - h² D1 (E w + e0) = 0      (kappa on the real points and J ghosts each side)
            h² D2 (h² kappa)            = h⁴ b / a

        the same discrete solution as a D2 D1 (E w + e0) = b, but the matrix of fourth differences
        (entries ~1/h⁴) is never formed, which lowers the round-off floor (tests/test_hard_cases.py).

        Assembled straight into LAPACK's band layout (:class:`~pdverify.band.Band`): positions
        p = -J .. n-1+J, two unknowns each (kappa_p, w_p), interleaved; both equations are Toeplitz block
        stencils, the ghost map adds a few entries at each end, and the w of positions outside the beam
        and of the supported points are held at zero (unit rows). Returns (M, rhs, J, free, info): w of
        real point i is unknown 2 (i + J) + 1."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        c = curvature_weights(params["horizon"], dx, "corrected")
        J = len(c)
        G = 2 * J
        if 2 * J + 1 > n:
            raise InputError(f"horizon = {params['horizon']:g}: the family ({J} points each side) does not fit in "
                             f"{n} points; use more points or a smaller horizon")
        A = scene.section.A
        a = scene.EI / A
        h2 = dx * dx
        st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])  # D1 = D2 stencil, offsets -J..J
        npos = n + 2 * J
        # ghost w (outside the beam) = Gm w_real + g0: onto the real columns of the kappa rows that reach them
        g_rows, g_cols, g_vals, e0, skip = self.ghosts(scene, n, dx, G)
        gpos = g_rows - G  # ghost position (extended numbering -> grid position, < 0 or > n - 1)
        p = np.unique(np.clip(np.r_[np.arange(-J, J), np.arange(n - J, n + J)], -J, n - 1 + J))  # rows reaching a ghost
        ge, kp = np.nonzero(np.abs(gpos[:, None] - p[None, :]) <= J)  # (ghost entry, kappa row) within a family
        rows, cols = 2 * (p[kp] + J), 2 * (g_cols[ge] + J) + 1
        off = np.r_[cols - rows, -2 * J - 1, 2 * J + 1]
        M = Band(2 * npos, int(-off.min()), int(off.max()))
        # unknowns k_p = h² kappa_p and w_p (entries of order one): kappa rows (dof 0) k_p - h² Σ_o st_o w_{p+o},
        # w rows (dof 1) h² Σ_o st_o k_{p+o}
        blocks = {o: [[1.0 if o == 0 else 0.0, -h2 * st[o + J]], [h2 * st[o + J], 0.0]] for o in range(-J, J + 1)}
        M.add_block_stencil(2, blocks)
        M.add_entries(rows, cols, -h2 * st[gpos[ge] - p[kp] + J] * g_vals[ge])
        rhs = np.zeros(2 * npos)
        gp = np.unique(gpos)
        gi, kq = np.nonzero(np.abs(gp[:, None] - p[None, :]) <= J)
        np.add.at(rhs, 2 * (p[kq] + J), h2 * st[gp[gi] - p[kq] + J] * e0[gp[gi] + G])
        rhs[2 * J + 1: 2 * (n + J): 2] = body_loads(scene, x, skip_ends=skip) / A * h2 * h2 / a
        fixed = fixed_points(scene, n)
        free = np.delete(np.arange(n), fixed)
        held = np.r_[2 * np.arange(J) + 1, 2 * (n + J + np.arange(J)) + 1, 2 * (np.asarray(fixed, np.int64) + J) + 1]
        M.fix(held, rhs)
        return M, rhs, J, free, {"ghosts_per_end": G, "form": "mixed (two second-order equations)",
                                 "boundary": "Taylor ghost points (degree 4, 4 real points)"}

    def reduced(self, K, b, fixed):
        """Master–slave elimination of the fixed points (w = 0): the rows/columns of the free points."""
        return eliminate(K, b, fixed)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        if self.form(params) == "mixed":
            if params["variant"] != "corrected":
                raise InputError("form = 'mixed': only the corrected variant has the two-equation form; "
                                 "use variant = corrected or form = direct")
            with timer("assemble"):
                M, rhs, J, free, binfo = self.assemble_mixed(scene, params)
            with timer("solve"):
                z, info = solve_linear(M, rhs, what="pd-eb (corrected, mixed form)")
                n = params["points"]
                w = z[2 * J + 1: 2 * (n + J): 2].copy()
                ndofs = n + 2 * J + len(free)  # kappa on every position, w on the free points
        else:
            with timer("assemble"):
                K, b, fixed, binfo = self.assemble_full(scene, params)
            with timer("solve"):
                w, info = solve_linear(K, b, what=f"pd-eb ({params['variant']})")
                ndofs = params["points"] - len(fixed)
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        rot = np.gradient(w, dx, edge_order=2)
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        flags = boundary_layer_warnings(scene, x, 2 * len(curvature_weights(params["horizon"], dx, params["variant"])) + 4)
        if flags:
            info.setdefault("warnings", []).extend(flags)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=x, w=w, rotation=rot,
                      dofs=ndofs, timings=timer.timings, info=info)


def stable_time_step(K: sp.spmatrix, density: float) -> float:
    """Central-difference limit dt = 2 / omega_max with omega_max² the largest eigenvalue of K / rho
    (ARPACK up to 5,000 unknowns; above, the Gershgorin bound max row sum |K|, which is safe)."""
    if K.shape[0] <= 5000:
        import scipy.sparse.linalg as spla

        lam = float(np.abs(spla.eigs(K.astype(float), k=1, which="LM", return_eigenvectors=False,
                                     v0=np.ones(K.shape[0]))[0]))  # fixed start: reproducible dt
    else:
        lam = float(np.abs(K).sum(axis=1).max())
    return 2.0 / np.sqrt(lam / density)


def simulate(scene: Scene, params: dict, t_end: float, dt: float | None = None, damping: float = 0.0,
             safety: float = 0.9, record_every: int = 10):
    """Explicit central differences for rho w_tt + c w_t + K w = b (Eq. 15 with damping), from rest.

    Shares the static operator; returns (t, w history at the recorded steps, dt, dt_limit).
    Raises SolveError when a forced dt exceeds the stable limit and the response blows up."""
    model = PDEulerBernoulli()
    params = model.resolve(scene, params)
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density (kg/m^3) to the scene")
    rho = scene.material.density
    Kf, bf, free, _ = model.assemble(scene, params)
    n_all = params["points"]
    limit = stable_time_step(Kf, rho)
    dt = safety * limit if dt is None else float(dt)
    steps = int(np.ceil(t_end / dt))
    w = np.zeros(len(free))
    w_old = np.zeros(len(free))
    hist, times = [], []
    scale = None
    c1 = damping * dt / (2 * rho)
    for s in range(1, steps + 1):
        acc = (bf - Kf @ w) * dt**2 / rho
        w_new = (2 * w - (1 - c1) * w_old + acc) / (1 + c1)
        w_old, w = w, w_new
        if s % record_every == 0 or s == steps:
            amp = np.abs(w).max()
            if scale is None and amp > 0:
                scale = amp
            if not np.isfinite(amp) or (scale and amp > 1e8 * scale):
                raise SolveError(f"dt = {dt:.4g} s: the explicit integration blew up at step {s}; "
                                 f"the stable limit is {limit:.4g} s (use dt below it)")
            full = np.zeros(n_all)
            full[free] = w
            hist.append(full)
            times.append(s * dt)
    return np.array(times), np.array(hist), dt, limit


MODELS = [PDEulerBernoulli()]
