"""The linear pair form of pd-bond-pair on any straight scene (:mod:`.pairs`, :mod:`.conditions`): supports inside
the span, springs at the ends and inside, segments of their own section and material, prescribed deflections.

Energy Π = ½ w^T (D^T A D + K_s) w - F^T w with the conditions C w = g of the supports, eliminated exactly
(w = T z + w0: each condition fixes one point's w through the others, chosen by a pivoted QR of C). Segments: each
pair's alpha comes from the harmonic mean of EI over the pair (:func:`pair_EI`; O'Grady & Foster write alpha(x) per
point, §3.1, and give no interface). Reactions are the conditions' multipliers and the springs' forces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from ...core.errors import SolveError
from ...core.scene import Scene
from .calibration import alpha, pair_family
from .conditions import Conditions, conditions, nodal_loads
from .mixed import solve_mixed
from .pairs import Pairs, build_pairs


def pair_EI(scene: Scene, centre: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """The EI of each pair centred at ``centre`` with bonds of length ``xi``: the harmonic mean of EI over
    [centre - xi, centre + xi] weighted by the triangle (xi - |s - centre|) / xi² (the weight with which the pair's
    deviation phi / xi averages the curvature). Under a moment M that varies little over the pair, phi = xi M <1/EI>,
    so the pair's energy a phi² / 2 with alpha from this EI is the beam's complementary energy M² <1/EI> / 2 over
    it: the pairs straddling an interface carry the flexibility of both sides (1 for a uniform beam, exactly). The
    segments at the ends continue beyond them."""
    pieces = scene.pieces()
    flex = np.zeros(len(centre))
    lo_all, hi_all = centre - xi, centre + xi
    for i, (a, b, sec, mat) in enumerate(pieces):
        a = -np.inf if i == 0 else a
        b = np.inf if i == len(pieces) - 1 else b
        lo, hi = np.maximum(lo_all, a), np.minimum(hi_all, b)
        flex += _triangle_mass(lo, hi, centre, xi) / (mat.E * sec.I)
    return 1.0 / flex


def _triangle_mass(lo, hi, c, xi):
    """∫_lo^hi (xi - |s - c|) / xi² ds for lo <= hi inside [c - xi, c + xi] (0 where lo >= hi)."""

    def F(s):  # the antiderivative of the triangle from c - xi
        t = (s - c) / xi
        return np.where(t <= 0, 0.5 * (1 + t) ** 2, 1.0 - 0.5 * (1 - t) ** 2)

    return np.where(hi > lo, F(np.maximum(hi, lo)) - F(lo), 0.0)


def end_rules(scene: Scene) -> tuple[str, str]:
    """The mirror ghost rule of each end: its support's name, ``free`` for a spring."""
    return tuple(scene.supports.kind(s) if scene.supports.kind(s) != "spring" else "free" for s in ("left", "right"))


def scene_pairs(scene: Scene, params: dict, omega: np.ndarray | None = None) -> Pairs:
    """The pairs of ``scene`` with the options ``params`` (points, horizon, variant, ends) and weights ``omega``;
    alpha per pair from :func:`pair_EI` (Eq. 5 / §3.1 with the local EI)."""
    n = params["points"]
    dx = scene.length / (n - 1)
    m, variant = params["horizon"], params["variant"]
    j, beta = pair_family(m, dx, variant)
    om = np.ones(len(j)) if omega is None else np.asarray(omega, float)
    pairs = build_pairs(n, dx, j, beta, om, np.ones(n), params["ends"], end_rules(scene))
    if not scene.segments:
        pairs.stiffness = pairs.stiffness * alpha(scene.EI, m, dx, variant, omega)
    else:
        EI = pair_EI(scene, pairs.centre * dx, pairs.xi)
        pairs.stiffness = pairs.stiffness * alpha(EI, m, dx, variant, omega)
    return pairs


@dataclass
class Elimination:
    """w = T z + w0 satisfies C w = g for every z; ``dep`` the points the conditions fix, ``Cd`` = C[:, dep],
    ``free`` the points z holds (in order)."""

    T: sp.csr_matrix
    w0: np.ndarray
    dep: np.ndarray
    Cd: np.ndarray
    free: np.ndarray

    def multipliers(self, residual: np.ndarray) -> np.ndarray:
        """The conditions' multipliers lambda from the residual K w - F at the fixed points (C_d^T lambda = -r_dep):
        the reactions the conditions exert (force up, moment counter-clockwise)."""
        if not len(self.dep):
            return np.zeros(0)
        r = np.abs(self.Cd).max(axis=1)  # each condition at its own scale (eliminate): C_d = diag(r) (C_d / r)
        return la.solve((self.Cd / r[:, None]).T, residual[self.dep]) / r


