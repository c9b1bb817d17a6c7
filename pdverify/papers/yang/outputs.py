"""Engineering outputs of ``pd-higher-order`` (Yang, Oterkus & Oterkus 2020): stresses through the
section at chosen stations (Eq. 6a-c), the support reactions (K u - b at the held DOFs) and the warnings of
interior point loads. Kept apart from the model's assembly (model.py, operator.py) because they only read a
solution and the scene.

Stresses (Eq. 6a-c, plane stress, E' = E / (1 - nu^2), G = E / (2 (1 + nu)))::

    sigma_xx = E' z (theta' + 2 nu w*) + E' z^3 theta*'
    sigma_zz = E' z (nu theta' + 2 w*) + E' z^3 nu theta*'
    tau_xz   = G (theta + w') + G z^2 (3 theta* + w*')

with the point values of theta, theta*, w, w* and their x-derivatives by second-order finite differences on the
grid (numpy.gradient, one-sided second order at the ends), linearly interpolated to the station. sigma_zz of
Eq. 6b is odd in z (e_zz = 2 z w*, Eq. 4b): the theory cannot carry a top-face load's even part, so sigma_zz is
not compared with the 2D solution (docs/models/yang.md).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import PointForce, PointMoment, Scene
from ...core.text import rounded_up
from ...numerics.load_warnings import NEAR_TOLERANCE
from ...numerics.loads import end_side
from ...theory.higher_order import layer_width


def section_stresses(
    x: np.ndarray, u: np.ndarray, stations: np.ndarray, h: float, E: float, nu: float, samples: int = 33
) -> list[dict]:
    """[{"x", "z", "sigma_xx", "sigma_zz", "tau_xz"}] at each station; u (n x 4) = (theta, theta*, w, w*)."""
    th, ts, w, ws = (u[:, k] for k in range(4))
    d = {k: np.gradient(f, x, edge_order=2) for k, f in (("th", th), ("ts", ts), ("w", w), ("ws", ws))}
    Ep, G = E / (1 - nu * nu), E / (2 * (1 + nu))
    z = np.linspace(-h / 2, h / 2, samples)
    out = []
    for xs in np.asarray(stations, float):

        def at(f, xs=xs):
            return float(np.interp(xs, x, f))

        a, c = at(d["th"]) + 2 * nu * at(ws), at(d["ts"])
        sxx = Ep * z * a + Ep * z**3 * c
        szz = Ep * z * (nu * at(d["th"]) + 2 * at(ws)) + Ep * z**3 * nu * c
        txz = G * (at(th) + at(d["w"])) + G * z**2 * (3 * at(ts) + at(d["ws"]))
        out.append(
            {
                "x": float(xs),
                "z": z.tolist(),
                "sigma_xx": sxx.tolist(),
                "sigma_zz": szz.tolist(),
                "tau_xz": txz.tolist(),
            }
        )
    return out


def reactions(end_rows: list, u: np.ndarray, area: float) -> dict[str, float]:
    """Support reactions from the end points' unconstrained rows: R = K u - b on (theta, theta*, w, w*) of the
    end point (the force the support puts on the beam, per unit area, times A). force = R_w (+z), moment
    (counter-clockwise) = -R_theta (a ccw moment C works on theta as -C, Eq. 16b); zero at a free end.
    ``end_rows``: [(point, first column, rows (4 x m), load (4,))] for the left and the right end."""
    out = {}
    for (_, c0, D, F), side in zip(end_rows, ("left", "right")):
        R = (D @ u[c0 : c0 + D.shape[1]] - F) * area
        out[f"force_{side}"] = float(R[2])
        out[f"moment_{side}"] = float(-R[0])
    return out


def not_cut(scene: Scene, positions, info: dict) -> list[float]:
    """The positions (point loads, supports inside the span) that are not on a point whose bonds the solve cut
    (``info["cuts"]``, within 1e-9 of the length)."""
    cut = info.get("cuts", ())
    return [a for a in positions if not any(abs(a - c) <= 1e-9 * scene.length for c in cut)]


def point_load_warnings(scene: Scene, params: dict, info: dict) -> list[str]:
    """The warnings of interior point loads on w: one not on a cut grid point (corrected variant, ``ends =
    truncated``, ``cuts = loads``: its neighbours' bonds average the kink under it), and concentrated loads that
    deform the section (a point moment, or any point load with ``loads = faces``: w*, theta* under it). Those of the
    recovered moment and shear: :func:`recovery_warnings`."""
    out = []
    faces = info.get("loads") == "faces"
    interior = interior_point_loads(scene)
    if params["variant"] != "paper" and info["ends"] == "truncated" and params.get("cuts", "loads") == "loads":
        spots = [ld.position for ld in interior] + [s.position for s in scene.supports.inner]
        uncut = not_cut(scene, spots, info)
        if uncut:
            at = ", ".join(f"{a:.6g}" for a in uncut)
            out.append(
                f"point load or support at x = {at} not on a cut grid point (between two points, or within 4J + 1 "
                "spacings of an end or another point load or support): split between its neighbours, whose bonds "
                "average the kink under it, so w converges at first order near it (docs/models/yang.md); put it on "
                "a grid point (points = L / spacing + 1)"
            )
    if params["variant"] == "paper":  # a couple on an end point that turns: not through the mirror layer's faces
        on = {end_side(scene, ld.position) for ld in scene.loads if isinstance(ld, PointMoment) and ld.value}
        ends = [s for s in ("left", "right") if s in on and scene.supports.kind(s) not in ("clamped", "guided")]
        if ends:
            out.append(
                f"variant = paper: a couple on the {' and '.join(ends)} end point does not converge (a couple on the "
                "pinned end of a clamped-pinned beam, L/h = 20: w 63 % and 51 % of max |w| off exact-higher-order at "
                "81 and 321 points); use variant corrected"
            )
    local = [ld.position for ld in interior if isinstance(ld, PointMoment) or faces]
    if local:
        at = ", ".join(f"{a:.6g}" for a in local)
        out.append(
            f"concentrated load at x = {at}: the higher-order theory deforms the section under it (w*, theta*; "
            "docs/models/yang.md), so within a few depths of the load w is not beam theory's and does not "
            "converge to it (clamped-clamped, L/h = 7.4, load at 7/8 L: 7 % of the largest deflection)"
        )
    return out


def interior_point_loads(scene: Scene) -> list:
    """The point forces and moments strictly inside the beam."""
    return [
        ld
        for ld in scene.loads
        if isinstance(ld, (PointForce, PointMoment)) and ld.value != 0.0 and 0.0 < ld.position < scene.length
    ]


def recovery_warnings(scene: Scene, interior: list, supports: list) -> list[str]:
    """Where the recovered moment and shear (:func:`.supports.section_forces`) do not converge at second order:
    within a few depths of a point load (``interior``) or a support inside the span (``supports``: positions) whose
    layers statics did not replace (the section's layers of w*, theta*, about 0.1 h wide: the moment resolved only
    once the spacing is below that, the shear at the 3 points either side not even then), and
    the shear next to where a distributed load starts or ends inside the beam (the bonds average the load's jump:
    first order there)."""
    out = []
    spots = [ld.position for ld in interior] + list(supports)
    if spots:
        at = ", ".join(f"{a:.6g}" for a in spots)
        out.append(
            f"moment and shear within 3 depths of x = {at} (point loads, supports inside the span) carry the "
            "section's layers (w*, theta*, ~0.1 h wide): the moment converges at no measured order until the spacing "
            "is below 0.1 h (L/h = 100: 0.1 % to 0.7 % of the largest moment between 641 and 1281 points); the shear "
            "at the 3 points either side does not converge at all (one spacing from a support inside the span, at "
            "spacings h/32 and h/128: 0.065 to 0.49 of the largest shear); w and the rotation converge at second "
            "order (docs/models/yang.md)"
        )
    edges = [v for ld in scene.loads if ld.type == "distributed" and ld.value != 0.0 for v in scene.span(ld)]
    edges = sorted({v for v in edges if 0.0 < v < scene.length})
    if edges:
        at = ", ".join(f"{a:.6g}" for a in edges)
        out.append(
            f"shear next to x = {at}, where a distributed load starts or ends, converges at first order (measured "
            "1.0 to 1.15, L/h = 100, 161 -> 641 points): the bonds average the load's jump; the moment there is "
            "second order (docs/models/yang.md)"
        )
    return out


SHEAR_STIFF = 1.0  # G / E past which the discretisation error grows (measured: docs/models/yang.md, Known limits)


def shear_stiff_warning(scene: Scene) -> list[str]:
    """A material whose shear modulus passes :data:`SHEAR_STIFF` times its Young's modulus (an auxetic one: nu below
    -0.5): the discretisation error grows with G / E, and the higher-order theory leaves plane-stress elasticity."""
    ratio = max(mat.G / mat.E for _, _, _, mat in scene.pieces())
    if not ratio > SHEAR_STIFF:
        return []
    return [
        f"G / E = {ratio:.3g} (poissons_ratio {min(m.poissons_ratio for *_, m in scene.pieces()):g}): the "
        "discretisation error grows with G / E past 1 (clamped-pinned, L/h = 20, a force and a couple, 641 points: "
        "3.9e-5 at G / E <= 1, 2.7e-4 at 1.5, 2.4e-3 at 5, 2.0e-2 at 50, falling at about second order) and the "
        "theory leaves plane-stress elasticity (fem-plane-stress 2.5 % off exact-higher-order at nu = -0.99); check "
        "with `pdverify solve --estimate` (docs/models/yang.md)"
    ]


SPURIOUS_LIMIT = 0.01  # the stiffening of shear = point above which a result says so


def spurious_shear_warning(scene: Scene, delta: float) -> list[str]:
    """``shear = point`` (Eq. 14d-f: theta_k alone in g and e): a pure bending field leaves a spurious shear energy
    that stiffens the beam by about (G / E) 1.5 (delta / h)^2 (module docstring of model.py); past
    :data:`SPURIOUS_LIMIT` the result says so with its size."""
    mat, h = scene.material, scene.section.depth
    size = mat.G / mat.E * 1.5 * (delta / h) ** 2
    if not size > SPURIOUS_LIMIT:
        return []
    return [
        f"shear = point (Eq. 14d-f, variant paper's): a spurious shear energy stiffens the beam by about (G/E) 1.5 "
        f"(delta/h)^2 = {size:.2g} here (delta = {delta / h:.3g} h); w 19 %, 5.4 %, 1.3 % off at 101, 201, 401 points "
        "on a pinned-pinned beam under a uniform load, L/h = 20; more points, or shear = path (variant corrected), "
        "which has none"
    ]


LAYER_RESOLVED, LAYER_UNSEEN = 1 / 8, 20  # spacings, in layer widths, between which a clamp's layer is in transition


def clamp_layer_warning(scene: Scene, dx: float) -> list[str]:
    """A clamped end on a grid in its layer's transition (:func:`~pdverify.theory.higher_order.layer_width` of
    Eq. 9): w* turns within that layer; on spacings from :data:`LAYER_UNSEEN` widths (the layer too thin to matter)
    down to :data:`LAYER_RESOLVED` of a width the errors change irregularly instead of falling at second order
    (docs/models/yang.md, "Clamped ends": cantilevers at L/h = 5 to 10^4)."""
    clamped = [side for side in ("left", "right") if getattr(scene.supports, side) == "clamped"]
    if not clamped:
        return []
    mat = scene.material
    width = layer_width(mat.poissons_ratio, mat.G * (1 - mat.poissons_ratio**2) / mat.E, scene.section.depth)
    if not LAYER_RESOLVED * width < dx < LAYER_UNSEEN * width:
        return []
    points = int(np.ceil(scene.length / (LAYER_RESOLVED * width))) + 1
    return [
        f"clamped {' and '.join(clamped)} end: the spacing is {dx / width:.3g} widths of the clamp's layer of w* "
        f"({width:.3g}, Eq. 9), in its transition: the error may change irregularly instead of falling at second "
        f"order until the spacing is an eighth of a width (at least {points} points)"
    ]


SECTION_LAYER = 2.0  # theta*, w*: error up to about this times (dx / width)^2 of their largest values (below)


def off_grid(scene: Scene, dx: float) -> list[str]:
    """The point loads and supports inside the span that lie between two points of the uniform grid of spacing
    ``dx`` (by more than 1e-9 of a spacing), named as the scene's keys."""
    at = [(f"loads[{i}]", ld.position) for i, ld in enumerate(scene.loads) if isinstance(ld, (PointForce, PointMoment))]
    at += [(f"supports.inner[{i}]", sp.position) for i, sp in enumerate(scene.supports.inner)]
    return [name for name, x in at if abs(x / dx - round(x / dx)) > 1e-9]


