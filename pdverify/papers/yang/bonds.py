"""Bond kernels of ``pd-higher-order`` (Yang, Oterkus & Oterkus 2020): the coefficients of Eq. 9 /
Eq. 15, the five bond measures (Eq. 14a-f and the corrected variant's centred and along-the-bond shear
measures), the bond weights (Eq. 14; partial volumes; the discrete calibration), the block-banded stiffness
(Eq. 15's Hessian), its interior stencil and the energy it is the Hessian of. Arrays in, arrays out; the model,
its variants and their reasons are in model.py."""

from __future__ import annotations

import functools

import numpy as np
import scipy.sparse as sp

from ...numerics.families import family
from ...theory.higher_order import NF, TH, TS, WS, W


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
    cuts: tuple[int, ...] = (),
) -> dict[int, np.ndarray]:
    """{offset d (+-1..+-J): per-point weight V_k omega_kd} for the bonds k -> k + d (zero where k + d
    is outside the grid). Paper: omega = dx / (delta^2 |xi|) (Eq. 14, V_j = A dx); corrected: calibrated
    on the discrete family so that Σ_j omega_kj xi^2 = 1, per point on its actual (possibly truncated)
    family (``calibrate = "point"``), with the end layers' weights of :func:`end_layer_weights` (``"patch"``),
    or on the full family (``"family"``, grids with ghost points).
    ``points``: the indices k (of the n-point grid) whose weights are wanted, ``volumes`` given on them
    (default all points); each weight is computed point by point, so a subset gets the same bits.
    ``fractions``: the paper's family volumes (:func:`family`). ``cuts`` (``"patch"`` only): interior points where
    the beam is treated as two sub-beams sharing that point (no bond crosses it; each side has its own patch-test
    end layer and half the point's volume): the weights are the sub-beams' weights added."""
    if cuts and calibrate == "patch" and variant != "paper":
        return _cut_weights(n, m, dx, variant, points, fractions, tuple(sorted(cuts)))
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
    if calibrate in ("point", "patch"):
        S = sum(r * (abs(off) * dx) ** 2 for off, r in raw.items())  # Σ beta |xi| over the actual family
    else:
        S = 2.0 * float(np.sum(beta * d * dx))
    out = {off: volumes * r / S for off, r in raw.items()}
    if calibrate == "patch":
        K, O, W = end_layer_weights(n, float(m), float(dx), fractions)
        for off in np.unique(O).tolist():  # the family's offsets, not its bonds
            sel = O == off
            full, given = np.zeros(n), np.zeros(n, bool)
            full[K[sel]], given[K[sel]] = W[sel], True
            out[off] = np.where(given[k], full[k], out[off])
    return out


def _cut_weights(n, m, dx, variant, points, fractions, cuts) -> dict[int, np.ndarray]:
    """:func:`bond_weights` of a grid cut at the points ``cuts``: the sum over the sub-beams [0, c1], [c1, c2], ...,
    [c_last, n - 1] of their own patch-calibrated weights (trapezoidal volumes on each sub-beam)."""
    k = np.arange(n) if points is None else np.asarray(points, np.int64)
    bounds = [0, *cuts, n - 1]
    out: dict[int, np.ndarray] = {}
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        inside = (k >= lo) & (k <= hi)
        kl = k[inside] - lo
        nn = hi - lo + 1
        V = np.where((kl == 0) | (kl == nn - 1), dx / 2, dx)
        for off, wt in bond_weights(nn, m, dx, variant, V, "patch", points=kl, fractions=fractions).items():
            full = out.setdefault(off, np.zeros(len(k)))
            full[inside] += wt
    return out


