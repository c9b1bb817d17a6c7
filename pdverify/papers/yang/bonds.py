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


def path_measures(off: int, dx: float, stretch: bool = False) -> np.ndarray:
    """M (5 x 4(|off| + 1)): the bond measures of k -> k + off on the points k + sign(off) a, a = 0..|off|, with
    the shear measures summed over the bond's nearest-neighbour segments (``shear = path``):
    g = w_j - w_k + Σ_a c_a theta_a, e = w*_j - w*_k + 3 Σ_a c_a theta*_a, c_a = xi/|off| (1/2 at the ends), the
    trapezoid rule of the rotation along the bond; one bond (|off| = 1) is the centred measure. If every
    nearest-neighbour shear measure vanishes so do all: no over-constraint of the J bonds (no locking).
    ``stretch``: the stretch measure by the same trapezoid, s = 2 Σ_a c_a w*_a, instead of Eq. 14b's 2 xi w*_k
    (``stretch = path``: every measure is then xi times a mean over the bond's segments)."""
    d = abs(off)
    xi = off * dx
    c = np.full(d + 1, xi / d)
    c[[0, d]] /= 2
    M = np.zeros((5, NF * (d + 1)))
    j = NF * d
    M[0, [TH, j + TH]] = -1.0, 1.0  # a
    if stretch:
        M[1, NF * np.arange(d + 1) + WS] = 2 * c  # s along the bond
    else:
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
    measures (a, c, g, e; s too with ``stretch = path``) or xi times a point value (s = 2 xi w*_k), so U = Σ_k Σ_j
    w_kj xi^2 Q^(mean segment strain, 2 w*_k) / 2h. A uniform state is in equilibrium (the patch test) only if every
    segment s carries the same total R_s = Σ_{bonds over s} w_kj xi^2 / d = dx, and it has the right energy only if
    every point keeps Σ_j w_kj xi^2 = V_k. The per-point calibration gives the second but not the first in the end
    layers (ghost forces: first order at m >= 2). Here both hold: the weights are the least change of the per-point
    ones, weighted by their size (min Σ ((w - w0) / w0)^2), subject to those linear conditions (a small dense solve
    per end layer; the interior keeps its weights, where both hold already). Mirror-symmetric by construction; for
    m = 1 the per-point weights already satisfy both (no change). The conditions are built as arrays over the bonds
    near the ends (no loop over points or bonds)."""
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
    nv = int(var.sum())
    A_cal = sp.csr_matrix((xi2[var], (np.searchsorted(layer, K[var]), np.arange(nv))), shape=(len(layer), nv))
    lo, hi = np.minimum(K, K + O), np.maximum(K, K + O)  # the segments [lo, hi) a bond covers
    share = np.abs(O) * dx * dx
    seg_of, bond_of = _segments(lo[var], hi[var])  # sparse: a bond of d spacings covers d segments
    segs, row = np.unique(seg_of, return_inverse=True)  # the segments some changing bond covers
    A_seg = sp.csr_matrix((share[var][bond_of], (row, bond_of)), shape=(len(segs), nv))
    seg_fix, bond_fix = _segments(lo[~var], hi[~var])  # the bonds that keep their weights
    fixed = np.bincount(seg_fix, (w0[~var] * share[~var])[bond_fix], n)[segs]
    A = sp.vstack([A_cal, A_seg]).tocsr()
    b = np.concatenate([V[layer], dx - fixed])
    x0 = w0[var]
    W = x0 * x0
    lam = np.linalg.lstsq((A @ sp.diags(W) @ A.T).toarray(), b - A @ x0, rcond=None)[0]
    x = x0 + W * (A.T @ lam)
    out = (K[var], O[var], x)
    for a in out:  # kept by the cache: read-only
        a.flags.writeable = False
    return out


def end_layer_ratios(n: int, m: float, dx: float, fractions: str) -> np.ndarray:
    """Each bond weight of :func:`end_layer_weights` over the interior weight of its offset (the same order)."""
    K, O, W = end_layer_weights(n, float(m), float(dx), fractions)
    d, beta = family(m, dx, "corrected", fractions)
    r = beta / (d * dx)
    interior = dx * r / (2.0 * np.sum(r * (d * dx) ** 2))  # V omega of a full family, offset by offset
    return W / interior[np.searchsorted(d, np.abs(O))]


def _segments(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(segment, bond) of every segment [s, s + 1) that a bond [lo, hi) covers, bond by bond."""
    d = hi - lo
    first = np.repeat(np.cumsum(d) - d, d)
    return np.repeat(lo, d) + np.arange(d.sum()) - first, np.repeat(np.arange(len(d)), d)


