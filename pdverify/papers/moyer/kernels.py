"""Kernels of the Moyer & Miraglia 2014 PD rod / Timoshenko beam: arrays in, arrays out.

Quadrature weights of the peridynamic integrals for a horizon delta = m dx (integer m), the
extension of the real points to ghost points (Taylor extrapolation as published, or a polynomial
that satisfies the support's conditions), and the line loads of a scene on a node grid.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.scene import Distributed, PointForce, PointMoment, PointTorque, Scene
from ...numerics.band import Band
from ...numerics.families import stencil_operator
from ...numerics.loads import cell_integral


def trapezoid_weights(m: int) -> np.ndarray:
    """Composite trapezoidal weights of the nodes j = 1..m of ∫_0^m (unit spacing): 1 inside, 1/2 at m."""
    w = np.ones(m)
    w[-1] = 0.5
    return w


def rod_kernel(m: int) -> np.ndarray:
    """c_j of I_i = Σ_j c_j (u_{i+j} + u_{i-j} - 2 u_i) (Eq. 14–19 with the index of Eq. 16 corrected).

    The trapezoidal rule of ∫_{-δ}^{δ} (u(x+ε) - u(x)) / |ε| dε puts weight Δ (Δ/2 at ε = ±δ) on the
    node at jΔ, and the integrand there is (u_{i±j} - u_i) / (jΔ): c_j = w_j / j. The limits at ε -> 0±
    cancel (Eq. 14). Σ_j c_j 2 j² = m², so B I_i = (2E/(δ²ρ)) (m² Δ² u''/2 ... ) = E u''/ρ exactly for a quadratic."""
    j = np.arange(1, m + 1)
    return trapezoid_weights(m) / j


def shear_kernel(m: int, variant: str) -> tuple[np.ndarray, np.ndarray]:
    """(offsets, weights) of I_i = PV ∫_{-δ}^{δ} ψ(x_i + ε)/ε dε = Σ_j a_j (ψ(x_i + s_j Δ) - ψ(x_i - s_j Δ)).

    ``paper`` (Eq. 47): ψ at the nodes (s_j = j), trapezoidal rule on [1, m], and the centre interval
    [-1, 1] as ψ_{i+1} - ψ_{i-1}: a_j = w_j / j + (1/2 if j = 1).
    ``corrected``: ψ at the half points (s_j = j - 1/2, where w' is a compact difference), midpoint
    rule on each unit interval: a_j = 1 / (j - 1/2). Both give I = 2δψ' for a linear ψ."""
    j = np.arange(1, m + 1)
    if variant == "paper":
        a = trapezoid_weights(m) / j
        a[0] += 0.5
        return j.astype(float), a
    return j - 0.5, 1.0 / (j - 0.5)


def toeplitz(n_rows: int, row0: int, n_cols: int, offsets, coefs) -> sp.csr_matrix:
    """Row r holds ``coefs`` at columns r + row0 + offsets (repeated offsets add up); the shared
    diagonal-wise builder of pd-eb."""
    return stencil_operator(n_rows, row0, n_cols, offsets, coefs)


# -- ghost points --------------------------------------------------------------------------


def taylor_rows(n_ghost: int, order: int) -> np.ndarray:
    """Ghost values f(t), t = 1..n_ghost spacings outside the end, from the first four real values
    (f_0 at the end, f_k k spacings inside): f(t) = f_0 + t f'(0) + t² f''(0)/2 (``order`` 1 or 2),
    the derivatives by second-order one-sided differences (Eq. 20–21, 53)."""
    t = np.arange(1, n_ghost + 1, dtype=float)[:, None]
    d1 = np.array([1.5, -2.0, 0.5, 0.0])  # outward first derivative times Δ
    d2 = np.array([2.0, -5.0, 4.0, -1.0])  # second derivative times Δ²
    G = np.zeros((n_ghost, 4))
    G[:, 0] = 1.0
    G += t * d1
    if order >= 2:
        G += t**2 / 2 * d2
    return G


def taylor_rows_cells(n_ghost: int, order: int, anchored: bool) -> np.ndarray:
    """Section 4 ghost cells: f(s) = f(0) + f'(0) s + f''(0) s²/2 (``order`` 1 or 2) about the end face
    s = 0, ghosts at s = (t - 1/2)Δ, the real cells at s = -(k + 1/2)Δ. The face value and derivatives
    come from the polynomial of degree order + 1 through the face value (``anchored``: the support
    fixes it to zero) and the first cells (second-order one-sided differences). Returns G (n_ghost x 4)
    on the first four cells."""
    deg = order + 1
    sr = -(np.arange(4) + 0.5)
    need = deg if anchored else deg + 1  # cells used
    pts = sr[:need]
    X = np.concatenate([[0.0], pts]) if anchored else pts
    V = X[:, None] ** np.arange(deg + 1)
    C = np.linalg.inv(V)  # coefficients from the values (face first when anchored)
    if anchored:
        C = C[:, 1:]  # the face value is zero
    sg = np.arange(1, n_ghost + 1) - 0.5
    Vg = sg[:, None] ** np.arange(order + 1)  # Taylor series truncated at ``order``
    G = np.zeros((n_ghost, 4))
    G[:, :need] = Vg @ C[: order + 1]
    return G


def constrained_ghosts(
    n_fields: int, degree: int, npts: int, n_ghost: int, constraints: list[tuple[dict, dict, float]]
) -> tuple[np.ndarray, np.ndarray]:
    """Ghost values as an affine map of the real values near an end: ghosts = R d + r0.

    Each field is a polynomial p_f(t) = Σ_q c_{f,q} t^q in the outward coordinate t = s/Δ (t = 0 at
    the end, t = -k at the k-th real point inward), fitted by least squares to its first ``npts`` real
    values d (field-major) subject to ``constraints``: each (coefficient terms {(f, q): factor},
    data terms {(f, k): factor}, constant) meaning Σ factor c_{f,q} = Σ factor d_{f,k} + constant.
    Returns R (n_fields n_ghost × n_fields npts) and r0 (per unit of the constants, summed)."""
    nc = degree + 1
    tr = -np.arange(npts, dtype=float)
    tg = np.arange(1, n_ghost + 1, dtype=float)
    Vr = tr[:, None] ** np.arange(nc)
    Vg = tg[:, None] ** np.arange(nc)
    V = np.kron(np.eye(n_fields), Vr)
    Vgh = np.kron(np.eye(n_fields), Vg)
    C = np.zeros((len(constraints), n_fields * nc))
    D = np.zeros((len(constraints), n_fields * npts))
    r = np.zeros(len(constraints))
    for i, (cterms, dterms, const) in enumerate(constraints):
        for (f, q), v in cterms.items():
            C[i, f * nc + q] += v
        for (f, k), v in dterms.items():
            D[i, f * npts + k] += v
        r[i] = const
    nk = len(constraints)
    KKT = np.block([[V.T @ V, C.T], [C, np.zeros((nk, nk))]])
    Z = np.linalg.inv(KKT)
    Z11, Z12 = Z[: n_fields * nc, : n_fields * nc], Z[: n_fields * nc, n_fields * nc :]
    Rc = Z11 @ V.T + Z12 @ D
    c0 = Z12 @ r
    return Vgh @ Rc, Vgh @ c0


def average_ghosts(degree: int, n_real: int, n_ghost: int) -> tuple[np.ndarray, np.ndarray]:
    """Interval averages of a polynomial p(s) = Σ a_q s^q extrapolated outward: the averages over the
    unit intervals centred at s = -(k + 1/2) (real, k = 0..n_real-1) are fitted by least squares with
    p(0) = v fixed; returns (R, r) with ghost averages (centres t + 1/2, t = 0..n_ghost-1) = R d + r v."""
    q = np.arange(degree + 1)

    def avg(c):
        c = np.asarray(c, float)[:, None]
        return ((c + 0.5) ** (q + 1) - (c - 0.5) ** (q + 1)) / (q + 1)

    Vr = avg(-(np.arange(n_real) + 0.5))
    Vg = avg(np.arange(n_ghost) + 0.5)
    pinv = np.linalg.pinv(Vr[:, 1:])
    R = Vg[:, 1:] @ pinv
    r = Vg[:, 0] - R @ Vr[:, 0]
    return R, r


# -- loads on a node grid ----------------------------------------------------------------------


def node_loads(scene: Scene, x: np.ndarray, component: str, ends_apart: bool):
    """Line loads on the nodes (per length): q (force) and mu (couple, ccw), and the loads applied
    exactly at the ends {0: (P, C), 1: (P, C)}.

    ``component``: "transverse" (load.value), "axial" (load.axial) or "torque" (point_torque, load.torque).
    Distributed loads: cell
    averages over [x - Δ/2, x + Δ/2] ∩ [0, L]; point forces and moments: P/Δ (C/Δ) split linearly
    between the two nearest nodes (the paper's body force p/(AΔ) in the loaded cell). ``ends_apart``:
    loads exactly at an end are returned in the end table instead (they enter the ghost conditions)."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    q, mu = np.zeros(n), np.zeros(n)
    ends = {0: [0.0, 0.0], 1: [0.0, 0.0]}
    lo = hi = None
    for load in scene.loads:
        if isinstance(load, Distributed):
            v = {"transverse": load.value, "axial": load.axial, "torque": load.torque}[component]
            if v != 0.0:
                if lo is None:
                    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
                q += cell_integral(load, scene, lo, hi, v) / (hi - lo)
            continue
        if isinstance(load, PointTorque):
            if component != "torque":
                continue
            v, target, slot = load.value, q, 0
        elif isinstance(load, PointForce):
            if component == "torque":
                continue
            v, target, slot = (load.value if component == "transverse" else load.axial), q, 0
        elif isinstance(load, PointMoment):
            if component != "transverse":
                continue
            v, target, slot = load.value, mu, 1
        else:  # pragma: no cover - the scene format has no other type
            continue
        if v == 0.0:
            continue
        pos = (load.position - x[0]) / dx  # x[0] = Δ/2 on a cell-centred grid
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1 or t < 0:
            t = 0.0
        if ends_apart and t == 0.0 and i in (0, n - 1):
            ends[0 if i == 0 else 1][slot] += v
            continue
        target[i] += v * (1 - t) / dx
        if t > 0:
            target[i + 1] += v * t / dx
    return q, mu, ends


def motion_value(motion, t):
    """Prescribed end motion at times t (array): sine_ramp = A sin(2π f t) until hold_after, then the
    value reached there (A for the paper's quarter-period endings); sine = A sin(2π f t); step = A."""
    t = np.asarray(t, dtype=float)
    A = motion.amplitude
    if motion.type == "step":
        return np.full_like(t, A)
    f = motion.frequency
    if motion.type == "sine":
        return A * np.sin(2 * np.pi * f * t)
    th = motion.hold_after
    return np.where(t < th, A * np.sin(2 * np.pi * f * t), A * np.sin(2 * np.pi * f * th))


def motion_final(motion, end_time: float) -> float:
    """The value a prescribed motion settles at (the value at end_time for an endless sine)."""
    if motion.type == "sine":
        return float(motion_value(motion, end_time))
    return float(motion_value(motion, 1e300 if motion.type == "step" else motion.hold_after + 1.0))


# -- operators that are a stencil away from the ends ----------------------------------------------


class EndPatched:
    """A banded operator on ``n`` points that is translation invariant away from the ends: the PD sums
    are one stencil in the interior, and only the rows whose family reaches a ghost point (the ghost
    maps, the end loads) differ. ``nr`` rows and ``nf`` columns per point, interleaved point-major (row
    nr p + a, column nf q + b). Rows of the points L .. n - R - 1 are the block stencil ``blocks``
    {o: (nr, nf) array}: row (p, a) holds blocks[o][a, b] at column (p + o, b); the rows of the first L
    and the last R points are explicit triplets (``rows``, ``cols``, ``vals``, global numbering).

    Built by :meth:`from_core` from the same operator assembled (sparse, as written in the paper's
    notation) on a short grid of the same spacing: its end rows are the end rows of any longer grid, its
    middle row is the stencil. Memory and assembly time are then O(n) with a handful of array passes."""

    def __init__(self, n: int, nr: int, nf: int, blocks: dict, L: int, R: int, rows, cols, vals):
        self.n, self.nr, self.nf, self.L, self.R = int(n), int(nr), int(nf), int(L), int(R)
        self.blocks = {int(o): np.asarray(C, float) for o, C in blocks.items()}
        self.rows, self.cols = np.asarray(rows, np.int64), np.asarray(cols, np.int64)
        self.vals = np.asarray(vals, float)
        pts = [abs(o) for o in self.blocks] + [0]
        if len(self.rows):
            pts.append(int(np.abs(self.cols // self.nf - self.rows // self.nr).max()))
        self.reach = max(pts)  # largest point offset of any entry

    @property
    def shape(self) -> tuple[int, int]:
        return (self.n * self.nr, self.n * self.nf)

    @classmethod
    def from_core(cls, core: sp.spmatrix, nr: int, nf: int, n: int) -> EndPatched:
        """The operator on ``n`` points from its assembly ``core`` on nc <= n points of the same spacing
        (n = nc: every row explicit). The stencil is the middle row of the core; L and R count the rows
        at each end that differ from it (compared bit for bit: equal rows come out of the same sums);
        the core must hold a stretch of stencil rows wider than the family, else it is too short."""
        core = sp.csr_matrix(core)
        nc = core.shape[0] // nr
        if n == nc:
            C = core.tocoo()
            return cls(n, nr, nf, {}, n, 0, C.row, C.col, C.data)
        D = core.toarray()
        r, c = np.nonzero(D)
        reach = int(np.abs(c // nf - r // nr).max()) if len(r) else 0
        Dp = np.pad(D, ((0, 0), (nf * reach, nf * reach)))
        p = np.arange(nc)[:, None, None, None]
        a = np.arange(nr)[None, :, None, None]
        o = np.arange(-reach, reach + 1)[None, None, :, None]
        b = np.arange(nf)[None, None, None, :]
        W = Dp[nr * p + a, nf * (p + reach + o) + b]  # W[p, a, o, b]: row (p, a), column (p + o, b)
        mid = nc // 2
        bad = np.flatnonzero((W != W[mid]).any(axis=(1, 2, 3)))
        L = int(bad[bad < mid].max()) + 1 if np.any(bad < mid) else 0
        R = nc - int(bad[bad > mid].min()) if np.any(bad > mid) else 0
        if L + R + 2 * reach + 1 > nc or n < L + R:
            raise RuntimeError(
                f"EndPatched: a core of {nc} points holds no stencil rows (L = {L}, R = {R}, "
                f"reach = {reach}); assemble a longer core"
            )
        blocks = {k - reach: W[mid, :, k, :].copy() for k in range(2 * reach + 1) if W[mid, :, k, :].any()}
        left = core[: nr * L].tocoo()
        right = core[nr * (nc - R) :].tocoo()
        shift_r, shift_c = nr * (n - nc), nf * (n - nc)
        rows = np.r_[left.row, right.row + nr * (nc - R) + shift_r]
        cols = np.r_[left.col, right.col + shift_c]
        return cls(n, nr, nf, blocks, L, R, rows, cols, np.r_[left.data, right.data])

    @staticmethod
    def add_ends(target: np.ndarray, v_core: np.ndarray, per: int) -> np.ndarray:
        """target + v for a vector v of the core grid (``per`` entries per point) whose entries belong
        to the ends (the ghost terms of the load vector): the core's first half is added at the start of
        the long grid, its second half at the end (in place where the grids differ; returned)."""
        v_core = np.asarray(v_core, float)
        if len(target) == len(v_core):
            return target + v_core
        h = per * (len(v_core) // per // 2)
        target[:h] += v_core[:h]
        target[len(target) - (len(v_core) - h) :] += v_core[h:]
        return target

    def stencil(self, a: int, b: int, scale: float = 1.0) -> dict:
        """{point offset: coefficient} of the block (a, b) of the interior stencil (zeros left out)."""
        return {o: float(C[a, b]) * scale for o, C in self.blocks.items() if C[a, b] != 0.0}

    def shortened(self, n: int) -> EndPatched:
        """The same operator on ``n`` <= self.n points: the same end rows and stencil (the right end's
        rows and columns moved by the difference); its end modes are those of the long grid."""
        if n >= self.n:
            return self
        if n < self.L + self.R + 2 * self.reach + 1:
            raise ValueError(f"shortened({n}): too short for the end rows (L = {self.L}, R = {self.R})")
        right = self.rows >= self.nr * (self.n - self.R)
        rows = np.where(right, self.rows - self.nr * (self.n - n), self.rows)
        cols = np.where(right, self.cols - self.nf * (self.n - n), self.cols)
        return EndPatched(n, self.nr, self.nf, self.blocks, self.L, self.R, rows, cols, self.vals)

    # -- conversions ---------------------------------------------------------------------------
    def band(self) -> Band:
        """The (square) operator as a :class:`~pdverify.numerics.band.Band`: the interior rows by
        ``Band.add_block_stencil``, then the explicit end rows added."""
        if self.nr != self.nf:
            raise ValueError("band(): the operator is not square per point")
        nf, n = self.nf, self.n
        offs = [nf * o + b - a for o in self.blocks for a in range(nf) for b in range(nf)]
        if len(self.rows):
            offs += (self.cols - self.rows).tolist()
        B = Band(nf * n, max(0, -min(offs)), max(0, max(offs)))
        B.add_block_stencil(nf, self.blocks, points=(self.L, n - self.R))
        if len(self.rows):
            B.add_entries(self.rows, self.cols, self.vals)
        return B

    def tocsr(self) -> sp.csr_matrix:
        if self.nr == self.nf:
            return self.band().tocsr()
        K = sp.csr_matrix((self.vals, (self.rows, self.cols)), shape=self.shape)
        lo, hi = self.L, self.n - self.R
        if hi > lo:
            p = np.arange(lo, hi)
            rr, cc, vv = [], [], []
            for o, C in self.blocks.items():
                for a in range(self.nr):
                    for b in range(self.nf):
                        if C[a, b] != 0.0:
                            (
                                rr.append(self.nr * p + a),
                                cc.append(self.nf * (p + o) + b),
                                vv.append(np.full(len(p), C[a, b])),
                            )
            K = K + sp.csr_matrix((np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=self.shape)
        return K.tocsr()

    def rows_csr(self, points: np.ndarray) -> sp.csr_matrix:
        """The rows of the given points (all their ``nr`` rows, in that order) as CSR over all columns."""
        points = np.asarray(points, np.int64)
        sel = (self.nr * points[:, None] + np.arange(self.nr)[None, :]).ravel()
        pos = np.full(self.nr * self.n, -1)
        pos[sel] = np.arange(len(sel))
        keep = pos[self.rows] >= 0
        rr, cc, vv = [pos[self.rows[keep]]], [self.cols[keep]], [self.vals[keep]]
        inner = (points >= self.L) & (points < self.n - self.R)
        p = points[inner]
        for o, C in self.blocks.items():
            for a in range(self.nr):
                for b in range(self.nf):
                    if C[a, b] != 0.0:
                        (
                            rr.append(pos[self.nr * p + a]),
                            cc.append(self.nf * (p + o) + b),
                            vv.append(np.full(len(p), C[a, b])),
                        )
        return sp.csr_matrix(
            (np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=(len(sel), self.shape[1])
        )

    # -- products ------------------------------------------------------------------------------
    def matvec(self, u: np.ndarray) -> np.ndarray:
        """y = A u: the interior by the stencil (pairs of symmetric offsets share a multiplication), the end
        rows by their triplets."""
        u = np.asarray(u, float)
        n, nr, nf, h = self.n, self.nr, self.nf, self.reach
        src = np.zeros((nf, n + 2 * h))
        src[:, h : h + n] = u.reshape(n, nf).T
        lo, hi = self.L, n - self.R
        out = np.zeros((nr, n))
        if hi > lo:
            tmp = np.empty(hi - lo)
            ops: list = []
            for a in range(nr):
                first = True
                for b in range(nf):
                    first = stencil_ops(ops, out[a, lo:hi], src[b], h + lo, h + hi, self.stencil(a, b), tmp, first)
            for f, args in ops:
                f(*args)
        y = out.T.ravel()
        if len(self.rows):
            np.add.at(y, self.rows, self.vals * u[self.cols])
        return y

    def __matmul__(self, u):
        return self.matvec(u)


def stencil_ops(
    ops: list, dst: np.ndarray, src: np.ndarray, lo: int, hi: int, st: dict, tmp: np.ndarray, first: bool
) -> bool:
    """Append to ``ops`` the numpy calls (ufunc, args) that add Σ_o st[o] src[lo + o: hi + o] to ``dst``
    (``first``: write it instead). Offsets ±o with equal (opposite) coefficients are summed (differenced)
    first and multiplied once: the PD kernels are even or odd. Returns the new ``first``."""
    done = set()
    for o in sorted(st, key=lambda o: (abs(o), o)):
        if o in done:
            continue
        c = st[o]
        a = src[lo + o : hi + o]
        if o and st.get(-o) in (c, -c):
            done |= {o, -o}
            ops.append((np.add if st[-o] == c else np.subtract, (a, src[lo - o : hi - o], tmp)))
            a = tmp
        else:
            done.add(o)
        if first:
            ops.append((np.multiply, (a, c, dst)))
            first = False
        else:
            ops.append((np.multiply, (a, c, tmp)))
            ops.append((np.add, (dst, tmp, dst)))
    return first
