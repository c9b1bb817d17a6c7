"""Where curved-beam theory stops describing the solid it stands for: the ratio of the axis' radius of curvature R to
the section's depth h.

Curved Timoshenko–Ehrenfest beam theory (exact-curved, pd-curved) takes the straight beam's section law on a curved
axis: a linear stress through the depth, N = EA ε, M = EI χ, no radial stress. The curved bar's own section law is
Winkler–Bach's hyperbolic hoop stress (Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., ch. 4, pure bending
of curved bars, Golovin's elasticity solution; Boresi & Schmidt, *Advanced Mechanics of Materials*, 6th ed., ch. 9):
its bending compliance is 1 / (E A e R) with e = R - r_n, r_n = h / ln((R + h/2) / (R - h/2)) for a rectangle, so

    A e R = I (1 + (h/R)² / 15 + O(h/R)⁴),

and its energy has an axial–bending coupling M N / (E A R), of relative size N I / (A R M) = (N R / M) (h/R)² / 12 (a
rectangle) to the bending energy. Both are of relative order (h/R)² in the displacements where the beam bends; in the
stresses the hyperbolic law differs from the linear one at order h/R (the inner fibre's stress). Where it carries its
loads by axial force (an arch under a load near its funicular, N R / M of order (R/h)²) the coupling is of order one
whatever R/h, and :func:`coupling_warning` says so with its size. Where it bends, the beam theory's deflection
differs from the plane-stress continuum's by c (h/R)², c depending on the loads and supports; with the largest c of
circular cantilevers (:data:`GAP_PER_RATIO_SQUARED`, docs/trust.md) that gap can pass 1 % of max |w| below
R/h = sqrt(c / 0.01) = 5 (:data:`THICK_RATIO`), and there a solve carries a warning naming R/h and the gap to expect.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial import polynomial as P

from ..core.geometry import geometry
from ..core.scene import Scene
from ..core.text import apart

# c of max |w_beam - w_2D| / max |w_2D| = c (h/R)^2 against fem-plane-stress on circular cantilevers under end forces
# (docs/trust.md, "curved-beam theory on a thick ring"): 0.13 (semicircle, tangential tip force) to 0.25 (quarter
# circle, normal tip force, R/h = 5)
GAP_PER_RATIO_SQUARED = (0.13, 0.25)
THICK_RATIO = 5.0  # R/h below which c (h/R)^2 can pass 1 %: sqrt(0.25 / 0.01) = 5
_SAMPLES = 1001  # points of a polynomial axis at which its curvature is taken (its largest |κ|)


def radius_to_depth(scene: Scene) -> float:
    """R/h: the smallest radius of curvature of the axis over the largest section depth along the beam (inf on a
    straight axis)."""
    if scene.is_straight:
        return math.inf
    axis = scene.axis
    if axis.type == "arc":
        kappa = abs(float(geometry(scene).curvature(0.0)))
    else:  # a polynomial axis y(x): kappa = y'' / (1 + y'^2)^(3/2), sampled in x (no arc-length inversion)
        c = np.asarray(axis.coefficients, float)
        x = np.linspace(*(float(v) for v in axis.x_range), _SAMPLES)
        d1, d2 = P.polyval(x, P.polyder(c)), P.polyval(x, P.polyder(c, 2))
        kappa = float(np.abs(d2 / (1 + d1**2) ** 1.5).max())
    depth = max(section.depth for _, _, section, _ in scene.pieces())
    return math.inf if kappa == 0.0 else 1.0 / (kappa * depth)


def thick_ring_warning(scene: Scene) -> str | None:
    """The one-line warning of a curved axis whose R/h is below :data:`THICK_RATIO`, with the gap to the 2D
    continuum it implies; None otherwise."""
    ratio = float(f"{radius_to_depth(scene):.12g}")  # a scaled copy's rounding decides no side of the limit
    if not ratio < THICK_RATIO:
        return None
    lo, hi = (c / ratio**2 for c in GAP_PER_RATIO_SQUARED)
    return (
        f"R/h = {apart(ratio, THICK_RATIO, 3)} (radius of curvature / section depth) is below {THICK_RATIO:g}: "
        f"curved-beam theory drops terms of order (h/R)^2 = {1 / ratio**2:.2g} (Winkler-Bach hoop stress, radial "
        "stress); its deflection differs from the 2D continuum's (fem-plane-stress) by "
        f"{100 * lo:.2g}-{100 * hi:.2g} % of max |w| here (c (h/R)^2, c = {GAP_PER_RATIO_SQUARED[0]:g}-"
        f"{GAP_PER_RATIO_SQUARED[1]:g} measured on circular cantilevers under end forces); for the solid's deflection "
        "use fem-plane-stress"
    )


COUPLING_LIMIT = 0.01  # the coupling's share of the bending curvature above which a result says so


def coupling_warning(scene: Scene, s: np.ndarray, N: np.ndarray, M: np.ndarray) -> str | None:
    """The warning of a curved beam that carries its loads by axial force: the coupling the theory leaves out adds a
    curvature N / (E A R) to the bending one, M / (E I); the largest ratio max_s |N(s)| I / (A R(s)) / max |M| over
    the points ``s`` (R(s) the axis' local radius of curvature, I / A the sections' largest) past
    :data:`COUPLING_LIMIT`; None otherwise."""
    if scene.is_straight or not np.abs(N).any():
        return None
    kappa = np.abs(geometry(scene).curvature(np.asarray(s, float)))
    gyration = max(section.I / section.A for _, _, section, _ in scene.pieces())  # I / A
    coupled = float(np.max(np.abs(N) * kappa)) * gyration
    bending = float(np.abs(M).max())
    share = coupled / bending if bending > 0.0 else math.inf
    if not share > COUPLING_LIMIT:
        return None
    return (
        "the beam carries part of its loads by axial force: curved-beam theory leaves out the coupling of N and M "
        "through the axis' curvature (Winkler-Bach: a curvature N / (E A R) beside M / (E I)), here max |N I / "
        f"(A R)| / max |M| = {apart(share, COUPLING_LIMIT)} of the bending curvature, whatever R/h (a 120 deg pinned "
        "arch under a uniform normal load, 0.31: 1.5 % of max |w| and 8 % of the rotation from the 2D continuum); for "
        "the solid's displacements use fem-plane-stress"
    )