def bond_pieces(C: np.ndarray, off: int, dx: float, h: float, centred: bool) -> list[tuple]:
    """The Hessian of one plain bond (point p to p + ``off``, :func:`bond_block`) divided by h, as (row shift, column
    offset, 4x4 block): the block sits in the row of point p + row shift at point offset ``col``, in the summation
    order of :func:`assemble_blocks`."""
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


def path_classes(C: np.ndarray, off: int, dx: float, h: float, stretch: bool = False) -> np.ndarray:
    """(3, 3, NF, NF): the Hessian blocks of one path bond (:func:`path_measures`) divided by h between its point
    classes 0 = the start, 1 = an interior point, 2 = the end. Every interior point has the same measures' columns
    (c Z: the trapezoid weight of its rotations in g and e, and of its w* in s with ``stretch``), so these nine
    blocks are all the bond's (d + 1)^2."""
    d = abs(off)
    M = path_measures(off, dx, stretch)
    pts = [0, 1, d] if d > 1 else [0, 0, d]  # one-segment bonds have no interior (its class unused)
    M3 = np.concatenate([M[:, NF * a : NF * a + NF] for a in pts], axis=1)
    B = M3.T @ C @ M3 / h
    return B.reshape(3, NF, 3, NF).transpose(0, 2, 1, 3)


def assemble_blocks(
    n: int,
    dx: float,
    C: np.ndarray,
    weights: dict[int, np.ndarray],
    h: float,
    centred: bool = False,
    path: bool = False,
    stretch: bool = False,
) -> sp.csr_matrix:
    """K = Σ_bonds (weight / h) bond_block, as a block-banded matrix (4x4 blocks, point offsets -J..J),
    filled offset by offset with array slices (no loop over points or bonds), then BSR -> CSR.
    ``path``: the bond measures of :func:`path_measures` (a bond couples the points along it; its (d + 1)^2 blocks
    are nine distinct ones, added in O(n J) block operations by :func:`_path_blocks`), with ``stretch`` its s too."""
    J = max(abs(o) for o in weights)
    if path:
        Kb = _path_blocks(n, J, dx, C, weights, h, stretch)
    else:
        Kb = _plain_blocks(n, J, dx, C, weights, h, centred)
    cols = np.arange(n)[:, None] + np.arange(-J, J + 1)[None, :]
    ok = (cols >= 0) & (cols < n)
    indptr = np.r_[0, np.cumsum(ok.sum(axis=1))]
    K = sp.bsr_matrix((Kb[ok], cols[ok], indptr), shape=(NF * n, NF * n))
    return K.tocsr()


def _plain_blocks(n, J, dx, C, weights, h, centred) -> np.ndarray:
    """Kb[p, J + o] = K[p, p + o] (4x4 blocks) of the plain bonds (:func:`bond_pieces`)."""
    Kb = np.zeros((n, 2 * J + 1, NF, NF))
    for off, wt in weights.items():
        lo, hi = max(0, -off), min(n, n - off)
        t = wt[lo:hi, None, None, None]
        for row, cols, blocks in _by_row(bond_pieces(C, off, dx, h, centred)):
            Kb[lo + row : hi + row, J + cols] += t * blocks  # the pieces of one row: distinct columns
    return Kb