def section_fields_warning(scene: Scene, dx: float) -> list[str]:
    """theta* and w* (the section's fields, Eq. 2-3) turn within the section's boundary layers (of
    :func:`~pdverify.theory.higher_order.layer_width`, Eq. 9) beside every support that holds w, every point load
    and the ends, which w, the rotation, M and V barely see: there they are off by about c (dx / width)^2 of their
    largest values once the spacing is below a width (measured against exact-higher-order, L/h = 5 to 1000, 101 to
    3,201 points, loads and supports on grid points: c up to 0.16 beside pinned ends, 0.53 beside pins inside the span,
    1.0 beside a point force, 1.2 beside springs), by their own size or more above, and by far more beside a point load
    or support between two grid points (w* 0.087 off at 1,601 points beside such a pin, where (dx / width)^2 gave
    0.0024; theta* 1.2e4 times its largest value beside such a couple at 51 points; docs/models/yang.md). One line
    where :data:`SECTION_LAYER` (dx / width)^2 passes 1e-3, or where such a load or support lies between two points."""
    mat = scene.material
    width = layer_width(mat.poissons_ratio, mat.G * (1 - mat.poissons_ratio**2) / mat.E, scene.section.depth)
    q = dx / width
    estimate, between = SECTION_LAYER * q * q, off_grid(scene, dx)
    if not (estimate > NEAR_TOLERANCE or between):
        return []
    points = int(np.ceil(scene.length / (width * np.sqrt(NEAR_TOLERANCE / SECTION_LAYER)))) + 1
    size = (
        f"off there by up to about {rounded_up(estimate)} of their largest values ({SECTION_LAYER:g} (spacing / "
        "width)²)"
        if q < 1.0
        else "off there by their own size or more (the spacing passes a width)"
    )
    beside = (
        f", and by far more beside {', '.join(between)}, between two grid points (up to many times their size: "
        "put it on a point)"
        if between
        else ""
    )
    return [
        f"theta_star and w_star (the section's fields θ*, w*) turn within the section's boundary layers (width "
        f"{width:.3g}, Eq. 9) beside the supports, point loads and ends, which w, the rotation, M and V barely see: "
        f"at a spacing of {q:.3g} widths they are {size}{beside} (docs/models/yang.md); use at least {points} points "
        "for 1e-3 in them"
    ]
