"""Build the report of a study folder: ``index.html`` and one page per paper.

The index opens with the summary (models and variants against their cards' checks, observed orders, worst error
at the finest grid and its cost, each linking to its evidence), then the papers' benchmarks, then figures that
show errors: per scene the error along the beam, per convergence series its log–log plot, per scene the
work–precision plot; then locking, horizons, the δ–Δx plane, dispersion relations, trust and every result. Its
figures are drawn by the page from inline data (:mod:`.plots`), filtered by paper, model, variant and scene;
nothing is loaded from anywhere. The paper pages keep the paper's own figures (:mod:`.papers`).

Every number in a table is a value of the study's tables, to the precision it carries (:mod:`.tables`), so it can
be traced to its row; re-running on the same results gives the same HTML apart from the one ``generated`` line."""

from __future__ import annotations

import time
from pathlib import Path

import pandas as pd

from ..verify.published import read_index
from . import beam_errors, error_measures, sweeps
from .inputs import StudyFolder, load
from .output import environment, make_folder, write
from .papers import paper_pages
from .plots import Palette
from .summary import summary
from .tables import row_tags, table, tags
from .text import case_anchor, fmt, options_of, readable, readable_options, short_reference, variant_of
from .waves import dispersion_plot, dispersion_sets

__all__ = ["build_report", "case_anchor", "environment", "fmt", "table"]

# the convergence table's columns, on the index page and on each paper's page
CONVERGENCE_COLUMNS = [
    "scene",
    "model",
    "options",
    "slenderness",
    "quantity",
    "n_grids",
    "observed_order",
    "promised_order",
    "below_order",
    "r2",
    "gci_order",
    "gci_fine",
    "richardson",
]
BENCHMARK_COLUMNS = [
    "name",
    "verdict",
    "model",
    "variant",
    "reference",
    "quantity",
    "position",
    "target",
    "computed",
    "ratio",
    "rel_error",
    "tolerance",
    "err_max",
    "observed_order",
    "case_id",
]
CHECK_COLUMNS = [
    "name",
    "scene",
    "model",
    "options",
    "slenderness",
    "quantity",
    "points",
    "errors",
    "pairwise_orders",
    "observed_order",
    "min",
    "max",
    "expected",
    "verdict",
    "message",
]
TRUST_COLUMNS = [
    "model",
    "options",
    "tolerance",
    "slenderness_trusted",
    "slenderness_not",
    "points_trusted",
    "points_not",
    "round_off_from_points",
    "statement",
]
RESULT_COLUMNS = [
    "case_id",
    "scene",
    "model",
    "variant",
    "points",
    "spacing",
    "horizon_factor",
    "degree",
    "slenderness",
    "dofs",
    "err_max",
    "err_l2",
    "err_at_max",
    "w_at_max",
    "w_ref_at_max",
    "assemble_s",
    "solve_s",
    "total_s",
    "cond",
    "error_bound",
    "status",
    "message",
    "warnings",
]


def build_report(study_dir: str | Path, out_dir: str | Path | None = None) -> Path:
    """Write ``index.html`` and the paper pages of the study folder ``study_dir`` into ``out_dir`` (default: the
    study folder); the index's path."""
    d = Path(study_dir)
    data = load(d)
    out = Path(out_dir) if out_dir else d
    make_folder(out)
    env = environment()
    generated = time.strftime("%Y-%m-%d %H:%M:%S")
    waves = dispersion_sets(data.ok, data.scene)
    pages = paper_pages(data, waves)
    for page in pages:
        write(out / page["href"], render_paper(env, data, page, generated))
    write(out / "index.html", render_index(env, data, out, pages, waves, generated))
    if out != d:
        write(out / "results.csv", (d / "results.csv").read_bytes())
    return out / "index.html"


def _tables(data: StudyFolder, link: str | None):
    """The table builder of a page: rows tagged for the filters (from their JSON options, before those are shown
    as text), units per scene, case ids linking to ``link``."""

    def make(df, columns=None, row_class=None, case_rows=False, full_on_hover=True):
        if df is None or df.empty:
            return table(df)
        tagged = {i: row_tags(r, data.scene_paper) for i, r in df.iterrows()}
        return table(
            readable_options(df),
            columns,
            row_class=row_class,
            case_link=link,
            case_rows=case_rows,
            unit_of_row=data.unit_of_row,
            filters=lambda r: tagged[r.name],
            full_on_hover=full_on_hover,
        )

    return make


def _benchmarks(bench: pd.DataFrame) -> pd.DataFrame:
    return bench.assign(reference=bench["reference"].map(short_reference)) if "reference" in bench else bench


