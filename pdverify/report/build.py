"""Build ``index.html`` from a study directory (the runner's tables and case files).

Every number in a table is the value of the results table, formatted with ``fmt`` (6 significant
digits), so it can be traced to its row; re-running on the same results gives the same HTML apart
from the one ``generated`` line.

~630 lines: one builder per page section (results, convergence, locking, benchmarks, checks, trust, papers,
cards) feeding one template; figures are in :mod:`figures`, a scene's extra figures (resultants, overlaid
transients, dispersion) in :mod:`scene_figures`, the performance page in :mod:`perf`.
"""

from __future__ import annotations

import csv
import html
import json
import time
from pathlib import Path

import jinja2
import numpy as np
import pandas as pd
from markupsafe import Markup

from ..core.errors import InputError, OutputError
from ..core.scene import UNITS
from ..registry import get_model
from ..study.store import case_file, read_curve, write_atomic
from ..verify.published import read_index
from . import figures
from .scene_figures import dispersion_figures, overlay_figures, resultant_figures

# the convergence table's columns, on the index page and on each paper's page
CONVERGENCE_COLUMNS = [
    "scene",
    "model",
    "options",
    "slenderness",
    "n_grids",
    "observed_order",
    "r2",
    "gci_order",
    "gci_fine",
    "richardson",
]


def fmt(v) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)) or v is pd.NA:
        return ""
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        return f"{float(v):.6g}"
    return str(v)


def case_anchor(case_id) -> str:
    """The id of a case's row in the 'All results' table of index.html."""
    return "case-" + "".join(ch for ch in str(case_id) if ch.isalnum() or ch in "-_")


def table(
    df: pd.DataFrame,
    columns: list[str] | None = None,
    row_class: str | None = None,
    case_link: str | None = None,
    case_rows: bool = False,
) -> Markup:
    """An HTML table of ``df`` (every value escaped). ``case_link``: each case id links to its row of the results
    table at this page prefix ("" on index.html, "index.html" elsewhere); ``case_rows``: rows carry that id."""
    if df is None or df.empty:
        return Markup("")
    cols = [c for c in (columns or list(df.columns)) if c in df.columns]
    head = "".join(f'<th class="{"l" if df[c].dtype == object else ""}">{html.escape(c)}</th>' for c in cols)
    rows = []
    for _, r in df.iterrows():
        cls = f' class="{html.escape(str(r[row_class]))}"' if row_class and row_class in r else ""
        if case_rows and "case_id" in r and isinstance(r["case_id"], str):
            cls += f' id="{case_anchor(r["case_id"])}"'
        cells = []
        for c in cols:
            v = r[c]
            klass = "verdict" if c == "verdict" else ("l" if isinstance(v, str) else "")
            text = html.escape(fmt(v))
            if c == "case_id" and case_link is not None and isinstance(v, str) and v:
                text = f'<a href="{html.escape(case_link)}#{case_anchor(v)}">{text}</a>'
            cells.append(f'<td class="{klass}">{text}</td>')
        rows.append(f"<tr{cls}>{''.join(cells)}</tr>")
    return Markup(f'<table class="sortable"><thead><tr>{head}</tr></thead><tbody>{"".join(rows)}</tbody></table>')


# columns that hold text whatever they look like: a scene named "123", "NA" or "True" stays that name
TEXT_COLUMNS = frozenset(
    "study case_id code scene_file model reference version variant element form scene units options quantity "
    "status message warnings artefact_message check verdict name".split()
)


def _read(d: Path, name: str) -> pd.DataFrame:
    p = d / f"{name}.csv"
    if not p.exists() or p.stat().st_size == 0:
        return pd.DataFrame()
    try:
        header = pd.read_csv(p, nrows=0).columns
        text = [c for c in header if c in TEXT_COLUMNS]
        numbers = {c: ["", "nan", "NaN", "NA", "None", "null"] for c in header if c not in TEXT_COLUMNS}
        df = pd.read_csv(p, dtype={c: "string" for c in text}, keep_default_na=False, na_values=numbers)
        for c in text:
            df[c] = df[c].fillna("").astype(str)
        return df
    except pd.errors.EmptyDataError:
        return pd.DataFrame()
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise InputError(
            f"{p}: not a readable CSV table ({str(exc).splitlines()[0][:120]}); run "
            f"`pdverify study STUDY.toml --out {d}` again"
        ) from None


