"""Figures of a load path on its paper's page: node health along the beam (O'Grady & Foster 2014, §3.2, Fig. 9): the
fraction of each point's bond pairs that never passed their critical angle (pd-bond-pair), the fraction of the
section's area that never yielded (exact-eb, fem-eb); and the load factor against the deflection at the path's peak
point (:mod:`pdverify.measure.paths`), loading and unloading. Curves in, inline SVG out (:mod:`.figures`)."""

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
    x); none without a path."""
    if not paths:
        return []
    curves = [(label, np.asarray(p["factor"]), np.asarray(p["w"]), float(p["x"])) for label, p in paths]
    return [figures.load_deflection(curves, f"{title}: load path", unit)]
