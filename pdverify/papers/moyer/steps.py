"""The step engines of the explicit time integration (:func:`~.transient.integrate`): one step of the
damped leapfrog / velocity-Verlet scheme (Eq. 7–11, 38–44) as one CSR product (small grids) or with the
operator's stencil applied matrix-free block by block (large grids).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .kernels import stencil_ops
from .system import Discrete

CHUNK = 16384  # points per block of the matrix-free time step (its arrays stay in the CPU cache)


class WholeStep:
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


class StencilStep:
    """One step of :func:`integrate`'s scheme with K applied matrix-free: fields stored apart (padded by
    the family's reach), the interior rows by the operator's stencil with the gains folded into its
    coefficients, the few end rows by small dense products, block by block of ``chunk`` points (default
    :data:`CHUNK`, read at each call) so that y = u + κV, the PD sums and the update of u and V run on
    data in cache (one pass over memory per step instead of one per operation and the matrix's ~25 values
    per point). The y of a block are formed one block ahead, before the update of u and V reaches the
    points they depend on."""

    def __init__(
        self,
        disc: Discrete,
        gd: np.ndarray,
        alpha: tuple,
        kappa: float,
        bG: np.ndarray,
        gd_field: tuple,
        chunk: int | None = None,
    ):
        op, nf = disc.op, disc.nf
        n, h = op.n, op.reach
        self.n, self.nf, self.h = n, nf, h
        U, V, Y = (np.zeros((nf, n + 2 * h)) for _ in range(3))
        self.U, self.V = U, V
        BG = bG.reshape(n, nf).T.copy()
        need = max(op.L, op.R) + 2 * h + 1
        P = max(CHUNK if chunk is None else chunk, need)  # CHUNK read here: a test lowers it
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
