"""One page per paper (a scene folder): its benchmarks, the paper's figures reproduced (deflection curves, curved
beams' resultants, time histories and energy ledgers, load steps), its convergence, horizon, locking and
speed-vs-error figures (matplotlib SVG, :mod:`.figures`), its dispersion relations once each and its
plane-stress pictures."""

from __future__ import annotations

import base64
import json
from dataclasses import dataclass, field

import numpy as np
from markupsafe import Markup

from ..study import forked
from . import figures
from .inputs import StudyFolder
from .path_figures import health_figures, load_path_figures, moment_curvature_figures
from .quantity_figures import QUANTITIES
from .scene_figures import overlay_figures, resultant_figures
from .text import fmt, folder, label, short_reference, slug
from .waves import Dispersion, svg


@dataclass
class PaperScene:
    name: str
    file: str
    folder: str
    reference: str
    figures: list[Markup] = field(default_factory=list)


def _history_label(h: dict, length: str) -> str:
    """A time history's vertical axis with its units: the scene's length, radians for a rotation probe."""
    text = f"{h.get('ylabel', 'displacement')} ({length})"
    if any(str(k).startswith(("rotation", "twist")) for k in h.get("series", {})):
        text += "; rotation (rad)"
    return text


def scene_figures(data: StudyFolder) -> list[PaperScene]:
    """Each scene's figures (in the study's order), per slenderness: the curves of every model and variant at its
    finest grid over the reference, the resultants N and Q where the runs give them, each dynamic run's time
    history and energy ledger, the overlay of several transient runs, a nonlinear run's deformed shapes."""
    scenes = []
    for sfile, g in data.ok.groupby("scene_file", sort=False):
        figs = []
        unit = data.length(sfile)
        force = "lbf" if data.units(sfile) == "inch-pound" else "N"
        for sl, gs in g.groupby(g["slenderness"].fillna(-1), sort=True):
            curves, ref, ylabels, resultant_curves, health, paths, laws = [], None, set(), [], [], [], []
            # at most one curve per (model, variant): the finest grid
            for _, grp in gs.groupby(["model", gs["options"].fillna("")], sort=True):
                r = grp.sort_values("points", na_position="first").iloc[-1]
                c = data.curve(r["case_id"])
                if c is None:
                    continue
                quantity = c.get("quantity", "w")  # what the model is measured on (pd-rod: u, pd-torsion: twist)
                y = c["w"] if quantity == "w" else c["fields"][quantity]
                ylabels.add(quantity)
                curves.append((label(r), c["x"], y))
                if "health" in c.get("fields", {}):  # a load path's node health (path_figures.py)
                    health.append((label(r), c["x"], c["fields"]["health"]))
                if c.get("load_path"):  # its load factor against the peak deflection (path_figures.py)
                    paths.append((label(r), c["load_path"]))
                if c.get("moment_curvature"):  # the section law its pairs follow (path_figures.py)
                    laws.append((label(r), c["moment_curvature"]))
                if {"N", "Q"} <= set(c.get("fields", {})):
                    resultant_curves.append((label(r), c))
                if ref is None or len(c["x"]) > len(ref[0]):
                    ref = (c["x"], c["w_ref"])
            title = g["scene"].iloc[0] + ("" if sl == -1 else f", L/h = {fmt(sl)}")
            if ref is not None and np.all(np.isnan(ref[1])):  # runs without a reference
                ref = None
            yunit = "rad" if ylabels == {"twist"} else unit
            figs.append(figures.deflection(curves, ref, title, " / ".join(sorted(ylabels)) or "w", unit, yunit))
            figs.extend(resultant_figures(resultant_curves, title, unit, force))
            figs.extend(load_path_figures(paths, title, unit))
            scene = data.scene(sfile, None if sl == -1 else sl) if laws else None
            figs.extend(moment_curvature_figures(laws, scene, title, f"{force} {unit}", unit))
            figs.extend(health_figures(health, title, unit))
            overlay = []
            for _, r in gs.iterrows():
                c = data.curve(r["case_id"]) or {}
                if c.get("history"):
                    h = c["history"]
                    ylabel = _history_label(h, unit)
                    overlay += [(label(r), h["t"], h["series"], ylabel)]
                    figs.append(figures.time_history(h["t"], h["series"], f"{label(r)}: time history", ylabel))
                    if h.get("energy"):
                        energy = "in lbf" if force == "lbf" else "J"
                        figs.append(figures.energy_ledger(h["energy"], f"{label(r)}: energy ledger", energy))
                if c.get("load_steps"):
                    exact = [
                        (np.array(st["exact_x"]), np.array(st["exact_z"])) for st in c["load_steps"] if "exact_x" in st
                    ]
                    figs.append(figures.deformed_shapes(c["load_steps"], f"{label(r)}: deformed shapes", exact, unit))
            figs.extend(overlay_figures(overlay, title))
        scenes.append(
            PaperScene(
                g["scene"].iloc[0],
                sfile,
                folder(sfile),
                short_reference(g["reference"].iloc[0]) if "reference" in g else "",
                [Markup(f) for f in figs],
            )
        )
    return scenes


