"""How finely pd-curved's particles resolve a curved axis: the strain its PDDO derivative gives a rigid translation
(docs/models/curved.md, "Coarse grids on a curved axis"). Arrays in, a number out.

A rigid translation c has the components c.t and c.n along the axis frame, and its strain D1(c.t) - kappa c.n is zero
(t' = kappa n: Frenet). The model takes t, n and kappa exactly from the axis but differentiates with the PDDO weights
of its families, so the translation strains by c.(D1 t - kappa n). :func:`frame_defect`, the largest of that over the
particles relative to the largest curvature, falls at the order of the derivative as the particles are refined; it is
0 on a straight axis. Where the supports leave the beam near a mechanism its response is mostly a rigid motion and
the defect counts that much more (:func:`amplification`). Past :data:`LIMITS` (the mixed form) most measured runs
were more than 10 % off their exact solution, where the model said nothing else (``PYTHONPATH=. python
benchmarks/curved_resolution.py``)."""

from __future__ import annotations

import numpy as np

from . import pddo as _pddo

# frame_defect past which, in the mixed form of degree P, most of the measured runs were more than 10 % off: 87
# curved scenes (arcs of 10 to 350 degrees, quadratic, cubic and sine axes, the studies' scenes; support pairs;
# L/h = 5 to 1e4) at 11 to 321 particles (benchmarks/curved_resolution.py, docs/models/curved.md); with the
# amplification of near mechanisms, 91 scenes (rings of 359 and 359.9 degrees pinned at both ends added)
LIMITS = {2: 0.02, 3: 0.0015, 4: 0.015, 5: 3e-4, 6: 1.1e-4}
STRAIGHT = 1e-12  # max |kappa| L below this: a straight axis (no frame to resolve)


def frame_defect(segs: list[np.ndarray], frames: list[tuple[np.ndarray, np.ndarray, np.ndarray]], degree: int,
                 size: int, length: float) -> float:  # fmt: skip
    """max |D1 t - kappa n| / max |kappa| over the segments' particles ``segs`` (arc lengths), ``frames`` their
    (t, n, kappa) (:func:`.particles.axis_frame`), D1 the PDDO first derivative of degree ``degree`` over families of
    ``size`` (:func:`.pddo.derivative_weights`); 0 on a straight axis."""
    top = max(float(np.abs(k).max()) for _, _, k in frames)
    if top * length <= STRAIGHT:
        return 0.0
    worst = 0.0
    for g, (t, n, kappa) in zip(segs, frames):
        fam, w = _pddo.derivative_weights(g, degree, size, orders=(1,))
        D1 = _pddo.operator(fam, w[1])
        worst = max(worst, float(np.abs(D1 @ t - kappa[:, None] * n).max()))
    return worst / top


def amplification(displacement: float, scene) -> float:
    """How near the supports leave the beam to a mechanism: its largest ``displacement`` relative to a cantilever's
    of the same length and the smallest EI under loads of the same sizes (a force F: F L^3 / 3 EI, a couple M:
    M L^2 / 2 EI, a line load of resultant Q at most: Q L^3 / 8 EI, summed). About 1 or below on a beam held as a
    cantilever or more firmly; large where the supports nearly let it move rigidly (a ring pinned at two points a
    degree apart: 260), where the response is mostly a rigid motion and the strain the defect gives a rigid motion
    counts that much more. 1 without loads (a manufactured body load)."""
    L = scene.length
    EI = min(mat.E * sec.I for _, _, sec, mat in scene.pieces())
    size = 0.0
    for load in scene.loads:
        if load.type == "point_force":
            size += np.hypot(load.value, load.axial) * L**3 / 3
        elif load.type == "point_moment":
            size += abs(load.value) * L**2 / 2
        elif load.type == "distributed":
            a, b = scene.span(load)
            size += np.hypot(load.value, load.axial) * (b - a) * L**3 / 8
    return float(displacement * EI / size) if size > 0 else 1.0


NEAR = 100.0  # amplification past which every result is warned (benchmarks/curved_resolution.py's rings: of 63 runs
# past it, 33 more than 10 % off, 20 within 1 %)


