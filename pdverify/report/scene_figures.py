"""Figures of one scene beyond its deflection curves: curved beams' resultants (N, Q), the overlay of several
transient runs, the PD rod and beam stencils' dispersion. Each takes what the report builder read (curves, case
rows, the output folder) and returns inline SVG strings (:mod:`.figures`)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from ..study.outdir import SCENES
from ..study.spec import _scene
from . import figures
from .waves import dispersion_figure

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


def dispersion_figures(d: Path, sfile: str, rows: pd.DataFrame) -> list[str]:
    """The dispersion figure of each PD rod / beam (model, variant) run on the scene, at its finest grid
    (:func:`pdverify.report.waves.dispersion_figure`; the scene from the study's ``scenes.json``)."""

    pd_rows = rows[rows["model"].isin(("pd-rod", "pd-timoshenko"))]
    if pd_rows.empty:
        return []
    try:
        text = json.loads((d / SCENES).read_text())[sfile]
    except (OSError, ValueError, KeyError):  # a study run before scenes.json was written
        return []
    figs = []
    for (model, variant), g in pd_rows.groupby(["model", pd_rows["variant"].fillna("corrected")], sort=True):
        fig = dispersion_figure(_scene(text, sfile, None), model, int(g["points"].max()), variant)
        figs += [fig] if fig else []
    return figs
