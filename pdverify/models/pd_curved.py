"""Model ``pd-curved``: planar curved Timoshenko–Ehrenfest beam by PDDO collocation (seed 004).

The seed's equations were lost in extraction; they are restored in the design note
(../shared/design/formulas-bondpair-curved.md §2–3) and re-derived here from virtual work (the signs
below were checked: the virtual-work identity, the straight-beam limit against ``exact-timoshenko``
and the closed-form semicircle of :mod:`pdverify.exact.curved`).

Axis r(s) (arc length s), tangent t, normal n = e_z × t, curvature κ (t' = κ n, n' = -κ t).
Unknowns per particle: u_t, u_n (u = u_t t + u_n n) and the section rotation φ (counter-clockwise).

* strains (seed Eq. 3):        ε = u_t' - κ u_n,   γ = u_n' + κ u_t - φ,   χ = φ'
* resultants (Eq. 4):          N = EA ε,   Q = kGA γ,   M = EI χ
* equilibrium (Eq. 8–10):      N' - κ Q + p_t = 0,   Q' + κ N + p_n = 0,   M' + Q + m = 0
* boundary (Eq. 11–13):        at s = L either u_t, u_n, φ given or N = F·t, Q = F·n, M = C̄;
                               at s = 0 the same with a minus sign.

For a straight beam Q = kGA(w' - φ) = -dM/dx: ``exact-timoshenko``'s V is -Q (Result.fields["V"]).

Collocation (Eq. 27–35): three equations per particle, every derivative replaced by PDDO functions of
degree P (:mod:`pdverify.models._pddo`), families of 2 m + 1 particles (m = ``horizon``, default
⌊P/2⌋ + 1, i.e. P + 3 members for even P, P + 2 for odd P, mixed form at even P >= 6: P + 1; see
:func:`default_horizon`), shifted inward
at the ends. Two forms:

* ``primal`` (the paper, Eq. 14–16): constitutive law substituted, second derivatives by g²:
  ``EA(u_t'' - κ' u_n - κ u_n') - κ kGA(u_n' + κ u_t - φ) + p_t = 0`` etc.;
* ``mixed`` (beyond the paper): first-derivative functions only, applied twice: N = EA(D1 u_t - κ u_n),
  then D1 N - κ Q + p_t = 0, ... With ``unknowns = resultants`` (default) N, Q, M are unknowns of their
  own (six per particle: the constitutive rows ε(u) - N/EA = 0, γ(u) - Q/kGA = 0, χ(u) - M/EI = 0 at every
  particle plus the equilibrium rows). The discrete solution is the same as with them substituted
  (``unknowns = displacements``, three per particle), but the condition number no longer grows like
  (L/h)²: semicircle, P = 6, 801 particles, L/h = 10^4: error 4.8e-11 instead of 1.1e-2 (round-off).

At each end particle the three boundary equations replace the three equilibrium equations (slot t
takes u_t or N, slot n takes u_n or Q, slot φ takes φ or M): clamped u_t = u_n = φ = 0; pinned
u_t = u_n = 0, M = ±C̄; roller u_n = 0, N, M = ±(F·t, C̄); free N, Q, M = ±(F·t, F·n, C̄); guided φ = 0,
N, Q = ±(F·t, F·n) (docs/supports.md).

Particles are uniform by default; ``grading`` (largest / smallest spacing, ``graded_by`` curvature or ends) or
``positions`` (arc lengths) place them non-uniformly (the seed: "not limited to uniform distributions of material
particles"), the families keep 2m + 1 members, so each particle's horizon follows its spacing.

Point loads inside the beam and the ends of a distributed load's span split the axis into segments
(each with its own particles and families; a PDDO function never reaches across a load
discontinuity). At an interface the two coincident particles carry continuity of u_t, u_n, φ and the
jumps N⁺ - N⁻ = -F·t, Q⁺ - Q⁻ = -F·n, M⁺ - M⁻ = -C (a counter-clockwise couple C). Distributed loads are
collocated point-wise (value along n, axial along t; ``frame = global``: (axial, value) = global
(x, y) components per unit arc length; ``sine``: times sin(π s / L)). Every equation row is divided
by its largest coefficient, the non-symmetric system is solved by LU (``solve_linear``; unknowns
interleaved per particle, so it is banded) and its condition number reported. The default form is
written straight into a :class:`~pdverify.band.Band` (6 x 6 block stencils, one diagonal per family
offset; :meth:`PDCurved.assemble_band`), which ``solve_linear`` factorises in place above 20,000 unknowns;
``assemble`` returns the same band as CSR.

Measured (tests/test_pd_curved.py, tests/test_curved_studies.py; max-norm relative displacement error,
L/h = 10, 41 -> 321 particles, observed order per doubling):

* ``primal``: order 2⌊P/2⌋: P = 2/3/4/5/6 -> 2.0/2.0/4.0/4.0/6.0 (straight sine), 2.0/2.0/4.0/4.3-4.5/6.1
  (semicircle), 2.0/2.0/4.0/4.0/6.0 (quintic): an odd degree converges like the even degree below it.
* ``mixed``: order 2⌈P/2⌉: 2.0/4.0/4.0/5.9/(6 until a floor) (straight), 2.0/4.0/4.0/6.0/6.0 (semicircle),
  2.0/4.0/4.0/6.0/6.9 (quintic): an odd degree gains one order. P = 6 with 9 members had a band of
  modes held only by the end families (condition ~ n^4 instead of n^2): error floor growing with n, 3.9e-8 /
  2.2e-7 / 1.2e-6 at 401 / 1601 / 6401 particles on the straight beam; the default is now 7 members
  (4.0e-13 / 5.3e-13 / 1.8e-12; see default_horizon).
* Locking (201 particles, error vs L/h = 10, 100, 1000, 10^4): ``primal`` error ~ (L/h)^2 for every
  degree until it saturates at ~1 (slope 2.0 for P >= 4; P = 2, 3 saturate by L/h = 1000); a higher
  degree lowers the constant (P = 6 straight 3.5e-11 -> 4.0e-7 at L/h = 1000), not the slope. ``mixed``
  is locking-free on the load-driven examples (straight P = 2: 4.4e-4 -> 4.8e-4; semicircle P = 4: 2.0e-8
  at every L/h) but not on the manufactured quintic, whose loads scale with EA and kGA (slope 2.0).
* 10^5 particles (clamped-free, six load types: four solves): 1.9 / 3.3 / 4.5 s in all at P = 2 / 4 / 6
  (resultant unknowns; the sparse assembly it replaced: 8.6-10 s at P = 4 on the same shared machine), of
  which the banded LU takes 75-80 %. ``pdverify bench`` (one tip load, 10^5 particles, P = 4): 0.74 s
  against 0.64 s for ``solve_banded`` on the same band (ratio 1.1-1.2; assembly 0.11 s).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..band import Band, Extent
from ..errors import InputError
from ..geometry import axis_abscissae, geometry
from ..linalg import solve_linear
from ..registry import Model, Option, System
from ..result import Result, Timer
from ..scene import Distributed, PointForce, PointMoment, Scene
from . import _pddo

# -- geometry ---------------------------------------------------------------------------------


def curvature_slope(scene: Scene, s: np.ndarray) -> np.ndarray:
    """dκ/ds (0 for straight and arc axes; polynomial: (1/J) d/dx [y''/J³], J = sqrt(1 + y'²))."""
    return axis_frame(scene, s)[3]


def axis_frame(scene: Scene, s: np.ndarray):
    """(t, n, κ, dκ/ds, x) at arc lengths s: tangent and normal (each (len(s), 2)), curvature, its slope and
    the axis abscissae x(s) (polynomial axes; None otherwise). On a polynomial axis s is inverted once
    (:func:`axis_abscissae`) and t, n, κ are the formulas of :mod:`pdverify.geometry` evaluated at that x
    (``geometry.frame`` and ``geometry.curvature`` would each invert s again: 0.37 s per call at 10^4
    particles, 8 s and 2 GB of temporaries at 10^5)."""
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
    tol = 1e-9 * L
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
    bps: list[float] = []
    loads: dict[int, list] = {}
    for p, load in sorted(zip(pos, at), key=lambda t: t[0]):
        if not bps or p - bps[-1] > tol:
            bps.append(p)
            loads[len(bps) - 1] = []
        if load is not None:
            loads[len(bps) - 1].append(load)
    return np.array(bps), loads, ends


def segment_grids(L: float, bps: np.ndarray, points: int, min_points: int, density=None) -> list[np.ndarray]:
    """Particles on each segment [b_i, b_{i+1}], about (points - 1) intervals in all, at least ``min_points``
    per segment. ``density`` None: uniform (a uniform grid of ``points`` particles when the breaks fall on
    it). Else a pair (s_table, cumulative) of a non-decreasing measure m(s) (m(0) = 0, m(L) = 1): the
    intervals of a segment are shared by its measure, and its particles sit at equal steps of m (the seed's
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
    tol = 1e-9 * L
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
    to the nearer end or to a point load inside the beam: particles gather at the supports and at point loads)."""
    L = scene.length
    s = np.linspace(0.0, L, samples)
    if by == "curvature":
        kap = np.abs(axis_frame(scene, s)[2])
        f = np.sqrt(kap / kap.max()) if kap.max() > 0 else np.zeros_like(s)
    else:
        marks = [0.0, L] + [ld.position for ld in scene.loads if isinstance(ld, (PointForce, PointMoment))]
        d = np.min(np.abs(s[:, None] - np.array(marks)[None, :]), axis=1)
        f = np.exp(-d / (0.1 * L))
    rho = 1.0 + (ratio - 1.0) * f
    m = np.concatenate([[0.0], np.cumsum((rho[1:] + rho[:-1]) * np.diff(s) / 2)])
    return s, m / m[-1]


def force_components(load, t: np.ndarray, n: np.ndarray) -> tuple[float, float, float]:
    """(F·t, F·n, C) of a point load at a point with unit tangent t and normal n."""
    if isinstance(load, PointMoment):
        return 0.0, 0.0, load.value
    if load.frame == "global":
        F = np.array([load.axial, load.value])
        return float(F @ t), float(F @ n), 0.0
    return load.axial, load.value, 0.0


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
        f = np.ones_like(s) if load.shape == "uniform" else np.sin(np.pi * s / scene.length)
        if load.frame == "global":
            pt += f * (load.axial * t[:, 0] + load.value * t[:, 1])
            pn += f * (load.axial * n[:, 0] + load.value * n[:, 1])
        else:
            pt += f * load.axial
            pn += f * load.value
    return pt, pn


# -- the model --------------------------------------------------------------------------------

_SUPPORT_SLOTS = {  # per slot (t, n, φ): True = the kinematic quantity is prescribed, False = the resultant
    "clamped": (True, True, True),
    "pinned": (True, True, False),
    "roller": (False, True, False),
    "free": (False, False, False),
    "guided": (False, False, True),
}


def default_horizon(degree: int, form: str = "primal") -> int:
    """⌊P/2⌋ + 1 (P + 3 members for even P, P + 2 for odd P), except the mixed form at even P >= 6: P/2
    (P + 1 members, the interpolating central stencil).

    Why: the mixed form applies the first-derivative function g^1 only, and every antisymmetric interior
    stencil annihilates the sawtooth (-1)^k; what keeps the neighbouring high-frequency modes away from zero
    is the slope of the stencil's symbol σ(θ) = Σ_j c_j sin(jθ) at θ = π, 2 Σ_j (-1)^(j+1) j c_j (h = 1).
    With P + 3 members the spare (two more than P + 1) coefficients are set by the weight, and that slope collapses
    at P = 6 (0.017, against 0.67 / 0.45 at P = 2 / 4 and 2.2 for the 7-member stencil) and changes sign
    at P = 8 and 10 (-0.41, -0.82: a spurious interior null mode). The modes near θ = π are then held only
    by the end families, the condition number grows like n^4 and the error has a floor that grows with n.
    P + 1 members give the interpolating stencil (slope 2.2 / 2.66 / 3.06 at P = 6 / 8 / 10), whose weights do
    not depend on w. The primal form keeps ⌊P/2⌋ + 1: its g^2 symbol Σ_j c_j cos(jθ) stays negative at P = 6
    (-0.096 at θ = π) and is positive there at P = 8 and 10 (0.32, 0.62), without a measured floor (straight sine,
    P = 8: 1.2e-10 at 1601 particles; see docs/models/curved.md)."""
    if form == "mixed" and degree % 2 == 0 and degree >= 6:
        return degree // 2
    return degree // 2 + 1


class PDCurved(Model):
    name = "pd-curved"
    title = "PDDO curved Timoshenko–Ehrenfest beam (u_t, u_n, φ), any degree"
    source = "PDDO planar curved Timoshenko–Ehrenfest beam (seed 004; design note §2–3)"
    options = (
        Option("points", int, 101, "particles along the axis, ends included", minimum=5),
        Option("degree", int, 4, "polynomial degree P of the PDDO functions", minimum=2, maximum=10),
        Option(
            "horizon",
            int,
            0,
            "family half-width m in particles (family 2m + 1); 0 = floor(P/2) + 1 (mixed form, even P >= 6: P/2)",
            minimum=0,
        ),
        Option(
            "grading",
            float,
            1.0,
            "largest / smallest particle spacing (1 = uniform particles; see graded_by)",
            minimum=1.0,
            maximum=1e3,
        ),
        Option(
            "graded_by",
            str,
            "curvature",
            "where particles gather when grading > 1: curvature (where the axis "
            "bends) | ends (at the supports and at point loads)",
            choices=("curvature", "ends"),
        ),
        Option(
            "positions",
            str,
            "",
            "particle arc lengths in m, comma-separated (0 and L added; breaks at point "
            "loads and load ends added): overrides the particles of points and grading (points still sets the "
            "output grid)",
        ),
        Option(
            "form",
            str,
            "mixed",
            "primal (the paper: second-derivative functions) | mixed (first-derivative functions applied twice)",
            choices=("primal", "mixed"),
        ),
        Option(
            "unknowns",
            str,
            "resultants",
            "mixed form only: resultants (u_t, u_n, φ, N, Q, M per particle: "
            "condition number free of the slenderness) | displacements (N, Q, M substituted: 3 per particle, "
            "the same discrete solution, condition ~ (L/h)^2)",
            choices=("resultants", "displacements"),
        ),
    )
    curved = True
    axial = True
    theory = "timoshenko"
    assembles = True

    def check(self, scene: Scene) -> list[str]:
        """The scene checks plus the axial rigid-body test on straight axes (e.g. two rollers slide along x)."""
        from ..geometry import mechanism_message

        out = super().check(scene)
        why = mechanism_message(scene)
        return out + ([why] if why is not None else [])

    # ---------------------------------------------------------------------------------------
    def discretise(self, scene: Scene, params: dict):
        P = params["degree"]
        m = params["horizon"] or default_horizon(P, params["form"])
        size = 2 * m + 1
        if size < P + 1:
            raise InputError(
                f"horizon = {m}: a family of {size} particles cannot carry degree {P}; "
                f"use horizon >= {int(np.ceil(P / 2))} or a lower degree"
            )
        if size > params["points"]:
            raise InputError(
                f"points = {params['points']}: fewer than one family ({size} particles for "
                f"degree {P}, horizon {m}); use more points"
            )
        bps, inner, ends = breakpoints(scene)
        if params.get("positions"):
            segs = given_grids(scene.length, bps, parse_positions(params["positions"], scene.length), size)
            return segs, inner, ends, m, size
        ratio = params.get("grading", 1.0)
        density = None if ratio == 1.0 else grading_density(scene, ratio, params.get("graded_by", "curvature"))
        segs = segment_grids(scene.length, bps, params["points"], size, density)
        return segs, inner, ends, m, size

    def assemble(self, scene: Scene, params: dict, body=None) -> System:
        """The collocation system of all the scene's loads as one :class:`~pdverify.band.Band`
        (:meth:`assemble_band`), z = (u_t, u_n, φ[, N, Q, M]) interleaved per particle; every unknown is
        free (the end conditions are rows of the system). ``solve`` factorises one such system per group of
        loads with the same breaks."""
        B, b, data = self.assemble_band(scene, params, body)
        return System(B, b, np.arange(B.n), data)

    def assemble_band(self, scene: Scene, params: dict, body=None):
        """(B, b, data): the collocation system (Eq. 27–35, boundary and interface rows replacing
        equilibrium or constitutive rows, rows then columns equilibrated) as a :class:`~pdverify.band.Band`
        with the unknowns of a particle interleaved. ``body(s, x)`` optionally adds distributed (p_t, p_n, m)
        at the arc lengths s (x: their axis abscissae on a polynomial axis, else None; the manufactured loads).

        The default form (mixed, resultants) is written straight into the band: the 6 x 6 block stencils of
        the constitutive and equilibrium rows (PDDO weights per particle, one band diagonal per family offset)
        and the boundary entries; the row and column scales are read and applied on the diagonals that were
        written, over the stretch that was written. The other forms (three unknowns per particle, stencils
        of D1 D1 and D2) are assembled as sparse products, as they always were, and copied into a band."""
        segs, inner, ends, m, size = self.discretise(scene, params)
        P = params["degree"]
        s = np.concatenate(segs)
        N = len(s)
        t, nv, kap, dkap, xa = axis_frame(scene, s)
        offs = np.cumsum([0] + [len(g) for g in segs])
        six = params["form"] == "mixed" and params.get("unknowns", "resultants") == "resultants"
        pt, pn, mm = np.zeros(N), np.zeros(N), np.zeros(N)
        for i, g in enumerate(segs):
            sl = slice(offs[i], offs[i + 1])
            pt[sl], pn[sl] = distributed_loads(scene, g, t[sl], nv[sl], 0.5 * (g[0] + g[-1]))
        if body is not None:
            bt, bn, bm = body(s, xa)
            pt, pn, mm = pt + bt, pn + bn, mm + bm
        data = dict(s=s, segs=segs, offs=offs, N=N, t=t, n=nv, horizon=m, family=size)
        if six:
            B, b, cs = self._assemble_resultants(scene, segs, offs, inner, ends, size, P, kap, t, nv, (pt, pn, mm))
            nf = 6
            data.update(Eps=None, Gam=None, Chi=None)
        else:
            K, b, cs, ops = self._assemble_displacements(
                scene, params, segs, offs, inner, ends, size, P, kap, dkap, t, nv, (pt, pn, mm)
            )
            B = Band.from_sparse(K)
            nf = 3
            data.update(ops)
        # perm: interleaved index i -> component-major index perm[i]; cscale (component-major) and cscale_i
        # (interleaved): the column scales, z = cscale_i * (solution of B)
        data.update(
            nf=nf, perm=np.arange(nf * N).reshape(nf, N).T.ravel(), cscale=cs.reshape(N, nf).T.ravel(), cscale_i=cs
        )
        return B, b, data

    def _conditions(self, scene: Scene, N: int, offs, segs, inner, ends, t, nv, eq0: int, six: bool, resultant):
        """Boundary (Eq. 11–13) and interface rows, component-major numbering (unknown c N + k, constitutive row
        c N + k, equilibrium row eq0 + c N + k): (rows replaced, their right-hand sides, (rows, cols, values)
        of their entries)."""
        # Boundary and interface conditions replace the equilibrium rows of the segment-end particles; with
        # N, Q, M as unknowns and one kinematic end in a slot, the continuity at an interface replaces the
        # constitutive row instead, on the side away from that end (else a segment between a load and a free end
        # has only resultant conditions and a spurious discrete compatibility condition: quintic
        # cantilever, load ending 0.22 m before the free end, 41 particles, P = 4: 170 % error). Dropping a
        # constitutive row at the outer ends too was measured worse (clamped-clamped straight sine, P = 4,
        # 81 particles: 7.5e-6 instead of 1.9e-6), so the outer conditions stay in the equilibrium rows.
        rr, rc, rv = [], [], []
        rb = {}

        def add(row, cols, vals):
            rr.append(np.full(len(cols), row)), rc.append(np.asarray(cols)), rv.append(np.asarray(vals, float))

        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            k = 0 if side == 0 else N - 1
            sign = -1.0 if side == 0 else 1.0
            F = np.zeros(3)
            for load in ends[side]:
                F += force_components(load, t[k], nv[k])
            for c, kin in enumerate(_SUPPORT_SLOTS[sup]):
                row = eq0 + c * N + k
                if kin:
                    add(row, [c * N + k], [1.0])
                    rb[row] = 0.0
                else:
                    add(row, *resultant(c, k))
                    rb[row] = sign * F[c]
        for i in range(len(segs) - 1):
            ka, kb = offs[i + 1] - 1, offs[i + 1]
            F = np.zeros(3)
            for load in inner.get(i, []):
                F += force_components(load, t[ka], nv[ka])
            for c in range(3):
                kl, kr = _SUPPORT_SLOTS[scene.supports.left][c], _SUPPORT_SLOTS[scene.supports.right][c]
                if six and kl != kr:  # one kinematic end: continuity into the constitutive row away from it
                    kc, kj = (kb, ka) if kl else (ka, kb)
                    row = c * N + kc
                else:  # both or neither (mirror-symmetric): both conditions replace equilibrium rows
                    kc, kj = ka, kb
                    row = eq0 + c * N + kc
                add(row, [c * N + ka, c * N + kb], [1.0, -1.0])
                rb[row] = 0.0
                cb, vb = resultant(c, kb)
                ca, va = resultant(c, ka)
                add(eq0 + c * N + kj, np.r_[cb, ca], np.r_[vb, -va])
                rb[eq0 + c * N + kj] = -F[c]
        rows = np.array(sorted(rb))
        return rows, np.array([rb[r] for r in rows]), (np.concatenate(rr), np.concatenate(rc), np.concatenate(rv))

    def _assemble_resultants(self, scene, segs, offs, inner, ends, size, P, kap, t, nv, loads):
        """Mixed form with N, Q, M as unknowns, straight into a band: (B, b, column scales), unknowns
        (u_t, u_n, φ, N, Q, M) and rows (constitutive t, n, φ; equilibrium t, n, φ) interleaved per particle:

            ε(u) - N/EA = 0,  γ(u) - Q/kGA = 0,  χ(u) - M/EI = 0        (Eq. 3–4)
            D1 N - κ Q + p_t = 0,  D1 Q + κ N + p_n = 0,  D1 M + Q + m = 0   (Eq. 8–10)

        with ε = D1 u_t - κ u_n, γ = D1 u_n + κ u_t - φ, χ = D1 φ. Every entry is written once (no sums), then
        each row is divided by its largest coefficient and each column by its largest after that: the same
        numbers, bit for bit, as the sparse assembly this replaced (scipy's products by diagonal matrices
        round each entry once, as here)."""
        N, nf = len(kap), 6
        EA, kGA, EI = scene.EA, scene.kGA, scene.EI
        bw = nf * (size - 1)  # the end families reach size - 1 particles
        B = Band(nf * N, bw, bw)
        ext = Extent(B)
        # particle's own block (offset 0): curvature couplings, compliances, Q in the moment equation
        C0 = [[0.0] * nf for _ in range(nf)]
        C0[0][1], C0[0][3] = -kap, -(1 / EA)
        C0[1][0], C0[1][2], C0[1][4] = kap, -1.0, -(1 / kGA)
        C0[2][5] = -(1 / EI)
        C0[3][4], C0[4][3], C0[5][4] = -kap, kap, 1.0
        ext.block(nf, 0, C0, 0, N)
        for i, g in enumerate(segs):  # a few segments (load discontinuities), never a loop over particles
            fam, W = _pddo.derivative_weights(g, P, size, (1,))
            W = W[1]
            first = fam[:, 0] - np.arange(len(g))  # offset of each family's first member (non-increasing)
            for o in range(-(size - 1), size):  # one band diagonal per family offset and unknown
                j = o - first
                k = np.flatnonzero((j >= 0) & (j < size))  # the particles reaching offset o: contiguous
                if not len(k):
                    continue
                k1, k2 = int(k[0]), int(k[-1]) + 1
                c = W[np.arange(k1, k2), j[k1:k2]]
                ext.block(
                    nf, o, [[c if a == b else 0.0 for b in range(nf)] for a in range(nf)], offs[i] + k1, offs[i] + k2
                )
        # boundary and interface rows (component-major numbering -> interleaved)
        rows, vals, (rr, rc, rv) = self._conditions(
            scene,
            N,
            offs,
            segs,
            inner,
            ends,
            t,
            nv,
            3 * N,
            True,
            lambda c, k: (np.array([(3 + c) * N + k]), np.array([1.0])),
        )
        inter = lambda i: (i % N) * nf + i // N  # noqa: E731
        rows, rr, rc = inter(rows), inter(rr), inter(rc)
        B.clear_rows(rows)
        B.add_entries(rr, rc, rv)
        ext.entries(rr, rc)
        b = np.zeros((N, nf))
        b[:, 3], b[:, 4], b[:, 5] = -loads[0], -loads[1], -loads[2]
        b = b.ravel()
        b[rows] = vals
        # equilibrate: each row divided by its largest coefficient, then each column
        rs = 1.0 / ext.abs_max(rows=True)
        ext.scale(rs, rows=True)
        b *= rs
        cs = 1.0 / ext.abs_max(rows=False)
        ext.scale(cs, rows=False)
        return B, b, cs

    def _assemble_displacements(self, scene, params, segs, offs, inner, ends, size, P, kap, dkap, t, nv, loads):
        """Three unknowns (u_t, u_n, φ) per particle: ``primal`` (Eq. 14–16) or ``mixed`` with the resultants
        substituted. Sparse assembly: (K interleaved CSR, b, column scales (ones), strain operators)."""
        N = len(kap)
        D1s, D2s = [], []
        for g in segs:  # a few segments (load discontinuities), never a loop over particles
            D = _pddo.derivative_matrices(g, P, size, (1, 2))
            D1s.append(D[1]), D2s.append(D[2])
        D1 = sp.block_diag(D1s, format="csr")
        D2 = sp.block_diag(D2s, format="csr")
        I = sp.identity(N, format="csr")
        Z = sp.csr_matrix((N, N))
        K_ = sp.diags(kap)
        Kp = sp.diags(dkap)
        EA, kGA, EI = scene.EA, scene.kGA, scene.EI
        # strain operators (rows: particles; block columns u_t, u_n, φ)
        Eps = sp.hstack([D1, -K_, Z], format="csr")
        Gam = sp.hstack([K_, D1, -I], format="csr")
        Chi = sp.hstack([Z, Z, D1], format="csr")
        if params["form"] == "mixed":  # condensed: the resultants substituted, D1 applied twice
            dEps, dGam, dChi = D1 @ Eps, D1 @ Gam, D1 @ Chi
        else:  # primal: the derivative of each strain written out, second derivatives by g^2
            dEps = sp.hstack([D2, -Kp - K_ @ D1, Z], format="csr")
            dGam = sp.hstack([Kp + K_ @ D1, D2, -D1], format="csr")
            dChi = sp.hstack([Z, Z, D2], format="csr")
        Kt = EA * dEps - kGA * (K_ @ Gam)
        Kn = kGA * dGam + EA * (K_ @ Eps)
        Kf = EI * dChi + kGA * Gam
        K = sp.vstack([Kt, Kn, Kf], format="csr")
        b = -np.concatenate(loads)
        res = [(EA * Eps).tocsr(), (kGA * Gam).tocsr(), (EI * Chi).tocsr()]  # N, Q, M

        def resultant(c, k):
            r = res[c].getrow(k).tocoo()
            return r.col, r.data

        rows, vals, (rr, rc, rv) = self._conditions(scene, N, offs, segs, inner, ends, t, nv, 0, False, resultant)
        n_all = 3 * N
        keep = np.ones(n_all)
        keep[rows] = 0.0
        R = sp.csr_matrix((rv, (rr, rc)), shape=(n_all, n_all))
        K = (sp.diags(keep) @ K + R).tocsr()
        b = b * keep
        b[rows] = vals
        # equilibrate: each row divided by its largest coefficient
        scale = 1.0 / abs(K).max(axis=1).toarray().ravel()
        K = (sp.diags(scale) @ K).tocsr()
        b = b * scale
        # interleave (particle-major) so the matrix is banded
        perm = np.arange(n_all).reshape(3, N).T.ravel()  # new index i -> old index perm[i]
        inv = np.empty_like(perm)
        inv[perm] = np.arange(n_all)
        Cm = K.tocoo()
        K = sp.csr_matrix((Cm.data, (inv[Cm.row], inv[Cm.col])), shape=K.shape)
        return K, b[perm], np.ones(n_all), dict(Eps=Eps, Gam=Gam, Chi=Chi)

    def solve(self, scene: Scene, params: dict, body=None) -> Result:
        """Superposition of single-load solutions: the loads are grouped by the breaks they need (a point
        load inside the beam: its position; a distributed load: its span ends inside the beam; end loads,
        full-span loads and ``body``: none), each group solved on particles that respect its own breaks,
        and the fields summed on the uniform output grid. So the result is exactly linear in the loads
        (a discretisation that depended on all loads together would not be), and each discontinuity is
        still resolved by its own segments."""
        timer = Timer()
        groups: dict[tuple, list] = {}
        for load in scene.loads:
            bps, _, _ = breakpoints(scene.model_copy(update={"loads": [load]}))
            groups.setdefault(tuple(np.round(bps / scene.length, 12)), []).append(load)
        if body is not None or not groups:
            groups.setdefault((), [])
        total, infos, dofs = None, [], 0
        for key, loads in sorted(groups.items()):
            sub = scene.model_copy(update={"loads": loads})
            out, info, n_dofs = self._solve_once(sub, params, body if key == () else None, timer)
            total = out if total is None else {k: total[k] + out[k] for k in total}
            infos.append(info)
            dofs += n_dofs
        info = dict(infos[int(np.argmax([i.get("cond", 0.0) for i in infos]))])
        warnings = sorted({w for i in infos for w in i.get("warnings", [])})
        if warnings:
            info["warnings"] = warnings
        info.update(solves=len(infos), segments=max(i["segments"] for i in infos))
        w, rot = total.pop("w"), total.pop("rotation")
        x = total.pop("x") / len(infos)
        return Result(
            scene=scene.name,
            model=self.name,
            parameters=dict(params),
            x=x,
            w=w,
            rotation=rot,
            fields=total,
            dofs=dofs,
            timings=timer.timings,
            info=info,
        )

    def _solve_once(self, scene: Scene, params: dict, body, timer: Timer):
        """Fields on the uniform output grid, solver info and unknowns of one discretisation."""
        with timer("assemble"):
            B, b, d = self.assemble_band(scene, params, body)
        with timer("solve"):  # factorises B in place above 20,000 unknowns (solve_band), else as CSR
            zi, info = solve_linear(B, b, what=f"pd-curved (degree {params['degree']}, {params['form']})")
        del B
        N, nf = d["N"], d["nf"]
        Z = (zi * d["cscale_i"]).reshape(N, nf)  # row k: the unknowns of particle k
        ut, un, phi = Z[:, 0], Z[:, 1], Z[:, 2]
        if nf == 6:
            Nf, Qf, Mf = Z[:, 3], Z[:, 4], Z[:, 5]
        else:
            z = Z.T.ravel()
            Nf, Qf, Mf = scene.EA * (d["Eps"] @ z), scene.kGA * (d["Gam"] @ z), scene.EI * (d["Chi"] @ z)
        # output on the uniform grid of ``points`` positions (independent of the loads): the particle value
        # where a particle sits there, else the degree-P PDDO interpolant g^0 of its segment; at a break
        # the left segment's (left limit of the resultants)
        T = self.output_map(d, scene.length, params["points"], params["degree"])
        t, nv = d["t"], d["n"]
        ux = ut * t[:, 0] + un * nv[:, 0]
        uy = ut * t[:, 1] + un * nv[:, 1]
        fields = {
            "x": d["x"],
            "w": T @ un,
            "rotation": T @ phi,
            "u": T @ ut,
            "N": T @ Nf,
            "Q": T @ Qf,
            "M": T @ Mf,
            "ux": T @ ux,
            "uy": T @ uy,
        }
        if scene.is_straight:
            fields["V"] = -fields["Q"]
        info.update(
            degree=params["degree"],
            horizon=d["horizon"],
            family=d["family"],
            form=params["form"],
            unknowns_per_particle=d["nf"],
            segments=len(d["segs"]),
            particles=N,
        )
        return fields, info, d["nf"] * N

    @staticmethod
    def output_map(d: dict, L: float, points: int, degree: int) -> sp.csr_matrix:
        """Sparse (points, particles) map from particle values to the uniform output grid."""
        x = np.linspace(0.0, L, points)
        x[-1] = L
        d["x"] = x
        segs, offs, size = d["segs"], d["offs"], d["family"]
        bps = np.array([g[-1] for g in segs[:-1]])
        seg = np.searchsorted(bps, x - 1e-12 * L, side="left")  # a break belongs to its left segment
        rows, cols, vals = [], [], []
        for i, g in enumerate(segs):  # a few segments
            k = np.flatnonzero(seg == i)
            if not len(k):
                continue
            j = np.clip(np.searchsorted(g, x[k]), 0, len(g) - 1)
            j = np.where((j > 0) & (np.abs(g[j - 1] - x[k]) < np.abs(g[j] - x[k])), j - 1, j)
            on = np.abs(g[j] - x[k]) <= 1e-12 * L
            rows.append(k[on]), cols.append(offs[i] + j[on]), vals.append(np.ones(on.sum()))
            if (~on).any():
                xo = x[k[~on]]
                fam = _pddo.nearest_families(g, xo, size)
                c = _pddo.pddo_weights(g, fam, degree, (0,), centers=xo)[0]
                rows.append(np.repeat(k[~on], size)), cols.append((offs[i] + fam).ravel()), vals.append(c.ravel())
        return sp.csr_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(points, offs[-1])
        )


MODELS = [PDCurved()]
