"""The index's figures of the other quantities a study measures (``quantities``: rotation, bending moment M, shear
force V, axial force N): per scene and quantity, |q − q_ref| along the beam on a log axis, one line per model and
variant at its finest grid; on a curved axis, the deformed axis and the rotation and moment along the arc (the
reference and the runs furthest from it).

The reference of each quantity at a run's points is stored in its case file (``curve["references"]``, written
by the study's runner); the values where the quantity jumps (at a point load, a couple, an inner support) are
left out, as the study's error columns leave them out. ``colour``: a run's row -> its colour index (the same
in every figure of the page)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..core.geometry import geometry
from ..core.result import quantity_of
from ..study.runner import jumps
from .plots import Axis, Figure, Series, positive, thin
from .text import label, unit_of

QUANTITIES = ("rotation", "moment", "shear", "axial")  # in the order the page shows them
SYMBOL = {"rotation": "rotation", "moment": "M", "shear": "V", "axial": "N"}
NAME = {"rotation": "rotation", "moment": "bending moment M", "shear": "shear force V", "axial": "axial force N"}
QUANTITY_POINTS = 64  # points kept per line of a quantity's error (the deflection's figure keeps plots.MAX_POINTS)
SHAPE_POINTS = 60  # points kept per line of a shape (a smooth curve): the page stays under 2 MB with every quantity
SHAPE_LINES = 3  # runs drawn beside the reference in a shape figure: the ones furthest from it
SHAPE_SCALE = 0.1  # the deformed axis' largest displacement drawn as this fraction of the beam's length


def values_of(curve: dict, quantity: str) -> np.ndarray | None:
    """A run's values of ``quantity`` at its points (None when the model gives none)."""
    got = quantity_of(curve.get("w"), curve.get("rotation"), curve.get("fields") or {}, quantity)
    return None if got is None else np.asarray(got, float)


def reference_of(curve: dict, quantity: str) -> np.ndarray | None:
    """The reference's values of ``quantity`` at a run's points, as the study stored them (None: not measured)."""
    ref = (curve.get("references") or {}).get(quantity)
    return None if ref is None else np.asarray(ref, float)


def measured_quantities(runs) -> list[str]:
    """The quantities (in :data:`QUANTITIES` order) whose reference some run stored."""
    got = {q for r in runs for q in (r.curve.get("references") or {})}
    return [q for q in QUANTITIES if q in got]


def _thinned(x: np.ndarray, y: np.ndarray, log: bool, limit: int = QUANTITY_POINTS) -> tuple[np.ndarray, np.ndarray]:
    idx = thin(x, y, log, limit)
    return x[idx], y[idx]


def quantity_error_figure(runs, quantity: str, title: str, xname: str, length: str, units: str, scene, colour):
    """|q − q_ref| along the axis for one quantity, one line per run that gives it and whose reference the study
    stored (NaN, a break in the line, where the quantity jumps); None when no run has both."""
    unit = unit_of(SYMBOL[quantity], units)
    series, zero, missing = [], [], []
    for r in runs:
        ref, got = reference_of(r.curve, quantity), values_of(r.curve, quantity)
        if ref is None or got is None:
            missing.append(label(r.row))
            continue
        err = np.abs(got - ref)
        if scene is not None:
            err[jumps(scene, r.x, quantity)] = np.nan
        if not positive(err):
            zero.append(label(r.row))
            continue
        x, y = _thinned(r.x, err, True)
        series.append(Series(label(r.row), x, y, r.model, r.variant, colour(r.row)))
    if not series and not zero:
        return None
    caption = "Each model and variant at its finest grid (n = points); left out where the quantity jumps."
    if zero:
        caption += " Equal to the reference at every point (nothing to draw on a log axis): " + "; ".join(zero) + "."
    if missing:
        caption += f" No {NAME[quantity]} (the model's or the reference's): " + "; ".join(missing) + "."
    s = SYMBOL[quantity]
    return Figure(
        f"{title}: {NAME[quantity]}, error along the beam",
        Axis(f"{xname} ({length})", length),
        Axis(f"|{s} − {s}_ref| ({unit})", unit, log=True),
        series,
        caption=caption,
    )


