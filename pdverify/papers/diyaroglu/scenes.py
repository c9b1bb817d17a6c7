"""Scenes as engineers draw them in ``pd-eb``'s corrected mixed form: point loads as the moment they cause, material
interfaces, elastic supports and supports inside the span. Arrays in, arrays out; the model is in model.py.

**Point loads as the kink of the moment.** The mixed form's unknowns are the moment m_p and w_p at each position,
with D1 w = f m (f the flexibility, 1/EI away from interfaces) and D2 m = q (Diyaroglu et al. Eq. 10a, 13-15 split
in two). A point force P at a makes the moment kink, m = P (x - a)_+ + a line; its load on the points is that kink's
divergence, q_p = P D2[(x - a)_+]_p, spread over the family around a (zero farther away, the same total force and
moment). The discrete moment is then the exact one near the load (a line on each side), instead of the kink smeared
over the horizon that one point carrying P/dx gives. A couple C makes the moment jump, m = -C H(x - a) (H = 1/2 at a
point exactly at a), so q_p = -C D2[H(x - a)]_p; the curvature rows take the jump's own part of the PD curvature,
D1 w = f m - (C/EI) (D1[(x - a)_+^2 / 2] - H(x - a)): the curvature the stencil sees of the exact w there. Loads
closer to an end than 2J spacings keep the split of Eq. 25 (the stencil of their kink would leave the grid).

**Material interfaces.** Diyaroglu et al. correct d where a family meets a free surface or a material interface
(section "Calculations for the near surface material points"), by a test state the point must reproduce. At an
interface the state a beam must carry is a uniform moment (the curvature jumps with 1/EI): each point within a
horizon of an interface takes the flexibility f_p = D1[g]_p, g'' = 1/EI(x) (the PD curvature of the uniform unit
moment's deflection) instead of 1/EI_p, so D1 w = f m holds exactly for any uniform moment across any number of
interfaces (:func:`flexibility`). Without it (f = 1/EI at the point) an interface on a grid point costs first order.

**Supports inside the span and springs.** Each support holds a measure of w with a reaction as its Lagrange
multiplier: w(a) by cubic interpolation between the four nearest points, its rotation w'(a) by the mean of the
one-sided second-order differences on either side (w'' jumps at a clamped support), an end's deflection and rotation
on its end points (a spring end is a free end with its spring's force and moment as end loads). The reaction enters
as a point load of its kind at a (the columns of :func:`load_column`); a spring's row is k measure + R = 0, a rigid
support's measure = 0.
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.scene import InnerSupport, PointForce, PointMoment, Scene, Spring
from ...core.text import more_points, spacings
from ...numerics.load_warnings import held_rotation_warnings
from ...numerics.loads import TIE, within
from ...numerics.recovery import STRETCH


def pieces_flexibility(scene: Scene, EI0: float) -> tuple[np.ndarray, np.ndarray]:
    """(breaks, EI0/EI per piece): the interfaces inside the beam and each piece's flexibility relative to EI0 (the
    first and last pieces extend beyond the ends)."""
    parts = scene.pieces()
    return np.array([a for a, _, _, _ in parts[1:]]), np.array([EI0 / (mat.E * sec.I) for _, _, sec, mat in parts])


def _double_integral(x0: np.ndarray, s: np.ndarray, breaks: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """g(s) = ∫_0^s (s - t) phi(x0 + t) dt for piecewise constant phi (pieces split at ``breaks``), elementwise."""
    lo = np.r_[-np.inf, breaks]
    hi = np.r_[breaks, np.inf]
    a, b = np.minimum(0.0, s)[..., None], np.maximum(0.0, s)[..., None]
    ta = np.clip(lo - x0[..., None], a, b)
    tb = np.clip(hi - x0[..., None], a, b)
    ss = s[..., None]
    return np.sign(s) * np.sum(phi * ((ss - ta) ** 2 - (ss - tb) ** 2) / 2, axis=-1)


def flexibility(
    scene: Scene, positions: np.ndarray, dx: float, c: np.ndarray, EI0: float, calibrated: bool = True
) -> np.ndarray:
    """EI0 f_p at the positions (in spacings, ghosts included): EI0/EI of the piece at x_p (exactly 1 on a uniform
    beam; at an interface the piece to its right), and, ``calibrated``, at the positions whose family reaches an
    interface the calibrated EI0 D1[g]_p, g'' = 1/EI(x) (module docstring)."""
    breaks, phi = pieces_flexibility(scene, EI0)
    x = positions * dx
    tb = breaks / dx
    tb = np.where(np.abs(tb - np.round(tb)) < 1e-9, np.round(tb), tb)  # an interface on a point: exactly there
    f = phi[np.searchsorted(tb, positions, side="right")]
    if not len(breaks) or not calibrated:
        return f
    J = len(c)
    near = np.any(np.abs(x[:, None] - breaks[None, :]) < J * dx * (1 + 1e-12), axis=1)
    if near.any():
        j = np.arange(1, J + 1) * dx
        xp = np.broadcast_to(x[near][:, None], (near.sum(), J))
        g = _double_integral(xp, np.broadcast_to(j, xp.shape), breaks, phi)
        g += _double_integral(xp, np.broadcast_to(-j, xp.shape), breaks, phi)
        f[near] = g @ c
    return f


# -- point loads ------------------------------------------------------------------------------------------------


def spread_ok(t0: float, n: int, J: int) -> bool:
    """A point load at t0 spacings is spread by its kink when every row it touches is real: 2J from both ends (within
    1e-9 spacings, as :func:`_offset_grid` puts a load on a point: the rounding of t0 decides neither side)."""
    return 2 * J - 1e-9 <= t0 <= n - 1 - 2 * J + 1e-9


def _offset_grid(t0: float, J: int, reach: int) -> tuple[np.ndarray, np.ndarray]:
    """(rows p, (p + o) - t0 for o = -J..J) of the rows within ``reach`` of t0 (a load within 1e-9 of a point
    counts as on it)."""
    t0 = round(t0) if abs(t0 - round(t0)) < 1e-9 else t0
    p = np.arange(int(np.floor(t0)) - reach, int(np.ceil(t0)) + reach + 1)
    return p, p[:, None] + np.arange(-J, J + 1)[None, :] - t0


def force_kink(t0: float, dx: float, st: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(rows, q): the line load of a unit point force at t0 spacings, D2[(x - a)_+] on the rows around it."""
    J = len(st) // 2
    p, d = _offset_grid(t0, J, J + 1)
    return p, (np.maximum(d, 0.0) * dx) @ st


