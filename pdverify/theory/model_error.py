"""How many times the first sine mode's model error g (pi delta / L)^2 each PD variant's continuum is off the local
beam theory on a support pair, over sine, uniform, partial and point loads: measured, for the model-error warning of
every result (:func:`pdverify.theory.continuum.model_error_warning`, docs/nonlocal.md).

``PYTHONPATH=. python benchmarks/model_error_factors.py --deltas 0.05 0.1`` (the continuum extrapolated from m = 32 to
128; and with ``--m 8 --continuum-m 32``, the larger of the two taken: pd-timoshenko ``corrected`` is singular to
working precision at m = 128 and ``energy`` refuses m past 12, so theirs are m = 8 to 32): a 1 m steel beam on every
support pair of clamped, pinned, guided and free ends that holds it (both orientations), under a sine load, a uniform
load, a uniform load on either half or on [0.25, 0.5] L, a point force at 0.5 or 0.75 L and a couple at 0.75 L, each
variant's continuum at delta = 0.05 and 0.1 L (:data:`FACTORS`) and at 0.2 L (:data:`FACTORS_02`, with ``--deltas 0.2``)
against exact-eb (exact-timoshenko for pd-timoshenko): the largest ratio per unordered pair, rounded up. Pairs where a
variant has no limit at fixed delta are left out (its warning says so instead), but for pd-timoshenko ``energy``, whose
every pair is one (its grid at m = 12 stands for it). Past 0.1 L the next terms of the expansion add more: a horizon up
to 0.2 L takes the larger of the two tables' factors, and one past 0.2 L the same and says that it was not measured
there (docs/nonlocal.md).
"""

from __future__ import annotations

from ..core.scene import Scene

FACTORS = {  # variant -> {unordered support pair: factor}
    "pd-eb corrected": {
        "clamped-clamped": 1.3, "clamped-free": 1.4, "clamped-guided": 1.0, "clamped-pinned": 1.1,
        "guided-pinned": 1.0, "pinned-pinned": 1.1,
    },
    "pd-eb paper": {  # its clamped ends' mirror images (the Appendix) add a model error of the same order
        "clamped-clamped": 7.8, "clamped-free": 1.0, "clamped-guided": 2.2, "clamped-pinned": 5.9,
        "guided-pinned": 1.0, "pinned-pinned": 2.5,
    },
    "pd-timoshenko corrected": {
        "clamped-clamped": 4.1, "clamped-free": 2.7, "clamped-guided": 2.0, "clamped-pinned": 2.7,
        "guided-pinned": 1.0, "pinned-pinned": 1.6,
    },
    "pd-timoshenko energy": {
        "clamped-clamped": 2.4, "clamped-free": 1.0, "clamped-guided": 1.0, "clamped-pinned": 1.8,
        "guided-pinned": 1.0, "pinned-pinned": 1.0,
    },
    "pd-bond-pair taylor": {"clamped-clamped": 1.9, "clamped-pinned": 1.6, "pinned-pinned": 1.2},
    "pd-bond-pair mirror": {"pinned-pinned": 1.2},
}  # fmt: skip
FACTORS_02 = {  # the same at delta = 0.2 L (pd-timoshenko energy refuses a horizon past L / 6)
    "pd-eb corrected": {
        "clamped-clamped": 7.9, "clamped-free": 2.7, "clamped-guided": 2.9, "clamped-pinned": 5.3,
        "guided-pinned": 3.3, "pinned-pinned": 2.5,
    },
    "pd-eb paper": {
        "clamped-clamped": 8.5, "clamped-free": 1.1, "clamped-guided": 2.4, "clamped-pinned": 6.4,
        "guided-pinned": 1.0, "pinned-pinned": 2.5,
    },
    "pd-timoshenko corrected": {
        "clamped-clamped": 3.2, "clamped-free": 2.2, "clamped-guided": 1.8, "clamped-pinned": 2.2,
        "guided-pinned": 1.0, "pinned-pinned": 1.2,
    },
    "pd-bond-pair taylor": {"clamped-clamped": 2.1, "clamped-pinned": 1.7, "pinned-pinned": 1.2},
    "pd-bond-pair mirror": {"pinned-pinned": 1.2},
}  # fmt: skip
MEASURED_UP_TO = (0.1, 0.2)  # delta / L of FACTORS and FACTORS_02
WHY = "the measured effect of its ends and of partial or point loads on this support pair (docs/nonlocal.md)"


def pair_factor(scene: Scene, variant: str, delta: float) -> tuple[float, str]:
    """(factor, why) of ``variant``'s table for the scene's pair of ends (a roller counts as pinned) at the horizon
    ``delta`` (a length): :data:`FACTORS` up to 0.1 L, the larger of both tables' beyond; the table's largest where
    the scene has supports inside the span, a spring or a pair the table does not hold; (1, "") where the factor is 1
    or there is no table."""
    tables = [FACTORS.get(variant) or {}]
    if delta > MEASURED_UP_TO[0] * scene.length * (1 + 1e-9):  # 0.1 L to rounding is 0.1 L (a scaled copy's too)
        tables.append(FACTORS_02.get(variant) or {})
    if not any(tables):
        return 1.0, ""
    key = "-".join(sorted({"roller": "pinned"}.get(k, k) for k in map(scene.supports.kind, ("left", "right"))))
    factor = max((max(t.values()) if scene.supports.inner or key not in t else t[key]) for t in tables if t)
    if factor <= 1.0:
        return 1.0, ""
    beyond = (
        f" (measured up to delta = {MEASURED_UP_TO[-1]:g} L; more beyond)"
        if delta > MEASURED_UP_TO[-1] * scene.length * (1 + 1e-9)
        else ""
    )
    return factor, WHY + beyond
