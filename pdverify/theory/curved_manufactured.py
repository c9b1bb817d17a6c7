"""Manufactured solution of the curved Timoshenko–Ehrenfest beam (docs/design/formulas.md §4; the quintic axis of
Curved PDDO beam 2024, §4.3).

Chosen fields (x̂ = (x - x0)/(x1 - x0) on the axis' x_range, U = 1e-3 L, L the arc length), all zero at
both ends, so the beam is clamped at both ends::

    u_t = U sin(pi x̂),   u_n = U sin(2 pi x̂),   phi = (U/L) sin(pi x̂) (1 - x̂)

The loads follow symbolically (sympy) from the equilibrium of pdverify/papers/curved/model.py with
d/ds = (1/J) d/dx, J = sqrt(1 + y'^2), kappa = y''/J^3::

    N = EA (u_t' - kappa u_n),  Q = kGA (u_n' + kappa u_t - phi),  M = EI phi'
    p_t = -(N' - kappa Q),  p_n = -(Q' + kappa N),  m = -(M' + Q)

``kind = "bending"`` (the locking test): a beam-like solution whose membrane and shear strains are O(h²/L²)
of the bending ones, as in a slender beam under a real load, so all its loads scale with EI (not EA, kGA).
A bending field in global components, inextensible and shear-free by construction::

    u_y^b = U g(x̂),   u_x^b = -U ∫_{x0}^{x} y'(ξ) g'(ξ) dξ,   g = x̂²(1 - x̂)²(a + b x̂)

(ε = t·du/ds = (u_x' + y' u_y')/J² = 0; the rotation of the tangent n·du/ds = U g'; (a, b) chosen so that
u_x^b(x1) = 0), plus membrane and shear parts scaled by the slenderness (EI/(EA L²) = h²/(12 L²) for a
rectangle)::

    u_t = t·u^b + c_a U sin(pi x̂),   u_n = n·u^b + c_a U sin(2 pi x̂),   c_a = EI/(EA L²)
    phi = U g'(x) - c_s (U/L) sin(pi x̂)(1 - x̂),   c_s = EI/(kGA L²)

so ε, γ = O(h²/L²) χ L and N, Q ~ M/L ~ EI U/L³ at every slenderness.

The scene cannot express such a load profile, so the loads are exposed through Python only:
``body(scene)`` returns them as a function of s for ``PDCurved.solve(scene, params, body=...)``; the model
``pd-curved-mms`` (pd-curved plus these loads) runs them from a study, and the reference model
``exact-curved-manufactured`` returns the chosen fields. Axis: polynomial (or straight: y = 0 on [0, L]).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..core.contract import Option
from ..core.errors import InputError
from ..core.geometry import geometry

NAMES = ("u_t", "u_n", "phi", "N", "Q", "M", "p_t", "p_n", "m")


KINDS = ("trig", "bending")
FIELDS = Option(
    "fields",
    str,
    "trig",
    "manufactured fields: trig (u_t, u_n, phi sines, membrane strains O(U/L)) | "
    "bending (beam-like: membrane and shear strains O(h^2/L^2) of the bending ones)",
    choices=KINDS,
)


def _bending_shape(y, x, xh):
    """g(x̂) = x̂²(1 - x̂)²(a + b x̂) with ∫ y' g' dx = 0 over the axis (so u_x^b vanishes at both ends);
    (a, b) = (1, 0) where the constraint holds for any g (a straight axis)."""
    import sympy as sp

    g0, g1 = xh**2 * (1 - xh) ** 2, xh**3 * (1 - xh) ** 2
    x0, x1 = sp.solve(sp.Eq(xh, 0), x)[0], sp.solve(sp.Eq(xh, 1), x)[0]  # xh is linear in x
    dy = sp.diff(y, x)
    i0, i1 = (float(sp.integrate(sp.expand(dy * sp.diff(g, x)), (x, x0, x1))) for g in (g0, g1))
    big = max(abs(i0), abs(i1))
    if big < 1e-12:
        return g0
    return (sp.nsimplify(i1 / big) * g0 - sp.nsimplify(i0 / big) * g1) * 16


@lru_cache(maxsize=16)
def _functions(coefficients: tuple, x0: float, x1: float, length: float, kind: str = "trig"):
    import sympy as sp

    x, EA, kGA, EI = sp.symbols("x EA kGA EI", real=True)
    y = sum(sp.nsimplify(c) * x**i for i, c in enumerate(coefficients)) if coefficients else sp.Integer(0)
    J = sp.sqrt(1 + sp.diff(y, x) ** 2)
    kap = sp.diff(y, x, 2) / J**3
    d = lambda f: sp.diff(f, x) / J  # noqa: E731  d/ds
    xh = (x - x0) / (x1 - x0)
    U = 1e-3 * length
    if kind == "bending":
        a, b = sp.nsimplify(x0), sp.nsimplify(x1)
        g = _bending_shape(y, x, (x - a) / (b - a))
        dy = sp.diff(y, x)
        uy = U * g
        xi = sp.Symbol("xi", real=True)
        ux = -U * sp.integrate(sp.expand(dy * sp.diff(g, x)).subs(x, xi), (xi, a, x))
        ca, cs = EI / (EA * length**2), EI / (kGA * length**2)
        dut, dun = ca * U * sp.sin(sp.pi * xh), ca * U * sp.sin(2 * sp.pi * xh)
        dphi = cs * U / length * sp.sin(sp.pi * xh) * (1 - xh)
        ut = (ux + dy * uy) / J + dut
        un = (-dy * ux + uy) / J + dun
        phi = U * sp.diff(g, x) - dphi
        # the bending part has ε = γ = 0 exactly: the resultants from the small parts only, so EA and kGA
        # cancel symbolically (EA times the round-off of ε^b would be a load error ~ (L/h)² eps)
        N = EA * (d(dut) - kap * dun)
        Q = kGA * (d(dun) + kap * dut + dphi)
    else:
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
    raise InputError(
        f"axis.type = {a.type!r}: the manufactured solution is written for a polynomial (or straight) "
        "axis; use one of those"
    )


def fields(scene, s: np.ndarray, x: np.ndarray | None = None, names=NAMES, kind: str = "trig") -> dict[str, np.ndarray]:
    """The chosen fields (``kind``: trig | bending), resultants and the loads they need (``names``: those of
    :data:`NAMES` wanted) at
    arc lengths s (``x``: their axis abscissae on a polynomial axis when the caller has them; else s is
    inverted here). The sympy derivation runs once per axis and length (cached); each call evaluates the
    lambdified expressions only."""

    coef, x0, x1 = axis_data(scene)
    s = np.asarray(s, float)
    if scene.axis.type != "polynomial":
        x = s
    elif x is None:
        x = geometry(scene)._x_of_s(s)
    if kind not in KINDS:
        raise InputError(f"fields = {kind!r}: the manufactured solution is one of {', '.join(KINDS)}")
    f = _functions(coef, x0, x1, float(scene.length), kind)
    out = {}
    for k in names:
        v = f[k](x, scene.EA, scene.kGA, scene.EI)
        out[k] = np.broadcast_to(np.asarray(v, float), x.shape).copy()
    return out


def body(scene, kind: str = "trig"):
    """(s, x) -> (p_t, p_n, m): the manufactured loads per unit length (for pd-curved's ``body`` hook; x: the
    axis abscissae of s, which pd-curved has already computed, or None)."""
    axis_data(scene)

    def loads(s, x=None):
        f = fields(scene, s, x, ("p_t", "p_n", "m"), kind)
        return f["p_t"], f["p_n"], f["m"]

    return loads


def manufactured_checks(scene) -> list[str]:
    """Why a scene cannot carry the manufactured solution: a polynomial axis clamped at both ends, no loads."""
    out = []
    if scene.axis.type != "polynomial":
        out.append(f"axis.type = {scene.axis.type!r}: the manufactured solution is written for a polynomial axis")
    if (scene.supports.left, scene.supports.right) != ("clamped", "clamped"):
        out.append(
            f"supports = {scene.supports.left}-{scene.supports.right}: the manufactured fields vanish at "
            "both ends; set both supports to clamped"
        )
    if scene.loads:
        out.append(
            "loads: the manufactured solution brings its own loads (pd-curved-mms adds them); remove the [[loads]]"
        )
    return out
