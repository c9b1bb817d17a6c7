"""The index's figures of sweeps: per convergence series a log–log plot of error against spacing with its fitted
order written on it and the promised slope beside; per scene the work–precision plot (error against time), the
error against slenderness (locking) and against the horizon factor; the δ–Δx plane's hook."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from markupsafe import Markup

from ..registry import get_model
from .beam_errors import line_key
from .inputs import StudyFolder
from .planes import planes
from .plots import Axis, Figure, Palette, Series, positive
from .quantity_figures import NAME
from .summary import conv_anchor, cost_anchor
from .tables import tags
from .text import fixed, fmt, folder, key_options, label, options_of, variant_key, variant_of

ERROR = "max rel. error (–)"


@dataclass
class Group:
    """Figures under one heading (a model and variant's convergence series, a scene's sweep)."""

    title: str
    anchor: str
    figures: list[Markup] = field(default_factory=list)


def _series_key(r) -> tuple:
    """A convergence series' key in convergence.csv and checks.csv (a missing slenderness as None: NaN is not
    equal to itself)."""
    sl = r.get("slenderness")
    return (r["scene"], r["model"], r.get("options"), None if pd.isna(sl) else float(sl), other_quantity(r))


def other_quantity(r) -> str | None:
    """The quantity of a convergence series or check other than the model's own (rotation, moment, shear, axial),
    None for the model's own (w, or e.g. pd-rod's u)."""
    q = r.get("quantity")
    return q if isinstance(q, str) and q in NAME else None


def _check_bands(checks: pd.DataFrame) -> dict[tuple, tuple[float, str]]:
    """Per checked series: the slope to draw (the middle of its band, or its lower bound) and its legend text. A
    check that matched no series (verdict missing: no scene) draws none."""
    out = {}
    for _, c in checks.iterrows() if not checks.empty else ():
        if not isinstance(c.get("scene"), str):
            continue
        lo, hi = c.get("min"), c.get("max")
        if pd.notna(lo) and pd.notna(hi):
            out[_series_key(c)] = (0.5 * (float(lo) + float(hi)), f"order check: {lo:g} to {hi:g}")
        elif pd.notna(lo):
            out[_series_key(c)] = (float(lo), f"order check: at least {lo:g}")
    return out


def _reference_slope(model: str, bands: dict, r) -> tuple[float, str] | None:
    """The slope drawn beside a series and its legend text: the series' order check where the study has one, else
    the order the model promises (``Model.order``)."""
    band = bands.get(_series_key(r))
    if band is not None:
        return band[0], f"slope {band[0]:g} ({band[1]})"
    if other_quantity(r):  # the model's promised order is its deflection's
        return None
    try:
        q = float(get_model(model).order)
    except Exception:  # a model of another installation
        return None
    return q, f"slope {q:g} (promised)"


def convergence_groups(data: StudyFolder, palette: Palette) -> list[Group]:
    """One group per model and variant (its anchor: :func:`conv_anchor`), one small plot per series: the errors
    against spacing, the least-squares line with its order p written on it, the promised slope dashed through
    the finest grid."""
    conv = data.table("convergence")
    if conv.empty:
        return []
    bands = _check_bands(data.table("checks"))
    groups: dict[str, Group] = {}
    conv = conv.assign(_key=[variant_key(str(r["model"]), options_of(r.get("options"))) for _, r in conv.iterrows()])
    for key, g in conv.sort_values(["_key"], kind="stable").groupby("_key", sort=False):
        opts = key_options(str(g["model"].iloc[0]), options_of(g["options"].iloc[0]))
        title = f"{g['model'].iloc[0]}: " + (", ".join(f"{k}={v}" for k, v in opts.items()) or "defaults")
        group = groups.setdefault(key, Group(title, conv_anchor(key)))
        for _, r in g.iterrows():
            h = np.array([float(v) for v in str(r["spacings"]).split()])
            e = np.array([float(v) for v in str(r["errors"]).split()])
            model = str(r["model"])
            variant = variant_of(model, options_of(r.get("options")))
            colour = palette(line_key(r))
            scene = str(r["scene"])
            length = data.length(scene=scene)
            p = r["observed_order"]
            extra = " ".join(
                f"{short}={fmt(r[k])}"
                for k, short in (("horizon_factor", "m"), ("degree", "P"), ("slenderness", "L/h"))
                if k in r and pd.notna(r[k]) and not (k == "horizon_factor" and r[k] == 0)  # m = 0: no horizon
            )
            series = [Series(label(r), h, e, model, variant, colour, "line+points")]
            notes = []
            good = (h > 0) & (e > 0) & np.isfinite(e)
            if pd.notna(p) and good.sum() >= 2:
                lh, le = np.log(h[good]), np.log(e[good])
                c = np.mean(le) - p * np.mean(lh)
                hs = np.array([h[good].min(), h[good].max()])
                series.append(
                    Series(f"fit: p = {fixed(p, 2)}", hs, np.exp(c) * hs**p, colour=colour, style="dash", guide=True)
                )
                mid = np.sqrt(hs[0] * hs[1])
                notes.append((mid, float(np.exp(c) * mid**p), f"p = {fixed(p, 2)}", colour))
                slope = _reference_slope(model, bands, r)
                if slope is not None:
                    q, text = slope
                    h0, e0 = h[good][np.argmin(h[good])], e[good][np.argmin(h[good])]
                    series.append(Series(text, hs, e0 * (hs / h0) ** q, colour=-1, style="dot", guide=True))
            quantity = other_quantity(r)
            fig = Figure(
                f"{scene}"
                + (f", {extra}" if extra else "")
                + (f": {NAME[quantity]}" if quantity else "")
                + (f": p = {fixed(p, 2)}" if pd.notna(p) else "")
                + (": exact to round-off, no order" if r.get("at_round_off") in (True, "True") else ""),
                Axis(f"Δx ({length})", length, log=True),
                Axis(ERROR, "", log=True),
                series,
                notes=notes,
                small=True,
            )
            figure_tags = tags(
                scenes=[scene], papers=[data.scene_paper.get(scene, "")], tag_model=False, tag_variant=False
            )
            group.figures.append(fig.html(figure_tags))
    return list(groups.values())


def _sweep_series(
    g: pd.DataFrame, by: str, palette: Palette, with_grid: bool = False, join: str | None = None
) -> tuple[list[Series], list[str]]:
    """One line per run (model and options; ``with_grid``: and grid) over the column ``by``, joined in the order
    of ``join`` (default ``by``), each point's grid on hover; the runs whose every error is zero (nothing to draw
    on a log axis)."""
    series, zero = [], []
    keys = [line_key(r) + (f" n={fmt(r['points'])}" if with_grid else "") for _, r in g.iterrows()]
    for key, gg in g.assign(_key=keys).groupby("_key", sort=True):
        gg = gg.sort_values(join or by, kind="stable")
        if not positive(gg["err_max"]):
            zero.append(key)
            continue
        r = gg.iloc[0]
        model = str(r["model"])
        series.append(
            Series(
                key,
                gg[by].to_numpy(float),
                gg["err_max"].to_numpy(float),
                model,
                variant_of(model, options_of(r.get("options"))),
                palette(line_key(r)),
                "line+points",
                labels=[f"n={fmt(v)}" for v in gg["points"]],
            )
        )
    return series, zero


def work_precision(data: StudyFolder, palette: Palette) -> list[Markup]:
    """Per scene (and slenderness): each run's max error against its total time, the grids of one model and
    variant joined, the Pareto front (speed_error.csv) dashed. The first figure of a scene carries its anchor
    (:func:`cost_anchor`)."""
    if "total_s" not in data.ok:
        return []
    ok = data.ok[data.ok["err_max"].notna() & data.ok["total_s"].notna()]
    se = data.table("speed_error")
    front = set(se.loc[se["pareto"].astype(str).str.lower() == "true", "case_id"]) if "pareto" in se else set()
    out = []
    for scene, g in ok.groupby("scene", sort=False):
        anchor = cost_anchor(scene)
        for sl, gs in g.groupby(g["slenderness"].fillna(-1), sort=True):
            series, zero = _sweep_series(gs, "total_s", palette, join="points")
            if not series:
                continue
            f = gs[gs["case_id"].isin(front)].sort_values("total_s")
            if len(f) >= 2:
                series.append(
                    Series(
                        "Pareto front",
                        f["total_s"].to_numpy(float),
                        f["err_max"].to_numpy(float),
                        style="dash",
                        guide=True,
                    )
                )
            title = f"{scene}" + ("" if sl == -1 else f", L/h = {fmt(sl)}")
            caption = "Each point a grid; time: the whole case (assembly and solve) on the machine that ran the study."
            if zero:
                caption += " Error 0 on every grid (not drawn): " + "; ".join(zero) + "."
            fig = Figure(
                f"{title}: work–precision",
                Axis("total time (s)", "s", log=True),
                Axis(ERROR, "", log=True),
                series,
                caption=caption,
                id=anchor,
            )
            anchor = ""
            out.append(fig.html(_scene_tags(scene, gs)))
    return out


def _scene_tags(scene: str, rows: pd.DataFrame) -> str:
    return tags(scenes=[scene], papers=[folder(rows["scene_file"].iloc[0])], tag_model=False, tag_variant=False)


def locking(data: StudyFolder, palette: Palette) -> list[Markup]:
    """Per scene: max error against slenderness, one line per run and grid (two or more slenderness values)."""
    ok = data.ok[data.ok["slenderness"].notna() & data.ok["err_max"].notna()]
    out = []
    for scene, g in ok.groupby("scene", sort=False):
        keep = [
            gg
            for _, gg in g.groupby(["model", g["options"].fillna(""), g["points"].fillna(-1)])
            if gg["slenderness"].nunique() >= 2
        ]
        if not keep:
            continue
        series, zero = _sweep_series(pd.concat(keep), "slenderness", palette, with_grid=True)
        if not series:
            continue
        fig = Figure(
            f"{scene}: error against slenderness",
            Axis("L/h (–)", "", log=True),
            Axis(ERROR, "", log=True),
            series,
            caption="Locking-free: flat; locking: the error grows with L/h."
            + (" Error 0 at every L/h (not drawn): " + "; ".join(zero) + "." if zero else ""),
        )
        out.append(fig.html(_scene_tags(scene, g)))
    return out


def horizons(data: StudyFolder, palette: Palette) -> list[Markup]:
    """Per scene: max error against the horizon factor m = δ/Δx at each model's finest grid."""
    ok = data.ok
    if "horizon_factor" not in ok:
        return []
    ok = ok[ok["horizon_factor"].notna() & ok["err_max"].notna()]
    out = []
    for scene, g in ok.groupby("scene", sort=False):
        finest = g.groupby("model")["points"].transform("max")
        g = g[g["points"] == finest]
        keys = [" ".join(p for p in line_key(r).split(" ") if not p.startswith("m=")) for _, r in g.iterrows()]
        g = g.assign(_hkey=keys)
        keep = [gg for _, gg in g.groupby("_hkey") if gg["horizon_factor"].nunique() >= 2]
        if not keep:
            continue
        series = []
        for gg in keep:
            gg = gg.sort_values("horizon_factor")
            r = gg.iloc[0]
            model = str(r["model"])
            key = f"{r['_hkey']} n={fmt(r['points'])}"
            series.append(
                Series(
                    key,
                    gg["horizon_factor"].to_numpy(float),
                    np.maximum(gg["err_max"].to_numpy(float), 1e-16),
                    model,
                    variant_of(model, options_of(r.get("options"))),
                    palette(r["_hkey"]),
                    "line+points",
                )
            )
        fig = Figure(
            f"{scene}: error against the horizon factor",
            Axis("m = δ/Δx (–)", ""),
            Axis(ERROR, "", log=True),
            series,
            caption="Each model at its finest grid (errors below 1e-16 drawn at 1e-16).",
        )
        out.append(fig.html(_scene_tags(scene, g)))
    return out


def delta_dx_planes(data: StudyFolder, palette: Palette) -> list[Group]:
    """Per PD model and variant: the δ–Δx plane of the runs that give their horizon as a length, with the model and
    discretisation errors along the three paths (:func:`pdverify.report.planes.planes`)."""
    return [Group(title, anchor, figures) for title, anchor, figures in planes(data, palette)]
