"""Figures of one scene on its paper's page beyond its deflection curves: curved beams' resultants (N, Q) and the
overlay of several transient runs. Each takes what the report builder read (curves, case rows) and returns inline
SVG strings (:mod:`.figures`)."""

from __future__ import annotations

import numpy as np

from . import figures

RESULTANTS = (("N", "axial force N"), ("Q", "shear force Q"))  # curved-beam fields drawn beside the deflection


def resultant_figures(curves: list[tuple[str, dict]], title: str, unit: str, force: str) -> list[str]:
    """Axial force N and shear force Q along the axis, one figure each, of the curves that return them
    (pd-curved and the exact curved beams: ``fields`` N and Q). The vertical range is the exact curves' (labels
    starting with ``exact-``) widened by half its span, so that a locked run's resultants (the primal form's N
    can be off by 50x) leave the axes instead of hiding the others; without an exact curve every curve sets it."""
    figs = []
    for key, name in RESULTANTS:
        got = [(label, c["x"], c["fields"][key]) for label, c in curves if key in c.get("fields", {})]
        if not got:
            continue
        exact = [y for label, _, y in got if label.startswith("exact-")]
        ylim = None
        if exact:
            lo, hi = min(float(np.min(y)) for y in exact), max(float(np.max(y)) for y in exact)
            pad = 0.5 * (hi - lo) or 0.5 * max(abs(lo), abs(hi), 1e-300)
            ylim = (lo - pad, hi + pad)
        figs.append(figures.deflection(got, None, f"{title}: {name}", key, unit, yunit=force, ylim=ylim))
    return figs


EARLY = 0.15  # the "early time" figure shows this fraction of the run (Moyer & Miraglia Figs 3 and 10)


def overlay_figures(runs: list[tuple[str, np.ndarray, dict, str]], title: str) -> list[str]:
    """Two or more runs with time histories on a scene: their first probe's response on one axis over the whole
    run and over its first :data:`EARLY` (where dispersion and grid effects show; the paper's Figs 3, 9, 10)."""
    if len(runs) < 2:
        return []
    probe = next(iter(runs[0][2]), None)
    curves = [(label, t, series[probe]) for label, t, series, _ in runs if probe in series]
    if len(curves) < 2:
        return []
    end = max(float(np.asarray(t)[-1]) for _, t, _ in curves)
    ylabel = runs[0][3]
    return [
        figures.histories_overlay(curves, f"{title}: {probe}, every run", ylabel),
        figures.histories_overlay(curves, f"{title}: {probe}, early time", ylabel, until=EARLY * end),
    ]
