"""HTML tables of the study's CSV tables: a header with its unit on every numeric column, each number to the
precision it carries (the full value on hover where it was rounded), wide tables scrolling in their own box,
rows tagged for the page's filters (paper, model, variant, scene)."""

from __future__ import annotations

import html
from collections.abc import Callable
from dataclasses import dataclass

import pandas as pd
from markupsafe import Markup

from .text import case_anchor, fixed, fmt, folder, missing, options_of, sig, variant_of

LENGTH, QUANTITY = "<length>", "<quantity>"  # units that depend on the row's scene (and measured quantity)


@dataclass(frozen=True)
class Column:
    """A column's header, its unit ('' for text; LENGTH or QUANTITY: the row's scene's) and how a value prints."""

    header: str
    unit: str = ""
    digits: int | None = 6  # significant digits (None: ``decimals``)
    decimals: int | None = None  # fixed decimals (orders of convergence)
    full_on_hover: bool = True  # a rounded value carries its full value as the cell's title

    def text(self, v) -> str:
        if isinstance(v, str) or self.unit == "":
            return fmt(v)
        if self.decimals is not None:
            return fixed(v, self.decimals)
        return sig(v, self.digits) if self.digits != 6 else fmt(v)


ONE = "–"  # dimensionless
COLUMNS = {
    # results
    "case_id": Column("case"),
    "points": Column("points", ONE),
    "spacing": Column("Δx", LENGTH, 4),
    "horizon_factor": Column("m = δ/Δx", ONE, 4),
    "degree": Column("degree P", ONE),
    "slenderness": Column("L/h", ONE, 4),
    "dofs": Column("DOFs", ONE),
    "err_max": Column("max rel. error", ONE, 3),
    "err_l2": Column("L2 rel. error", ONE, 3),
    "err_at_max": Column("rel. error at max", ONE, 3),
    "err_max_rotation": Column("max rel. error of the rotation", ONE, 3),
    "err_max_moment": Column("max rel. error of M", ONE, 3),
    "err_max_shear": Column("max rel. error of V", ONE, 3),
    "err_max_axial": Column("max rel. error of N", ONE, 3),
    "w_at_max": Column("value at max", QUANTITY),
    "w_ref_at_max": Column("reference at max", QUANTITY),
    "assemble_s": Column("assemble", "s", 2),
    "solve_s": Column("solve", "s", 2),
    "total_s": Column("total", "s", 2),
    "cond": Column("cond", ONE, 2),
    "error_bound": Column("round-off bound", ONE, 2),
    # benchmarks
    "target": Column("target", QUANTITY),
    "position": Column("position", LENGTH),
    "computed": Column("computed", QUANTITY),
    "ratio": Column("ratio", ONE),
    "rel_error": Column("rel. error", ONE, 3),
    "tolerance": Column("tolerance", ONE, 3),
    "observed_order": Column("observed order", ONE, decimals=2),
    # convergence, checks, locking
    "n_grids": Column("grids", ONE),
    "r2": Column("R²", ONE, decimals=4),
    "gci_order": Column("GCI order", ONE, decimals=2),
    "gci_fine": Column("GCI fine", ONE, 2),
    "richardson": Column("Richardson value", QUANTITY),
    "errors": Column("max rel. errors", ONE, 3),
    "pairwise_orders": Column("pairwise orders", ONE, decimals=2),
    "min": Column("min order", ONE, decimals=2),
    "max": Column("max order", ONE, decimals=2),
    "n": Column("cases", ONE),
    "locking_slope": Column("locking slope", ONE, decimals=2),
    "slenderness_at_1pct": Column("L/h at 1 %", ONE, 3),
    # trust, speed summary
    "slenderness_trusted": Column("L/h within tolerance", ONE),
    "slenderness_not": Column("L/h outside it", ONE),
    "points_trusted": Column("points within tolerance", ONE),
    "points_not": Column("points outside it", ONE),
    "round_off_from_points": Column("round-off from points", ONE),
    "growth_from_points": Column("growth from points", ONE),
    "cheapest_1pct_s": Column("cheapest within 1 %", "s", 2),
    "cheapest_0.1pct_s": Column("cheapest within 0.1 %", "s", 2),
    "cheapest_1pct_case": Column("case within 1 %"),
    "cheapest_0.1pct_case": Column("case within 0.1 %"),
}


SERIES = {"points", "spacings", "errors", "pairwise_orders"}  # a series' values, one per grid, in one cell


def column(name: str) -> Column:
    """The column's spec; a column not listed prints as text under its own name."""
    return COLUMNS.get(name, Column(name))


def cell_text(name: str, v) -> str:
    """A value as the report prints it in column ``name``."""
    return column(name).text(v)


def tags(model="", variant="", scenes=(), papers=(), tag_model: bool = True, tag_variant: bool = True) -> str:
    """The data attributes the page's filters read: '|'-separated values (a row may belong to several scenes)."""
    attrs = []
    for key, values in (
        ("model", [model] if tag_model else None),
        ("variant", [variant] if tag_variant else None),
        ("scene", list(scenes)),
        ("paper", list(papers)),
    ):
        if values is None:
            continue
        attrs.append(f' data-{key}="{html.escape("|".join(str(v) for v in dict.fromkeys(values)))}"')
    return "".join(attrs)


