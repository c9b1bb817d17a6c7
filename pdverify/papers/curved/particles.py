"""pd-curved's particles: the axis frame at the particles, the segments between load discontinuities, the
particle distributions (uniform, graded, given positions), the family size, and the loads at the particles.

The curved PDDO beam paper's quadrature "is not limited to uniform distributions of material particles": segments
hold 2m + 1-member families of consecutive particles (m = :func:`default_horizon` unless given), whatever their
spacing.
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.geometry import axis_abscissae, geometry
from ...core.scene import Distributed, PointForce, PointMoment, Scene
from .supports import BREAK, support_breaks

# -- geometry ---------------------------------------------------------------------------------


def curvature_slope(scene: Scene, s: np.ndarray) -> np.ndarray:
    """dκ/ds (0 for straight and arc axes; polynomial: (1/J) d/dx [y''/J³], J = sqrt(1 + y'²))."""
    return axis_frame(scene, s)[3]


def axis_frame(scene: Scene, s: np.ndarray):
    """(t, n, κ, dκ/ds, x) at arc lengths s: tangent and normal (each (len(s), 2)), curvature, its slope and
    the axis abscissae x(s) (polynomial axes; None otherwise). On a polynomial axis s is inverted once
    (:func:`axis_abscissae`) and t, n, κ are the formulas of :mod:`pdverify.core.geometry` evaluated at that x
    (``geometry.frame`` and ``geometry.curvature`` would each invert s again, the costly step on large grids)."""
    s = np.asarray(s, float)
    geo = geometry(scene)
    if scene.axis.type != "polynomial":
        t, n = geo.frame(s)
        return t, n, geo.curvature(s), np.zeros_like(s), None
    from numpy.polynomial import polynomial as Pn

    c = np.asarray(scene.axis.coefficients, float)
    x = axis_abscissae(scene, s)
    th = np.arctan(Pn.polyval(x, Pn.polyder(c)))
    t = np.stack([np.cos(th), np.sin(th)], axis=-1)
    n = np.stack([-np.sin(th), np.cos(th)], axis=-1)
    d1, d2, d3 = (Pn.polyval(x, Pn.polyder(c, k)) for k in (1, 2, 3))
    kap = d2 / (1 + d1**2) ** 1.5
    J2 = 1 + d1**2
    dkap = (d3 / J2**1.5 - 3 * d1 * d2**2 / J2**2.5) / np.sqrt(J2)
    return t, n, kap, dkap, x


# -- segments and loads -----------------------------------------------------------------------


def breakpoints(scene: Scene) -> tuple[np.ndarray, dict, dict]:
    """Interior break positions (sorted), the point loads there {index: [loads]} and the end point
    loads {0: [...], 1: [...]} (loads exactly at s = 0 or s = L)."""
    L = scene.length
    tol = BREAK * L
    pos, at = [], []
    ends = {0: [], 1: []}
    for load in scene.loads:
        if isinstance(load, (PointForce, PointMoment)):
            if load.position <= tol:
                ends[0].append(load)
            elif load.position >= L - tol:
                ends[1].append(load)
            else:
                pos.append(load.position), at.append(load)
        elif isinstance(load, Distributed):
            for v in scene.span(load):
                if tol < v < L - tol:
                    pos.append(v), at.append(None)
    for v in support_breaks(scene):  # supports inside the span and segment ends (.supports)
        pos.append(v), at.append(None)
    bps: list[float] = []
    loads: dict[int, list] = {}
    for p, load in sorted(zip(pos, at), key=lambda t: t[0]):
        if not bps or p - bps[-1] > tol:
            bps.append(p)
            loads[len(bps) - 1] = []
        if load is not None:
            loads[len(bps) - 1].append(load)
    return np.array(bps), loads, ends


def merged_break_warnings(scene: Scene) -> list[str]:
    """Breaks that :func:`breakpoints` takes as one (within 1e-9 L) and that lie further apart than the positions'
    rounding (1e-14 L): a support or segment joint beside another or beside a load or a span's end. The model puts
    them on the first one's place, so a result that depends on their distance is lost (and the scene's mirror image
    merges them on the other's place). One warning per pair, as the beam elements' (reference_fem)."""
    L = scene.length
    held = [(f"supports.inner[{i}]", s.position) for i, s in enumerate(scene.supports.inner)]
    held += [(f"segments[{i}].end", g.end) for i, g in enumerate(scene.segments[:-1])] if scene.segments else []
    marks = list(held)
    for i, load in enumerate(scene.loads):
        if isinstance(load, (PointForce, PointMoment)):
            marks.append((f"loads[{i}]", load.position))
        elif isinstance(load, Distributed):
            marks += [(f"loads[{i}] (span)", v) for v in scene.span(load) if 0.0 < v < L]
    out = []
    for k, (a, x) in enumerate(held):
        for b, y in marks[k + 1 :]:
            if 1e-14 * L < abs(x - y) <= BREAK * L:
                out.append(
                    f"{a} at {x:g} and {b} at {y:g} lie {abs(x - y):.3g} apart, within {BREAK:g} of the length: "
                    "pd-curved takes them as one break, and a result that depends on that distance is lost; give them "
                    "one position, or the scene in a shorter length"
                )
    return out


def segment_grids(L: float, bps: np.ndarray, points: int, min_points: int, density=None) -> list[np.ndarray]:
    """Particles on each segment [b_i, b_{i+1}], about (points - 1) intervals in all, at least ``min_points``
    per segment. ``density`` None: uniform (a uniform grid of ``points`` particles when the breaks fall on
    it). Else a pair (s_table, cumulative) of a non-decreasing measure m(s) (m(0) = 0, m(L) = 1): the
    intervals of a segment are shared by its measure, and its particles sit at equal steps of m (the paper's
    non-uniform particles: spacing ∝ 1/ρ for m = ∫ρ ds / ∫ρ ds)."""
    edges = np.concatenate([[0.0], bps, [L]])
    out = []
    if density is not None:
        st, cm = density
        me = np.interp(edges, st, cm)
    for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
        if density is None:
            k = max(min_points - 1, int(np.floor((points - 1) * (b - a) / L + 0.5 + 1e-9)))
            out.append(np.linspace(a, b, k + 1))
            continue
        k = max(min_points - 1, int(np.floor((points - 1) * (me[i + 1] - me[i]) + 0.5 + 1e-9)))
        g = np.interp(np.linspace(me[i], me[i + 1], k + 1), cm, st)
        g[0], g[-1] = a, b
        out.append(g)
    return out


def parse_positions(text: str, L: float) -> np.ndarray:
    """The ``positions`` option: arc lengths (m) separated by commas or spaces, strictly increasing, in [0, L]
    (0 and L are added when missing). Raises InputError naming the option."""
    try:
        s = np.array([float(v) for v in text.replace(",", " ").split()], float)
    except ValueError:
        raise InputError(
            f'positions = {text!r}: give arc lengths in m separated by commas, e.g. "0, 0.1, 0.25"'
        ) from None
    tol = 1e-12 * L
    if not np.all(np.isfinite(s)) or s.min(initial=0.0) < -tol or s.max(initial=0.0) > L + tol:
        raise InputError(f"positions: every arc length must lie in [0, L] = [0, {L:g}] m; remove the others")
    if np.any(np.diff(s) <= 0):
        raise InputError("positions: the arc lengths must increase strictly; sort them and remove repeats")
    s = np.clip(s, 0.0, L)
    return np.unique(np.concatenate([[0.0], s, [L]]))


def given_grids(L: float, bps: np.ndarray, s: np.ndarray, min_points: int) -> list[np.ndarray]:
    """The particles s (from :func:`parse_positions`) split at the breaks: each segment [a, b] takes the given
    positions strictly inside it (those within 1e-9 L of a break dropped) and its two ends."""
    edges = np.concatenate([[0.0], bps, [L]])
    tol = BREAK * L
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        g = np.concatenate([[a], s[(s > a + tol) & (s < b - tol)], [b]])
        if len(g) < min_points:
            raise InputError(
                f"positions: {len(g)} particles on [{a:g}, {b:g}] m (between supports, point loads and "
                f"load ends), fewer than one family ({min_points}); add positions there"
            )
        out.append(g)
    return out


def grading_density(scene: Scene, ratio: float, by: str, samples: int = 4001):
    """(s_table, m(s)) for :func:`segment_grids`: density ρ = 1 + (ratio - 1) f(s), f in [0, 1], so the
    largest spacing is about ``ratio`` times the smallest. ``by``: ``curvature`` (f = sqrt(|κ| / max |κ|):
    particles gather where the axis bends; the square root spreads them over the bend's flanks, which on
    y = 10 x^5 needed fewer particles than f = |κ / max κ|) or ``ends`` (f = exp(-d / (L/10)), d the distance
    to the nearer end, support inside the span, segment joint or point load: particles gather at the supports, the
    joints and the point loads)."""
    L = scene.length
    s = np.linspace(0.0, L, samples)
    if by == "curvature":
        kap = np.abs(axis_frame(scene, s)[2])
        f = np.sqrt(kap / kap.max()) if kap.max() > 0 else np.zeros_like(s)
    else:
        marks = [0.0, L] + [ld.position for ld in scene.loads if isinstance(ld, (PointForce, PointMoment))]
        marks += [sup.position for sup in scene.supports.inner] + [g.start for g in scene.segments[1:]]
        d = np.min(np.abs(s[:, None] - np.array(marks)[None, :]), axis=1)
        f = np.exp(-d / (0.1 * L))
    rho = 1.0 + (ratio - 1.0) * f
    m = np.concatenate([[0.0], np.cumsum((rho[1:] + rho[:-1]) * np.diff(s) / 2)])
    return s, m / m[-1]


ENDS_GRADING = 10.0  # particles graded by ends past this ratio: families of more than P + 1 members jump


def graded_families_warning(params: dict, m: int) -> str:
    """Particles graded by ends past :data:`ENDS_GRADING` in the primal form, or in the mixed form with families of
    2m + 1 > P + 1 members (an odd degree, or a ``horizon`` given above P/2): the members' weights are lopsided where
    the particles gather, and the error jumps from grid to grid instead of falling (docs/models/curved.md, graded
    particles); "" otherwise (the mixed form's interpolating central stencil, :func:`default_horizon`'s choice at an
    even degree)."""
    P, ratio = params["degree"], params.get("grading", 1.0)
    if params.get("graded_by") != "ends" or ratio <= ENDS_GRADING:
        return ""
    if params["form"] == "primal":
        return (
            f"grading = {ratio:g} by ends in the primal form: its second-derivative families are lopsided where the "
            "particles gather, and the error does not fall steadily with points (a pinned-pinned quarter circle of "
            "radius 2 m under a couple and a uniform load, P = 3, grading 20: 0.26, 0.35, 0.047 of max |w| at 81, "
            f"161, 321 particles, uniform 0.063, 0.013, 3.3e-3); use the mixed form, or grading <= {ENDS_GRADING:g}"
        )
    if 2 * m + 1 <= P + 1:
        return ""
    return (
        f"grading = {ratio:g} by ends with families of {2 * m + 1} particles at degree {P}: more than the {P + 1} of "
        "the interpolating stencil, and lopsided where the particles gather, so the error does not fall steadily with "
        "points (a guided beam on a spring end and an inner pin under a sine load and a point force, P = 5, grading "
        "100: 0.58, 0.33, 2.8e-3 of max |w| at 81, 161, 321 particles, uniform 5.1e-8, 9.8e-10, 1.6e-11); use an "
        f"even degree with the default horizon, or grading <= {ENDS_GRADING:g}"
    )


def distributed_loads(
    scene: Scene, s: np.ndarray, t: np.ndarray, n: np.ndarray, inside: float
) -> tuple[np.ndarray, np.ndarray]:
    """(p_t, p_n) per unit arc length at the particles s of one segment (``inside``: a position strictly
    inside the segment, to decide which spans cover it)."""
    pt, pn = np.zeros_like(s), np.zeros_like(s)
    for load in scene.loads:
        if not isinstance(load, Distributed):
            continue
        a, b = scene.span(load)
        if not a <= inside <= b:
            continue
        f = scene.load_shape(load, s)
        if load.frame == "global":
            pt += f * (load.axial * t[:, 0] + load.value * t[:, 1])
            pn += f * (load.axial * n[:, 0] + load.value * n[:, 1])
        else:
            pt += f * load.axial
            pn += f * load.value
    return pt, pn


def default_horizon(degree: int, form: str = "primal", graded_ends: bool = False) -> int:
    """⌊P/2⌋ + 1 (P + 3 members for even P, P + 2 for odd P), except the mixed form at even P >= 6, or at any even P
    on particles graded by ends (``graded_ends``: ``grading`` > 1 with ``graded_by = "ends"``): P/2 (P + 1 members,
    the interpolating central stencil).

    Why: the mixed form applies the first-derivative function g^1 only, and every antisymmetric interior
    stencil annihilates the sawtooth (-1)^k; what keeps the neighbouring high-frequency modes away from zero
    is the slope of the stencil's symbol σ(θ) = Σ_j c_j sin(jθ) at θ = π, 2 Σ_j (-1)^(j+1) j c_j (h = 1).
    With P + 3 members the spare (two more than P + 1) coefficients are set by the weight, and that slope collapses
    at P = 6 (0.017, against 0.67 / 0.45 at P = 2 / 4 and 2.2 for the 7-member stencil) and changes sign
    at P = 8 and 10 (-0.41, -0.82: a spurious interior null mode). The modes near θ = π are then held only
    by the end families, the condition number grows like n^4 and the error has a floor that grows with n.
    P + 1 members give the interpolating stencil (slope 2.2 / 2.66 / 3.06 at P = 6 / 8 / 10), whose weights do
    not depend on w. The primal form keeps ⌊P/2⌋ + 1: its g^2 symbol Σ_j c_j cos(jθ) stays negative at P = 6
    (-0.096 at θ = π) and is positive there at P = 8 and 10 (0.32, 0.62), yet its errors at P = 8 show no floor
    (docs/models/curved.md). On particles gathered at the supports and point loads, P + 3 members at P = 2 and 4 hold
    those modes no longer: the error jumps from grid to grid instead of falling (docs/models/curved.md, graded
    particles), where the interpolating stencil converges at its order."""
    if form == "mixed" and degree % 2 == 0 and (degree >= 6 or graded_ends):
        return degree // 2
    return degree // 2 + 1