@functools.lru_cache(maxsize=64)
def end_layer_weights(n: int, m: float, dx: float, fractions: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(points k, offsets, V_k omega) of the bonds of the points within 2J of either end (corrected variant, truncated
    families, trapezoidal volumes V = dx, dx/2 at the ends), replacing the per-point calibration there.

    Why: with the along-the-bond measures every bond measure is xi times the mean of nearest-neighbour segment
    measures (a, c, g, e) or xi times a point value (s = 2 xi w*_k), so U = Σ_k Σ_j w_kj xi^2 Q^(mean segment
    strain, 2 w*_k) / 2h. A uniform state is in equilibrium (the patch test) only if every segment s carries the
    same total R_s = Σ_{bonds over s} w_kj xi^2 / d = dx, and it has the right energy only if every point keeps
    Σ_j w_kj xi^2 = V_k. The per-point calibration gives the second but not the first in the end layers (ghost
    forces: first order at m >= 2). Here both hold: the weights are the least change of the per-point ones,
    weighted by their size (min Σ ((w - w0) / w0)^2), subject to those linear conditions (a small dense
    solve per end layer; the interior keeps its weights, where both hold already). Mirror-symmetric by
    construction; for m = 1 the per-point weights already satisfy both (no change). The conditions are built as
    arrays over the bonds near the ends (no loop over points or bonds)."""
    d, beta = family(m, dx, "corrected", fractions)
    J = int(d.max())
    KL = min(2 * J, (n - 1) // 2)  # layer points per end (a short grid: the two layers meet)
    off = np.concatenate([d, -d]).astype(np.int64)  # the family's offsets, this side first
    bb = np.concatenate([beta, beta])
    layer = np.array(sorted(set(range(KL + 1)) | set(range(n - 1 - KL, n))), np.int64)
    near = np.array(sorted(set(range(min(n, KL + 2 * J + 1))) | set(range(max(0, n - 1 - KL - 2 * J), n))), np.int64)
    V = np.full(n, dx)
    V[[0, n - 1]] = dx / 2
    # the per-point calibrated weights of the bonds of the points near the ends, point by point, offsets in order
    K, O = np.repeat(near, len(off)), np.tile(off, len(near))
    r = np.tile(bb, len(near)) / (np.abs(O) * dx)
    inside = (K + O >= 0) & (K + O < n)
    K, O, r = K[inside], O[inside], r[inside]
    xi2 = (np.abs(O) * dx) ** 2
    at = np.searchsorted(near, K)  # each bond's point among the near ones
    w0 = V[K] * r / np.bincount(at, weights=r * xi2, minlength=len(near))[at]
    var = np.isin(K, layer)  # the bonds whose weights change
    A_cal = (K[var][None, :] == layer[:, None]) * xi2[var][None, :]  # each layer point's calibration
    lo, hi = np.minimum(K, K + O), np.maximum(K, K + O)  # the segments [lo, hi) a bond covers
    cover = np.zeros(n + 1)
    np.add.at(cover, lo[var], 1.0)
    np.add.at(cover, hi[var], -1.0)
    segs = np.flatnonzero(np.cumsum(cover)[: n - 1] > 0)  # the segments some changing bond covers
    over = (segs[:, None] >= lo[None, :]) & (segs[:, None] < hi[None, :])  # segment x bond
    share = np.abs(O) * dx * dx
    A_seg = over[:, var] * share[var][None, :]
    fixed = over[:, ~var] @ (w0[~var] * share[~var])  # the bonds that keep their weights
    A = np.vstack([A_cal, A_seg])
    b = np.concatenate([V[layer], dx - fixed])
    x0 = w0[var]
    W = x0 * x0
    lam = np.linalg.lstsq((A * W) @ A.T, b - A @ x0, rcond=None)[0]
    x = x0 + W * (A.T @ lam)
    out = (K[var], O[var], x)
    for a in out:  # kept by the cache: read-only
        a.flags.writeable = False
    return out


def bond_pieces(C: np.ndarray, off: int, dx: float, h: float, centred: bool, path: bool) -> list[tuple]:
    """The Hessian of one bond (point p to p + ``off``) divided by h, as (row shift, column offset, 4x4 block):
    the block sits in the row of point p + row shift at point offset ``col``. Plain bonds couple their two ends
    (:func:`bond_block`); with ``path`` (:func:`path_measures`) every pair of points along the bond. The order is
    the summation order of :func:`assemble_blocks` and :func:`uniform_blocks` (their rows agree bit for bit)."""
    if path:
        M = path_measures(off, dx)
        B = M.T @ C @ M / h
        sg, d = (1 if off > 0 else -1), abs(off)
        return [
            (sg * a, sg * (b - a), B[NF * a : NF * a + NF, NF * b : NF * b + NF])
            for a in range(d + 1)
            for b in range(d + 1)
        ]
    B = bond_block(C, off * dx, centred) / h
    return [(0, 0, B[:NF, :NF]), (0, off, B[:NF, NF:]), (off, -off, B[NF:, :NF]), (off, 0, B[NF:, NF:])]


def _by_row(pieces: list[tuple]) -> list[tuple]:
    """The pieces of :func:`bond_pieces` grouped by their row shift, in order: (row shift, columns, blocks); a row's
    pieces sit in distinct columns, so each group is one slice update, and every entry of K still sums its terms in
    the pieces' order."""
    rows: dict[int, list] = {}
    for row, col, block in pieces:
        rows.setdefault(row, []).append((col, block))
    return [(row, np.array([c for c, _ in got]), np.array([b for _, b in got])[None]) for row, got in rows.items()]


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
        t = wt[lo:hi, None, None, None]
        for row, cols, blocks in _by_row(bond_pieces(C, off, dx, h, centred, path)):
            Kb[lo + row : hi + row, J + cols] += t * blocks  # the pieces of one row: distinct columns
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


def uniform_blocks(
    C: np.ndarray, dx: float, weights: dict[int, float], h: float, centred: bool = False, path: bool = False
) -> dict[int, np.ndarray]:
    """{point offset o: 4x4 block K[p, p + o]} of a row p whose own bonds and whose partners' bonds all
    carry the interior weights ``weights`` (offset -> V omega): Eq. 15's Hessian summed bond by bond in
    the order of :func:`assemble_blocks` (the same bits as its interior rows)."""
    J = max(abs(o) for o in weights)
    blocks = {o: np.zeros((NF, NF)) for o in range(-J, J + 1)}
    for off, wt in weights.items():
        for _, col, block in bond_pieces(C, off, dx, h, centred, path):
            blocks[col] += wt * block
    return blocks
