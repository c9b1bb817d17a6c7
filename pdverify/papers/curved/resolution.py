"""How finely pd-curved's particles resolve a curved axis: the strain its PDDO derivative gives a rigid translation
(docs/models/curved.md, "Coarse grids on a curved axis"). Arrays in, a number out.

A rigid translation c has the components c.t and c.n along the axis frame, and its strain D1(c.t) - kappa c.n is zero
(t' = kappa n: Frenet). The model takes t, n and kappa exactly from the axis but differentiates with the PDDO weights
of its families, so the translation strains by c.(D1 t - kappa n). :func:`frame_defect`, the largest of that over the
particles relative to the largest curvature, falls at the order of the derivative as the particles are refined; it is
0 on a straight axis. Past :data:`LIMITS` (the mixed form) most measured runs were more than 10 % off their exact
solution, where the model said nothing else (``PYTHONPATH=. python benchmarks/curved_resolution.py``)."""

from __future__ import annotations

import numpy as np

from . import pddo as _pddo

# frame_defect past which, in the mixed form of degree P, most of the measured runs were more than 10 % off: 87
# curved scenes (arcs of 10 to 350 degrees, quadratic, cubic and sine axes, the studies' scenes; support pairs;
# L/h = 5 to 1e4) at 11 to 321 particles (benchmarks/curved_resolution.py, docs/models/curved.md)
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


def limit(degree: int) -> float:
    """The limit of a degree: its own; past the measured ones, the highest measured degree's."""
    return LIMITS.get(degree, LIMITS[max(LIMITS)])


def resolution_warning(defect: float, degree: int) -> str:
    """The warning of a mixed-form solve whose ``defect`` (:func:`frame_defect`, the largest over its solves) passes
    the degree's :func:`limit`; "" otherwise."""
    if not defect > limit(degree):
        return ""
    measured = "" if degree in LIMITS else f" (degree {degree} not measured: degree {max(LIMITS)}'s limit)"
    return (
        f"pd-curved: the particles resolve the curved axis too coarsely for degree {degree}: its derivative of the "
        f"axis frame strains a rigid translation by {defect:.2g} of the largest curvature, past "
        f"{limit(degree):g}{measured}; of the measured runs past that limit 75 % were more than 10 % off (median "
        "45 %) and 9 % within 1 % (docs/models/curved.md); use more particles, or check the result with `pdverify "
        "solve --estimate`"
    )
