"""The summary at the top of the report: one row per model and variant, its verification card's verdict and each
check's (linking to the card), and what the study measured on its scenes: the observed orders (linking to the
convergence plots), the worst error at the finest grid (linking to that scene's error figure) and its cost
(linking to the scene's work–precision figure)."""

from __future__ import annotations

import html
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
from markupsafe import Markup

from ..registry import get_model
from ..verify.card import check_anchor
from ..verify.published import read_index
from .inputs import StudyFolder
from .quantity_figures import NAME, QUANTITIES, SYMBOL
from .tables import tags
from .text import fixed, folder, key_options, options_of, sig, slug, variant_key, variant_of

VERDICTS = ("pass", "fail")
# a series whose error is below this on every grid reproduces its reference to round-off: its fitted "order" is
# the round-off's growth under refinement (about -2 for a fourth-order operator), not the model's
ROUND_OFF = 1e-9


def _check_cell(verdict: str, caveat: str, summary: str = "", href: str | None = None) -> str:
    """A check's verdict; with a caveat (errors against a reference whose round-off bound passes 1e-6) marked *
    and the caveat in the cell's title, beside the check's measured summary; ``href``: the check on its card."""
    cls = html.escape((verdict or "none").replace("/", ""))
    text = html.escape(verdict) + ("*" if caveat else "")
    if href:
        text = f'<a href="{html.escape(href)}">{text}</a>'
    title = "; ".join(t for t in (summary, caveat.lstrip("; ") if caveat else "") if t)
    if not title:
        return f'<td class="chk-{cls}">{text}</td>'
    return f'<td class="chk-{cls}" title="{html.escape(title)}">{text}</td>'


def conv_anchor(key: str) -> str:
    """The id of a model and variant's convergence plots."""
    return "conv-" + slug(key)


def scene_anchor(scene: str) -> str:
    """The id of a scene's error figures."""
    return "scene-" + slug(scene)


def cost_anchor(scene: str) -> str:
    """The id of a scene's work–precision figure."""
    return "wp-" + slug(scene)


@dataclass
class Row:
    """What the summary says of one model and variant."""

    model: str
    options: dict[str, str]
    key: str
    variant: str
    card: dict | None = None
    card_href: str = ""
    scenes: list[str] = field(default_factory=list)
    papers: list[str] = field(default_factory=list)
    orders: list[float] = field(default_factory=list)
    quantity_orders: dict[str, list[float]] = field(default_factory=dict)  # rotation, moment, shear, axial
    worst: tuple[float, str, int] | None = None  # (error, scene, points) at the finest grid
    cost: tuple[float, str, int] | None = None  # (seconds, scene, points) at the finest grid
    exact_series: int = 0  # convergence series at round-off on every grid (no order to observe)


def _study_rows(data: StudyFolder) -> dict[str, Row]:
    rows: dict[str, Row] = {}
    res = data.res
    for (model, options), g in res.groupby(["model", res["options"].fillna("")], sort=True):
        opts = options_of(options)
        key = variant_key(model, opts)
        row = rows.setdefault(key, Row(model, key_options(model, opts), key, variant_of(model, opts)))
        row.scenes += [s for s in dict.fromkeys(g["scene"]) if s not in row.scenes]
        row.papers += [p for p in dict.fromkeys(g["scene_file"].map(folder)) if p not in row.papers]
        ok = g[(g["status"] == "ok") & g["err_max"].notna()]
        for (scene, _sl), gs in ok.groupby(["scene", ok["slenderness"].fillna(-1)], sort=False):
            fine = gs.sort_values("points", na_position="first").iloc[-1]
            points = int(fine["points"]) if pd.notna(fine["points"]) else 0
            if row.worst is None or fine["err_max"] > row.worst[0]:
                row.worst = (float(fine["err_max"]), scene, points)
            t = fine.get("total_s")
            if pd.notna(t) and (row.cost is None or t > row.cost[0]):
                row.cost = (float(t), scene, points)
    conv = data.table("convergence")
    if not conv.empty:
        for _, r in conv.iterrows():
            key = variant_key(str(r["model"]), options_of(r.get("options")))
            if key not in rows or pd.isna(r["observed_order"]):
                continue
            quantity = r.get("quantity")
            if isinstance(quantity, str) and quantity in SYMBOL:  # another quantity than the model's own
                rows[key].quantity_orders.setdefault(quantity, []).append(float(r["observed_order"]))
            elif max(float(v) for v in str(r["errors"]).split()) < ROUND_OFF:
                rows[key].exact_series += 1
            else:
                rows[key].orders.append(float(r["observed_order"]))
    return rows


