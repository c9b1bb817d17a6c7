"""The pair form solved with the pair forces as unknowns beside the deflection (O'Grady & Foster 2014, Eq. 2 with
small rotations), pdverify's mixed form of the bond-pair beam:

    f_p / a_p - (D w)_p = -phi^p_p       (elastic pairs: f = a (phi - phi^p), phi^p the plastic offset, Eq. 7)
    f_p               = f̄_p              (pairs at their cap, Eq. 7, or broken, f̄ = 0, Eq. 8)
    D^T f + K_s w     = F                (equilibrium of every point; K_s the springs)

with w = T z + w0 (the supports' conditions eliminated, :func:`.general.eliminate`). Assembling D^T A D instead
would round like N⁴ eps (fourth differences of w); here each equation rounds like a second difference. The unknowns
are ordered point by point (each point's pairs beside its w), so the matrix is banded.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...numerics.band import bandwidths
from ...numerics.linalg import solve_linear
from ...numerics.memory import check_band


def solve_mixed(pairs, elim, Ks, F, what: str, a=None, elastic=None, fixed=None, offset=None):
    """(w, f, info): the deflection and the pair forces of :class:`.pairs.Pairs` ``pairs`` under the supports'
    :class:`.general.Elimination` ``elim``, springs ``Ks`` and nodal loads ``F``. ``a``: pair stiffness (default the
    pairs'); ``elastic`` (bool per pair, default all) with ``fixed`` the forces of the others; ``offset`` the plastic
    offsets phi^p."""
    D, T, w0 = pairs.D, elim.T, elim.w0
    a = pairs.stiffness if a is None else a
    P = D.shape[0]
    elastic = np.ones(P, bool) if elastic is None else np.asarray(elastic, bool)
    fixed = np.zeros(P) if fixed is None else np.asarray(fixed, float)
    offset = np.zeros(P) if offset is None else np.asarray(offset, float)
    DT = (D @ T).tocsr()
    e = elastic.astype(float)
    # row p: elastic -> -f/a + DT z = offset - D w0; fixed -> f = fixed
    inv_a = np.where(elastic, 1.0 / np.where(elastic, a, 1.0), 0.0)
    top = sp.hstack([sp.diags(np.where(elastic, -inv_a, 1.0)), sp.diags(e) @ DT])
    Kz = (T.T @ Ks @ T).tocsr()
    bottom = sp.hstack([DT.T, Kz])
    M = sp.vstack([top, bottom]).tocsr()
    rhs = np.r_[np.where(elastic, offset - D @ w0, fixed), T.T @ (F - Ks @ w0)]
    # symmetric scaling: sqrt(a) on the elastic pairs' rows, 1/sqrt(diag of the reduced stiffness) on the points'
    kdiag = np.asarray((DT.multiply(DT)).T @ np.where(elastic, a, 0.0)).ravel() + Kz.diagonal()
    s = np.r_[
        np.where(elastic, np.sqrt(np.where(elastic, a, 1.0)), 1.0), 1.0 / np.sqrt(np.where(kdiag > 0, kdiag, 1.0))
    ]
    perm = _banded_order(pairs.centre, pairs.offset, elim.free)
    Mp = M[perm][:, perm]
    lower, upper = bandwidths(Mp)
    fix = "use fewer points, or a shorter horizon (at a fixed horizon_length the band grows with the points)"
    check_band(Mp.shape[0], lower, upper, what, fix)
    inv = np.empty_like(perm)
    inv[perm] = np.arange(len(perm))
    y, info = solve_linear(Mp, rhs[perm], what=what, scaling=s[perm], watch=inv[P:])
    y = y[inv]
    f, z = y[:P], y[P:]
    w = T @ z + w0
    return w, f, info


def _banded_order(centre, offset_j, free) -> np.ndarray:
    """The permutation that orders the unknowns (pairs, then free points) point by point: the pairs centred at a
    point, then that point's w."""
    J = int(np.max(offset_j)) + 2
    return np.argsort(np.r_[centre * J + offset_j, free * J + J - 1], kind="stable")
