"""Manufactured solution of the curved Timoshenko–Ehrenfest beam (design note §4, quintic example).

Chosen fields (x̂ = (x - x0)/(x1 - x0) on the axis' x_range, U = 1e-3 L, L the arc length), all zero at
both ends, so the beam is clamped at both ends::

    u_t = U sin(pi x̂),   u_n = U sin(2 pi x̂),   phi = (U/L) sin(pi x̂) (1 - x̂)

The loads follow symbolically (sympy) from the equilibrium of pdverify/models/pd_curved.py with
d/ds = (1/J) d/dx, J = sqrt(1 + y'^2), kappa = y''/J^3::

    N = EA (u_t' - kappa u_n),  Q = kGA (u_n' + kappa u_t - phi),  M = EI phi'
    p_t = -(N' - kappa Q),  p_n = -(Q' + kappa N),  m = -(M' + Q)

The scene cannot express such a load profile, so the loads are exposed through Python only:
``body(scene)`` returns them as a function of s for ``PDCurved.solve(scene, params, body=...)``; the model
``pd-curved-mms`` (pd-curved plus these loads) runs them from a study, and the reference model
``exact-curved-manufactured`` returns the chosen fields. Axis: polynomial (or straight: y = 0 on [0, L]).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .errors import InputError

NAMES = ("u_t", "u_n", "phi", "N", "Q", "M", "p_t", "p_n", "m")


@lru_cache(maxsize=16)
def _functions(coefficients: tuple, x0: float, x1: float, length: float):
    import sympy as sp

    x, EA, kGA, EI = sp.symbols("x EA kGA EI", real=True)
    y = sum(sp.nsimplify(c) * x**i for i, c in enumerate(coefficients)) if coefficients else sp.Integer(0)
    J = sp.sqrt(1 + sp.diff(y, x) ** 2)
    kap = sp.diff(y, x, 2) / J**3
    d = lambda f: sp.diff(f, x) / J  # noqa: E731  d/ds
    xh = (x - x0) / (x1 - x0)
    U = 1e-3 * length
    ut = U * sp.sin(sp.pi * xh)
    un = U * sp.sin(2 * sp.pi * xh)
    phi = U / length * sp.sin(sp.pi * xh) * (1 - xh)
    N = EA * (d(ut) - kap * un)
    Q = kGA * (d(un) + kap * ut - phi)
    M = EI * d(phi)
    pt = -(d(N) - kap * Q)
    pn = -(d(Q) + kap * N)
    m = -(d(M) + Q)
    exprs = (ut, un, phi, N, Q, M, pt, pn, m)
    return {k: sp.lambdify((x, EA, kGA, EI), e, "numpy") for k, e in zip(NAMES, exprs)}


def axis_data(scene) -> tuple[tuple, float, float]:
    a = scene.axis
    if a.type == "polynomial":
        return tuple(float(c) for c in a.coefficients), float(a.x_range[0]), float(a.x_range[1])
    if a.type == "straight":
        return (0.0,), 0.0, float(scene.length)
    raise InputError(f"axis.type = {a.type!r}: the manufactured solution is written for a polynomial (or straight) "
                     "axis; use one of those")


def fields(scene, s: np.ndarray, x: np.ndarray | None = None, names=NAMES) -> dict[str, np.ndarray]:
    """The chosen fields, resultants and the loads they need (``names``: those of :data:`NAMES` wanted) at
    arc lengths s (``x``: their axis abscissae on a polynomial axis when the caller has them; else s is
    inverted here). The sympy derivation runs once per axis and length (cached); each call evaluates the
    lambdified expressions only."""
    from .geometry import geometry

    coef, x0, x1 = axis_data(scene)
    s = np.asarray(s, float)
    if scene.axis.type != "polynomial":
        x = s
    elif x is None:
        x = geometry(scene)._x_of_s(s)
    f = _functions(coef, x0, x1, float(scene.length))
    out = {}
    for k in names:
        v = f[k](x, scene.EA, scene.kGA, scene.EI)
        out[k] = np.broadcast_to(np.asarray(v, float), x.shape).copy()
    return out


def body(scene):
    """(s, x) -> (p_t, p_n, m): the manufactured loads per unit length (for pd-curved's ``body`` hook; x: the
    axis abscissae of s, which pd-curved has already computed, or None)."""
    axis_data(scene)

    def loads(s, x=None):
        f = fields(scene, s, x, ("p_t", "p_n", "m"))
        return f["p_t"], f["p_n"], f["m"]

    return loads