def eliminate(C: sp.csr_matrix, g: np.ndarray, n: int, what: str) -> Elimination:
    """The elimination of the conditions C w = g (m of them on n points)."""
    m = C.shape[0]
    if m == 0:
        return Elimination(sp.identity(n, format="csr"), np.zeros(n), np.zeros(0, int), np.zeros((0, 0)), np.arange(n))
    cols = np.unique(C.indices)
    Cs = C[:, cols].toarray()
    # each row at its own scale: a slope's rows carry 1 / dx, a deflection's 1, so an absolute mix reads a short
    # beam's (a spacing of 4e-11) slope rows as dependent on nothing (the rank's test is relative to the largest)
    Cs /= np.abs(Cs).max(axis=1, keepdims=True)
    _, R, piv = la.qr(Cs, pivoting=True, mode="economic")
    d = np.abs(np.diag(R))
    if len(d) < m or d.min() <= 1e-10 * d.max():
        raise SolveError(f"{what}: the supports' conditions repeat or contradict one another; give each once")
    dep = cols[piv[:m]]
    ind = np.setdiff1d(np.arange(n), dep)
    Cd = C[:, dep].toarray()
    r = np.abs(Cd).max(axis=1)
    Cd_inv = la.inv(Cd / r[:, None]) / r[None, :]  # inv(diag(1/r) C_d) diag(1/r): each row at its own scale
    top = sp.csr_matrix((np.ones(len(ind)), (ind, np.arange(len(ind)))), shape=(n, len(ind)))
    dense = -Cd_inv @ C[:, ind].toarray()  # m rows: the fixed points' w in terms of the free ones
    nz = np.nonzero(dense)
    T = top + sp.csr_matrix((dense[nz], (dep[nz[0]], nz[1])), shape=(n, len(ind)))
    w0 = np.zeros(n)
    w0[dep] = Cd_inv @ g
    return Elimination(T.tocsr(), w0, dep, Cd, ind)


def reactions(cond: Conditions, elim: Elimination, residual: np.ndarray, w: np.ndarray) -> dict[str, float]:
    """Every support's force and moment on the beam (up, counter-clockwise), named as exact-eb names them."""
    out: dict[str, float] = {}
    lam = elim.multipliers(residual)
    for name, value in zip(cond.names, lam):
        out[name] = out.get(name, 0.0) + float(value)
    for name, row, k in cond.spring_rows:
        out[name] = out.get(name, 0.0) - k * float(sum(c * w[p] for p, c in row.items()))
    return out


def linear_system(scene: Scene, params: dict, omega=None):
    """(K_r, rhs, elimination, (pairs, conditions, K, F)): the reduced system K_r z = rhs of the linear pair form,
    w = T z + w0."""
    n = params["points"]
    dx = scene.length / (n - 1)
    pairs = scene_pairs(scene, params, omega)
    cond = conditions(scene, n, dx)
    elim = eliminate(cond.rows, cond.values, n, f"pd-bond-pair ({params['variant']}, {params['ends']} ends)")
    K = pairs.stiffness_matrix() + cond.springs
    F = nodal_loads(scene, n, dx)
    Kr = (elim.T.T @ K @ elim.T).tocsr()
    return Kr, elim.T.T @ (F - K @ elim.w0), elim, (pairs, cond, K, F)


def reaction_couples(
    cond: Conditions, elim: Elimination, residual: np.ndarray, w: np.ndarray, ends: bool = True
) -> np.ndarray:
    """The nodal forces of the supports' couples (the rotations held inside the span, rotational springs): force pairs
    that carry no shear (:func:`.recovery.shear`). ``ends = False`` leaves out the end springs' couples: at mirror ends
    the moment near the end is re-derived by statics (:func:`.recovery.end_statics`), with no force pair in it."""
    out = np.zeros(len(w))
    lam = elim.multipliers(residual)
    for name, value, row in zip(cond.names, lam, cond.rows):
        if name.startswith("moment"):
            out += value * row.toarray().ravel()
    for name, row, k in cond.spring_rows:
        if name.startswith("moment") and (ends or "inner" in name):
            r = np.zeros(len(w))
            r[list(row)] = list(row.values())
            out -= k * (r @ w) * r
    return out


def solve_pairs_linear(scene: Scene, params: dict, omega=None):
    """(x, w, pairs, f, info): the linear pair form of ``scene`` solved in the mixed form (:mod:`.mixed`); ``f`` the
    pair forces; info holds the reactions and the solve's info."""
    n = params["points"]
    dx = scene.length / (n - 1)
    pairs = scene_pairs(scene, params, omega)
    cond = conditions(scene, n, dx)
    what = f"pd-bond-pair ({params['variant']}, {params['ends']} ends)"
    elim = eliminate(cond.rows, cond.values, n, what)
    F = nodal_loads(scene, n, dx)
    w, f, info = solve_mixed(pairs, elim, cond.springs, F, what)
    g = pairs.D.T @ f + cond.springs @ w  # the nodal forces of the pairs and springs: loads plus reactions
    info["reactions"] = reactions(cond, elim, g - F, w)
    info["nodal_forces"] = g
    info["reaction_couples"] = reaction_couples(cond, elim, g - F, w, ends=params["ends"] != "mirror")
    return np.arange(n) * dx, w, pairs, f, info


