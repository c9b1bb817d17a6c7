"""The static solve of the Moyer & Miraglia models with supports inside the span and elastic supports, and their
reactions (:mod:`.pieces` says how each is imposed).

With the variant's operator K and loads b on the scene's plain ends (:func:`.pieces.plain_ends`), every support
condition k adds an unknown force (or couple) R_k acting as the model's own point load at its place, the load column
f_k (:func:`load_column`), and holds c_k·u: rigid, c_k·u = 0; a spring, R_k = -k c_k·u:

    K u = b + Σ_k R_k f_k.

A spring's R_k is eliminated at once (K + k f_k c_kᵀ: two points' entries). A rigid support's R_k is eliminated from
its two rows (the row of the point with the smaller weight minus f's ratio times the other's), and the other row is
replaced by c_k·u = 0: one band one point wider, one banded solve, and R_k from the replaced row as it was. A support
on a point (within 1e-9 of the spacing) is that point's unknown held. A point that a support at an end already
holds is left out of c (its value is zero), and its share of R_k goes to that end.

Reactions (``info["reactions"]``, keyed as exact-eb's: force +z, moment counter-clockwise on the beam; a rod's
``axial_*``, a bar's ``torque_*`` as exact-rod's): the inner supports' R_k and the springs' -k c·u, and at the rigid
ends the held rows' residual (K u - b) times the point's share of the length (variant energy: its rows are the
gradient of an energy, so that residual is the end's force) or the resultant fields at the end (the other variants,
whose ghost closures carry the end's force; rod and bar: -N(0), N(L)). The set is then balanced against the scene's
loads by the least change (``balance_change``, relative to the largest reaction: round-off where the model's own
reactions balance, O(Δ²) where its discrete loads' moment differs from the scene's).
"""

from __future__ import annotations

import re

import numpy as np

from ...core.errors import InputError
from ...core.reactions import load_resultants
from ...core.scene import Distributed, PointForce, PointMoment, PointTorque, Scene
from ...numerics.band import Band
from .kernels import node_loads
from .pieces import Hold, bond_stiffness, holds, interpolation
from .system import Discrete, static_solution, static_system

_UNIT = {"force": "transverse", "moment": "transverse", "axial": "axial", "torque": "torque"}


def _unit_load(reaction: str, at: float):
    if reaction == "force":
        return PointForce(type="point_force", position=at, value=1.0)
    if reaction == "moment":
        return PointMoment(type="point_moment", position=at, value=1.0)
    if reaction == "axial":
        return PointForce(type="point_force", position=at, value=0.0, axial=1.0)
    return PointTorque(type="point_torque", position=at, value=1.0)


def load_column(build, scene: Scene, disc: Discrete, hold: Hold) -> dict[int, float]:
    """{DOF: f}: the rows of a unit point load (force, couple, axial force or torque) at the hold's place, as the
    model applies it. Inside the span: split linearly between the two points around it, per length (variant energy:
    per its points' volumes, ``disc.weights``); at an end, where each variant has its own closure: the change of the
    operator's load vector (``build``: scene -> Discrete) when the unit load is added."""
    x, nf = disc.x, disc.nf
    L = x[-1]
    if 0.0 < hold.position < L:
        one = scene.model_copy(update={"loads": [_unit_load(hold.reaction, hold.position)]})
        q, mu, _ = node_loads(one, x, _UNIT[hold.reaction], ends_apart=True)
        f = mu if hold.reaction == "moment" else q
        col = np.zeros(nf * len(x))
        col[hold.slot :: nf] = f
        if disc.weights is not None:
            col /= disc.weights
    else:
        with_load = scene.model_copy(update={"loads": [_unit_load(hold.reaction, hold.position)]})
        without = scene.model_copy(update={"loads": []})
        col = build(with_load).b - build(without).b
    size = np.abs(col).reshape(-1, nf).max(axis=0)  # each field's rows in their own units (w and γ: a length apart)
    nz = np.flatnonzero(np.abs(col) > 1e-14 * np.tile(size, len(x)))
    return {int(d): float(col[d]) for d in nz}


def _widened(B: Band, extra: int) -> Band:
    """The band with ``extra`` more diagonals on each side (zeros)."""
    W = Band(B.n, B.lower + extra, B.upper + extra)
    W.data[extra : extra + B.data.shape[0]] = B.data
    return W


