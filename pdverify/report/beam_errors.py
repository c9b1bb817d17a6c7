"""The index's figures of each scene: |quantity − reference| along the beam on a log axis, one line per model and
variant at its finest grid (the deflection curves of ten models lie on top of each other; their errors do not),
and the shape only where the shape is the point: a large-rotation run's deformed axis at its load steps against
the exact elastica, and on a curved axis the reference with the few runs furthest from it."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from markupsafe import Markup

from .inputs import StudyFolder
from .plots import Axis, Figure, Palette, Series, positive
from .summary import scene_anchor
from .tables import tags
from .text import fmt, folder, label, options_of, short_reference, unit_of, variant_of

CURVED_LINES = 3  # runs drawn beside the reference on a curved axis: the ones furthest from it


def line_key(r) -> str:
    """A run's label without its grid and slenderness: what keeps its colour from figure to figure."""
    return " ".join(p for p in label(r).split(" ") if not p.startswith(("n=", "L/h=")))


@dataclass
class Run:
    """A run at its finest grid on one scene and slenderness: its row, positions, measured quantity, reference."""

    row: pd.Series
    x: np.ndarray
    q: str
    y: np.ndarray
    ref: np.ndarray
    curve: dict

    @property
    def model(self) -> str:
        return str(self.row["model"])

    @property
    def variant(self) -> str:
        return variant_of(self.model, options_of(self.row.get("options")))


@dataclass
class SceneSection:
    """What the index shows of one scene."""

    name: str
    file: str
    paper: str
    reference: str
    figures: list[Markup] = field(default_factory=list)
    note: str = ""

    @property
    def anchor(self) -> str:
        return scene_anchor(self.name)

    @property
    def tags(self) -> Markup:
        return Markup(tags(scenes=[self.name], papers=[self.paper], tag_model=False, tag_variant=False))


def finest_runs(data: StudyFolder, rows: pd.DataFrame) -> list[Run]:
    """One run per (model, options): its finest grid, with its curves (a run whose case file is gone is left out)."""
    runs = []
    for _, grp in rows.groupby(["model", rows["options"].fillna("")], sort=True):
        r = grp.sort_values("points", na_position="first").iloc[-1]
        c = data.curve(r["case_id"])
        if c is None:
            continue
        q = c.get("quantity", "w")  # what the model is measured on (pd-rod: u, pd-torsion: twist)
        y = np.asarray(c["w"] if q == "w" else c["fields"][q], float)
        runs.append(Run(r, np.asarray(c["x"], float), q, y, np.asarray(c["w_ref"], float), c))
    return runs


def error_figure(runs: list[Run], title: str, xname: str, length: str, units: str, palette: Palette) -> Figure | None:
    """|q − q_ref| along the axis, one line per run; None when no run has a reference."""
    runs = [r for r in runs if np.isfinite(r.ref).any()]
    if not runs:
        return None
    quantities = sorted({r.q for r in runs})
    yunit = " / ".join(sorted({unit_of(q, units) for q in quantities}))
    q = " / ".join(quantities)
    series, zero = [], []
    for r in runs:
        err = np.abs(r.y - r.ref)
        if not positive(err):
            zero.append(label(r.row))
            continue
        series.append(Series(label(r.row), r.x, err, r.model, r.variant, palette(line_key(r.row))))
    caption = "Each model and variant at its finest grid (n = points)."
    if zero:
        caption += " Equal to the reference at every point (nothing to draw on a log axis): " + "; ".join(zero) + "."
    return Figure(
        f"{title}: error along the beam",
        Axis(f"{xname} ({length})", length),
        Axis(f"|{q} − {q}_ref| ({yunit})", yunit, log=True),
        series,
        caption=caption,
    )


def load_step_figure(run: Run, title: str, length: str) -> Figure:
    """A nonlinear run's deformed axis at its recorded load steps, the exact elastica dashed (equal scales)."""
    series = []
    exact_x, exact_z = [], []
    for i, st in enumerate(run.curve["load_steps"]):
        series.append(
            Series(
                f"load factor {st['factor']:.2f}", np.asarray(st["x"]), np.asarray(st["z"]), run.model, run.variant, i
            )
        )
        if "exact_x" in st:
            exact_x += [*np.asarray(st["exact_x"], float), np.nan]
            exact_z += [*np.asarray(st["exact_z"], float), np.nan]
    if exact_x:
        series.append(Series("exact elastica", np.array(exact_x), np.array(exact_z), style="dash", guide=True))
    return Figure(
        f"{title}: {label(run.row)}, deformed axis",
        Axis(f"x ({length})", length),
        Axis(f"z ({length})", length),
        series,
        equal=True,
    )


def curved_shape_figure(runs: list[Run], title: str, length: str, units: str, palette: Palette) -> Figure | None:
    """On a curved axis: the reference deflection and the :data:`CURVED_LINES` runs with the largest error."""
    runs = [r for r in runs if np.isfinite(r.ref).any()]
    if not runs:
        return None
    ref = max(runs, key=lambda r: len(r.x))
    worst = sorted(runs, key=lambda r: -float(r.row["err_max"]) if pd.notna(r.row["err_max"]) else 0.0)
    worst = worst[:CURVED_LINES]
    q = ref.q
    unit = unit_of(q, units)
    series = [Series("reference", ref.x, ref.ref, style="dash", guide=True)]
    series += [Series(label(r.row), r.x, r.y, r.model, r.variant, palette(line_key(r.row))) for r in worst]
    return Figure(
        f"{title}: {q} along the curved axis",
        Axis(f"s ({length})", length),
        Axis(f"{q} ({unit})", unit),
        series,
        caption=f"The reference and the {len(worst)} run(s) furthest from it (largest max error); the others lie "
        "closer to the reference (their errors: the figure beside).",
    )


def scene_sections(data: StudyFolder, palette: Palette) -> list[SceneSection]:
    """One section per scene (in the study's order): its error figure per slenderness and reference, its shapes
    where they are the point, a note where it has no reference."""
    sections = []
    for sfile, g in data.ok.groupby("scene_file", sort=False):
        name = str(g["scene"].iloc[0])
        units = data.units(sfile)
        length = data.length(sfile)
        scene = data.scene(sfile)
        curved = scene is not None and not scene.is_straight
        references = g["reference"].map(short_reference) if "reference" in g else pd.Series("", index=g.index)
        sec = SceneSection(name, sfile, folder(sfile), "; ".join(dict.fromkeys(references)))
        for sl, gs in g.groupby(g["slenderness"].fillna(-1), sort=True):
            title = name + ("" if sl == -1 else f", L/h = {fmt(sl)}")
            runs = finest_runs(data, gs)
            # one error figure per reference: runs measured against different references are not one comparison
            for ref, rg in gs.groupby(references[gs.index], sort=False):
                against = f", against {ref}" if references.nunique() > 1 else ""
                err = error_figure(finest_runs(data, rg), title, "s" if curved else "x", length, units, palette)
                if err is not None:
                    err.title += against
                    sec.figures.append(err.html(sec.tags))
            if curved:
                shape = curved_shape_figure(runs, title, length, units, palette)
                if shape is not None:
                    sec.figures.append(shape.html(sec.tags))
            for r in runs:
                if r.curve.get("load_steps"):
                    sec.figures.append(load_step_figure(r, title, length).html(sec.tags))
        if not sec.figures:
            dynamic = any(data.curve(c) and data.curve(c).get("history") for c in g["case_id"])
            sec.note = "No reference on this scene: no error to draw." + (
                " Its time histories are on the paper's page." if dynamic else ""
            )
        sections.append(sec)
    return sections
