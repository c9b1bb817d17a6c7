"""The derived tables of a study (convergence, locking, speed vs error, trust), from its results rows.

Each table groups the rows by a few of their columns and computes one output per group from that group's
rows alone (in the study's order), the groups sorted by key (missing values last). Rows are dicts with
None for a missing value (:func:`rows_of` turns a results DataFrame into them).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..measure.metrics import at_round_off, gci, locking_slope, observed_order, pareto
from ..registry import models

GROUP = ("scene", "model", "options", "slenderness")  # a convergence series: every option but the grid
SHOWN = ("variant", "horizon_factor", "degree")  # columns repeated from the series' finest grid
LOCKING = ("scene", "model", "options", "points")
SPEED_ERROR = ("scene", "model", "variant", "case_id", "points", "total_s", "err_max", "pareto")
TRUST_TOLERANCE = 0.01
ROUND_OFF_VISIBLE = 1e-6  # an error that grows under refinement counts as trouble above this
EPS = float(np.finfo(float).eps)
# a growing error is called round-off only when it is within this factor of cond·eps: the estimate bounds the
# relative error of the solve up to the norm's dimension factor (1-norm estimate against a max-norm error)
ROUND_OFF_FACTOR = 100.0
# trust is judged per slenderness band (a model that is right for slender beams may be wrong for thick
# ones and vice versa): thick, where the shear deformation ~ (h/L)² is above the 1 % trust tolerance for
# any shear-flexible section; moderate; slender, where (L/h)² conditioning starts to matter
SLENDERNESS_BANDS = (("thick", 0.0, 10.0), ("moderate", 10.0, 100.0), ("slender", 100.0, float("inf")))
# a series converges far below the order its model's equations promise (Model.promised_order) when its observed order is
# under this fraction of it, on errors above round-off (the finest grid's error above ORDER_NOISE and 10x its bound)
FAR_BELOW = 0.5
ORDER_NOISE = 1e-10


def slenderness_band(slenderness) -> str:
    """'thick (L/h < 10)', 'moderate (10 <= L/h < 100)', 'slender (L/h >= 100)', or '' when unknown."""
    if slenderness is None:
        return ""
    for name, lo, hi in SLENDERNESS_BANDS:
        if lo <= float(slenderness) < hi:
            if lo == 0.0:
                return f"{name} (L/h < {hi:g})"
            return f"{name} ({lo:g} <= L/h < {hi:g})" if hi < float("inf") else f"{name} (L/h >= {lo:g})"
    return ""


def _none(v):
    """A missing value (NaN, pandas' NA) as None: hashable, equal to itself."""
    if v is None or v is pd.NA or (isinstance(v, float) and v != v):
        return None
    return v


def _float(v) -> float:
    return float("nan") if v is None else float(v)


def rows_of(df: pd.DataFrame) -> list[dict]:
    """A results table's rows as dicts, every missing value None."""
    return [{k: _none(v) for k, v in r.items()} for r in df.to_dict("records")]


def _ok(r: dict) -> bool:
    return r.get("status") == "ok"


# ---- one group each ---------------------------------------------------------------------------------


def _convergence(key: tuple, rows: list[dict]) -> list[dict]:
    """The observed order of one series (fit of log error vs log spacing over its grids, R^2) and the GCI of
    its three finest grids; nothing below three distinct grids (never an order from two points). ``series``: "grid"
    (the horizon in spacings: it shrinks with the grid, the model's promised order applies) or "fixed horizon" (a
    ``horizon_length`` held while the grid is refined: the error tends to the model error, its m-convergence is in
    nonlocal.csv, so no order is promised here). A quantity whose every error is below the round-off level
    (``metrics.ROUND_OFF_LEVEL``: the model is exact for it) gets no order (``at_round_off``)."""
    rows = [r for r in rows if _ok(r)]
    if not rows:
        return []
    order = np.argsort([_float(r.get("spacing")) for r in rows], kind="stable")
    rows = [rows[i] for i in order]
    h = np.array([_float(r.get("spacing")) for r in rows])
    w = np.array([_float(r.get("w_at_max")) for r in rows])
    n_grids = len(np.unique(h))
    if n_grids < 3:
        return []
    out = []
    # the model's own quantity first (an order check reads that row), then every other one the study measures
    extra = [c[len("err_max_") :] for c in dict.fromkeys(k for r in rows for k in r) if c.startswith("err_max_")]
    series = "fixed horizon" if np.isfinite(_float(rows[0].get("horizon_length"))) else "grid"
    for quantity, column in [(rows[0].get("quantity") or "w", "err_max"), *((q, f"err_max_{q}") for q in extra)]:
        err = np.array([_float(r.get(column)) for r in rows])
        if column != "err_max" and not np.isfinite(err).any():
            continue  # the model or the reference gives none of it
        exact = at_round_off(err)
        p, r2 = (float("nan"), float("nan")) if exact else observed_order(h, err)
        flag = (
            order_flag(key[1], p, err[-1], _float(rows[-1].get("error_bound")), rows[0].get("options"))
            if series == "grid"
            else {"promised_order": float("nan"), "below_order": False}
        )
        out.append(
            dict(
                zip(GROUP, key),
                **{c: rows[0].get(c) for c in SHOWN},
                quantity=quantity,
                n_grids=int(n_grids),
                spacings=" ".join(f"{v:.4g}" for v in h),
                errors=" ".join(f"{v:.3e}" for v in err),
                observed_order=p,
                r2=r2,
                series=series,
                at_round_off=exact,
                **flag,
                **(gci(h, w) if column == "err_max" else {}),
            )
        )
    return out


def order_flag(model: str, observed: float, finest: float, bound: float, options=None) -> dict:
    """``promised_order`` (the model's :meth:`~pdverify.core.contract.Model.promised_order` with the series'
    ``options``, a dict or its JSON text) and ``below_order``: the observed order is under FAR_BELOW of it on errors
    above round-off (an error at round-off has no order)."""
    m = models().get(model)
    if isinstance(options, str):
        options = json.loads(options) if options.strip() else {}
    promised = float(m.promised_order(options or {})) if m is not None and m.order else float("nan")
    resolved = finest > max(ORDER_NOISE, 10 * (bound if np.isfinite(bound) else 0.0))
    below = bool(np.isfinite(observed) and np.isfinite(promised) and resolved and observed < FAR_BELOW * promised)
    return {"promised_order": promised, "below_order": below}


def _locking(key: tuple, rows: list[dict]) -> list[dict]:
    """Slope of log error vs log slenderness at one grid (0: locking-free) and the slenderness where the
    error first passes 1 %."""
    rows = [r for r in rows if _ok(r) and r.get("slenderness") is not None]
    s = np.array([_float(r["slenderness"]) for r in rows])
    if len(np.unique(s)) < 2:
        return []
    slope, at1 = locking_slope(s, np.array([_float(r.get("err_max")) for r in rows]))
    return [
        dict(
            zip(LOCKING, key),
            **{c: rows[0].get(c) for c in SHOWN},
            n=len(rows),
            locking_slope=slope,
            slenderness_at_1pct=at1,
        )
    ]


def _with_error(rows: list[dict]) -> list[dict]:
    return [r for r in rows if _ok(r) and r.get("err_max") is not None]  # runs without a reference: no error


def _pareto(key: tuple, rows: list[dict]) -> dict:
    """case_id -> on the scene's Pareto front of (total seconds, error)."""
    rows = _with_error(rows)
    if not rows:
        return {}
    front = pareto([_float(r.get("total_s")) for r in rows], [r["err_max"] for r in rows])
    return {r["case_id"]: bool(f) for r, f in zip(rows, front)}


def _cheapest(key: tuple, rows: list[dict]) -> list[dict]:
    """For one (scene, model): the cheapest case reaching 1 % and 0.1 % error."""
    rows = _with_error(rows)
    if not rows:
        return []
    out = dict(zip(("scene", "model"), key))
    for tol, label in ((1e-2, "1pct"), (1e-3, "0.1pct")):
        hit = [r for r in rows if r["err_max"] <= tol]
        best = hit[int(np.argmin([_float(r.get("total_s")) for r in hit]))] if hit else None
        out[f"cheapest_{label}_case"] = best["case_id"] if best else ""
        out[f"cheapest_{label}_s"] = _float(best.get("total_s")) if best else float("nan")
    return [out]


def _ranges(values, ok) -> str:
    """'a – b' runs of consecutive ok values (sorted), comma separated; '' when none."""
    out, run = [], []
    for v, good in zip(values, ok):
        if good:
            run.append(v)
        elif run:
            out.append(run)
            run = []
    if run:
        out.append(run)
    f = lambda v: f"{v:g}"  # noqa: E731
    return ", ".join(f(r[0]) if len(r) == 1 else f"{f(r[0])} – {f(r[-1])}" for r in out)


def _trust(key: tuple, rows: list[dict], tol: float = TRUST_TOLERANCE) -> list[dict]:
    """For one model, option set and slenderness band: the slenderness values and grids at which every scene
    is within ``tol`` of its reference, and the grid from which refining makes the error grow past
    ``ROUND_OFF_VISIBLE``: ``round_off_from_points`` when that error is within ``ROUND_OFF_FACTOR`` of the
    case's cond·eps (round-off explains it), ``growth_from_points`` otherwise (far above cond·eps, or no
    condition estimate: not shown to be round-off). A failed case counts as not trustworthy."""
    rows = [r for r in rows if '"model": "none"' not in (r.get("reference") or "")]
    if not rows:
        return []
    model, options, band = key
    ok = [_ok(r) for r in rows]
    err = [_float(r.get("err_max")) for r in rows]
    good = [o and e <= tol for o, e in zip(ok, err)]  # NaN errors compare False
    slen = [-1.0 if r.get("slenderness") is None else float(r["slenderness"]) for r in rows]
    points = [_float(r.get("points")) if any(r.get("points") is None for r in rows) else r.get("points") for r in rows]
    by_sn: dict = {}  # per slenderness: some grid at which every case is good
    for i in range(len(rows)):
        by_sn.setdefault(slen[i], {}).setdefault(points[i], []).append(good[i])
    by_s = {s: any(all(v) for v in by_n.values()) for s, by_n in sorted(by_sn.items())}
    sl = [(s, g) for s, g in by_s.items() if s > 0]
    trusted_s = {s for s, g in by_s.items() if g}
    by_n: dict = {}
    for i in range(len(rows)):
        if not trusted_s or slen[i] in trusted_s:
            by_n.setdefault(points[i], []).append(good[i])
    by_n = {n: all(v) for n, v in sorted(by_n.items())}
    series: dict = {}
    for i, r in enumerate(rows):
        if ok[i]:
            series.setdefault((r.get("scene"), slen[i]), []).append((points[i], err[i], _float(r.get("cond"))))
    floor, growth = [], []
    for e in series.values():
        e = sorted(e, key=lambda t: t[0])  # stable: equal grids keep their row order
        rise = [k for k in range(1, len(e)) if e[k][1] > 2.0 * e[k - 1][1] and e[k][1] > ROUND_OFF_VISIBLE]
        if rise:
            n, err_k, cond = e[rise[0]]
            (floor if cond == cond and err_k <= ROUND_OFF_FACTOR * cond * EPS else growth).append((int(n), err_k, cond))
    row = {
        "model": model,
        "options": options,
        "slenderness_band": band,
        "tolerance": tol,
        "slenderness_trusted": _ranges([s for s, _ in sl], [g for _, g in sl]) if sl else "",
        "slenderness_not": ", ".join(f"{s:g}" for s, g in sl if not g),
        "points_trusted": _ranges(list(by_n), list(by_n.values())),
        "points_not": ", ".join(str(int(n)) for n, g in by_n.items() if not g),
        "round_off_from_points": min(floor)[0] if floor else None,
        "growth_from_points": min(growth)[0] if growth else None,
    }
    parts = [f"{model}" + (f" [{band}]" if band else "")]
    if sl:
        parts.append(f"within {tol:.0%} for L/h {row['slenderness_trusted'] or 'none of the values tried'}")
    parts.append(f"on grids of {row['points_trusted'] or 'none of the sizes tried'} points")
    if floor:
        n, e, c = min(floor)
        parts.append(
            f"(from {n} points refining makes the error grow past {ROUND_OFF_VISIBLE:g}: round-off, "
            f"error {e:.2g} within {ROUND_OFF_FACTOR:g} cond·eps = {c * EPS:.2g})"
        )
    if growth:
        n, e, c = min(growth)
        why = (
            f"far above cond·eps = {c * EPS:.2g}: not round-off"
            if c == c
            else "no condition estimate: not shown to be round-off"
        )
        parts.append(
            f"(from {n} points refining makes the error grow past {ROUND_OFF_VISIBLE:g}: error {e:.2g}, {why})"
        )
    row["statement"] = " ".join(parts)
    return [row]


# ---- groupings --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Grouping:
    key: Callable[[dict], tuple]  # a row's group (None for a missing value)
    compute: Callable[[tuple, list], Any]  # (key, the group's rows in the study's order) -> its output


def _columns(*names):
    return lambda r: tuple(_none(r.get(k)) for k in names)


GROUPINGS = {
    "convergence": Grouping(_columns(*GROUP), _convergence),
    "locking": Grouping(_columns(*LOCKING), _locking),
    "pareto": Grouping(_columns("scene"), _pareto),
    "cheapest": Grouping(_columns("scene", "model"), _cheapest),
    "trust": Grouping(
        lambda r: (_none(r.get("model")), _none(r.get("options")) or "", slenderness_band(_none(r.get("slenderness")))),
        _trust,
    ),
}


def _order(key: tuple):
    return tuple((v is None, v if v is not None else 0) for v in key)  # missing last, as pandas sorts


def grouped(name: str, rows: list[dict], compute=None) -> list[tuple[tuple, Any]]:
    """(key, output) of every group of ``rows`` under grouping ``name``, keys sorted."""
    g = GROUPINGS[name]
    compute = compute or g.compute
    members: dict = {}
    for r in rows:
        members.setdefault(g.key(r), []).append(r)
    return [(key, compute(key, members[key])) for key in sorted(members, key=_order)]


# ---- the tables, as rows (what the runner writes) ----------------------------------------------------


def _rows(data) -> list[dict]:
    return rows_of(data) if isinstance(data, pd.DataFrame) else data


EMPTY_CONVERGENCE = [
    *GROUP,
    "n_grids",
    "observed_order",
    "r2",
    "promised_order",
    "below_order",
]  # the header when no case is ok


def convergence_rows(rows: list[dict]) -> list[dict]:
    return [o for _, out in grouped("convergence", rows) for o in out]


def locking_rows(rows: list[dict]) -> list[dict]:
    return [o for _, out in grouped("locking", rows) for o in out]


def speed_error_rows(rows: list[dict]) -> tuple[list[dict], list[dict]]:
    """Every case with an error: (total seconds, error) and whether it is on its scene's Pareto front (in
    the study's order); per scene and model, the cheapest case reaching 1 % and 0.1 %."""
    kept = _with_error(rows)
    if not kept:
        return [], []
    front = {cid: f for _, flags in grouped("pareto", rows) for cid, f in flags.items()}
    se = [{**{c: r.get(c) for c in SPEED_ERROR[:-1]}, "pareto": front[r["case_id"]]} for r in kept]
    return se, [o for _, out in grouped("cheapest", rows) for o in out]


def trust_rows(rows: list[dict], tol: float = TRUST_TOLERANCE) -> list[dict]:
    """Per model and option set: where every scene is within ``tol`` of its reference (:func:`_trust`); none
    when no case has an error at all (every one failed before it was measured)."""
    if not any("err_max" in r for r in rows):
        return []
    compute = None if tol == TRUST_TOLERANCE else (lambda key, group: _trust(key, group, tol))
    return [o for _, out in grouped("trust", rows, compute) for o in out]


def trust_table(results, tol: float = TRUST_TOLERANCE) -> pd.DataFrame:
    """:func:`trust_rows` as a DataFrame; ``results``: row dicts or a DataFrame."""
    return pd.DataFrame(trust_rows(_rows(results), tol))