def sweep_figures(data: StudyFolder) -> dict[str, list[tuple[str, Markup]]]:
    """(scene, figure) lists of the sweeps: convergence (log-log error vs spacing per scene), horizon (error vs
    horizon factor at each model's finest grid), locking (error vs slenderness), speed vs error."""
    conv, lock, se = data.table("convergence"), data.table("locking"), data.table("speed_error")
    ok = data.ok
    conv_figs = []
    if not conv.empty and "quantity" in conv:  # the models' own quantity; the others: the index and the table
        conv = conv[~conv["quantity"].isin(QUANTITIES)]
    if not conv.empty:
        for scene, g in conv.groupby("scene", sort=False):
            series = []
            for _, r in g.iterrows():
                h = np.array([float(v) for v in str(r["spacings"]).split()])
                e = np.array([float(v) for v in str(r["errors"]).split()])
                series.append((label(r), h, e, r["observed_order"]))
            conv_figs.append((scene, Markup(figures.convergence(series, str(scene), data.length(scene=scene)))))
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
            fig = figures.scatter(
                groups,
                "horizon factor m = δ/Δx (–)",
                "max relative error (–)",
                f"error vs horizon: {scene}",
                logx=False,
            )
            horizon_figs.append((scene, Markup(fig)))
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
                        label(gg.iloc[0]).replace(f" L/h={fmt(gg.iloc[0]['slenderness'])}", ""),
                        gg["slenderness"].to_numpy(float),
                        gg["err_max"].to_numpy(float),
                    )
                )
            fig = figures.scatter(
                groups, "slenderness L/h (–)", "max relative error (–)", f"locking: {scene}", connect=True
            )
            lock_figs.append((scene, Markup(fig)))
    speed_figs = []
    if not se.empty:
        for scene, g in se.groupby("scene", sort=False):
            groups = [
                (m, gg["total_s"].to_numpy(float), np.maximum(gg["err_max"].to_numpy(float), 1e-16))
                for m, gg in g.groupby("model")
            ]
            fr = g[g["pareto"].astype(bool)]
            fig = figures.scatter(
                groups,
                "total time (s)",
                "max relative error (–)",
                f"speed vs error: {scene}",
                front=(fr["total_s"].to_numpy(float), np.maximum(fr["err_max"].to_numpy(float), 1e-16)),
            )
            speed_figs.append((scene, Markup(fig)))
    return {"convergence": conv_figs, "horizon": horizon_figs, "locking": lock_figs, "speed": speed_figs}


def plane_stress_images(data: StudyFolder) -> list[dict]:
    """The plane-stress cases' pictures (``vtu/<case>.png``, drawn by the solving process) with their VTU files
    and the paper folder of each."""
    d = data.d
    images = []
    for png in sorted((d / "vtu").glob("*.png")) if (d / "vtu").exists() else []:
        r = data.res[data.res["case_id"] == png.stem]
        name = f"{r['scene'].iloc[0]}: {label(r.iloc[0])}" if len(r) else png.stem
        images.append(
            {
                "label": name,
                "data": base64.b64encode(png.read_bytes()).decode(),
                "vtu": f"vtu/{png.stem}.vtu",
                "folder": folder(r["scene_file"].iloc[0]) if len(r) else "",
            }
        )
    return images


def paper_pages(data: StudyFolder, waves: list[Dispersion]) -> list[dict]:
    """What each paper's page shows (in the order of the study's scenes): its title, file name, the verdicts of
    its benchmarks, its scenes and their figures, its sweep figures, its dispersion relations (each once), its
    plane-stress pictures."""
    sweeps = forked.start(lambda: sweep_figures(data))  # in a second process while this one draws the scenes
    scenes = scene_figures(data)
    sweeps = sweeps()
    images = plane_stress_images(data)
    bench = data.table("benchmarks")
    pages = []
    for name in dict.fromkeys(s.folder for s in scenes):
        names = {s.name for s in scenes if s.folder == name}
        pb = bench[bench["scene_file"].map(folder) == name] if "scene_file" in bench else bench.iloc[0:0]
        verdicts = pb["verdict"].value_counts().to_dict() if "verdict" in pb else {}
        pages.append(
            {
                "folder": name,
                "title": data.titles.get(name, name),
                "href": f"paper-{slug(name)}.html",
                "summary": ", ".join(f"{k}: {v}" for k, v in sorted(verdicts.items())) or "no benchmarks",
                "n_scenes": len(names),
                "names": names,
                "benchmarks": pb,
                "scenes": [s for s in scenes if s.folder == name],
                "sweeps": {k: [f for sc, f in v if sc in names] for k, v in sweeps.items()},
                "waves": [(Markup(svg(w)), "; ".join(w.scenes)) for w in waves if name in w.papers],
                "images": [im for im in images if im["folder"] == name],
            }
        )
    return pages
