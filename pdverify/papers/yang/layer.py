"""The clamped end's w* boundary layer of ``pd-higher-order`` (corrected variant, option ``clamp = layer``).

A clamp fixes the end face: w* = 0 there. Away from the end w* follows the section's Poisson contraction
(the s^2 and nu a s terms of Eq. 9), so w* climbs from 0 to that value over a layer of width
ell = sqrt(D / R) = h sqrt(3 (1 - nu) / 160) ~ 0.11 h, with D = G h^5 / 80 (the e^2 term, e = w*' xi + ...) and
R = E' h^3 / 3 (the s^2 term, s = 2 xi w*) of Eq. 9. Once the spacing is many ell (every slender beam on any
practical grid), holding w* = 0 on the end point spreads the layer over the end point's volume dx / 2: the
clamp's stiffening acts over dx / 2 instead of ~ell, a first-order error in dx (docs/models/yang.md).

``clamp = layer`` keeps the face condition's energy but not its grid: w* of the end point is free, and a spring
k (per unit area) ties it to zero. The continuous layer's energy for an outer value w_p is S w_p^2 / 2,
S = sqrt(D R) / h (per unit area: the section is the rectangle of depth h). The grid's own layer (w* of the
end point free to move, the rest relaxing) has the stiffness s_d, the Schur complement of the operator's
w*-w* block onto the end point (the discrete Dirichlet-to-Neumann map). The spring in series with the grid,
k s_d / (k + s_d) = S, gives k = S s_d / (s_d - S): the layer's energy is S's whatever the spacing. On a grid
that resolves the layer s_d -> S and k -> infinity: the face condition again (:func:`spring`)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...core.scene import Scene
from ...numerics.band import Band
from ...theory.higher_order import NF, WS

DECAY = 20  # the window of the discrete layer reaches this many ell beyond the end's bonds (e^-20 ~ 2e-9)


def layer_constants(E: float, nu: float, G: float, h: float) -> tuple[float, float]:
    """(S, ell): the continuous layer's stiffness per unit area, sqrt(D R) / h, and its width sqrt(D / R), with
    D = G h^5 / 80 (Eq. 9's h^5/80 G e^2) and R = E' h^3 / 3 (Eq. 9's E' h^3/12 s^2, s = 2 xi w*)."""
    D = G * h**5 / 80
    R = E / (1.0 - nu * nu) * h**3 / 3
    return float(np.sqrt(D) * np.sqrt(R) / h), float(np.sqrt(D / R))  # sqrt(D R) would overflow for E past ~1e159


def block_window(B: Band, points: np.ndarray) -> sp.csc_matrix:
    """The w*-w* block B[dofs][:, dofs], dofs = NF points + WS, of consecutive ``points`` (either order), read
    from the band (:meth:`Band.values`); sparse, with the band's reach."""
    dofs = NF * np.asarray(points) + WS
    size = len(dofs)
    reach = min(B.upper, B.lower) // NF
    a = np.arange(size)
    rows, cols, vals = [], [], []
    for o in range(-min(reach, size - 1), min(reach, size - 1) + 1):  # window positions a -> a + o
        i = a[max(0, -o) : size - max(0, o)]
        r, c = dofs[i], dofs[i + o]
        rows.append(i), cols.append(i + o), vals.append(B.values(r, c))
    return sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size))


def grid_layer_stiffness(B: Band, end: int, n: int, reach: int, dx: float, ell: float) -> float:
    """s_d: the Schur complement onto w* of the end point (``end`` = 0 or n - 1) of the band's w*-w* block over
    the end's window: ``reach`` points (the end's bonds and end layers) plus DECAY ell. The other DOFs are held:
    the layer is w*'s alone, as S is."""
    size = min(n, reach + int(np.ceil(DECAY * ell / dx - 1e-9)) + 1)
    points = np.arange(size) if end == 0 else n - 1 - np.arange(size)
    K = block_window(B, points)
    c = K[1:, 0].toarray().ravel()
    return float(K[0, 0] - c @ spla.spsolve(K[1:, 1:].tocsc(), c))


def spring(s_d: float, S: float) -> float:
    """k = S s_d / (s_d - S): the spring that, in series with the grid's layer s_d, has the continuous layer's
    stiffness S; inf (the face condition w* = 0) where the grid's layer is already as stiff or softer, or where
    S is not a positive number (a degenerate material: the solve reports it)."""
    return S / (1.0 - S / s_d) if 0 < S < s_d else np.inf  # S s_d / (s_d - S), without the product's overflow


def clamp_springs(B: Band, scene: Scene, n: int, dx: float, reach: int, drop: list) -> dict:
    """``clamp = layer``: the spring k = S s_d / (s_d - S) on w* of each clamped end point, added to the band;
    where the grid's layer is already as stiff as the face's (s_d <= S) w* is held (appended to ``drop``).
    Returns {side: {"w_star": "spring" | "held ...", "grid_over_face": s_d / S, "spring_over_face": k / S,
    "width": the layer's width ell}}."""
    mat = scene.material
    S, ell = layer_constants(mat.E, mat.poissons_ratio, mat.G, scene.section.depth)
    ends = [(s, e) for s, e in (("left", 0), ("right", n - 1)) if getattr(scene.supports, s) == "clamped"]
    grid = [grid_layer_stiffness(B, end, n, reach, dx, ell) for _, end in ends]  # both before either spring
    out = {}
    for (side, end), s_d in zip(ends, grid):
        k = spring(s_d, S)
        dof = NF * end + WS
        if np.isfinite(k):
            B.add_entries(np.array([dof]), np.array([dof]), np.array([k]))
        else:
            drop.append(dof)
        ratio = (s_d / S, k / S) if S > 0 else (np.inf, np.inf)
        out[side] = {
            "w_star": "spring" if np.isfinite(k) else "held (the grid resolves the layer)",
            "grid_over_face": ratio[0],
            "spring_over_face": ratio[1],
            "width": ell,
        }
    return out