def render_paper(env, data: StudyFolder, page: dict, generated: str) -> str:
    make = _tables(data, "index.html")
    names = page["names"]
    conv, lock = data.table("convergence"), data.table("locking")
    measures = {}
    for s in page["scenes"]:
        got = error_measures.scene_measures(data, s.file)
        if got is not None:
            measures[s.file] = (make(got[0]), got[1])
    return env.get_template("paper.html.j2").render(
        measures=measures,
        meta=data.meta,
        generated=generated,
        page=page,
        benchmarks=make(_benchmarks(page["benchmarks"]), BENCHMARK_COLUMNS, row_class="verdict"),
        scenes=page["scenes"],
        convergence_figs=page["sweeps"]["convergence"],
        horizon_figs=page["sweeps"]["horizon"],
        locking_figs=page["sweeps"]["locking"],
        locking=make(lock[lock["scene"].isin(names)] if "scene" in lock else lock),
        speed_figs=page["sweeps"]["speed"],
        convergence=make(conv[conv["scene"].isin(names)] if "scene" in conv else conv, CONVERGENCE_COLUMNS),
        waves=page["waves"],
        images=page["images"],
    )


def filter_choices(data: StudyFolder, pages: list[dict]) -> dict:
    """The values each filter offers: papers (with their titles), models and variants (of the study's runs and of
    its cards), scenes by paper."""
    res = data.res
    runs = [(m, options_of(o)) for m, o in zip(res["model"], res["options"])]
    cards = [(c["model"], c.get("options", {})) for c in (read_index(data.d) or {"cards": []})["cards"]]
    variants = sorted({variant_of(m, o) for m, o in runs + cards})
    return {
        "papers": [(p["folder"], p["title"]) for p in pages],
        "models": sorted({m for m, _ in runs + cards}),
        "variants": [(v or "-", v or "(no variant)") for v in variants],
        "scenes": {p["title"]: [s.name for s in p["scenes"]] for p in pages},
    }


def render_index(env, data: StudyFolder, out: Path, pages: list[dict], waves, generated: str) -> str:
    palette = Palette()
    scenes = beam_errors.scene_sections(data, palette)
    conv_groups = sweeps.convergence_groups(data, palette)
    cost_figs = sweeps.work_precision(data, palette)
    top = summary(
        data,
        out,
        {g.anchor for g in conv_groups},
        {s.anchor for s in scenes},
        {sweeps.cost_anchor(s) for s in data.ok["scene"]},
    )
    make = _tables(data, "")
    meta = data.meta
    conv, lock = data.table("convergence"), data.table("locking")
    rows = [{"item": k, "value": readable(v)} for k, v in meta.items() if k not in ("date",)]
    cards_s = (read_index(data.d) or {}).get("wall_s")
    if cards_s is not None and meta.get("wall_s") is not None:  # the verification cards run after the cases
        rows += [
            {"item": "cards_s (the verification cards)", "value": readable(cards_s)},
            {"item": "cases and cards (s)", "value": readable(float(meta["wall_s"]) + float(cards_s))},
        ]
    meta_rows = pd.DataFrame(rows)
    performance = None
    for cand in (out / "bench" / "index.html", out.parent / "bench" / "index.html"):
        if cand.exists():
            performance = cand.relative_to(out).as_posix() if cand.is_relative_to(out) else "../bench/index.html"
            break
    papers_of = {}
    for s in scenes:
        papers_of.setdefault(s.paper, []).append(s)
    titles = {p["folder"]: p["title"] for p in pages}
    return env.get_template("index.html.j2").render(
        meta=meta,
        counts=", ".join(f"{k}: {v}" for k, v in (meta.get("counts") or {}).items()),
        generated=generated,
        description=data.description,
        filters=filter_choices(data, pages),
        summary=top,
        benchmarks=make(_benchmarks(data.table("benchmarks")), BENCHMARK_COLUMNS, row_class="verdict"),
        checks=make(data.table("checks"), CHECK_COLUMNS, row_class="verdict"),
        papers=pages,
        performance=performance,
        scene_groups=[(paper, titles.get(paper, paper), secs) for paper, secs in papers_of.items()],
        convergence_groups=conv_groups,
        convergence=make(conv, CONVERGENCE_COLUMNS),
        cost_figs=cost_figs,
        speed_summary=make(data.table("speed_error_summary")),
        locking_figs=sweeps.locking(data, palette),
        locking=make(lock),
        horizon_figs=sweeps.horizons(data, palette),
        delta_dx=sweeps.delta_dx_planes(data, palette),
        waves=[
            dispersion_plot(w).html(tags(scenes=w.scenes, papers=w.papers, tag_model=False, tag_variant=False))
            for w in waves
        ],
        trust=make(data.table("trust"), TRUST_COLUMNS),
        images=[(p, len(p["images"])) for p in pages if p["images"]],
        results=make(data.res, RESULT_COLUMNS, row_class="status", case_rows=True, full_on_hover=False),
        meta_table=table(meta_rows),
        study_text=data.study_text,
    )