def _row(B: Band, r: int) -> tuple[np.ndarray, np.ndarray]:
    """(columns, values) of the stored non-zero entries of row r."""
    cols = np.arange(max(0, r - B.lower), min(B.n, r + B.upper + 1))
    vals = B.values(np.full(len(cols), r), cols)
    keep = vals != 0.0
    return cols[keep], vals[keep]


def solve_with_holds(scene: Scene, disc: Discrete, build, kind: str, what: str, couples=None):
    """(u, solve info, {Hold: reaction}, the reactions' loads per DOF, kinks) of the static problem with the scene's
    inner supports and springs (module docstring); ``disc`` the variant's operator on the plain ends, ``build`` makes
    it for another scene's loads; ``couples``: a → (rows, u_s) of a couple applied on its kink (variant energy,
    :mod:`.couples`), used for the supports' moments where it gives one; kinks: (position, R, u_s) of those."""
    nf, x = disc.nf, disc.x
    B, rhs, held = static_system(scene, disc)
    fixed = set(disc.prescribed)
    items, singular, plain = [], {}, []
    for h in holds(scene, kind):
        pts, wts = interpolation(x, h.position)
        c = {int(nf * p + h.slot): float(w) for p, w in zip(pts, wts) if nf * p + h.slot not in fixed}
        got = couples(h.position) if couples is not None and h.reaction == "moment" and h.label != "left" else None
        if couples is not None and h.reaction == "moment" and h.label.startswith("inner") and got is None:
            plain.append(h.label)  # no kink accepted there: the couple on the two points around it
        if got is not None and h.label != "right":
            nz = np.flatnonzero(got[0])
            f, singular[h] = {int(d): float(got[0][d]) for d in nz}, got[1]
        else:
            f = load_column(build, scene, disc, h)
        items.append((h, c, f, kink(scene, kind, h, x)))
    springs = [(h, c, f, eps) for h, c, f, eps in items if h.stiffness is not None and c]
    rigid = [(h, c, f, eps) for h, c, f, eps in items if h.stiffness is None and c]
    _check_apart(rigid, x, scene)
    P = _pivots(rigid, fixed)
    reach = [abs(q - p) for p in P for _, c, f, _ in rigid for q in list(f) + list(c)]
    spread = [abs(q - d) for _, c, f, _ in springs for q in f for d in c]
    # a row moved onto another, or a condition's entries, that far from the diagonal; a pivot row that a spring's terms
    # reach carries them along when it is moved, so the two reaches add
    extra = max(reach, default=0) + max(spread, default=0)
    if extra > 0:
        B = _widened(B, extra)
    for h, c, f, eps in springs:  # K + k' f cᵀ, k' = k / (1 + k ε)
        rows, cols = np.meshgrid(list(f), list(c), indexing="ij")
        vals = h.stiffness / (1 + h.stiffness * eps) * np.outer(list(f.values()), list(c.values()))
        B.add_entries(rows.ravel(), cols.ravel(), vals.ravel())
    kept = None
    if rigid:
        kept = _eliminate(B, rhs, rigid, P, fixed)
    u, info = static_solution(scene, disc, what, (B, rhs, held))
    if plain:
        info["couples_on_two_points"] = plain
    R = {}
    if kept is not None:
        G, rowsP, bP = kept
        r = np.array([vals @ u[cols] for cols, vals in rowsP]) - bP
        for (h, *_), v in zip(rigid, G @ r):
            R[h] = float(v)
    for h, c, _, eps in springs:
        R[h] = float(-h.stiffness / (1 + h.stiffness * eps) * sum(w * u[d] for d, w in c.items()))
    loads = np.zeros(len(u))
    for h, _, f, _ in items:
        for d, v in f.items():
            loads[d] += R.get(h, 0.0) * v
    kinks = [(h.position, R.get(h, 0.0), us) for h, us in singular.items()]
    return u, info, R, loads, kinks