def _step(d: np.ndarray) -> np.ndarray:
    return np.where(d > 0, 1.0, np.where(d < 0, 0.0, 0.5))


def couple_kink(t0: float, dx: float, st: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rows, q, kappa): a unit counter-clockwise couple at t0 spacings: its line load -D2[H(x - a)] and its part of
    the PD curvature D1[(x - a)_+^2 / 2] - H(x_p - a) (to be divided by EI), on the rows around it."""
    J = len(st) // 2
    p, d = _offset_grid(t0, J, J + 1)
    q = -(_step(d) @ st)
    kappa = ((np.maximum(d, 0.0) * dx) ** 2 / 2) @ st - _step(d[:, J])
    return p, q, kappa


def spreads(load, scene: Scene, n: int, dx: float, J: int) -> bool:
    """Whether the load enters by its kink (:func:`force_kink`, :func:`couple_kink`, :func:`distributed_kink`): every
    kink it makes lies 2J spacings from both ends (a point load exactly at an end is an end load)."""
    if load.type in ("point_force", "point_moment"):
        return load.value != 0.0 and spread_ok(load.position / dx, n, J)
    if load.type != "distributed" or load.value == 0.0:
        return False
    return all(spread_ok(v / dx, n, J) for v in scene.span(load) if 0.0 < v < scene.length)


def edge_loads(scene: Scene, n: int, dx: float, J: int) -> tuple[list[int], int]:
    """(the distributed loads whose shear an edge near an end spoils, as indices into the scene's loads; the spacings
    from an end where that happens): taken by their cell averages (:func:`spreads`: an edge within 2J spacings of an
    end), or with fewer than STRETCH points between an edge and its end, where the shear is differenced across it
    (:func:`~pdverify.numerics.recovery.derivative`; at horizon 1, 2J = 2, an edge on the second point from an end)."""
    L = scene.length

    def crossed(e: float) -> bool:
        return 0.0 < e < L and np.ceil(min(e, L - e) / dx - 1e-9) < STRETCH

    loads = [
        i
        for i, ld in enumerate(scene.loads)
        if ld.type == "distributed"
        and ld.value != 0.0
        and (not spreads(ld, scene, n, dx, J) or any(crossed(e) for e in scene.span(ld)))
    ]
    return loads, max(2 * J, STRETCH)


def distributed_kink(load, scene: Scene, n: int, dx: float, st: np.ndarray) -> np.ndarray | None:
    """The line load on the n points of a distributed load as the divergence of its particular moment,
    q_p = D2[Mp]_p, Mp the mean of the two particular moments of the span [a, b], S_a - S_b and T_b - T_a (S_e the
    moment of the load's shape acting from e on, zero before e; T_e the moment of the load acting up to e, zero past
    e; the two differ by a linear function, which D2 annihilates, and each is the other's mirror image, so a mirrored
    scene takes the mirrored load). On the rows whose stencil straddles e each takes D2 of its kink in coordinates
    local to e (no cancellation); the rows whose stencil lies on the loaded side take the load itself (uniform: 1,
    which is D2 of x^2 / 2; sine: sin(k x_p), so that the PD equilibrium Eq. 10a holds with the load of the paper,
    and the continuum at a fixed horizon is the paper's), the rows on the other side 0. A span that reaches an end of
    the beam continues beyond it. None when a span end lies inside 2J spacings of an end (its rows would leave the
    grid: the caller keeps the cell averages)."""
    J = len(st) // 2
    L = scene.length
    a, b = scene.span(load)
    if not spreads(load, scene, n, dx, J):
        return None
    p = np.arange(n)
    k = np.pi / L
    own = np.ones(n) if load.shape == "uniform" else np.sin(k * p * dx)  # the load itself (Eq. 10a's b)

    def kink(e: float, u: np.ndarray) -> np.ndarray:
        """The moment at a distance u >= 0 on the loaded side of e of the load acting from e on (the sine's
        phase from the end the moment starts at: sin(k (L - x)) = sin(k x))."""
        if load.shape == "uniform":
            return u**2 / 2
        return (k * np.cos(k * e) * u - 2 * np.cos(k * (e + u / 2)) * np.sin(k * u / 2)) / k**2

    def d2(t: float, side: int) -> np.ndarray:
        """D2[S_e] (``side`` = 1) or D2[T_e] (``side`` = -1) on every row, e = t dx."""
        out = own * (side * (p - t) >= J - 1e-9)
        rows, d = _offset_grid(t, J, J)
        across = (rows >= 0) & (rows < n) & (np.abs(rows - t) < J - 1e-9)
        u = side * d[across] * dx  # distance from e on the loaded side, per row and offset
        e = t * dx if side == 1 else L - t * dx
        out[rows[across]] = np.where(u > 0, kink(e, np.maximum(u, 0.0)), 0.0) @ st
        return out

    zero = np.zeros(n)
    s_a, t_a = (own, zero) if a <= 0.0 else (d2(a / dx, 1), d2(a / dx, -1))
    s_b, t_b = (zero, own) if b >= L else (d2(b / dx, 1), d2(b / dx, -1))
    return load.value * 0.5 * ((s_a - s_b) + (t_b - t_a))


# -- supports as measures of w ---------------------------------------------------------------------------------


def _lagrange(nodes: np.ndarray, t: float) -> np.ndarray:
    """Weights of p(t) for the polynomial through ``nodes`` (in spacings)."""
    return np.array([np.prod([(t - o) / (a - o) for o in nodes if o != a]) for a in nodes])


def _one_sided(t: float, n: int) -> list[np.ndarray]:
    """The four points at or left of t and the four at or right of it, those that lie in the grid."""
    left = int(np.floor(t)) - np.arange(4)
    right = int(np.ceil(t)) + np.arange(4)
    return [nodes for nodes in (left, right) if nodes.min() >= 0 and nodes.max() <= n - 1]


def deflection_row(t0: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(points, weights) of w at t0 spacings: the point itself, or the mean of the cubic extrapolations from the
    four points on either side (fourth order also where w'' jumps, at a clamped support; mirror-symmetric)."""
    if abs(t0 - round(t0)) < 1e-9:
        return np.array([int(round(t0))]), np.array([1.0])
    sides = _one_sided(t0, n)
    pts = np.concatenate(sides)
    return pts, np.concatenate([_lagrange(s.astype(float), t0) for s in sides]) / len(sides)


def _lagrange_derivative(nodes: np.ndarray, t: float) -> np.ndarray:
    """Weights of p'(t) for the polynomial through ``nodes`` (in spacings)."""
    k = len(nodes)
    out = np.zeros(k)
    for i in range(k):
        others = [nodes[m] for m in range(k) if m != i]
        den = np.prod([nodes[i] - o for o in others])
        out[i] = sum(np.prod([t - o for o in others if o != skip]) for skip in others) / den
    return out


def rotation_row(t0: float, n: int, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """(points, weights) of w'(a) at t0 spacings: the mean of the one-sided cubic derivatives from the four points
    at or left of a and the four at or right of it (third order with w'' jumping at a); at an end point the one-sided
    cubic derivative into the beam."""
    t = float(round(t0)) if abs(t0 - round(t0)) < 1e-9 else t0
    if t <= 0.0 or t >= n - 1:
        nodes = np.arange(4) if t <= 0.0 else n - 1 - np.arange(4)
        return nodes, _lagrange_derivative(nodes.astype(float), t) / dx
    sides = _one_sided(t, n)
    pts = np.concatenate(sides)
    return pts, np.concatenate([_lagrange_derivative(s.astype(float), t) for s in sides]) / (dx * len(sides))


# -- the reactions as unknowns -----------------------------------------------------------------------------------


def reaction_unknowns(scene: Scene) -> list[dict]:
    """One entry per reaction the mixed form takes as an unknown: ``key`` (its name in ``info["reactions"]``),
    ``kind`` ("force" or "moment"), ``at`` (position), ``stiffness`` (None: rigid) and ``end`` (0, 1 or None)."""
    out = []
    L = scene.length
    for side, at, e in (("left", 0.0, 0), ("right", L, 1)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            if sup.stiffness:
                out.append(dict(key=f"force_{side}", kind="force", at=at, stiffness=sup.stiffness, end=e))
            if sup.rotational_stiffness:
                out.append(dict(key=f"moment_{side}", kind="moment", at=at, stiffness=sup.rotational_stiffness, end=e))
    for i, s in enumerate(scene.supports.inner):
        s: InnerSupport
        spring = s.type == "spring"
        if s.holds_deflection:
            out.append(
                dict(
                    key=f"force_inner_{i}",
                    kind="force",
                    at=s.position,
                    stiffness=s.stiffness if spring else None,
                    end=None,
                )
            )
        if s.holds_rotation:
            k = s.rotational_stiffness if spring else None
            out.append(dict(key=f"moment_inner_{i}", kind="moment", at=s.position, stiffness=k, end=None))
    return out


def unit_load(r: dict):
    """The scene load a unit reaction ``r`` acts as (a point force or counter-clockwise couple at its position)."""
    if r["kind"] == "force":
        return PointForce(type="point_force", position=r["at"], value=1.0)
    return PointMoment(type="point_moment", position=r["at"], value=1.0)


def measure_row(r: dict, n: int, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """(points, weights) of the measure of w the reaction ``r`` resists: the deflection or the rotation at its
    position (an end's on its end points)."""
    t0 = r["at"] / dx
    inner = 0.0 < t0 < n - 1 and abs(t0 - round(t0)) >= 1e-9  # between two points: four on a side are needed
    if inner and not _one_sided(t0, n):  # only a support inside the span lies between points (keys kind_inner_i)
        kind, _, i = r["key"].partition("_inner_")
        raise InputError(
            f"supports.inner[{i}] at {r['at']:g} (its {kind}) lies between points {int(t0)} and {int(t0) + 1} of "
            f"{n}, with fewer than four points on either side for its measure of w: use more points (or a grid with a "
            "point on it)"
        )
    if r["kind"] == "force":
        return deflection_row(t0, n)
    return rotation_row(t0, n, dx)


def inner_layer_warnings(scene: Scene, x: np.ndarray, reach: int, delta: float | None = None) -> list[str]:
    """Supports inside the span and interfaces closer to an end than ``reach`` spacings: inside the ends' boundary
    layer, whose ghost polynomial assumes one smooth solution (as :func:`pdverify.numerics.loads
    .boundary_layer_warnings` for loads); and point forces near a support that holds the rotation (``delta``: the
    horizon, :func:`~pdverify.numerics.load_warnings.held_rotation_warnings`)."""
    dx = x[1] - x[0]
    L = scene.length
    spots = [(f"supports.inner[{i}]", s.position) for i, s in enumerate(scene.supports.inner)]
    spots += [(f"segments[{i}].start", g.start) for i, g in enumerate(scene.segments) if i > 0]
    out = []
    for name, a in spots:
        d = min(a, L - a)
        if within(d, reach, dx):
            out.append(
                f"{name} at {a:g} is {spacings(d / dx)} from an end, inside the boundary layer of {reach} "
                f"spacings: expect large errors; {more_points(np.ceil((reach - TIE) * L / d) + 1)}"
            )
    # a support's measures reach 4 points either side (deflection_row, rotation_row): another kink there spoils them
    others = [(f"loads[{i}]", ld.position) for i, ld in enumerate(scene.loads) if hasattr(ld, "position")]
    others += [
        (f"loads[{i}] (span)", v)
        for i, ld in enumerate(scene.loads)
        if ld.type == "distributed"
        for v in scene.span(ld)
    ]
    others += spots
    said = set()  # two supports near each other: one line for the pair
    for (name, a), sup in zip(spots, scene.supports.inner):
        gap = [(o, b, abs(b - a)) for o, b in others if o != name and 0.0 < b < L]
        near = [(o, b) for o, b, d in gap if 0.0 < d and within(d, 4, dx) and (o, name) not in said]
        for o, b in near:
            said.add((name, o))
            out.append(
                f"{name} at {a:g} and {o} at {b:g} are {spacings(abs(b - a) / dx)} apart: the support's "
                f"one-sided rows (4 points a side) straddle it, first order there; at least "
                f"{int(np.ceil(4 * L / abs(b - a))) + 1} points set them 4 spacings apart"
            )
        joint = [o for o, b, d in gap if o.startswith("segments") and d <= 1e-9 * L]
        if joint and sup.holds_rotation:
            out.append(
                f"{name} at {a:g} is on a segment joint ({joint[0]}) and holds the rotation: its couple makes the "
                "moment jump where the joint's flexibility is calibrated for a moment that does not, so the deflection "
                f"is first order in the spacing there ({SUPPORT_ON_JOINT}); a support a few spacings off the joint "
                "converges at second order"
            )
    return out + held_rotation_warnings(scene, dx, delta=delta)


# a pinned-roller 2 m beam, h = 30 mm over [0, 0.8], 100 mm beyond, clamped at 0.8 inside the span, a couple at 1.2
# (docs/models/diyaroglu.md, "Segments")
SUPPORT_ON_JOINT = (
    "measured 0.23, 0.076, 0.021 of max |w| at 41, 161, 641 points on a beam whose EI steps 37-fold there"
)