def pinned_segments(segs: list[np.ndarray], points: int, size: int, length: float) -> list[tuple[float, float, int]]:
    """(start, end, points needed) of the segments between breaks that hold one family of ``size`` particles, the
    least a segment takes (:func:`.particles.segment_grids`): their families are all one-sided, and below the points
    needed (where a uniform share of the grid first gives a segment more) their spacing does not fall with the
    grid's, nor does their error."""
    out = []
    for g in segs:
        a, b = float(g[0]), float(g[-1])
        if len(g) <= size:
            need = int(np.ceil((size - 0.5 - 1e-9) * length / (b - a))) + 1
            while int(np.floor((need - 1) * (b - a) / length + 0.5 + 1e-9)) < size:  # segment_grids' own rounding
                need += 1
            out.append((a, b, need))
    return out


def pinned_note(pinned: list[tuple[float, float, int]], size: int) -> str:
    """What ``info["irregular"]`` says of the pinned segment that needs the most points ("" without one): a
    self-convergence estimate (``solve --estimate``, ``advise``) then does not call its grids asymptotic."""
    if not pinned:
        return ""
    a, b, need = max(pinned, key=lambda p: p[2])
    return (
        f"pd-curved: the segment [{a:.4g}, {b:.4g}] between breaks (supports, point loads, load ends) holds one "
        f"family ({size} particles) at every grid below {need} points, so its spacing and error do not fall with the "
        "grid's"
    )


def near_mechanism_warning(amplified: float, pinned: list[tuple[float, float, int]]) -> str:
    """The warning of a solve whose supports leave the beam near a mechanism: its :func:`amplification` past
    :data:`NEAR`, or past 1 with a pinned segment (:func:`pinned_segments`); "" otherwise."""
    if not (amplified >= NEAR or (pinned and amplified > 1.0)):
        return ""
    head = (
        f"pd-curved: the supports leave the beam near a mechanism (its displacement {amplified:.3g} times a "
        "cantilever's under these loads, mostly a rigid motion), so every discretisation error counts about that "
        "many times more"
    )
    if pinned:
        a, b, need = max(pinned, key=lambda p: p[2])
        head += (
            f", and the segment [{a:.4g}, {b:.4g}] holds one family at every grid below {need} points, where its "
            "error does not fall with the grid's (a 359.9-degree ring pinned at both ends, a force at 0.01 L: 6 % off "
            f"at 161 to 641 particles); use points >= {need} and check"
        )
    else:
        head += (
            " (rings of 359 and 359.9 degrees pinned at both ends, 41 to 321 particles: of 63 runs past 100 times, "
            "33 more than 10 % off, 20 within 1 %); check"
        )
    return head + " the result with `pdverify solve --estimate` (docs/models/curved.md)"


def limit(degree: int) -> float:
    """The limit of a degree: its own; past the measured ones, the highest measured degree's."""
    return LIMITS.get(degree, LIMITS[max(LIMITS)])


def resolution_warning(defect: float, degree: int, amplified: float = 1.0) -> str:
    """The warning of a mixed-form solve whose ``defect`` (:func:`frame_defect`, the largest over its solves), times
    its :func:`amplification` ``amplified`` where that passes 1, passes the degree's :func:`limit`; "" otherwise."""
    amplified = max(1.0, amplified)
    if not defect * amplified > limit(degree):
        return ""
    measured = "" if degree in LIMITS else f" (degree {degree} not measured: degree {max(LIMITS)}'s limit)"
    near = (
        ""
        if amplified == 1.0
        else f", times {amplified:.2g} where the supports leave the beam near a mechanism (its displacement that many "
        f"times a cantilever's under these loads, mostly a rigid motion): {defect * amplified:.2g}"
    )
    return (
        f"pd-curved: the particles resolve the curved axis too coarsely for degree {degree}: its derivative of the "
        f"axis frame strains a rigid translation by {defect:.2g} of the largest curvature{near}, past "
        f"{limit(degree):g}{measured}; of the measured runs past that limit 76 % were more than 10 % off (median "
        "59 %) and 8 % within 1 % (docs/models/curved.md); use more particles, or check the result with `pdverify "
        "solve --estimate`"
    )