def _pivots(rigid, fixed) -> list[int]:
    """One row per rigid condition whose equation gives up its reaction for the condition: the row of a held unknown
    (the condition's own, as a held end's row is) where the load column has an entry there, else the largest entry
    of the column among the rows not taken yet. A couple applied on its kink (:mod:`.couples`) loads the rows of w
    around the support most, by up to (L/h)^2 times its rotation row; pivoting on one of those leaves slender beams
    singular to working precision (a clamp inside the span, L/h = 100 from 201 points), on the rotation's own row they
    stay second order (L/h = 10^4, where that row holds 2e-4 to 5e-3 of the column; docs/models/moyer.md). Whatever
    the elimination's multipliers cost in rounding is in the solve's round-off bound: its entries are the final ones."""
    P = []
    for _, c, f, _ in rigid:
        free = [d for d in f if d not in P and d not in fixed]
        own = [d for d in free if d in c and f[d] != 0.0]
        P.append(max(own or free, key=lambda d: (abs(f[d]), d in c)))
    return P


def _eliminate(B: Band, rhs: np.ndarray, rigid, P, fixed):
    """The reactions R = G (K_P u - b_P) eliminated from every other row of their load columns and the rows P
    replaced by the conditions c·u + ε R = 0 (scaled as the row's diagonal). Returns (G, rows P, b_P) for R."""
    F = np.array([[f.get(p, 0.0) for _, _, f, _ in rigid] for p in P])  # F[i, k] = f_k at row p_i
    G = np.linalg.inv(F)
    rowsP = [_row(B, p) for p in P]
    bP = rhs[P].copy()
    others = sorted({q for _, _, f, _ in rigid for q in f} - set(P) - set(fixed))
    for q in others:  # row q: K_q u - b_q = Σ_k f_k[q] R_k
        coef = np.array([f.get(q, 0.0) for _, _, f, _ in rigid]) @ G
        for i, (cols, vals) in enumerate(rowsP):
            if coef[i]:
                B.add_entries(np.full(len(cols), q), cols, -coef[i] * vals)
                rhs[q] -= coef[i] * bP[i]
    for k, (p, (_, c, _, eps)) in enumerate(zip(P, rigid)):
        scale = abs(B.values([p], [p])[0]) or 1.0
        B.clear_rows([p])
        B.add_entries(np.full(len(c), p), list(c), scale * np.array(list(c.values())))
        rhs[p] = 0.0
        for i, (cols, vals) in enumerate(rowsP):
            if G[k, i] and eps:
                B.add_entries(np.full(len(cols), p), cols, scale * eps * G[k, i] * vals)
                rhs[p] += scale * eps * G[k, i] * bP[i]
    return G, rowsP, bP


def kink(scene: Scene, kind: str, hold: Hold, x: np.ndarray) -> float:
    """ε of the held value's interpolation: a support's force R bends the field's slope by -R/S at its place (S = kGA
    for a beam's deflection, EI for its rotation, EA or GJ for a rod's or bar's unknown, over the interval around it),
    so the two points around it interpolate c·u = u(a) - ε R with ε = t (1 - t) Δ / S; 0 on a point."""
    dx = x[1] - x[0]
    pos = (hold.position - x[0]) / dx
    i = int(np.clip(np.floor(pos), 0, len(x) - 2))
    t = pos - i
    if t < 1e-9 or t > 1 - 1e-9:
        return 0.0
    key = {"force": "kGA", "moment": "EI", "axial": "EA", "torque": "GJ"}[hold.reaction]
    S = float(bond_stiffness(scene, x[i], x[i + 1], key))
    return t * (1 - t) * dx / S


def _check_apart(rigid, x, scene):
    """Two rigid conditions on one unknown (two supports between the same points) cannot both hold: one line."""
    owner = {}
    for h, c, *_ in rigid:
        for d in c:
            if d in owner and owner[d] != h.label:
                dx = x[1] - x[0]
                a, b = (re.sub(r"^inner_(\d+)$", r"inner[\1]", v) for v in (owner[d], h.label))  # the scene's names
                raise InputError(
                    f"supports.{a} and supports.{b} are within one spacing ({dx:.4g}) of each other at "
                    f"points = {len(x)}; use more points (a spacing below their distance)"
                )
            owner[d] = h.label


# -- reactions ----------------------------------------------------------------------------------------------------

END_KEYS = {"beam": ("force", "moment"), "axial": ("axial",), "torsion": ("torque",)}
_HELD_BY = {  # the rigid end supports that hold each reaction component
    "force": ("clamped", "pinned", "roller"),
    "moment": ("clamped", "guided"),
    "axial": ("clamped", "pinned"),
    "torque": ("clamped", "pinned", "roller"),
}


