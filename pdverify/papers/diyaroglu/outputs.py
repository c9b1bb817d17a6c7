"""Engineering outputs of ``pd-eb`` (Diyaroglu et al. 2019) from a solution: the moment, the shear force, the
rotation and the support reactions, and the mirror image of a result. Arrays in, arrays out.

* moment M (sagging): the PD moment state of Eq. 10a, M = dW/dkappa A = EI kappa (a = EI/A, Eq. 33): the mixed
  form's own unknown, or EI times the PD curvature (Eq. 11a) of the solved w on the grid extended by its ghosts
  (corrected: Taylor ghosts; paper: the mirror images and the Appendix's free-end rows);
* shear V = dM/dx and rotation w' by second-order differences that never straddle a jump
  (:func:`pdverify.numerics.recovery.derivative`: V jumps at point forces and inner supports, w'' at couples,
  clamped inner supports and interfaces); between point loads a few spacings apart, where no such stretch fits, by
  statics from the points beside them (M, V) and the integral of M / EI (the rotation);
* reactions: the mixed form's multipliers (springs, inner supports), the moment at ends that hold the rotation and
  the shear at ends that hold the deflection, two of them closed by statics
  (:func:`pdverify.numerics.statics.closed_reactions`).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import HELD, PointForce, PointMoment, Scene, Spring
from ...core.text import listed
from ...numerics.loads import end_side, support_couples, support_side
from ...numerics.recovery import derivative, jump_positions, kink_positions
from ...numerics.statics import closed_reactions, rotation_over, statics_over
from .mixed import point_load_terms
from .operator import ghost_map, mirror_map, paper_curvature


def direct_moment(scene: Scene, w: np.ndarray, dx: float, c: np.ndarray, variant: str, reading: str) -> np.ndarray:
    """M = EI kappa at the points, kappa the PD curvature of the direct form's w on its extended grid."""
    n, J = len(w), len(c)
    if variant == "paper":
        left, right = scene.supports.left, scene.supports.right
        layer = {
            side: reading == "layer" and sup in ("pinned", "roller") and J > 2 for side, sup in ((0, left), (1, right))
        }
        D = paper_curvature(n, J, c, dx, left, right, layer)
        M = scene.EI * (D @ (mirror_map(n, J, left, right, layer) @ w))
        return held_rotation_ends(M, left, right)
    G = 2 * J
    g_rows, g_cols, g_vals, e0, skip = ghost_map(scene, n, dx, G)
    ext = e0.copy()
    ext[G : G + n] += w
    np.add.at(ext, g_rows, g_vals * w[g_cols])
    st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])
    kappa = np.convolve(ext, st[::-1], mode="valid")[G - J : G - J + n]
    _, curv = point_load_terms(scene, n, dx, st, skip)  # the couples' own part of the PD curvature
    return scene.EI * (kappa + curv[J : J + n])


def held_rotation_ends(M: np.ndarray, left: str, right: str) -> np.ndarray:
    """The paper variant's moment at a clamped or guided end point extrapolated from the three points beside it (second
    order): its PD curvature there, of the Appendix's mirror images, is about half the beam's (47 % to 49 % of max |M|
    off on clamped beams under a uniform load at 41 to 641 points, the moment reactions as far), where the points
    beside it carry the variant's bias only (1-3 %)."""
    M = np.array(M, float)
    if len(M) >= 4:
        if left in ("clamped", "guided"):
            M[0] = 3 * M[1] - 3 * M[2] + M[3]
        if right in ("clamped", "guided"):
            M[-1] = 3 * M[-2] - 3 * M[-3] + M[-4]
    return M


def fields(scene: Scene, x: np.ndarray, w: np.ndarray, M: np.ndarray, ends_inside: bool = True) -> dict:
    """rotation, moment and shear at the points (module docstring); the end points on their support's side of the
    loads on them (:func:`~pdverify.numerics.loads.support_side`), where the reactions read them. ``ends_inside``: M at
    the end points is the beam's side (the mixed form's unknowns and the corrected curvature, whose Taylor ghosts
    carry the end loads); the paper variant's mirror images leave the end points' curvature as it is (a couple on a
    pinned end point: 0, its support's side)."""
    rot = derivative(x, w, jump_positions(scene, "moment"))
    V = derivative(x, M, np.r_[jump_positions(scene, "shear"), jump_positions(scene, "moment")], kink_positions(scene))
    M, V, rot = close_loads_by_statics(scene, x, M, V, rot)
    if ends_inside:
        M = support_side(scene, M, "moment")
    return {"rotation": rot, "M": M, "V": support_side(scene, V, "shear")}


CLOSE_LOADS = 3  # spacings: point loads this close leave M's differences no stretch of three points between them