def _path_blocks(n, J, dx, C, weights, h, stretch) -> np.ndarray:
    """Kb[p, J + o] = K[p, p + o] of the path bonds in O(n J) block operations (``stretch``: :func:`path_measures`).

    A bond k -> k + sg d couples its start, its end and its d - 1 interior points, whose blocks are those of three
    classes (:func:`path_classes`). The end-end blocks are placed offset by offset. An end meets each interior
    point of its bond at one column offset, with the same block: the column o = +-b of an end row collects the bonds
    longer than b, a running sum over the offsets from the longest down (``run``: indexed by the start or end point).
    The interior-interior block is the same for every bond (c = xi / d = sg dx): the column o of an interior row
    collects the weights of the bonds on which both points are interior, a prefix or suffix sum of length
    d - 1 - |o| over the bond's interior points (``S``), times that block at the end."""
    Kd, S = np.zeros((2 * J + 1, n, NF, NF)), np.zeros((2 * J + 1, n))
    p = np.arange(n)
    for sg in (1, -1):
        run = np.zeros((4, n, NF, NF))  # start row, end row (both by the row), interior row to start, to end
        for d in range(J, 0, -1):
            off = sg * d
            if off in weights:
                t = np.zeros(n + 2 * d)  # t[d + k]: the weight of the bond from k (zero where it does not exist)
                lo, hi = max(0, -off), min(n, n - off)
                t[d + lo : d + hi] = np.asarray(weights[off], float)[lo:hi]
                B = path_classes(C, off, dx, h, stretch)
                start, end = t[d : d + n], t[d - off : d - off + n]  # by the row p: the bond from p, to p
                for e, w in ((0, start), (2, end)):
                    Kd[J, :] += w[:, None, None] * B[e, e]
                    Kd[J + (off if e == 0 else -off)] += w[:, None, None] * B[e, 2 - e]
                if d > 1:
                    run += np.stack([start, end, start, end])[:, :, None, None] * B[[0, 2, 1, 1], [1, 1, 0, 2]][:, None]
                    V = t[d + p[None, :] - sg * np.arange(1, d)[:, None]]  # V[a - 1, p]: the bond whose point a is p
                    ahead, behind = np.cumsum(V, axis=0), np.cumsum(V[::-1], axis=0)
                    o = np.arange(-(d - 2), d - 1)  # interior pairs' column offsets
                    L = d - 1 - np.abs(o)
                    S[J + o] += np.where((sg * o >= 0)[:, None], ahead[L - 1], behind[L - 1])
            if d > 1:  # the interior point b = d - 1 of every bond longer than b, from its start and from its end
                b = d - 1
                Kd[J + sg * b] += run[0]
                Kd[J - sg * b] += run[1]
                q = p - sg * b  # interior row p to the start k = p - sg b, and to the end q = p + sg b
                Kd[J - sg * b] += np.where(((q >= 0) & (q < n))[:, None, None], run[2][np.clip(q, 0, n - 1)], 0.0)
                q = p + sg * b
                Kd[J + sg * b] += np.where(((q >= 0) & (q < n))[:, None, None], run[3][np.clip(q, 0, n - 1)], 0.0)
    if J > 1:  # the interior-interior block, the same for every bond of two or more segments
        Kd += S[:, :, None, None] * path_classes(C, J, dx, h, stretch)[1, 1]
    return Kd.transpose(1, 0, 2, 3)


def energy(
    u: np.ndarray,
    x: np.ndarray,
    C: np.ndarray,
    weights: dict[int, np.ndarray],
    h: float,
    centred: bool = False,
    path: bool = False,
    stretch: bool = False,
) -> float:
    """Strain energy U = Σ_k V_k W_k (Eq. 13, 15) evaluated directly from the bond measures (for the
    gradient checks: K must equal the Hessian of this function); ``stretch``: s along the path (with ``path``)."""
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
        ws = uk[:, WS]  # Eq. 14b: the stretch at the bond's start
        if path:  # trapezoid of the rotations along the bond (path_measures), as a mean rotation
            d, sg = abs(off), (1 if off > 0 else -1)
            along = [u[lo + sg * a : hi + sg * a] for a in range(d + 1)]
            c = np.full(d + 1, 1.0 / d)
            c[[0, d]] /= 2
            th = sum(ca * ua[:, TH] for ca, ua in zip(c, along))
            ts = sum(ca * ua[:, TS] for ca, ua in zip(c, along))
            if stretch:
                ws = sum(ca * ua[:, WS] for ca, ua in zip(c, along))
        m = np.stack(
            [
                uj[:, TH] - uk[:, TH],
                2 * xi * ws,
                uj[:, TS] - uk[:, TS],
                uj[:, W] - uk[:, W] + xi * th,
                uj[:, WS] - uk[:, WS] + 3 * xi * ts,
            ]
        )
        U += 0.5 / h * np.sum(wt[lo:hi] * np.einsum("pb,pq,qb->b", m, C, m))
    return U


def uniform_blocks(
    C: np.ndarray,
    dx: float,
    weights: dict[int, float],
    h: float,
    centred: bool = False,
    path: bool = False,
    stretch: bool = False,
) -> dict[int, np.ndarray]:
    """{point offset o: 4x4 block K[p, p + o]} of a row p whose own bonds and whose partners' bonds all
    carry the interior weights ``weights`` (offset -> V omega): the middle row of :func:`assemble_blocks` on
    2J + 1 points of those weights (every bond that meets it lies on them), so the same bits as its interior rows."""
    J = max(abs(o) for o in weights)
    n = 2 * J + 1
    K = assemble_blocks(n, dx, C, {o: np.full(n, float(w)) for o, w in weights.items()}, h, centred, path, stretch)
    row = K[NF * J : NF * J + NF].toarray()
    return {o: row[:, NF * (J + o) : NF * (J + o) + NF] for o in range(-J, J + 1)}
