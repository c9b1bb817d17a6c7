"""Figures of a load path on its paper's page: node health along the beam (O'Grady & Foster 2014, §3.2, Fig. 9): the
fraction of each point's bond pairs that never passed their critical angle (pd-bond-pair), the fraction of the
section's area that never yielded (exact-eb, fem-eb); the load factor against the deflection at the path's peak
point (:mod:`pdverify.measure.paths`), loading and unloading; and the section's moment-curvature law (Eq. 7's pairs)
over the fibre theory's. Curves in, inline SVG out (:mod:`.figures`)."""

from __future__ import annotations

import numpy as np

from . import figures


def health_figures(curves: list[tuple[str, np.ndarray, np.ndarray]], title: str, unit: str) -> list[str]:
    """One figure of every run's ``health`` field along the axis at the path's last step; none without one."""
    if not curves:
        return []
    return [
        figures.deflection(curves, None, f"{title}: node health", "health", unit, yunit="fraction", ylim=(-0.05, 1.05))
    ]


def load_path_figures(paths: list[tuple[str, dict]], title: str, unit: str) -> list[str]:
    """One figure of every run's load factor against its peak deflection (``load_path`` of its case: factor, w,
    x), or of the force a prescribed deflection takes where every path gives it; none without a path."""
    if not paths:
        return []
    if all("force" in p for _, p in paths):  # deflection control: the force that holds the prescribed deflection
        curves = [(label, np.asarray(p["force"]), np.asarray(p["w"]), float(p["x"])) for label, p in paths]
        return [figures.load_deflection(curves, f"{title}: load path", unit, "force at the prescribed deflection (N)")]
    curves = [(label, np.asarray(p["factor"]), np.asarray(p["w"]), float(p["x"])) for label, p in paths]
    return [figures.load_deflection(curves, f"{title}: load path", unit)]


def moment_curvature_figures(laws: list[tuple[str, dict]], scene, title: str, units: str, unit: str) -> list[str]:
    """One figure of every run's section law (``moment_curvature`` of its case: kappa, moment) over the fibre
    theory's for the scene's section and yield stress (exact-eb's and fem-eb's, :meth:`Profile.fibre_moment`); none
    without a law."""
    if not laws:
        return []
    curves = [(label, np.asarray(law["kappa"]), np.asarray(law["moment"])) for label, law in laws]
    ref = None
    profile = scene.section.profile if scene is not None else None
    if profile is not None and scene.material.yield_stress:
        kappa = max((c[1] for c in curves), key=lambda k: k.max())
        ref = (kappa, profile.fibre_moment(kappa, scene.material.E, scene.material.yield_stress))
    return [figures.moment_curvature(curves, ref, f"{title}: moment-curvature of the section", units, unit)]
