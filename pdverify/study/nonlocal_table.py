"""The nonlocal table of a study (``nonlocal.csv``, docs/nonlocal.md): for every PD series whose rows carry the split
errors (:mod:`pdverify.study.split`), three orders, each a least-squares fit of log error against log length over
three or more points (``observed_order``, with ``r2``) and the slope of its two finest points (``finest_order``):

* ``m-convergence``: ``err_disc`` (discrete - continuum) against the spacing dx at a fixed horizon delta;
* ``model error``: ``err_model`` (continuum - local) against delta (one value per delta: its finest grid's);
* ``dm-convergence``: ``err_max`` (discrete - local, the total) against delta at a fixed m = delta / dx.

The first two are measured against the model's continuum, which reports its own error (``continuum_error``, an
extrapolation's estimate): where that estimate is above a tenth of the smallest error of the fit, the continuum
could decide the order, and the row gives none (``continuum_in_doubt``; its errors are still listed). Where the model
has no limit at that horizon (``continuum_no_limit`` of its rows) there is no continuum to converge to: the row gives
none either and says why (``no_limit``). A fit whose every error is below ``metrics.ROUND_OFF_LEVEL`` (the variant
reproduces the load's solution: a uniform load on the corrected variants) gives none (``at_round_off``), as in
convergence.csv.

A series is the rows of one scene, model, slenderness and option set but for the grid and the horizon.
"""

from __future__ import annotations

import json

import numpy as np

from ..measure.metrics import at_round_off, log_slope, observed_order

KEY = ("scene", "model", "options", "slenderness")
CONTINUUM_SHARE = 0.1  # a continuum whose own error estimate passes this share of an error could decide it
HORIZON_KEYS = ("horizon", "horizon_length", "continuum", "continuum_m")  # not in a series' key
PATHS = {
    "m-convergence": ("spacing", "err_disc", "horizon"),
    "model error": ("horizon", "err_model", None),
    "dm-convergence": ("horizon", "err_max", "m"),
}


def _f(v) -> float:
    return float("nan") if v is None else float(v)


def _text(v) -> str:
    """A text cell: "" for None or NaN (a column some rows lack)."""
    return v if isinstance(v, str) else ""


def series_options(options: str | None) -> str:
    """The options of a row without its grid and horizon (the key of a nonlocal series)."""
    try:
        opts = json.loads(options or "{}")
    except ValueError:
        return options or ""
    return json.dumps({k: v for k, v in opts.items() if k not in HORIZON_KEYS}, sort_keys=True)


def _fit(path: str, held, rows: list[dict], base: dict) -> dict | None:
    """One order: the rows' error against their length, one point per length (the finest grid's)."""
    xcol, ecol, _ = PATHS[path]
    by_x: dict = {}
    for r in sorted(rows, key=lambda r: -_f(r.get("points"))):  # the finest grid first: kept per length
        x = round(_f(r.get(xcol)), 12)
        if np.isfinite(x) and x not in by_x:
            by_x[x] = (_f(r.get(ecol)), _f(r.get("continuum_error")), _text(r.get("continuum_no_limit")))
    if len(by_x) < 3:
        return None
    x = np.array(sorted(by_x))
    e, own = (np.array([by_x[v][i] for v in x]) for i in (0, 1))
    no_limit = "" if path == "dm-convergence" else next((by_x[v][2] for v in x if by_x[v][2]), "")
    doubt = path != "dm-convergence" and (
        bool(no_limit) or bool(np.nanmax(np.append(own, 0.0)) > CONTINUUM_SHARE * e.min())
    )
    exact = at_round_off(e)  # no order to measure
    p, r2 = observed_order(x, e) if not (doubt or exact) else (float("nan"), float("nan"))
    fine = log_slope(x[:2], e[:2])[0] if not (doubt or exact) else float("nan")
    return {
        **base,
        "path": path,
        "held": "" if held is None else f"{PATHS[path][2]} = {held:.6g}",
        "n": len(x),
        "lengths": " ".join(f"{v:.4g}" for v in x),
        "errors": " ".join(f"{v:.3e}" for v in e),
        "observed_order": p,
        "r2": r2,
        "finest_order": fine,
        "continuum_in_doubt": doubt,
        "no_limit": no_limit,
        "at_round_off": exact,
    }


def nonlocal_rows(rows: list[dict]) -> list[dict]:
    """The nonlocal table's rows (module docstring), series sorted by their key, paths in the order of :data:`PATHS`."""
    series: dict = {}
    for r in rows:
        if r.get("status") not in ("ok", "suspect") or r.get("err_disc") is None:
            continue
        key = (r.get("scene"), r.get("model"), series_options(r.get("options")), r.get("slenderness"))
        series.setdefault(key, []).append(r)
    out = []
    for key in sorted(series, key=lambda k: tuple((v is None, str(v)) for v in k)):
        group = series[key]
        base = dict(zip(KEY, key), variant=group[0].get("variant"), quantity=group[0].get("quantity"))
        for path, (_, _, hold) in PATHS.items():
            if hold is None:
                found = _fit(path, None, group, base)
                out += [found] if found else []
                continue
            held: dict = {}
            for r in group:
                held.setdefault(round(_f(r.get(hold)), 9), []).append(r)
            for value in sorted(held):
                found = _fit(path, value, held[value], base) if np.isfinite(value) else None
                out += [found] if found else []
    return out