def summary(data: StudyFolder, out: Path, conv_keys: set[str], scene_ids: set[str], cost_ids: set[str]) -> dict:
    """The summary table (Markup) and what the page says around it: the cards' count, failures, whether the study
    requires them, caveats. ``conv_keys``, ``scene_ids``, ``cost_ids``: the convergence groups, scene sections
    and work–precision figures the page holds (a cell links only to evidence that is there)."""
    rows = _study_rows(data)
    index = read_index(data.d) or {"cards": [], "required": False}
    for card in index["cards"]:
        opts = card.get("options", {})
        key = variant_key(card["model"], opts)
        row = rows.get(key) or rows.setdefault(
            key, Row(card["model"], key_options(card["model"], opts), key, variant_of(card["model"], opts))
        )
        row.card = card
        row.card_href = Path(os.path.relpath(data.d / "verify" / card["folder"] / "card.html", out)).as_posix()
    judged = {c["check"] for card in index["cards"] for c in card.get("checks", []) if c["verdict"] in VERDICTS}
    # the checks that judge something (pass or fail on some card): the others inform, on the card
    checks = [c for c in dict.fromkeys(c["check"] for card in index["cards"] for c in card["checks"]) if c in judged]
    head = ["model", "options", "card"]
    head += ["observed orders on the study's scenes (–)", "promised order (–)"]
    head += ["worst max rel. error at the finest grid (–)", "most costly finest grid (s)"]
    head += checks
    head += ["papers"]
    cells_head = "".join(
        f'<th class="{"l" if h in ("model", "options", "papers") else "chk" if h in checks else ""}">'
        f"{html.escape(h)}</th>"
        for h in head
    )
    body = []
    caveats = 0
    for row in sorted(rows.values(), key=lambda r: (r.model, r.key)):
        card = row.card
        opts = ", ".join(f"{k}={v}" for k, v in row.options.items()) or "defaults"
        cells = [f'<td class="l">{html.escape(row.model)}</td>', f'<td class="l">{html.escape(opts)}</td>']
        if card is not None:
            cells.append(
                f'<td class="verdict"><a href="{html.escape(row.card_href)}">{html.escape(card["verdict"])}</a></td>'
            )
        else:
            cells.append('<td class="verdict nocard" title="the study ran no card for it">–</td>')
        cells += _measured_cells(row, conv_keys, scene_ids, cost_ids)
        got = {c["check"]: c for c in card.get("checks", [])} if card is not None else {}
        for name in checks:
            c = got.get(name)
            if c is None:
                cells.append('<td class="chk-none"></td>')
                continue
            caveats += bool(c.get("caveat"))
            cells.append(
                _check_cell(
                    c["verdict"], c.get("caveat", ""), c.get("summary", ""), f"{row.card_href}#{check_anchor(name)}"
                )
            )
        cells.append(f'<td class="l">{html.escape(", ".join(row.papers))}</td>')
        klass = card["verdict"] if card is not None else "nocard"
        attrs = tags(row.model, row.variant, row.scenes, row.papers)
        body.append(f'<tr class="f {html.escape(klass)}"{attrs}>{"".join(cells)}</tr>')
    table = Markup(
        f'<div class="wide"><table class="sortable summary"><thead><tr>{cells_head}</tr></thead>'
        f"<tbody>{''.join(body)}</tbody></table></div>"
    )
    cards = index["cards"]
    return {
        "table": table,
        "cards": bool(cards),
        "required": bool(index.get("required")),
        "n": len(cards),
        "n_fail": sum(c["verdict"] == "fail" for c in cards),
        "caveats": caveats,
    }


def _promised(model: str, card: dict | None) -> float | None:
    """The order the model promises (its card's expected order); None for an exact solution (no grid error)."""
    try:
        m = get_model(model)
    except Exception:  # a model of another installation
        m = None
    if m is not None and type(m).__module__.startswith("pdverify.exact"):
        return None
    if card is not None and card.get("expected_order") is not None:
        return float(card["expected_order"])
    return float(m.order) if m is not None else None


def _range(orders: list[float]) -> str:
    """Fitted orders as their range ('1.95 to 2.18'), one value when they agree to two decimals."""
    lo, hi = min(orders), max(orders)
    return fixed(lo, 2) if fixed(lo, 2) == fixed(hi, 2) else f"{fixed(lo, 2)} to {fixed(hi, 2)}"


def _measured_cells(row: Row, conv_keys: set[str], scene_ids: set[str], cost_ids: set[str]) -> list[str]:
    def link(text: str | list[str], anchor: str, present: set[str], title: str = "", klass: str = "") -> str:
        """A cell of ``text`` (a list: one line each), linked to ``anchor`` where the page holds it."""
        t = f' title="{html.escape(title)}"' if title else ""
        t += f' class="{klass}"' if klass else ""
        shown = "<br>".join(map(html.escape, [text] if isinstance(text, str) else text))
        if anchor in present:
            return f'<td{t}><a href="#{html.escape(anchor)}">{shown}</a></td>'
        return f"<td{t}>{shown}</td>"

    out = []
    orders = [o for o in row.orders if np.isfinite(o)]
    exact = (
        f"; {row.exact_series} series at round-off on every grid (error < {ROUND_OFF:g}) left out"
        if row.exact_series
        else ""
    )
    others = {q: [o for o in v if np.isfinite(o)] for q, v in row.quantity_orders.items()}
    others = {q: v for q, v in others.items() if v}
    if orders or others:
        lines = ([_range(orders)] if orders else []) + [
            f"{SYMBOL[q]}: {_range(v)}" for q in QUANTITIES if q in others for v in [others[q]]
        ]
        named = [("the model's own quantity", orders), *((NAME[q], others[q]) for q in QUANTITIES if q in others)]
        title = "; ".join(
            f"{len(v)} convergence series of {name}; fitted orders: " + ", ".join(fixed(o, 3) for o in v)
            for name, v in named
            if v
        )
        out.append(link(lines, conv_anchor(row.key), conv_keys, title + exact, "orders"))
    elif row.exact_series:
        out.append(link("round-off", conv_anchor(row.key), conv_keys, exact.lstrip("; ")))
    else:
        out.append('<td title="no series of three or more grids in this study"></td>')
    promised = _promised(row.model, row.card)
    if promised is None:
        out.append('<td title="an exact solution: no grid error">–</td>')
    else:
        out.append(f"<td>{promised:g}</td>")
    if row.worst is not None:
        e, scene, n = row.worst
        out.append(link(sig(e, 3), scene_anchor(scene), scene_ids, f"{scene}, {n} points: {e!r}"))
    else:
        out.append('<td title="no case of this model measured against a reference"></td>')
    if row.cost is not None:
        t, scene, n = row.cost
        out.append(link(sig(t, 2), cost_anchor(scene), cost_ids, f"{scene}, {n} points: {t:.4g} s"))
    else:
        out.append("<td></td>")
    return out