def reactions(scene: Scene, kind: str, R: dict, end_values: dict, ends_from: str) -> dict:
    """``info["reactions"]``: the inner supports' and springs' R (:func:`solve_with_holds`), the rigid ends'
    ``end_values`` {(side, key): value} (``ends_from`` says where they come from), balanced against the scene's loads
    by the least change (module docstring)."""
    out, rows = {}, []
    for side in ("left", "right"):
        at = 0.0 if side == "left" else scene.length
        sup = getattr(scene.supports, side)
        for key in END_KEYS[kind]:
            name = f"{key}_{side}"
            rigid = isinstance(sup, str) and sup in _HELD_BY[key]
            out[name] = end_values.get((side, key), 0.0) if rigid else 0.0
            if rigid:
                rows.append((name, key, at))
    for h, v in R.items():
        name = f"{h.reaction}_{h.label}"
        out[name] = out.get(name, 0.0) + v
        if h.stiffness is None:
            rows.append((name, h.reaction, h.position))
    change = _balance(scene, kind, out, rows)
    out["method"] = (
        "inner supports: the multipliers of their conditions; springs: -k times the held value; rigid ends: "
        + ends_from
        + "; balanced against the loads by the least change"
    )
    out["balance_change"] = change
    return out


def _balance(scene: Scene, kind: str, out: dict, rows: list) -> float:
    """Move the rigid reactions ``rows`` by the least change (moments per length) that makes the reactions balance
    the scene's loads; returns the largest change over the largest reaction."""
    L = scene.length
    if kind == "beam":
        P, Mo = load_resultants(scene)
        target = np.array([-P, -Mo])

        def coef(key, at):
            return np.array([1.0, at]) if key == "force" else np.array([0.0, 1.0])

        total = np.zeros(2)
        for name, v in out.items():
            total += coef(name.split("_")[0], _position(scene, name)) * v
    else:
        target = np.array([-_axial_total(scene, kind)])

        def coef(key, at):
            return np.array([1.0])

        total = np.array([sum(out.values())])
    if not rows:
        return 0.0
    A = np.column_stack([coef(key, at) for _, key, at in rows])
    w = np.array([1.0 if key in ("force", "axial", "torque") else L * L for _, key, at in rows])  # moment/L in N
    if kind == "torsion":
        w[:] = 1.0
    # the moment equation about mid-span (a mirror image's is the same equation mirrored; about an end, the
    # compromise below would depend on which end) and over L, in the force equation's unit: where the rows cannot meet
    # both (one inner support, the rest springs) the least-squares balance then weighs them alike in any length unit
    # and in the mirror image
    S = np.array([[1.0, 0.0], [-0.5, 1.0 / L]])[: A.shape[0], : A.shape[0]]  # (force, moment about 0 / L - force / 2)
    A, residual = S @ A, S @ (target - total)
    M = (A * w) @ A.T
    rank = np.linalg.matrix_rank(M)
    if rank == 0:
        return 0.0
    d = (A * w).T @ (np.linalg.pinv(M) @ residual)
    for (name, _, _), dv in zip(rows, d):
        out[name] += float(dv)
    big = max(abs(v) for v in out.values() if isinstance(v, float)) or 1.0
    return float(np.abs(d).max() / big)


def _position(scene: Scene, name: str) -> float:
    side = name.split("_", 1)[1]
    if side == "left":
        return 0.0
    if side == "right":
        return scene.length
    return scene.supports.inner[int(side.split("_")[1])].position


def _axial_total(scene: Scene, kind: str) -> float:
    """The scene's total axial force (``kind = "axial"``) or torque (``"torsion"``)."""
    total = 0.0
    for load in scene.loads:
        if isinstance(load, Distributed):
            v = load.axial if kind == "axial" else load.torque
            if v:
                a, b = scene.span(load)
                if load.shape == "uniform":
                    total += v * (b - a)
                else:
                    k = np.pi / scene.length
                    total += v * (np.cos(k * a) - np.cos(k * b)) / k
        elif kind == "axial" and isinstance(load, PointForce):
            total += load.axial
        elif kind == "torsion" and isinstance(load, PointTorque):
            total += load.value
    return total