def quantity_error_figures(runs, title: str, xname: str, length: str, units: str, scene, colour) -> list[Figure]:
    """One :func:`quantity_error_figure` per quantity the runs measured."""
    figs = []
    for q in measured_quantities(runs):
        fig = quantity_error_figure(runs, q, title, xname, length, units, scene, colour)
        if fig is not None:
            figs.append(fig)
    return figs


def _worst(runs, column: str) -> list:
    """The :data:`SHAPE_LINES` runs with the largest ``column`` (max relative error of that quantity)."""

    def key(r):
        v = r.row.get(column)
        return -float(v) if v is not None and pd.notna(v) else 0.0

    return sorted(runs, key=key)[:SHAPE_LINES]


def along_arc_figure(runs, quantity: str, title: str, length: str, units: str, colour) -> Figure | None:
    """On a curved axis, ``quantity`` (rotation or moment) along the arc: the reference of the finest run and the
    :data:`SHAPE_LINES` runs with the largest error of that quantity; None when no run stored its reference."""
    have = [r for r in runs if reference_of(r.curve, quantity) is not None and values_of(r.curve, quantity) is not None]
    if not have:
        return None
    ref = max(have, key=lambda r: len(r.x))
    unit = unit_of(SYMBOL[quantity], units)
    ref_line = _thinned(ref.x, reference_of(ref.curve, quantity), False, SHAPE_POINTS)
    series = [Series("reference", *ref_line, style="dash", guide=True)]
    worst = _worst(have, f"err_max_{quantity}")
    for r in worst:
        x, y = _thinned(r.x, values_of(r.curve, quantity), False, SHAPE_POINTS)
        series.append(Series(label(r.row), x, y, r.model, r.variant, colour(r.row)))
    return Figure(
        f"{title}: {NAME[quantity]} along the curved axis",
        Axis(f"s ({length})", length),
        Axis(f"{SYMBOL[quantity]} ({unit})", unit),
        series,
        caption=f"The reference and the {len(worst)} run(s) furthest from it (largest max error of "
        f"{NAME[quantity]}); their errors: the figure of its error along the beam.",
    )


def deformed_axis_figure(runs, title: str, length: str, scene, colour) -> Figure | None:
    """On a curved axis, the axis and the deformed axis (position + k·(ux, uy), one k for every line, chosen so
    that the largest displacement is :data:`SHAPE_SCALE` of the length): an exact run's where the scene has one,
    and the :data:`SHAPE_LINES` runs with the largest deflection error. None without ux, uy or the scene."""
    have = [r for r in runs if {"ux", "uy"} <= set(r.curve.get("fields") or {})]
    if scene is None or not have:
        return None
    geo = geometry(scene)
    exact = [r for r in have if r.model.startswith("exact-")]
    exact_ids = {id(r) for r in exact[:1]}
    drawn = exact[:1] + _worst([r for r in have if not r.model.startswith("exact-")], "err_max")
    big = max(float(np.max(np.hypot(r.curve["fields"]["ux"], r.curve["fields"]["uy"]), initial=0.0)) for r in drawn)
    k = SHAPE_SCALE * scene.length / big if big > 0 else 1.0
    s0 = np.linspace(0.0, scene.length, SHAPE_POINTS + 1)
    axis = geo.position(s0)
    series = [Series("axis", axis[:, 0], axis[:, 1], style="dot", guide=True)]
    for r in drawn:
        p = geo.position(r.x)
        x, y = p[:, 0] + k * r.curve["fields"]["ux"], p[:, 1] + k * r.curve["fields"]["uy"]
        idx = thin(x, y, False, SHAPE_POINTS)  # along the arc: x is not monotone, but the kept ends and extremes are
        if id(r) in exact_ids:
            series.append(Series(f"{label(r.row)} (exact)", x[idx], y[idx], style="line", guide=True))
        else:
            series.append(Series(label(r.row), x[idx], y[idx], r.model, r.variant, colour(r.row)))
    return Figure(
        f"{title}: deformed axis (displacements × {k:.3g})",
        Axis(f"x ({length})", length),
        Axis(f"y ({length})", length),
        series,
        equal=True,
        caption=f"The axis (dotted), {'an exact solution (grey) and ' if exact else ''}the "
        f"{len(drawn) - len(exact_ids)} run(s) with the largest deflection error; displacements drawn {k:.3g} times "
        "their size.",
    )
