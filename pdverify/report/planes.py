"""The index's δ–Δx planes (docs/nonlocal.md): per PD model and variant, per scene, the errors of the runs that give
their horizon as a length (``horizon_length``), split by :mod:`pdverify.study.split`, along the three paths:

* m-convergence: at each horizon δ, the discretisation error (discrete − continuum) against the spacing Δx;
* the model error (continuum − local) against δ;
* δm-convergence: at each fixed m = δ/Δx, the total error (discrete − local) against δ.

The orders of nonlocal.csv (:mod:`pdverify.study.nonlocal_table`) are written in the figure's title.
"""

from __future__ import annotations

import re

import pandas as pd

from ..study.nonlocal_table import series_options
from .plots import Axis, Figure, Palette, Series
from .tables import tags
from .text import fixed, fmt, key_options, options_of, variant_key, variant_of

NEEDED = ("err_model", "err_disc", "err_max", "horizon", "spacing", "m")
PATH_SHORT = {"m-convergence": "m", "model error": "model", "dm-convergence": "δm"}


def _orders(nonlocal_table: pd.DataFrame, scene: str, model: str, options: str) -> str:
    """'orders: m 2.00 (δ = 0.1), model 2.01, δm 1.98 (m = 8)': each path's fitted orders of this series."""
    if nonlocal_table.empty:
        return ""
    sel = nonlocal_table[(nonlocal_table["scene"] == scene) & (nonlocal_table["model"] == model)]
    parts = []
    for _, r in sel.iterrows():
        doubt = str(r.get("continuum_in_doubt")).lower() == "true"  # the continuum's own error could decide it
        exact = str(r.get("at_round_off")).lower() == "true"  # every error below the round-off level
        if _strip(r.get("options")) != options or (pd.isna(r.get("observed_order")) and not (doubt or exact)):
            continue
        held = str(r.get("held") or "").replace("horizon = ", "δ = ")
        path = PATH_SHORT.get(r["path"], r["path"])
        no_limit = isinstance(r.get("no_limit"), str) and bool(r.get("no_limit"))
        value = "none (no limit at fixed δ)" if no_limit else "none (continuum in doubt)" if doubt else None
        value = value or ("none (exact to round-off)" if exact else None)
        value = value or fixed(r["observed_order"], 2)
        parts.append(f"{path} {value}" + (f" ({held})" if held else ""))
    return "orders: " + ", ".join(parts) if parts else ""


def _strip(options) -> str:
    """A row's options without its grid and horizon (nonlocal.csv writes its series' options so)."""
    return series_options(options if isinstance(options, str) else None)


def _anchor(key: str) -> str:
    return "delta-dx-" + re.sub(r"[^a-z0-9]+", "-", key.lower()).strip("-")


def _figure(g: pd.DataFrame, scene: str, length: str, model: str, variant: str, orders: str) -> Figure:
    series = []
    for i, (delta, gd) in enumerate(sorted(g.groupby("horizon"), key=lambda t: -t[0])):
        gd = gd.sort_values("spacing")
        good = gd["err_disc"] > 0
        if good.sum():
            series.append(
                Series(
                    f"discretisation, δ = {fmt(delta)}",
                    gd.loc[good, "spacing"].to_numpy(float),
                    gd.loc[good, "err_disc"].to_numpy(float),
                    model,
                    variant,
                    i,
                    "line+points",
                    labels=[f"m={fmt(v)}" for v in gd.loc[good, "m"]],
                )
            )
    finest = g.sort_values("points").groupby("horizon").tail(1).sort_values("horizon")
    good = finest["err_model"] > 0
    if good.sum():
        series.append(
            Series(
                "model error (continuum − local) against δ",
                finest.loc[good, "horizon"].to_numpy(float),
                finest.loc[good, "err_model"].to_numpy(float),
                model,
                variant,
                -1,
                "dash",
            )
        )
    for j, (m, gm) in enumerate(sorted(g.groupby(g["m"].round(6)))):
        gm = gm.sort_values("horizon")
        if gm["horizon"].nunique() >= 2 and (gm["err_max"] > 0).all():
            series.append(
                Series(
                    f"total at m = {fmt(m)} against δ",
                    gm["horizon"].to_numpy(float),
                    gm["err_max"].to_numpy(float),
                    model,
                    variant,
                    10 + j,
                    "points",
                )
            )
    return Figure(
        f"{scene}" + (f": {orders}" if orders else ""),
        Axis(f"Δx (discretisation), δ (model error, total) ({length})", length, log=True),
        Axis("max rel. error (–)", "", log=True),
        series,
        small=True,
        caption="Lines: discrete − continuum at each horizon δ against Δx; dashed: continuum − local against δ; "
        "points: discrete − local at each fixed m against δ. Errors of 0 are not drawn.",
    )


def planes(data, palette: Palette) -> list[tuple[str, str, list]]:
    """(title, anchor, figures) of the δ–Δx figures, one per PD model and variant."""
    res = data.ok
    if any(c not in res for c in NEEDED):
        return []
    res = res[res["err_disc"].notna() & res["horizon"].notna() & res["spacing"].notna()]
    if res.empty:
        return []
    nl = data.table("nonlocal")
    keys = [variant_key(str(r["model"]), options_of(r.get("options"))) for _, r in res.iterrows()]
    groups = []
    for key, g in res.assign(_key=keys).groupby("_key", sort=True):
        model = str(g["model"].iloc[0])
        opts = options_of(g["options"].iloc[0])
        shown = key_options(model, opts)
        title = f"{model}: " + (", ".join(f"{k}={v}" for k, v in shown.items()) or "defaults")
        figures = []
        variant = variant_of(model, opts)
        for scene, gs in g.groupby("scene", sort=False):
            for options, go in gs.groupby(gs["options"].map(_strip), sort=True):
                if go["horizon"].nunique() < 1 or len(go) < 2:
                    continue
                orders = _orders(nl, scene, model, options)
                fig = _figure(go, str(scene), data.length(scene=scene), model, variant, orders)
                figures.append(
                    fig.html(tags(scenes=[scene], papers=[data.scene_paper.get(scene, "")], tag_model=False))
                )
        if figures:
            groups.append((title, _anchor(key), figures))
    return groups
