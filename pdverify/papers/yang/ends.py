"""Ends and loads of ``pd-higher-order`` (Yang, Oterkus & Oterkus 2020): Appendix B's mirror images
(Eq. B39-B41), polynomial ghost points (``ends = taylor``), the end conditions and their constraint maps, the
volumes of the extended grid, and the load vector (Eq. 16b; ``loads = faces``). The model, its variants and
their reasons are in model.py."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.scene import Distributed, PointForce, PointMoment, Scene
from ...numerics.loads import cell_integral
from ...theory.higher_order import NF, TH, TS, WS, W, point_work

MIRROR = {  # (sign of theta, theta*, w, w*) of the fictitious images, Appendix B
    "clamped": np.array([-1.0, -1.0, 1.0, 1.0]),
    "guided": np.array([-1.0, -1.0, 1.0, 1.0]),
    "pinned": np.array([1.0, 1.0, -1.0, -1.0]),
    "roller": np.array([1.0, 1.0, -1.0, -1.0]),  # no axial unknown: roller = pinned
}


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
        if not isinstance(load, (PointForce, PointMoment)):  # torques: not carried
            continue
        pos = float(np.clip((load.position - x[0]) / dx, 0.0, n - 1))  # cell-centred grids: beyond the end points
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1:
            t = 0.0
        at_end = t == 0.0 and i in (0, n - 1)
        g = point_work(load, h, faces, at_end)
        for node, wgt in ((i, 1.0 - t), (i + 1, t)):
            if wgt != 0.0:
                F[node] += wgt * g
    return F / A


def end_conditions(
    n: int, left: str, right: str, variant: str, pin: str, h: float, about: str = "point", clamp: str = "face"
) -> tuple[list, list]:
    """(drop, tie): the DOFs held at zero and the ties (slave, master, c), u_slave = c u_master, of the end
    conditions. clamped: theta = theta* = w = w* = 0 (the end face fixed; ``clamp = layer``: w* left free, its
    zero enforced through the layer spring of :mod:`.layer`); guided: theta = theta* = 0;
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
            drop += [NF * k + f for f in ((TH, TS, W) if clamp == "layer" else (TH, TS, W, WS))]
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
    n: int,
    left: str,
    right: str,
    variant: str,
    pin: str,
    h: float,
    numbering: str = "unknowns",
    about: str = "point",
    clamp: str = "face",
) -> sp.csr_matrix:
    """T: u = T z with the end conditions built in (:func:`end_conditions`). ``numbering = "unknowns"``:
    T is 4n x unknowns (the held DOFs eliminated); ``"points"``: 4n x 4n, the numbering of u kept and the
    columns of the held DOFs zero (the band's form: unit rows added by ``Band.fix``)."""
    drop, tie = end_conditions(n, left, right, variant, pin, h, about, clamp)
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


def extended_volumes(k: np.ndarray, n: int, G: tuple[int, int], dx: float, ends: str, variant: str) -> np.ndarray:
    """V_k / A of the extended points k (G[0] ghosts, the n real points, G[1] ghosts): the paper's mirror
    layers carry full volumes (Appendix B); otherwise ghosts carry none and the two end points dx/2."""
    k = np.asarray(k)
    if ends == "mirror" and variant == "paper":
        return np.full(k.shape, dx)
    real = (k >= G[0]) & (k < G[0] + n)
    end = (k == G[0]) | (k == G[0] + n - 1)
    return np.where(real, np.where(end, dx / 2, dx), 0.0)