def close_loads_by_statics(scene: Scene, x: np.ndarray, M: np.ndarray, V: np.ndarray, rotation: np.ndarray) -> tuple:
    """(M, V, rotation) with the points from one before to one after each cluster of point loads (forces, couples) and
    ends of distributed loads at most :data:`CLOSE_LOADS` spacings apart (a short patch: V 0.49 of max |V| off at its
    ends when it spans one spacing) taken by statics between the points beside it, whose M and rotation hold
    (:func:`~pdverify.numerics.statics.statics_over`, a point on a load the mean of its two sides; the rotation by the
    integral of M / EI, :func:`~pdverify.numerics.statics.rotation_over`): the differences of M and w have no stretch
    of three points between such loads (V 35-58 % of max |V| off at and between two loads 1 and 2 spacings apart, the
    rotation 1.9 % of max |rotation| between two couples 1 spacing apart, 201 points, clamped-clamped). A cluster
    with a support inside the span keeps its values."""
    dx = x[1] - x[0]
    at = [ld.position for ld in scene.loads if isinstance(ld, (PointForce, PointMoment)) and ld.value]
    at = sorted([a for a in at if 0.0 < a < scene.length] + list(kink_positions(scene)))  # distributed loads' ends
    spans = [
        (np.floor((a - x[0]) / dx + 1e-9) - 1, np.ceil((b - x[0]) / dx - 1e-9) + 2)
        for a, b in zip(at, at[1:])
        if b - a <= CLOSE_LOADS * dx * (1 + 1e-9)
    ]
    if not spans:
        return M, V, rotation
    M, V, kept = statics_over(scene, x, M, V, spans, [s.position for s in scene.supports.inner])
    return M, V, rotation_over(scene, x, M, rotation, spans, kept)


def reactions(scene: Scene, x: np.ndarray, M: np.ndarray, V: np.ndarray, multipliers: dict) -> dict:
    """Every support's reaction (force +z, moment counter-clockwise on the beam): the multipliers, M at ends that
    hold the rotation (moment_left = -M(0), moment_right = M(L)), V at ends that hold the deflection
    (force_left = V(0), force_right = -V(L)), closed by statics."""
    own = dict(multipliers)
    for side, i, sgn in (("left", 0, 1.0), ("right", -1, -1.0)):
        sup = getattr(scene.supports, side)
        if isinstance(sup, Spring):
            continue
        if HELD[sup][1]:
            own[f"force_{side}"] = sgn * float(V[i])
        if HELD[sup][2]:
            own[f"moment_{side}"] = -sgn * float(M[i])
    return closed_reactions(scene, own)


def mirror_reactions(r: dict) -> dict:
    """The reactions of the mirror image x -> L - x: ends swapped, moments reversed (inner supports keep their
    index)."""
    out = {}
    for k, v in r.items():
        if not isinstance(v, float):
            out[k] = v
            continue
        side = {"left": "right", "right": "left"}
        parts = k.split("_")
        if parts[1] in side:
            parts[1] = side[parts[1]]
        out["_".join(parts)] = -v if parts[0] == "moment" else v
    return out


def recovery_warnings(scene: Scene, params: dict) -> list[str]:
    """The paper variant's moment and shear near point loads that bend the beam (inside the span, or on an end point
    that does not take them: a couple on a pinned or free end, a force on a free or guided end): Eq. 25 puts a load on
    one or two points, so
    the PD curvature smears the moment's kink over the horizon and the shear beside the load does not converge (the
    corrected variant spreads every load by its kink: second order everywhere, docs/models/diyaroglu.md)."""
    if params["variant"] != "paper":
        return []

    def bends(ld) -> bool:  # a force on an end that holds the deflection goes into the support (a couple on a
        # clamped or guided end point too: support_couples takes it off before the solve)
        side = end_side(scene, ld.position)
        return side is None or ld.type == "point_moment" or not scene.supports.holds_deflection_at(side)

    loads = support_couples(scene)[1].loads
    at = [ld.position for ld in loads if ld.type in ("point_force", "point_moment") and ld.value != 0.0 and bends(ld)]
    if not at:
        return []
    return [
        f"variant = paper: the moment and shear near the point loads at x = {listed(at)} are the "
        "PD curvature of Eq. 25's split load, smeared over the horizon: beside the simply supported benchmark's "
        "centre force the shear is 3.8 % of its largest value off at 101, 401 and 1601 points (no convergence), "
        "the moment 2.1 %, 0.90 %, 0.60 %; beside a load on an end point the shear grows like 1 / dx (a couple on a "
        "pinned end: 22, 87 and 349 times max |V| at 41, 161 and 641 points) and the moment stays 30 % off; use "
        "variant = corrected"
    ]