def row_tags(r, scene_paper: dict[str, str] | None = None) -> str:
    """Filter attributes of a table row from its columns (model, variant or options, scene, scene_file); the
    paper from the scene file's folder, or by scene name from ``scene_paper``."""
    model = str(r["model"]) if "model" in r and isinstance(r["model"], str) else ""
    variant = r["variant"] if "variant" in r and isinstance(r["variant"], str) and r["variant"] else None
    if variant is None:
        variant = variant_of(model, options_of(r.get("options"))) if model else ""
    scene = str(r["scene"]) if "scene" in r and isinstance(r["scene"], str) else ""
    paper = ""
    if "scene_file" in r and isinstance(r["scene_file"], str) and r["scene_file"]:
        paper = folder(r["scene_file"])
    elif scene_paper and scene in scene_paper:
        paper = scene_paper[scene]
    return tags(model, variant, [scene] if scene else [], [paper] if paper else [], tag_model=bool(model))


def _units(df: pd.DataFrame, cols: list[str], unit_of_row: Callable | None) -> dict[str, list[str] | str]:
    """Per column with a scene-dependent unit: the one unit of every row (a string) or each row's (a list)."""
    out = {}
    for c in cols:
        spec = column(c)
        if spec.unit not in (LENGTH, QUANTITY):
            continue
        per_row = [unit_of_row(r, spec.unit) if unit_of_row else "" for _, r in df.iterrows()]
        known = {u for u, v in zip(per_row, df[c]) if u and not missing(v)} or {u for u in per_row if u}
        out[c] = known.pop() if len(known) == 1 else ("" if not known else per_row)
    return out


def header(name: str, unit: str | list[str]) -> str:
    """'max rel. error (–)', 'Δx (m)'; 'computed (unit per row)' when the rows' units differ."""
    spec = column(name)
    if spec.unit == "":
        return spec.header
    u = spec.unit if spec.unit not in (LENGTH, QUANTITY) else unit
    if isinstance(u, list):
        return f"{spec.header} (unit per row)"
    return f"{spec.header} ({u})" if u else spec.header


def table(
    df: pd.DataFrame,
    columns: list[str] | None = None,
    row_class: str | None = None,
    case_link: str | None = None,
    case_rows: bool = False,
    unit_of_row: Callable | None = None,
    filters: Callable | None = None,
    full_on_hover: bool = True,
) -> Markup:
    """An HTML table of ``df`` (every value escaped) in a box that scrolls sideways. ``case_link``: each case id
    links to its row of the results table at this page prefix ("" on index.html, "index.html" elsewhere);
    ``case_rows``: rows carry that id; ``unit_of_row(row, LENGTH or QUANTITY)``: the unit of a scene-dependent
    column in that row; ``filters(row)``: the row's filter attributes (:func:`tags`); ``full_on_hover``: a rounded
    number carries its full value as the cell's title."""
    if df is None or df.empty:
        return Markup("")
    cols = [c for c in (columns or list(df.columns)) if c in df.columns]
    units = _units(df, cols, unit_of_row)
    head = "".join(
        f'<th class="{"l" if column(c).unit == "" else ""}" title="{html.escape(c)}">'
        f"{html.escape(header(c, units.get(c, '')))}</th>"
        for c in cols
    )
    rows = []
    for i, (_, r) in enumerate(df.iterrows()):
        classes = [str(r[row_class])] if row_class and row_class in r else []
        classes += ["f"] if filters is not None else []  # a row the page's filters show or hide
        attrs = f' class="{html.escape(" ".join(classes))}"' if classes else ""
        if case_rows and "case_id" in r and isinstance(r["case_id"], str):
            attrs += f' id="{case_anchor(r["case_id"])}"'
        if filters is not None:
            attrs += filters(r)
        cells = []
        for c in cols:
            v = r[c]
            spec = column(c)
            klass = "verdict" if c == "verdict" else ("l" if isinstance(v, str) or spec.unit == "" else "")
            text = spec.text(v)
            title = ""
            if (
                full_on_hover
                and spec.full_on_hover
                and isinstance(v, (float, int))
                and not isinstance(v, bool)
                and not missing(v)
                and text != fmt(v)
                and text != repr(v)
            ):
                title = f' title="{float(v)!r}"'
            if isinstance(units.get(c), list) and text and units[c][i]:
                text = f"{text} {units[c][i]}"
            text = html.escape(text)
            if c in SERIES and isinstance(v, str):  # one grid's value a line, none broken
                text, klass = "<br>".join(text.split()), "nw"
            if c == "case_id" and case_link is not None and isinstance(v, str) and v:
                text = f'<a href="{html.escape(case_link)}#{case_anchor(v)}">{text}</a>'
            cells.append(f'<td class="{klass}"{title}>{text}</td>')
        rows.append(f"<tr{attrs}>{''.join(cells)}</tr>")
    return Markup(
        f'<div class="wide"><table class="sortable"><thead><tr>{head}</tr></thead>'
        f"<tbody>{''.join(rows)}</tbody></table></div>"
    )