def _short_rows(path: Path) -> tuple[int, int, int] | None:
    """(line, fields, header fields) of the first row whose field count differs from the header's, or None."""
    with open(path, newline="", encoding="utf-8") as fh:
        rows = csv.reader(fh)
        want = len(next(rows, []))
        for line, row in enumerate(rows, start=2):
            if row and len(row) != want:
                return line, len(row), want
    return None


def _label(r) -> str:
    """Model, then its string options that differ from the model's defaults, then grid and horizon."""
    parts = [str(r["model"])]
    opts = json.loads(r["options"]) if isinstance(r.get("options"), str) else {}
    try:
        model = get_model(str(r["model"]))
    except Exception:  # a model of another installation: show every string option
        model = None
    for k, v in sorted(opts.items()):
        if k in ("horizon", "degree") or not isinstance(v, str):
            continue
        opt = model.option(k) if model is not None else None
        if opt is not None and opt.default == v and k != "variant":
            continue
        parts.append(v)
    for k, short in (("points", "n"), ("horizon_factor", "m"), ("degree", "P"), ("slenderness", "L/h")):
        if k in r and pd.notna(r[k]):
            parts.append(f"{short}={fmt(r[k])}")
    return " ".join(parts)


def _short_reference(ref) -> str:
    """'fem-plane-stress (element=q8, layers=16, points=201)' for the JSON reference of a row."""
    try:
        d = json.loads(ref)
    except (TypeError, ValueError):
        return "" if ref is None or (isinstance(ref, float) and np.isnan(ref)) else str(ref)
    if not isinstance(d, dict):
        return str(d)
    model = d.pop("model", "?")
    return f"{model} ({', '.join(f'{k}={v}' for k, v in sorted(d.items()))})" if d else str(model)


def _options_text(options) -> str:
    """'analysis=auto, grid=nodes, horizon=2' for the JSON options of a row."""
    try:
        d = json.loads(options)
    except (TypeError, ValueError):
        return "" if options is None or (isinstance(options, float) and np.isnan(options)) else str(options)
    return ", ".join(f"{k}={v}" for k, v in sorted(d.items())) if isinstance(d, dict) else str(d)


def _readable(v) -> str:
    """A value of meta.json as text: 'numpy 2.4.6, scipy 1.17.1' for a table, 'a; b' for a list."""
    if isinstance(v, dict):
        sep = " " if all(isinstance(x, str) for x in v.values()) else ": "
        return ", ".join(f"{k}{sep}{_readable(x)}" for k, x in v.items())
    if isinstance(v, list):
        return "; ".join(_readable(x) for x in v) or "none"
    return fmt(v)


def _units_of(res: pd.DataFrame, key: str, kind: str = "length") -> dict:
    """Length unit ('m', 'in'; ``kind = "force"``: 'N', 'lbf') of each scene (by ``key``: scene_file or scene),
    from the rows' ``units``."""

    if "units" not in res or key not in res:
        return {}
    out = {}
    for k, u in zip(res[key], res["units"]):
        if isinstance(u, str) and u in UNITS and k not in out:
            out[k] = UNITS[u][kind]
    return out


def _curve(d: Path, path: Path) -> dict:
    """A case's curves, or InputError naming the damaged file (``pdverify study`` recomputes it)."""
    try:
        return read_curve(path)
    except ValueError:
        raise InputError(
            f"{path}: a damaged case file (not a whole, readable case record); run "
            f"`pdverify study STUDY.toml --out {d}` again, which recomputes it, then the report"
        ) from None


def _folder(scene_file) -> str:
    """The name of the scene's folder (one report page per folder: a paper's scenes)."""
    return Path(str(scene_file)).parent.name or "scenes"


def _slug(text: str) -> str:
    import re

    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "scenes"


