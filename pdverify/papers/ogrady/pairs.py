"""The bond pairs of a straight beam in the small-rotation form (O'Grady & Foster 2014, Eq. 1–2): pdverify's
general path for supports anywhere, springs, segments and pairs that yield or break.

A pair (k, j) is centred at point k with bonds to k - j and k + j. Its deviation from straight is
phi = (w_{k+j} - 2 w_k + w_{k-j}) / xi_j (Eq. 3, 1 + cos theta ≈ phi² / 2) and its energy a phi² / 2 with
a = alpha_k omega_j beta_j dx² (times ½ at an end point with mirror ends: the trapezoid rule), alpha_k from the EI
at the centre (Eq. 5 / §3.1 per point, as the paper's alpha(x) in its discrete equation of motion). The pair force
f = a phi is the moment of the rotational spring; each bond carries f / xi (Eq. 2 with sin theta ≈ phi).

``phi = D w``: D is the sparse (pairs x points) matrix of the second differences, the points outside the beam
eliminated by the ghost rule of ``ends``: ``mirror`` (the energy form's reflections, docs/models/ogrady.md) or
``none`` (the paper's §3.1: no points outside the beam, a pair whose partner would lie outside it is absent).
Arrays in, arrays out; no loops over points or pairs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass
class Pairs:
    """The pairs of one grid: ``centre`` and ``offset`` (k, j), ``xi`` = j dx, ``D`` (phi = D w), ``stiffness`` a
    (energy a phi² / 2), ``omega`` (the weight of each pair, Eq. 6), ``n`` points, spacing ``dx``."""

    centre: np.ndarray
    offset: np.ndarray
    xi: np.ndarray
    D: sp.csr_matrix
    stiffness: np.ndarray
    omega: np.ndarray
    n: int
    dx: float

    def moments(self, w: np.ndarray) -> np.ndarray:
        """The elastic pair forces f = a phi (moments of the rotational springs)."""
        return self.stiffness * (self.D @ w)

    def stiffness_matrix(self, a: np.ndarray | None = None) -> sp.csr_matrix:
        """K = D^T diag(a) D (default a: the elastic stiffness of every pair)."""
        a = self.stiffness if a is None else a
        return (self.D.T @ sp.diags(a) @ self.D).tocsr()

    def section_moment(self, f: np.ndarray) -> np.ndarray:
        """The bending moment at each point: the statical moment, about the section through the point, of the forces
        of every pair that straddles it (a pair's end forces f / xi at levers up to xi give a triangle of height f
        over [k - j, k + j]): EI kappa under uniform curvature. Sagging positive (f > 0 for a pair bent concave
        up). It balances the loads exactly: its second difference is the nodal load over dx² at every point whose
        pairs all lie inside the beam.

        The triangle's height at offset o from its centre is f (1 - |o| / j), so the pairs centred at k give the point
        k + o the sum over j > |o| of f_kj - |o| f_kj / j: two suffix sums over the family, O(n J) (not a row per pair
        and offset, O(n J²))."""
        k, j = self.centre, self.offset
        J = int(j.max())
        F = np.zeros((self.n, J + 1))  # F[k, j - 1] = f of pair (k, j); column J stays 0 (the empty suffix)
        F[k, j - 1] = f
        A = np.cumsum(F[:, ::-1], axis=1)[:, ::-1]  # A[k, q] = sum over j > q of f_kj
        F[k, j - 1] = f / j
        B = np.cumsum(F[:, ::-1], axis=1)[:, ::-1]  # B[k, q] = sum over j > q of f_kj / j
        q = np.abs(np.arange(-(J - 1), J))  # |o| of the offsets o = -(J - 1) ... J - 1
        G = A[:, q] - q * B[:, q]  # (n, 2J - 1): what the pairs at k give the point k + o
        p = np.arange(self.n)[:, None] + np.arange(-(J - 1), J)[None, :]
        ok = (p >= 0) & (p < self.n)
        return np.bincount(p[ok], G[ok], self.n)


def ghost_rows(rule: str, side: int, n: int, G: int):
    """(ghost extended indices, source real indices, weights) of the ghosts of one end under the mirror ``rule``
    (the support's name; springs use ``free``): clamped and guided w_g = w_r, pinned and roller w_g = 2 w_s - w_r,
    free the cubic extrapolation of the last four points. Extended index e = k + G."""
    i = np.arange(1, G + 1)
    g = (G - i) if side == 0 else (G + n - 1 + i)
    s = 0 if side == 0 else n - 1
    if rule == "free":
        t = np.arange(4)
        # Lagrange weights of the points 0..3 at -i
        lag = np.ones((4, G))
        for m in range(4):
            for q in range(4):
                if q != m:
                    lag[m] *= (-i - t[q]) / (t[m] - t[q])
        src = t if side == 0 else n - 1 - t
        return np.repeat(g, 4), np.tile(src, G), lag.T.ravel()
    r = i if side == 0 else n - 1 - i
    ok = (r >= 0) & (r < n)
    g, r = g[ok], r[ok]
    if rule in ("pinned", "roller"):
        return np.r_[g, g], np.r_[np.full(len(g), s), r], np.r_[np.full(len(g), 2.0), -np.ones(len(g))]
    return g, r, np.ones(len(g))


def build_pairs(
    n: int,
    dx: float,
    j: np.ndarray,
    beta: np.ndarray,
    omega: np.ndarray,
    alpha_k: np.ndarray,
    ends: str,
    rules: tuple[str, str],
) -> Pairs:
    """The pairs of ``n`` points, family offsets ``j`` with volume fractions ``beta`` and weights ``omega``,
    ``alpha_k`` per point; ``ends`` = ``mirror`` (ghosts by the ``rules`` of the left and right ends) or ``none``."""
    G = int(j.max())
    N = n + 2 * G
    rows, cols, vals = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
    alive = np.zeros(N, bool)
    alive[G : G + n] = True
    if ends == "mirror":
        for side, rule in enumerate(rules):
            g, src, wgt = ghost_rows(rule, side, n, G)
            rows.append(g), cols.append(src), vals.append(wgt)
            alive[g] = True
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(N, n))
    k = np.repeat(np.arange(n), len(j))
    jj = np.tile(j, n)
    bb = np.tile(beta, n)
    om = np.tile(omega, n)
    e = k + G
    ok = alive[e - jj] & alive[e + jj]
    k, jj, bb, om, e = k[ok], jj[ok], bb[ok], om[ok], e[ok]
    xi = jj * dx
    P = len(k)
    r = np.repeat(np.arange(P), 3)
    c = np.stack([e - jj, e, e + jj], axis=1).ravel()
    v = (np.array([1.0, -2.0, 1.0])[None, :] / xi[:, None]).ravel()
    D = (sp.csr_matrix((v, (r, c)), shape=(P, N)) @ T).tocsr()
    end_weight = np.where((k == 0) | (k == n - 1), 0.5, 1.0) if ends == "mirror" else np.ones(P)
    a = alpha_k[k] * om * bb * dx**2 * end_weight
    return Pairs(k, jj, xi, D, a, om, n, dx)
