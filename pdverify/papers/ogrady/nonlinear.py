"""Geometrically nonlinear bond-pair beam: the full rotational-spring energy (O'Grady & Foster Eq. 2 is
its gradient), axial bonds, follower end couples, Newton with load stepping.

Energy (docs/design/formulas.md §1, large rotations), positions r_k in the plane (x, z):
    Π = Σ_k Σ_j alpha beta_j dx² (1 + cos theta_kj) + Σ bonds ½ c_a beta_j dx² (|Y| - xi)² / xi - loads
with cos theta = u·v / (|u||v|), u = r_{k+j} - r_k, v = r_{k-j} - r_k. Every term depends on lengths and
angles only, so a rigid motion gives zero force. Forces are the exact gradient (closed form per
element); element tangents by complex-step differentiation of that gradient (exact to round-off).
Everything is written in displacements (reference offsets added exactly), so small loads lose no
digits to the cancellation of positions. Ghost points are linear images of real points: clamped =
reflection through the line normal to the clamp at the support, pinned and roller = point reflection
through the support, guided = reflection through the vertical line of the support, free = cubic
extrapolation of the last four points (affine, so rigid motions stay exact); the axial bonds see a free end's
ghosts as the point reflection 2 r_0 - r_k (affine too). The end points' pair energy counts half (trapezoid
rule) and each bond the fraction of its reference length inside the beam, so every end is second order and a
uniform stretch carries exactly EA (docs/models/ogrady.md).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.errors import InputError, SolveError
from ...core.scene import Distributed, Scene
from ...numerics.linalg import solve_linear
from ...numerics.loads import body_loads
from .ends import axial_mechanism, held_dofs, point_couples, point_forces

_H = 1e-30  # complex step


def _norm(a):
    return np.sqrt(a[..., 0] ** 2 + a[..., 1] ** 2)  # complex-safe (no abs)


def element_sum(size: int, points: tuple, forces: np.ndarray) -> np.ndarray:
    """(size, 2): the elements' forces summed on their points. ``forces`` (n, 2 len(points)) holds the force on the
    t-th point of each element in columns 2t, 2t + 1. Summed in order, the elements' first points first: the same
    bits as np.add.at on zeros, by one bincount per component (complex forces part by part)."""
    idx = np.concatenate(points)
    cols = [np.concatenate([forces[:, 2 * t + c] for t in range(len(points))]) for c in (0, 1)]
    if np.iscomplexobj(forces):
        out = np.zeros((size, 2), complex)
        for c, col in enumerate(cols):
            out[:, c].real, out[:, c].imag = np.bincount(idx, col.real, size), np.bincount(idx, col.imag, size)
        return out
    return np.stack([np.bincount(idx, col, size) for col in cols], axis=1)


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
        parts = [Xi[:, 2 * p : 2 * p + 2] for p in range(m // 2)]
        H[:, :, i] = grad_fn(*parts, *args).imag / _H
    return H


class NonlinearBondPair:
    """Assembled on the extended grid (ghosts + real points); ``T`` maps real positions to it."""

    def __init__(self, scene: Scene, n: int, j: np.ndarray, beta: np.ndarray, alpha: float):
        if (why := axial_mechanism(scene)) is not None:
            raise InputError(why)
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
        real = lambda e: (e >= G) & (e < G + n)  # noqa: E731
        for jj, bb in zip(j, beta):
            k = np.arange(n) + G
            ok = (k - jj >= 0) & (k + jj < N)
            # trapezoid weights: half the end points' pair energy (the mirror ghosts make the end point's
            # energy the centre of a symmetric extension, counted once in full otherwise: a first-order error)
            wk = np.where((k == G) | (k == G + n - 1), 0.5, 1.0)
            centres.append(k[ok]), offs.append(np.full(ok.sum(), jj)), kp.append(alpha * bb * dx**2 * wk[ok])
            a = np.arange(N - jj)
            ra, rc = real(a), real(a + jj)
            # each bond weighted by the fraction of its reference length inside [0, L] (a bond from point k to
            # the ghost at k - jj counts k / jj): the weighted bond lengths of each offset sum to L, so a
            # uniform strain carries exactly EA (half of every ghost bond overcounted L by dx: first order)
            inside = np.clip(np.minimum(a + jj, G + n - 1) - np.maximum(a, G), 0, None) / jj
            ok2 = (ra | rc) & (inside > 0)
            wb = inside[ok2]
            bi.append(a[ok2]), bj.append(a[ok2] + jj), kb.append(c_a * bb * dx**2 / (jj * dx) * wb)
            xib.append(np.full(ok2.sum(), jj * dx))
        self.pc, self.po, self.pk = (np.concatenate(a) for a in (centres, offs, kp))
        self.ba, self.bc, self.bk, self.bxi = (np.concatenate(a) for a in (bi, bj, kb, xib))
        self._ghost_map()
        self._loads()

    # ghosts ----------------------------------------------------------------------------------
    def _ghost_map(self):
        sup = (self.scene.supports.left, self.scene.supports.right)
        self.T, self.alive = self._map(sup)
        self.T_abs = abs(self.T)
        # axial bonds see a free end's ghosts as the point reflection of the real points (2 r_0 - r_k, affine
        # as well): a uniform stretch continues through the end, so with the length fractions of the bond
        # weights it carries exactly EA (the cubic extrapolation of the pairs' ghosts would be first order under
        # an axial end force)
        self.Tb, _ = self._map(tuple("pinned" if s_ == "free" else s_ for s_ in sup))
        self.Tb_abs = abs(self.Tb)
        self._trim()

    def _map(self, supports):
        """(T, alive): the ghost map of the extended grid for the ghost rules of ``supports`` (left, right)."""
        n, G, N = self.n, self.G, self.N
        rows, cols, vals = [2 * G + np.arange(2 * n)], [np.arange(2 * n)], [np.ones(2 * n)]

        def put(r, c, v):
            rows.append(r), cols.append(c), vals.append(np.full(len(r), v))

        alive = np.zeros(N, bool)
        alive[G : G + n] = True
        for side, sup in ((0, supports[0]), (1, supports[1])):
            s = 0 if side == 0 else n - 1  # support point (real index)
            i = np.arange(1, G + 1)
            r = i if side == 0 else n - 1 - i
            if sup == "free":  # cubic extrapolation of the last four real positions (affine: rigid motions exact)
                t = np.arange(4)
                lag = np.prod(
                    [
                        np.where(
                            t[:, None] == m,
                            1.0,
                            (-i[None, :] - t[m]) / np.where(t[:, None] == m, 1.0, t[:, None] - t[m]),
                        )
                        for m in range(4)
                    ],
                    axis=0,
                )  # lag[q, i]: weight of point q at -i
                g = (G - i) if side == 0 else (G + n - 1 + i)
                src = t if side == 0 else n - 1 - t
                alive[g] = True
                for d in (0, 1):
                    rows.append(np.repeat(2 * g + d, 4)), cols.append(np.tile(2 * src + d, G))
                    vals.append(lag.T.ravel())
                continue
            i, r = i[(r >= 0) & (r < n)], r[(r >= 0) & (r < n)]
            g = (G - i) if side == 0 else (G + n - 1 + i)
            alive[g] = True
            # x: reflection through the vertical line of the support: 2 x_s - x_r
            put(2 * g, np.full(len(g), 2 * s), 2.0), put(2 * g, 2 * r, -1.0)
            if sup in ("pinned", "roller"):  # point reflection: 2 z_s - z_r
                put(2 * g + 1, np.full(len(g), 2 * s + 1), 2.0), put(2 * g + 1, 2 * r + 1, -1.0)
            else:  # clamped, guided: z_r (zero slope)
                put(2 * g + 1, 2 * r + 1, 1.0)
        rows, cols, vals = (np.concatenate(v) for v in (rows, cols, vals))
        return sp.csr_matrix((vals, (rows, cols)), shape=(2 * N, 2 * n)), alive

    def _trim(self):
        n = self.n
        # element lists only where every point exists
        ok = self.alive[self.pc - self.po] & self.alive[self.pc + self.po]
        self.pc, self.po, self.pk = self.pc[ok], self.po[ok], self.pk[ok]
        okb = self.alive[self.ba] & self.alive[self.bc]
        self.ba, self.bc, self.bk, self.bxi = self.ba[okb], self.bc[okb], self.bk[okb], self.bxi[okb]
        self.free = np.setdiff1d(np.arange(2 * n), held_dofs(self.scene.supports.left, self.scene.supports.right, n))

    # loads -----------------------------------------------------------------------------------
    def _loads(self):
        n, dx = self.n, self.dx
        self.F = np.zeros(2 * n)
        # distributed loads: vertical dead loads on the points (tributary lengths)
        dist = [l for l in self.scene.loads if isinstance(l, Distributed)]
        if dist:
            sub = self.scene.model_copy(update={"loads": dist})
            trib = np.full(n, dx)
            trib[[0, -1]] = dx / 2
            self.F[1::2] += body_loads(sub, self.X0[:, 0]) * trib
            axial = sub.model_copy(update={"loads": [l.model_copy(update={"value": l.axial}) for l in dist]})
            self.F[0::2] += body_loads(axial, self.X0[:, 0]) * trib  # the axial components, same cells
        self.F += point_forces(self.scene, n, dx)
        self.ca, self.cc, self.cC = point_couples(self.scene, n, dx)

    # residual and tangent --------------------------------------------------------------------
    def gradient(self, P: np.ndarray, lam: float) -> np.ndarray:
        """∂Π/∂(real displacements) at load factor lam (P: displacements of the real points)."""
        Xe = (self.T @ P).reshape(-1, 2)
        gp = pair_grad(Xe[self.pc - self.po], Xe[self.pc], Xe[self.pc + self.po], self.pk, self.po * self.dx)
        g = element_sum(self.N, (self.pc - self.po, self.pc, self.pc + self.po), gp)
        Xb = (self.Tb @ P).reshape(-1, 2)
        h = element_sum(self.N, (self.ba, self.bc), bond_grad(Xb[self.ba], Xb[self.bc], self.bk, self.bxi))
        out = self.T.T @ g.ravel() + self.Tb.T @ h.ravel()
        if len(self.cC):
            Pr = P.reshape(-1, 2)
            gc = couple_grad(Pr[self.ca], Pr[self.cc], lam * self.cC, (self.cc - self.ca) * self.dx)
            out = out + element_sum(self.n, (self.ca, self.cc), gc).ravel()
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
        shape = (2 * self.N, 2 * self.N)

        def assembled():
            out = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape)
            rows.clear(), cols.clear(), vals.clear()
            return out

        scatter(element_tangent(pair_grad, [Xe[a], Xe[b], Xe[c]], self.pk, self.po * self.dx), [a, b, c])
        K = self.T.T @ assembled() @ self.T
        Xb = (self.Tb @ P).reshape(-1, 2)
        scatter(element_tangent(bond_grad, [Xb[self.ba], Xb[self.bc]], self.bk, self.bxi), [self.ba, self.bc])
        K = (K + self.Tb.T @ assembled() @ self.Tb).tocsr()
        if len(self.cC):
            Pr = P.reshape(-1, 2)
            Hc = element_tangent(couple_grad, [Pr[self.ca], Pr[self.cc]], lam * self.cC, (self.cc - self.ca) * self.dx)
            dofs = np.concatenate(
                [np.stack([2 * self.ca, 2 * self.ca + 1], 1), np.stack([2 * self.cc, 2 * self.cc + 1], 1)], 1
            )
            K = K + sp.csr_matrix(
                (Hc.reshape(len(Hc), -1).ravel(), (np.repeat(dofs, 4, axis=1).ravel(), np.tile(dofs, (1, 4)).ravel())),
                shape=K.shape,
            )
        return K

    def apply_linear(self, P: np.ndarray) -> np.ndarray:
        """K P with K the tangent at rest, evaluated element by element (a complex step of
        :meth:`gradient` at zero load): no assembled fourth differences, so its round-off is that of the
        element forces (~N² times smaller than that of the assembled K times P)."""
        h = 1e-30 / max(np.abs(P).max(), 1e-300)
        return self.gradient(1j * h * np.asarray(P, float), 0.0).imag / h

    def _internal_scale(self, P: np.ndarray, size) -> np.ndarray:
        """Per real DOF, the sum of ``size`` (an array's magnitudes) of every pair and bond force meeting there,
        through |T| and |Tb|."""
        Xe = (self.T @ P).reshape(-1, 2)
        gp = size(pair_grad(Xe[self.pc - self.po], Xe[self.pc], Xe[self.pc + self.po], self.pk, self.po * self.dx))
        g = element_sum(self.N, (self.pc - self.po, self.pc, self.pc + self.po), gp)
        Xb = (self.Tb @ P).reshape(-1, 2)
        h = element_sum(self.N, (self.ba, self.bc), size(bond_grad(Xb[self.ba], Xb[self.bc], self.bk, self.bxi)))
        return self.T_abs.T @ g.ravel() + self.Tb_abs.T @ h.ravel()

    def linear_force_scale(self, P: np.ndarray) -> np.ndarray:
        """:meth:`force_scale` of the linear problem at rest: per real DOF the magnitudes of the terms
        :meth:`apply_linear` sums (each pair and bond force's first order in P, by the same complex step) and of
        the loads and couples at rest; eps times it is the round-off floor of the linear residual."""
        step = 1e-30 / max(np.abs(P).max(), 1e-300)
        linear = self._internal_scale(1j * step * np.asarray(P, float), lambda g: np.abs(g.imag) / step)
        return linear + self.force_scale(np.zeros_like(P), 1.0)

    def force_scale(self, P: np.ndarray, lam: float) -> np.ndarray:
        """Per real DOF, the sum of the magnitudes of every force that meets there (pair and bond forces
        through |T|, couples, loads): the size of the terms whose sum is the residual, so eps times it is
        the residual's round-off floor."""
        out = self._internal_scale(P, np.abs) + np.abs(lam * self.F)
        if len(self.cC):
            Pr = P.reshape(-1, 2)
            gc = np.abs(couple_grad(Pr[self.ca], Pr[self.cc], lam * self.cC, (self.cc - self.ca) * self.dx))
            out = out + element_sum(self.n, (self.ca, self.cc), gc).ravel()
        return out

    def newton(self, P: np.ndarray, lam: float, tol: float = 1e-11, max_iter: int = 30):
        """Newton iterations at load factor ``lam`` from ``P``: (P, iterations, converged, relative residual).

        Converged when every residual component is below ``tol`` times the internal forces that meet at
        its DOF (:meth:`force_scale`: the forces whose sum is the residual; a test against the load alone
        asks for less than the round-off floor on fine grids, where the pair forces are ~N² times the
        nodal loads), or when the residual has stopped falling (at the floor) after an increment below
        1e-10 of the displacements. Each step is shortened by secants on the slope of the energy along it
        while the energy rises steeply at its end (a line search that needs the gradient only). A Newton direction
        along which the energy rises, from a residual larger than the one it started from, ends the attempt
        unconverged (the iterate has left the basin of the stable equilibrium; :meth:`solve` splits the step)."""
        free = self.free
        P = P.copy()
        R = self.gradient(P, lam)[free]
        rn = start = np.abs(R).max()
        floor = max(tol, 64 * np.finfo(float).eps)
        for it in range(max_iter):
            scale = self.force_scale(P, lam)[free]
            if np.all(np.abs(R) <= floor * scale):
                return P, it, True, 0.0
            K = self.tangent(P, lam)[free][:, free]
            du, _ = solve_linear(K, -R, what="pd-bond-pair Newton step", condition=False, bound=False)
            t, g0 = 1.0, float(R @ du)  # slope of the energy along du at t = 0 (< 0)
            if g0 > 0 and rn > start:  # an ascent direction from a worse state than the start: diverged
                return P, it + 1, False, rn / max(scale.max(), 1e-300)
            for _ in range(12):
                P_try = P.copy()
                P_try[free] += t * du
                R_try = self.gradient(P_try, lam)[free]
                g1 = float(R_try @ du)
                if np.all(np.isfinite(R_try)) and (g0 >= 0 or g1 <= 0.5 * abs(g0)):
                    break
                t *= float(np.clip(g0 / (g0 - g1), 0.1, 0.9)) if np.isfinite(g1) else 0.5  # secant on the slope
            rn_try = np.abs(R_try).max()
            small = np.abs(t * du).max() <= 1e-10 * max(np.abs(P).max(), 1e-300)
            if rn_try >= rn and small:  # stagnated at the floor: keep P
                return P, it + 1, True, 0.0
            P, R, rn = P_try, R_try, rn_try
            if small and it > 0:
                return P, it + 1, True, 0.0
        return P, max_iter, False, rn / max(scale.max(), 1e-300)

    def solve(self, steps: int = 10, snapshots: int = 5, max_halvings: int = 8):
        """Load stepping to lam = 1 in ``steps`` equal steps; a step whose Newton iterations do not converge
        is split in halves (up to ``max_halvings`` times) from the last converged state.
        Returns (displacements (n, 2), snapshots, Newton iterations per requested step)."""
        P = np.zeros(2 * self.n)  # displacements of the real points
        shots, iters = [], []
        keep = set(np.linspace(1, steps, min(snapshots, steps)).round().astype(int))
        for s in range(1, steps + 1):
            lam0, lam1, n_it, dl = (s - 1) / steps, s / steps, 0, 1.0 / steps
            while lam0 < lam1 - 1e-15:
                lam = min(lam0 + dl, lam1)
                P_new, it, ok, rel = self.newton(P, lam)
                n_it += it
                if ok:
                    P, lam0 = P_new, lam
                    continue
                dl /= 2
                if dl < 1.0 / steps / 2**max_halvings:
                    raise SolveError(
                        f"pd-bond-pair nonlinear: Newton did not converge at load factor {lam:.4g} "
                        f"(step {s}/{steps}, split {max_halvings} times; residual {rel:.2e} of the "
                        "internal forces); use more steps (-o steps=...)"
                    )
            iters.append(n_it)
            if s in keep:
                Pr = P.reshape(-1, 2) + self.X0
                shots.append({"factor": lam1, "x": Pr[:, 0].tolist(), "z": Pr[:, 1].tolist()})
        return P.reshape(-1, 2), shots, iters
