"""Geometrically nonlinear bond-pair beam: the full rotational-spring energy (O'Grady & Foster Eq. 2 is
its gradient), axial bonds, follower end couples, Newton with load stepping.

Energy (design note §1, nonlinear path), positions r_k in the plane (x, z):
    Π = Σ_k Σ_j alpha beta_j dx² (1 + cos theta_kj) + Σ bonds ½ c_a beta_j dx² (|Y| - xi)² / xi - loads
with cos theta = u·v / (|u||v|), u = r_{k+j} - r_k, v = r_{k-j} - r_k. Every term depends on lengths and
angles only, so a rigid motion gives zero force. Forces are the exact gradient (closed form per
element); element tangents by complex-step differentiation of that gradient (exact to round-off).
Everything is written in displacements (reference offsets added exactly), so small loads lose no
digits to the cancellation of positions. Ghost points are linear images of real points: clamped = reflection through the line normal to the
clamp at the support, pinned = point reflection through the support, guided = reflection through the
vertical line of the support, free = none (truncated families).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..errors import SolveError
from ..linalg import solve_linear
from ..scene import Distributed, PointForce, PointMoment, Scene

_H = 1e-30  # complex step


def _norm(a):
    return np.sqrt(a[..., 0] ** 2 + a[..., 1] ** 2)  # complex-safe (no abs)


def pair_grad(a, b, c, k, xi):
    """∂/∂(a, b, c) of k (1 + cos theta) for pairs centred at b; a, b, c are displacements (n, 2) of
    points at -xi, 0, +xi (the reference offsets are added exactly); returns (n, 6)."""
    u, v = c - b, a - b
    u = u + np.stack([xi, 0 * xi], axis=1)
    v = v - np.stack([xi, 0 * xi], axis=1)
    # 1 + cos theta = 1 - cos phi, phi = angle(u) - angle(-v) (small for a nearly straight pair):
    # d/dphi = sin phi, written with the cross product of small quantities (no cancellation)
    lu2 = u[:, 0] ** 2 + u[:, 1] ** 2
    lv2 = v[:, 0] ** 2 + v[:, 1] ** 2
    sphi = (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / np.sqrt(lu2 * lv2)
    du = (sphi / lu2)[:, None] * np.stack([-u[:, 1], u[:, 0]], axis=1)
    dv = -(sphi / lv2)[:, None] * np.stack([-v[:, 1], v[:, 0]], axis=1)
    return k[:, None] * np.concatenate([dv, -(du + dv), du], axis=1)


def bond_grad(a, c, k, xi):
    """∂/∂(a, c) of ½ k (|Y| - xi)², Y = xi e_x + (c - a) with a, c displacements; the stretch is
    computed as (2 xi du_x + |du|²) / (|Y| + xi), free of cancellation for small displacements."""
    du = c - a
    d = du + np.stack([xi, 0 * xi], axis=1)
    L = _norm(d)
    stretch = (2 * xi * du[:, 0] + du[:, 0] ** 2 + du[:, 1] ** 2) / (L + xi)
    f = (k * stretch / L)[:, None] * d
    return np.concatenate([-f, f], axis=1)


def couple_grad(a, c, C, xi):
    """∂/∂(a, c) of -C psi, psi the direction angle of the chord a -> c (displacements a, c of points
    xi apart); returns (n, 4)."""
    d = c - a + np.stack([xi, 0 * xi], axis=1)
    L2 = d[:, 0] ** 2 + d[:, 1] ** 2
    g = np.stack([-d[:, 1], d[:, 0]], axis=1) / L2[:, None]
    return -C[:, None] * np.concatenate([-g, g], axis=1)


def element_tangent(grad_fn, pts: list[np.ndarray], *args):
    """(n, m, m) Hessians of the elements by complex steps of the closed-form gradient."""
    X = np.concatenate(pts, axis=1).astype(complex)
    n, m = X.shape
    H = np.empty((n, m, m))
    for i in range(m):
        Xi = X.copy()
        Xi[:, i] += 1j * _H
        parts = [Xi[:, 2 * p:2 * p + 2] for p in range(m // 2)]
        H[:, :, i] = grad_fn(*parts, *args).imag / _H
    return H


class NonlinearBondPair:
    """Assembled on the extended grid (ghosts + real points); ``T`` maps real positions to it."""

    def __init__(self, scene: Scene, n: int, j: np.ndarray, beta: np.ndarray, alpha: float):
        self.scene, self.n = scene, n
        L = scene.length
        self.dx = dx = L / (n - 1)
        self.G = G = int(j.max())
        N = n + 2 * G
        self.N = N
        self.X0 = np.stack([np.linspace(0, L, n), np.zeros(n)], axis=1)
        # elements on the extended grid (index e = k + G)
        centres, offs, kp = [], [], []
        bi, bj, kb, xib = [], [], [], []
        c_a = scene.EA / np.sum(j * dx * beta * dx)
        for jj, bb in zip(j, beta):
            k = np.arange(n) + G
            ok = (k - jj >= 0) & (k + jj < N)
            centres.append(k[ok]), offs.append(np.full(ok.sum(), jj)), kp.append(np.full(ok.sum(), alpha * bb * dx**2))
            kb_ = np.arange(n) + G
            ok2 = kb_ + jj < N
            bi.append(kb_[ok2]), bj.append(kb_[ok2] + jj), kb.append(np.full(ok2.sum(), c_a * bb * dx**2 / (jj * dx))),
            xib.append(np.full(ok2.sum(), jj * dx))
        self.pc, self.po, self.pk = (np.concatenate(a) for a in (centres, offs, kp))
        self.ba, self.bc, self.bk, self.bxi = (np.concatenate(a) for a in (bi, bj, kb, xib))
        self._ghost_map()
        self._loads()

    # ghosts ----------------------------------------------------------------------------------
    def _ghost_map(self):
        n, G, N = self.n, self.G, self.N
        rows, cols, vals = [], [], []
        const = np.zeros(2 * N)

        def put(r, c, v):
            rows.append(r), cols.append(c), vals.append(v)

        for i in range(n):
            for d in (0, 1):
                put(2 * (i + G) + d, 2 * i + d, 1.0)
        self.alive = np.zeros(N, bool)
        self.alive[G:G + n] = True
        for side, sup in ((0, self.scene.supports.left), (1, self.scene.supports.right)):
            if sup == "free":
                continue
            s = 0 if side == 0 else n - 1  # support point (real index)
            for i in range(1, G + 1):
                r = i if side == 0 else n - 1 - i
                if not 0 <= r < n:
                    continue
                g = (G - i) if side == 0 else (G + n - 1 + i)
                self.alive[g] = True
                # x: reflection through the vertical line of the support: 2 x_s - x_r
                put(2 * g, 2 * s, 2.0), put(2 * g, 2 * r, -1.0)
                if sup == "pinned":  # point reflection: 2 z_s - z_r
                    put(2 * g + 1, 2 * s + 1, 2.0), put(2 * g + 1, 2 * r + 1, -1.0)
                else:  # clamped, guided: z_r (zero slope)
                    put(2 * g + 1, 2 * r + 1, 1.0)
        self.T = sp.csr_matrix((vals, (rows, cols)), shape=(2 * N, 2 * n))
        # element lists only where every point exists
        ok = self.alive[self.pc - self.po] & self.alive[self.pc + self.po]
        self.pc, self.po, self.pk = self.pc[ok], self.po[ok], self.pk[ok]
        okb = self.alive[self.ba] & self.alive[self.bc]
        self.ba, self.bc, self.bk, self.bxi = self.ba[okb], self.bc[okb], self.bk[okb], self.bxi[okb]
        # constrained real DOFs: support points (x and z for clamped/pinned at the left; the right
        # pinned end is a roller: z only); guided: x fixed
        fixed = []
        for side, sup in ((0, self.scene.supports.left), (1, self.scene.supports.right)):
            s = 0 if side == 0 else n - 1
            if sup in ("clamped", "pinned"):
                fixed += [2 * s + 1] + ([2 * s] if (side == 0 or sup == "clamped") else [])
            if sup == "guided":
                fixed += [2 * s]
        if self.scene.supports.left == "free" and self.scene.supports.right in ("pinned", "guided"):
            fixed += [2 * (n - 1)]  # someone must hold the axial rigid motion
        self.free = np.setdiff1d(np.arange(2 * n), fixed)

    # loads -----------------------------------------------------------------------------------
    def _loads(self):
        from .pd_eb import body_loads

        n, dx = self.n, self.dx
        self.F = np.zeros(2 * n)
        # distributed loads: vertical dead loads on the points (tributary lengths)
        dist = [l for l in self.scene.loads if isinstance(l, Distributed)]
        if dist:
            sub = self.scene.model_copy(update={"loads": dist})
            trib = np.full(n, dx)
            trib[[0, -1]] = dx / 2
            self.F[1::2] += body_loads(sub, self.X0[:, 0]) * trib
        couples_a, couples_c, couples = [], [], []
        for load in self.scene.loads:
            if isinstance(load, PointForce):
                i = int(np.argmin(np.abs(self.X0[:, 0] - load.position)))
                self.F[2 * i + 1] += load.value
                self.F[2 * i] += load.axial
            elif isinstance(load, PointMoment):
                i = int(np.argmin(np.abs(self.X0[:, 0] - load.position)))
                a, c = (i, i + 1) if i < n - 1 else (i - 1, i)
                couples_a.append(a), couples_c.append(c), couples.append(load.value)
        self.ca, self.cc, self.cC = np.array(couples_a, int), np.array(couples_c, int), np.array(couples, float)

    # residual and tangent --------------------------------------------------------------------
    def gradient(self, P: np.ndarray, lam: float) -> np.ndarray:
        """∂Π/∂(real displacements) at load factor lam (P: displacements of the real points)."""
        Xe = (self.T @ P).reshape(-1, 2)
        g = np.zeros((self.N, 2))
        gp = pair_grad(Xe[self.pc - self.po], Xe[self.pc], Xe[self.pc + self.po], self.pk, self.po * self.dx)
        for t, idx in enumerate((self.pc - self.po, self.pc, self.pc + self.po)):
            np.add.at(g, idx, gp[:, 2 * t:2 * t + 2])
        gb = bond_grad(Xe[self.ba], Xe[self.bc], self.bk, self.bxi)
        np.add.at(g, self.ba, gb[:, :2])
        np.add.at(g, self.bc, gb[:, 2:])
        out = self.T.T @ g.ravel()
        if len(self.cC):
            Pr = P.reshape(-1, 2)
            gc = couple_grad(Pr[self.ca], Pr[self.cc], lam * self.cC, (self.cc - self.ca) * self.dx)
            o2 = np.zeros((self.n, 2))
            np.add.at(o2, self.ca, gc[:, :2])
            np.add.at(o2, self.cc, gc[:, 2:])
            out = out + o2.ravel()
        return out - lam * self.F

    def tangent(self, P: np.ndarray, lam: float) -> sp.csr_matrix:
        Xe = (self.T @ P).reshape(-1, 2)
        rows, cols, vals = [], [], []

        def scatter(H, idx_list):
            dofs = np.concatenate([np.stack([2 * i, 2 * i + 1], axis=1) for i in idx_list], axis=1)
            m = dofs.shape[1]
            rows.append(np.repeat(dofs, m, axis=1).ravel()), cols.append(np.tile(dofs, (1, m)).ravel())
            vals.append(H.reshape(len(H), -1).ravel())

        a, b, c = self.pc - self.po, self.pc, self.pc + self.po
        scatter(element_tangent(pair_grad, [Xe[a], Xe[b], Xe[c]], self.pk, self.po * self.dx), [a, b, c])
        scatter(element_tangent(bond_grad, [Xe[self.ba], Xe[self.bc]], self.bk, self.bxi), [self.ba, self.bc])
        K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(2 * self.N, 2 * self.N))
        K = (self.T.T @ K @ self.T).tocsr()
        if len(self.cC):
            Pr = P.reshape(-1, 2)
            Hc = element_tangent(couple_grad, [Pr[self.ca], Pr[self.cc]], lam * self.cC, (self.cc - self.ca) * self.dx)
            r, cl, v = [], [], []
            dofs = np.concatenate([np.stack([2 * self.ca, 2 * self.ca + 1], 1), np.stack([2 * self.cc, 2 * self.cc + 1], 1)], 1)
            K = K + sp.csr_matrix((Hc.reshape(len(Hc), -1).ravel(), (np.repeat(dofs, 4, axis=1).ravel(),
                                                                      np.tile(dofs, (1, 4)).ravel())), shape=K.shape)
        return K

    def solve(self, steps: int = 10, tol: float = 1e-10, max_iter: int = 40, snapshots: int = 5):
        P = np.zeros(2 * self.n)  # displacements of the real points
        free = self.free
        ref = max(np.abs(self.F).max(), np.abs(self.cC).max() / self.dx if len(self.cC) else 0.0, 1e-300)
        shots, iters = [], []
        keep = set(np.linspace(1, steps, min(snapshots, steps)).round().astype(int))
        for s in range(1, steps + 1):
            lam = s / steps
            for it in range(max_iter):
                R = self.gradient(P, lam)[free]
                if np.abs(R).max() <= tol * ref:
                    break
                K = self.tangent(P, lam)[free][:, free]
                du, _ = solve_linear(K, -R, what="pd-bond-pair Newton step", condition=False)
                P[free] += du
            else:
                raise SolveError(f"pd-bond-pair nonlinear: Newton did not converge at load step {s}/{steps} "
                                 f"(residual {np.abs(R).max() / ref:.2e} relative); use more steps (-o steps=...)")
            iters.append(it)
            if s in keep:
                Pr = P.reshape(-1, 2) + self.X0
                shots.append({"factor": lam, "x": Pr[:, 0].tolist(), "z": Pr[:, 1].tolist()})
        return P.reshape(-1, 2), shots, iters