def off_grid_holds(scene: Scene, dx: float) -> list[str]:
    """A clamp or rotational spring inside the span between two points of the grid of spacing ``dx``: the pair form
    spreads its couple over them, and M beside it does not converge (docs/models/ogrady.md, "Known limits")."""
    out = []
    for i, s in enumerate(scene.supports.inner):
        off = abs(s.position / dx - round(s.position / dx)) > 1e-9 * scene.length / dx
        if (s.type == "clamped" or (s.type == "spring" and s.rotational_stiffness)) and off:
            out.append(
                f"supports.inner[{i}] ({s.type}) at x = {s.position:g} lies between two points of the grid: the "
                "bond-pair beam spreads its couple over them, so M beside it does not converge with the points (30-50 "
                "% of max |M| off at 161-1281 points, a clamp at 1.07 m of a 2 m beam; w 1.1 %, 1.3 %, 0.25 %, 0.35 "
                "%, not first order); give points that put it on a grid point, or use pd-eb or pd-timoshenko"
            )
    return out


def first_order_warnings(scene: Scene, dx: float | None = None) -> list[str]:
    """The supports the pair form holds at first order only, or (a clamp or rotational spring inside the span between
    two points of the grid of spacing ``dx``) not at all in M (measured: docs/models/ogrady.md)."""
    out = off_grid_holds(scene, dx) if dx is not None else []
    joints = {g.start for g in scene.segments[1:]}
    for i, s in enumerate(scene.supports.inner):
        if any(line.startswith(f"supports.inner[{i}] ") for line in out):
            continue
        if s.type == "clamped" or (s.type == "spring" and s.rotational_stiffness):
            on = any(abs(s.position - j) <= 1e-9 * scene.length for j in joints)
            joint = (  # docs/models/diyaroglu.md, "Known limits": the same scene, EI stepping 37-fold at the clamp
                "; on a segment joint the constant is large: 0.31, 0.12, 0.039 of max |w| at 41, 161, 641 points "
                "where EI steps 37-fold there"
                if on
                else ""
            )
            out.append(
                f"supports.inner[{i}] ({s.type}): the bond-pair beam holds the centred slope there, first order in "
                "the spacing, the rotation too (measured order 0.99 for a clamp at mid-span; the deflection converges "
                "at order 2 without it; examples, each relative to its largest value, h the spacing: on a "
                "pinned-pinned beam clamped at mid-span w 3.2 h / L, the rotation 6.1 h / L and M 2.4 h / L off "
                "under a force at L / 4, w about 0.8 h / d and the rotation 1.6 h / d under a force d from the clamp "
                "(w 0.21, 0.15, 0.086 at 201, 401, 801 points at d = 0.01 L), more on other supports (w 0.57 at 801 "
                "points on a cantilever clamped inside at 0.5 L, a force 0.01 L from it) and far more where the force "
                "is in a short span beside a long side that the clamp's slope turns (a cantilever clamped inside at "
                "0.3 L: w 0.28, 0.15 at 801, 1601 points under a force at 0.25 L; 1.31, 0.71 at 0.29 L), and M and V "
                "in a short span beside it (a clamp 0.04 L from a pinned end: V 0.60, 0.19, 0.10 of max |V| and M "
                "0.096, 0.034, 0.018 of max |M| at 201, 801, 1601 points); `solve "
                "--estimate` gives this scene's where its grids are asymptotic and says so where they are not; pd-eb "
                f"and pd-timoshenko are second order there){joint}"
            )
    for side in ("left", "right"):
        end = getattr(scene.supports, side)
        if not isinstance(end, str) and end.rotational_stiffness:
            out.append(
                f"supports.{side}: a rotational spring acts on the end slope of the bond-pair beam, which is first "
                "order in the spacing, and with it w, the rotation and M (its boundary layer; measured order 1.0; "
                "examples with k = kr = 1e12 on a 1 m steel beam, each relative to its largest value, h the spacing: "
                "M 3.7 h / L; w 5.4 h / L and the rotation 9.1 h / L under a uniform load; w about 2.4 h / d and the "
                "rotation 3.2 h / d under a force d from the end (w 46 h / L at d = 0.05 L, 115 h / L at 0.02 L); a "
                "soft spring, kr L / EI below 1, far less; `solve --estimate` gives this scene's; pd-eb and "
                "pd-timoshenko are second order there)"
            )
    return out
