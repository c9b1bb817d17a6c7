"""Loads, supports and springs on the points of the pair form (:mod:`.pairs`): nodal forces, the linear conditions
the supports put on w (held deflections and rotations anywhere along the beam, prescribed deflections) and the
springs' stiffness. A position between two points acts on both, split linearly (the consistent load of a linear
interpolant); a rotation is the centred slope (w_{k+1} - w_{k-1}) / (2 dx) at an interior point and the one-sided
second-order slope at an end point, split the same way. Arrays in, arrays out.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ...core.errors import SolveError
from ...core.scene import Distributed, PointForce, PointMoment, Scene, Spring
from ...numerics.loads import cell_integral

HOLDS_W = ("clamped", "pinned", "roller")


def split(position: float, n: int, dx: float) -> list[tuple[int, float]]:
    """[(point, weight)]: ``position`` between its two nearest points, weights 1 - t and t (one point when on it)."""
    pos = position / dx
    i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
    t = pos - i
    if abs(t) < 1e-9 or i == n - 1:
        return [(i, 1.0)]
    return [(i, 1.0 - t), (i + 1, t)]


def value_row(position: float, n: int, dx: float) -> dict[int, float]:
    """{point: weight} of the linear interpolant of w at ``position``."""
    return dict(split(position, n, dx))


def slope_row(position: float, n: int, dx: float) -> dict[int, float]:
    """{point: weight} of the rotation w' at ``position``: centred slopes at interior points, one-sided
    (-3 w_0 + 4 w_1 - w_2) / (2 dx) at the ends, split linearly between the two nearest points."""
    row: dict[int, float] = {}
    for node, wgt in split(position, n, dx):
        if 0 < node < n - 1:
            terms = {node - 1: -1.0, node + 1: 1.0}
        elif node == 0:
            terms = {0: -3.0, 1: 4.0, 2: -1.0}
        else:
            terms = {n - 1: 3.0, n - 2: -4.0, n - 3: 1.0}
        for p, c in terms.items():
            row[p] = row.get(p, 0.0) + wgt * c / (2 * dx)
    return row


def nodal_loads(scene: Scene, n: int, dx: float, loads=None) -> np.ndarray:
    """Nodal forces of the scene's ``loads`` (default all): distributed loads as the integrals over each point's cell
    [x - dx/2, x + dx/2] within the beam, point forces split linearly, point moments as the couples of
    :func:`slope_row` (the work C w' of a couple C)."""
    x = np.arange(n) * dx
    L = scene.length
    F = np.zeros(n)
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    for load in scene.loads if loads is None else loads:
        if isinstance(load, Distributed):
            F += cell_integral(load, scene, lo, hi)
        elif isinstance(load, PointForce):
            for p, c in value_row(load.position, n, dx).items():
                F[p] += c * load.value
        elif isinstance(load, PointMoment):
            for p, c in slope_row(load.position, n, dx).items():
                F[p] += c * load.value
    return F


@dataclass
class Conditions:
    """What the supports do to w: ``rows`` (m x n, sparse) and ``values`` of the conditions rows @ w = values,
    their ``names`` (the reaction each condition's multiplier is: ``force_left``, ``moment_inner_0``, ...), the
    springs' stiffness matrix ``springs`` and, per spring, (reaction name, row, stiffness) in ``spring_rows``."""

    rows: sp.csr_matrix
    values: np.ndarray
    names: list[str]
    springs: sp.csr_matrix
    spring_rows: list = field(default_factory=list)


def _sparse(rows: list[dict[int, float]], n: int) -> sp.csr_matrix:
    r = np.concatenate([np.full(len(d), i) for i, d in enumerate(rows)]) if rows else np.zeros(0, int)
    c = np.concatenate([list(d) for d in rows]) if rows else np.zeros(0, int)
    v = np.concatenate([list(d.values()) for d in rows]) if rows else np.zeros(0)
    return sp.csr_matrix((v, (r.astype(int), np.asarray(c, int))), shape=(len(rows), n))


def stiff_springs(scene: Scene, springs: list, dx: float) -> None:
    """SolveError naming the springs whose stiffness against the beam's at one spacing (k dx^3 / EI for a deflection,
    k dx / EI for a rotation, EI the least of the segments') passes 1/eps: added to the pairs' equations, the beam's
    own stiffness there is lost in the spring's rounding (a spring of 1e40 N/m left a rigid support's beam 40 % off,
    its round-off bound blind to it)."""
    EI = min(mat.E * sec.I for _, _, sec, mat in scene.pieces())
    found = []
    for name, _, k in springs:
        ratio = k * (dx**3 if name.startswith("force") else dx) / EI
        if ratio * np.finfo(float).eps > 1.0:
            what = "k dx^3 / EI" if name.startswith("force") else "k dx / EI"
            kind, _, where = name.partition("_")
            field = f"inner[{where[6:]}]" if where.startswith("inner_") else where
            key = "stiffness" if kind == "force" else "rotational_stiffness"
            found.append(f"supports.{field}.{key} = {k:g} ({what} = {ratio:.2g})")
    if found:
        raise SolveError(
            f"pd-bond-pair: springs far stiffer than the beam at this spacing, beyond what float64 adds to it (1/eps): "
            f"{'; '.join(found)}; give a rigid support there (pinned, clamped) instead"
        )


def conditions(scene: Scene, n: int, dx: float, factor: float = 1.0) -> Conditions:
    """The conditions and springs of ``scene``'s supports on ``n`` points (the rotation of a clamped or guided end is
    held by its mirror ghosts). Prescribed deflections (``[[loads]] type = "displacement"``) are conditions with
    value ``factor`` times theirs."""
    L = scene.length
    rows, values, names, springs = [], [], [], []
    for side, at in (("left", 0.0), ("right", L)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            if sup.stiffness:
                springs.append((f"force_{side}", value_row(at, n, dx), sup.stiffness))
            if sup.rotational_stiffness:
                springs.append((f"moment_{side}", slope_row(at, n, dx), sup.rotational_stiffness))
            continue
        if sup in HOLDS_W:
            rows.append(value_row(at, n, dx)), values.append(0.0), names.append(f"force_{side}")
    for i, s in enumerate(scene.supports.inner):
        if s.type == "spring":
            if s.stiffness:
                springs.append((f"force_inner_{i}", value_row(s.position, n, dx), s.stiffness))
            if s.rotational_stiffness:
                springs.append((f"moment_inner_{i}", slope_row(s.position, n, dx), s.rotational_stiffness))
            continue
        rows.append(value_row(s.position, n, dx)), values.append(0.0), names.append(f"force_inner_{i}")
        if s.type == "clamped":
            rows.append(slope_row(s.position, n, dx)), values.append(0.0), names.append(f"moment_inner_{i}")
    for i, load in enumerate(scene.loads):
        if load.type == "displacement":
            rows.append(value_row(load.position, n, dx)), values.append(factor * load.value)
            names.append(f"force_displacement_{i}")
    stiff_springs(scene, springs, dx)
    Ks = sp.csr_matrix((n, n))
    for _, row, k in springs:
        r = _sparse([row], n)
        Ks = Ks + k * (r.T @ r)
    return Conditions(_sparse(rows, n), np.array(values, float), names, Ks.tocsr(), springs)