def build_report(study_dir: str | Path, out_dir: str | Path | None = None) -> Path:
    d = Path(study_dir)
    if not (d / "results.csv").exists():
        raise InputError(f"{d}: no results.csv; run `pdverify study STUDY.toml --out {d}` first")
    out = Path(out_dir) if out_dir else d
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(
            f"{out}: cannot make the report folder ({exc.strerror or exc}); choose another --out"
        ) from None
    try:
        meta = json.loads((d / "meta.json").read_text()) if (d / "meta.json").exists() else {"study": d.name}
    except (ValueError, UnicodeDecodeError):
        raise InputError(
            f"{d / 'meta.json'}: not valid JSON; run `pdverify study STUDY.toml --out {d}` again"
        ) from None
    res = _read(d, "results")
    again = f"run `pdverify study STUDY.toml --out {d}` again"
    if res.empty:
        raise InputError(f"{d / 'results.csv'}: no cases (an empty table); {again}")
    for col in ("case_id", "scene_file", "scene", "status", "model", "slenderness", "points", "err_max"):
        if col not in res:
            raise InputError(f"{d / 'results.csv'}: no '{col}' column; not a pdverify results table ({again})")
    short = _short_rows(d / "results.csv")
    if short:
        line, got, want = short
        raise InputError(f"{d / 'results.csv'}: line {line} has {got} fields, the header {want}; {again}")
    if not isinstance(meta, dict):
        raise InputError(f"{d / 'meta.json'}: not a JSON object; run `pdverify study STUDY.toml --out {d}` again")
    unit_of_file, unit_of_scene = _units_of(res, "scene_file"), _units_of(res, "scene")
    force_of_file = _units_of(res, "scene_file", "force")
    conv, lock, se, sesum, bench, trust, checks = (
        _read(d, n)
        for n in ("convergence", "locking", "speed_error", "speed_error_summary", "benchmarks", "trust", "checks")
    )
    ok = res[res["status"] == "ok"] if "status" in res else res

    from functools import lru_cache

    curve_of = lru_cache(maxsize=None)(lambda path: _curve(d, path))  # each case file decoded once per build
    scenes = []
    for sfile, g in ok.groupby("scene_file", sort=False):
        figs = []
        for sl, gs in g.groupby(g["slenderness"].fillna(-1), sort=True):
            curves, ref, ylabels, resultant_curves = [], None, set(), []
            # at most one curve per (model, variant): the finest grid
            for _, grp in gs.groupby(["model", gs["options"].fillna("")], sort=True):
                r = grp.sort_values("points", na_position="first").iloc[-1]
                path = case_file(d / "cases", r["case_id"])
                if path is None:
                    continue
                c = curve_of(path)
                quantity = c.get("quantity", "w")  # what the model is measured on (pd-rod: u, pd-torsion: twist)
                y = c["w"] if quantity == "w" else c["fields"][quantity]
                ylabels.add(quantity)
                curves.append((_label(r), c["x"], y))
                if {"N", "Q"} <= set(c.get("fields", {})):
                    resultant_curves.append((_label(r), c))
                if ref is None or len(c["x"]) > len(ref[0]):
                    ref = (c["x"], c["w_ref"])
            title = g["scene"].iloc[0] + ("" if sl == -1 else f", L/h = {fmt(sl)}")
            if ref is not None and np.all(np.isnan(ref[1])):  # runs without a reference
                ref = None
            unit = unit_of_file.get(sfile, "m")
            figs.append(figures.deflection(curves, ref, title, " / ".join(sorted(ylabels)) or "w", unit))
            force = force_of_file.get(sfile, "N")
            figs.extend(resultant_figures(resultant_curves, title, unit, force))
            overlay = []
            for _, r in gs.iterrows():
                path = case_file(d / "cases", r["case_id"])
                c = curve_of(path) if path is not None else {}
                if c.get("history"):
                    h = c["history"]
                    overlay += [(_label(r), h["t"], h["series"], h.get("ylabel", "displacement"))]
                    figs.append(
                        figures.time_history(
                            h["t"], h["series"], f"{_label(r)}: time history", h.get("ylabel", "displacement")
                        )
                    )
                    if h.get("energy"):
                        energy = "in lbf" if force_of_file.get(sfile) == "lbf" else "J"
                        figs.append(figures.energy_ledger(h["energy"], f"{_label(r)}: energy ledger", energy))
                if c.get("load_steps"):
                    exact = [
                        (np.array(st["exact_x"]), np.array(st["exact_z"])) for st in c["load_steps"] if "exact_x" in st
                    ]
                    figs.append(
                        figures.deformed_shapes(
                            c["load_steps"], f"{_label(r)}: deformed shapes", exact, unit_of_file.get(sfile, "m")
                        )
                    )
            figs.extend(overlay_figures(overlay, title))
        figs.extend(dispersion_figures(d, sfile, g))
        scenes.append(
            {
                "name": g["scene"].iloc[0],
                "file": sfile,
                "folder": _folder(sfile),
                "reference": _short_reference(g["reference"].iloc[0]) if "reference" in g else "",
                "figures": [Markup(f) for f in figs],
            }
        )

    conv_figs = []
    if not conv.empty:
        for scene, g in conv.groupby("scene", sort=False):
            series = []
            for _, r in g.iterrows():
                h = np.array([float(v) for v in str(r["spacings"]).split()])
                e = np.array([float(v) for v in str(r["errors"]).split()])
                series.append((_label(r), h, e, r["observed_order"]))
            conv_figs.append((scene, Markup(figures.convergence(series, str(scene), unit_of_scene.get(scene, "m")))))
    horizon_figs = []
    hz = ok[ok["horizon_factor"].notna() & ok["err_max"].notna()] if "horizon_factor" in ok else ok.iloc[0:0]
    for scene, g in hz.groupby("scene", sort=False):
        groups = []
        others = g["options"].map(
            lambda o: " ".join(
                f"{v}" for k, v in sorted(json.loads(o).items()) if k != "horizon" and isinstance(v, str)
            )
        )
        for (model, rest, pts), gg in g.groupby(["model", others, "points"], sort=True):
            if gg["horizon_factor"].nunique() >= 2 and pts == g[g["model"] == model]["points"].max():
                gg = gg.sort_values("horizon_factor")
                groups.append(
                    (
                        f"{model} {rest} n={fmt(pts)}",
                        gg["horizon_factor"].to_numpy(float),
                        np.maximum(gg["err_max"].to_numpy(float), 1e-16),
                    )
                )
        if groups:
            horizon_figs.append(
                (
                    scene,
                    Markup(
                        figures.scatter(
                            groups,
                            "horizon factor m = delta / dx",
                            "max relative error",
                            f"error vs horizon: {scene}",
                            logx=False,
                        )
                    ),
                )
            )
    lock_figs = []
    if not lock.empty:
        lk = ok[ok["slenderness"].notna()]
        for scene, g in lk.groupby("scene", sort=False):
            groups = []
            for _key, gg in g.groupby(["model", g["options"].fillna(""), g["points"].fillna(-1)]):
                gg = gg.sort_values("slenderness")
                if gg["slenderness"].nunique() < 2 or not (gg["err_max"] > 0).any():
                    continue  # one slenderness is no sweep; a zero error (an exact model) has no log
                groups.append(
                    (
                        _label(gg.iloc[0]).replace(f" L/h={fmt(gg.iloc[0]['slenderness'])}", ""),
                        gg["slenderness"].to_numpy(float),
                        gg["err_max"].to_numpy(float),
                    )
                )
            lock_figs.append(
                (
                    scene,
                    Markup(
                        figures.scatter(
                            groups, "slenderness L/h", "max relative error", f"locking: {scene}", connect=True
                        )
                    ),
                )
            )
    speed_figs = []
    if not se.empty:
        for scene, g in se.groupby("scene", sort=False):
            groups = [
                (m, gg["total_s"].to_numpy(float), np.maximum(gg["err_max"].to_numpy(float), 1e-16))
                for m, gg in g.groupby("model")
            ]
            fr = g[g["pareto"].astype(bool)]
            speed_figs.append(
                (
                    scene,
                    Markup(
                        figures.scatter(
                            groups,
                            "total time (s)",
                            "max relative error",
                            f"speed vs error: {scene}",
                            front=(fr["total_s"].to_numpy(float), np.maximum(fr["err_max"].to_numpy(float), 1e-16)),
                        )
                    ),
                )
            )

    images = []
    for png in sorted((d / "vtu").glob("*.png")) if (d / "vtu").exists() else []:
        import base64

        r = res[res["case_id"] == png.stem]
        label = f"{r['scene'].iloc[0]}: {_label(r.iloc[0])}" if len(r) else png.stem
        images.append(
            {"label": label, "data": base64.b64encode(png.read_bytes()).decode(), "vtu": f"vtu/{png.stem}.vtu"}
        )
    counts = ", ".join(f"{k}: {v}" for k, v in (meta.get("counts") or {}).items())
    meta_rows = pd.DataFrame([{"item": k, "value": _readable(v)} for k, v in meta.items() if k not in ("date",)])
    env = environment()
    generated = time.strftime("%Y-%m-%d %H:%M:%S")
    bench_cols = [
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
    study_file = d / "study.toml"
    titles, description = {}, ""
    if study_file.exists():
        import tomllib

        try:
            spec = tomllib.loads(study_file.read_text())
            titles = dict(spec.get("papers", {}))
            description = str(spec.get("description", ""))
        except (tomllib.TOMLDecodeError, AttributeError):
            titles = {}
    papers = []
    for folder in dict.fromkeys(s["folder"] for s in scenes):
        names = {s["name"] for s in scenes if s["folder"] == folder}
        pick = lambda figs, names=names: [f for sc, f in figs if sc in names]  # noqa: E731
        pb = bench[bench["scene_file"].map(_folder) == folder] if "scene_file" in bench else bench.iloc[0:0]
        if "reference" in pb:
            pb = pb.assign(reference=pb["reference"].map(_short_reference))
        verdicts = pb["verdict"].value_counts().to_dict() if "verdict" in pb else {}
        page = {
            "folder": folder,
            "title": titles.get(folder, folder),
            "href": f"paper-{_slug(folder)}.html",
            "summary": ", ".join(f"{k}: {v}" for k, v in sorted(verdicts.items())) or "no benchmarks",
            "n_scenes": len(names),
        }
        html_page = env.get_template("paper.html.j2").render(
            meta=meta,
            generated=generated,
            page=page,
            benchmarks=table(pb, bench_cols, row_class="verdict", case_link="index.html"),
            scenes=[s for s in scenes if s["folder"] == folder],
            convergence_figs=pick(conv_figs),
            horizon_figs=pick(horizon_figs),
            locking_figs=pick(lock_figs),
            locking=table(readable_options(lock[lock["scene"].isin(names)] if "scene" in lock else lock)),
            speed_figs=pick(speed_figs),
            convergence=table(
                readable_options(conv[conv["scene"].isin(names)] if "scene" in conv else conv),
                CONVERGENCE_COLUMNS,
            ),
        )
        _write(out / page["href"], html_page)
        papers.append(page)
    performance = None
    for cand in (out / "bench" / "index.html", out.parent / "bench" / "index.html"):
        if cand.exists():
            performance = cand.relative_to(out).as_posix() if cand.is_relative_to(out) else "../bench/index.html"
            break
    page = env.get_template("index.html.j2").render(
        cards=cards_table(d, out),
        meta=meta,
        counts=counts,
        generated=generated,
        papers=papers,
        performance=performance,
        description=description,
        benchmarks=table(
            bench.assign(reference=bench["reference"].map(_short_reference)) if "reference" in bench else bench,
            bench_cols,
            row_class="verdict",
            case_link="",
        ),
        scenes=scenes,
        convergence_figs=[f for _, f in conv_figs],
        horizon_figs=[f for _, f in horizon_figs],
        convergence=table(
            readable_options(conv),
            CONVERGENCE_COLUMNS,
        ),
        locking_figs=[f for _, f in lock_figs],
        locking=table(readable_options(lock)),
        images=images,
        checks=table(
            readable_options(checks),
            [
                "name",
                "scene",
                "model",
                "options",
                "slenderness",
                "points",
                "errors",
                "pairwise_orders",
                "observed_order",
                "min",
                "max",
                "expected",
                "verdict",
                "message",
            ],
            row_class="verdict",
        ),
        trust=table(
            readable_options(trust),
            [
                "model",
                "options",
                "tolerance",
                "slenderness_trusted",
                "slenderness_not",
                "points_trusted",
                "points_not",
                "round_off_from_points",
                "statement",
            ],
        ),
        speed_figs=[f for _, f in speed_figs],
        speed_summary=table(readable_options(sesum), case_link=""),
        results=table(
            res,
            [
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
            ],
            row_class="status",
            case_rows=True,
        ),
        meta_table=table(meta_rows),
        study_text=study_file.read_text(encoding="utf-8", errors="replace") if study_file.exists() else "",
    )
    index = out / "index.html"
    _write(index, page)
    if out != d:
        _write(out / "results.csv", (d / "results.csv").read_bytes())
    return index


def _check_cell(verdict: str, caveat: str) -> str:
    """A check's verdict in the cards table; with a caveat (errors against a reference whose round-off bound passes
    1e-6) marked * and the caveat as the cell's title."""
    cls = html.escape((verdict or "none").replace("/", ""))
    if not caveat:
        return f'<td class="chk-{cls}">{html.escape(verdict)}</td>'
    return f'<td class="chk-{cls}" title="{html.escape(caveat.lstrip("; "))}">{html.escape(verdict)}*</td>'


def cards_table(d: Path, out: Path) -> dict | None:
    """The study's verification cards (``d/verify/cards.json``, pdverify.verify.published): one row per card,
    its verdict, each check's verdict and a link to its card.html (relative to the report in ``out``)."""
    import os

    index = read_index(d)
    if not index or not index["cards"]:
        return None
    checks = list(dict.fromkeys(c["check"] for card in index["cards"] for c in card.get("checks", [])))
    head = "".join(f"<th>{html.escape(h)}</th>" for h in ["model", "options", "verdict", *checks, "cases", "card"])
    rows = []
    caveats = 0
    for card in index["cards"]:
        got = {c["check"]: c["verdict"] for c in card.get("checks", [])}
        said = {c["check"]: c["caveat"] for c in card.get("checks", []) if c.get("caveat")}
        caveats += len(said)
        link = Path(os.path.relpath(d / "verify" / card["folder"] / "card.html", out)).as_posix()
        opts = ", ".join(f"{k}={v}" for k, v in card.get("options", {}).items()) or "defaults"
        cells = [
            f'<td class="l">{html.escape(str(card["model"]))}</td>',
            f'<td class="l">{html.escape(opts)}</td>',
            f'<td class="verdict">{html.escape(card["verdict"])}</td>',
        ]
        cells += [_check_cell(got.get(c, ""), said.get(c, "")) for c in checks]
        cells.append(f"<td>{int(card.get('cases', 0))} ({int(card.get('failed_cases', 0))} failed)</td>")
        cells.append(f'<td class="l"><a href="{html.escape(link)}">card.html</a></td>')
        rows.append(f'<tr class="{html.escape(card["verdict"])}">{"".join(cells)}</tr>')
    n_fail = sum(c["verdict"] == "fail" for c in index["cards"])
    return {
        "table": Markup(
            f'<table class="sortable"><thead><tr>{head}</tr></thead><tbody>{"".join(rows)}</tbody></table>'
        ),
        "required": bool(index.get("required")),
        "n": len(index["cards"]),
        "n_fail": n_fail,
        "caveats": caveats,
    }


def environment() -> jinja2.Environment:
    """The templates, every value escaped unless it is Markup (tables and figures built here)."""
    return jinja2.Environment(loader=jinja2.FileSystemLoader(Path(__file__).parent / "templates"), autoescape=True)


def readable_options(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with its JSON ``options`` column as 'key=value, ...' text."""
    if df is None or df.empty or "options" not in df:
        return df
    return df.assign(options=df["options"].map(_options_text))


def _write(path: Path, data) -> None:
    """A report file written whole (temporary file, then renamed) or OutputError naming it (exit code 4)."""

    try:
        write_atomic(path, data)
    except OSError as exc:
        raise OutputError(f"{path}: cannot write the report ({exc.strerror or exc}); choose another --out") from None
