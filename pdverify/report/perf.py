"""The performance page: ``pdverify bench --out DIR`` writes ``DIR/bench.jsonl`` (one object per
line, as printed) and ``DIR/index.html`` (cost vs points per model against the banded-solve limit of
the same matrix, each model's work-precision curve (time vs max error against the exact solution) and
its cheapest run within 1e-6, the ratio table and the targets of the performance issue with their
verdicts; a run counts toward a target only when its error is within 1e-6)."""

from __future__ import annotations

import json
import os
import platform
import time
from pathlib import Path

import numpy as np
import pandas as pd
from markupsafe import Markup

from ..core.version import __version__
from ..measure.cost import ACCURACY, accurate
from . import figures
from .output import environment, write
from .tables import table

RATIO_TARGET = 2.0  # total time / banded solve of the same matrix, at the largest size
UPDATES_TARGET = 5e7  # point-updates per second of explicit dynamics at 10^6 points
MEMORY_TARGET_MB = 2048.0  # peak memory of a 10^6-point static run


def targets(rows: pd.DataFrame, slopes: dict[str, float]) -> pd.DataFrame:
    """One row per (model, target): measured value at the model's largest size and the verdict."""
    out = []
    ok = rows[rows.get("status", "ok") == "ok"] if "status" in rows else rows
    for model, g in ok.groupby("model", sort=True):
        counted = g[[accurate(r) for r in g.to_dict("records")]]
        if counted.empty:
            out.append(
                {
                    "model": model,
                    "target": f"max error <= {ACCURACY:g} (needed to count)",
                    "points": int(g["points"].max()),
                    "measured": _worst_error(g),
                    "verdict": "fail",
                }
            )
            continue
        g = counted
        big = g.loc[g["points"].idxmax()]
        if pd.notna(big.get("ratio")):
            out.append(
                {
                    "model": model,
                    "target": f"total / limit <= {RATIO_TARGET:g}",
                    "points": int(big["points"]),
                    "measured": float(big["ratio"]),
                    "verdict": "pass" if big["ratio"] <= RATIO_TARGET else "fail",
                }
            )
        if pd.notna(big.get("updates_per_s")):
            out.append(
                {
                    "model": model,
                    "target": f"updates/s >= {UPDATES_TARGET:.0e}",
                    "points": int(big["points"]),
                    "measured": float(big["updates_per_s"]),
                    "verdict": "pass" if big["updates_per_s"] >= UPDATES_TARGET else "fail",
                }
            )
        if pd.notna(big.get("peak_mem_mb")) and big["points"] >= 1_000_000:
            out.append(
                {
                    "model": model,
                    "target": f"peak memory < {MEMORY_TARGET_MB:g} MB",
                    "points": int(big["points"]),
                    "measured": float(big["peak_mem_mb"]),
                    "verdict": "pass" if big["peak_mem_mb"] < MEMORY_TARGET_MB else "fail",
                }
            )
        if model in slopes:
            out.append(
                {
                    "model": model,
                    "target": "cost ~ N^1 (slope <= 1.2)",
                    "points": int(big["points"]),
                    "measured": slopes[model],
                    "verdict": "pass" if slopes[model] <= 1.2 else "fail",
                }
            )
    return pd.DataFrame(out)


def _worst_error(g: pd.DataFrame) -> float:
    e = pd.to_numeric(g["max_error"], errors="coerce") if "max_error" in g else pd.Series(dtype=float)
    return float(e.max()) if e.notna().any() else float("nan")


def cheapest(rows: pd.DataFrame) -> pd.DataFrame:
    """Per model: its cheapest run (least total_s) within ``ACCURACY`` of the exact solution, or a row
    saying none reached it (with the smallest error it did reach)."""
    out = []
    ok = rows[rows["status"] == "ok"] if "status" in rows else rows
    for model, g in ok.groupby("model", sort=True):
        good = g[[accurate(r) for r in g.to_dict("records")]]
        if len(good):
            r = good.loc[good["total_s"].idxmin()]
            out.append(
                {
                    "model": model,
                    "points": int(r["points"]),
                    "max_error": float(r["max_error"]),
                    "total_s": float(r["total_s"]),
                    "statement": f"cheapest run within {ACCURACY:g}",
                }
            )
        else:
            e = pd.to_numeric(g["max_error"], errors="coerce") if "max_error" in g else pd.Series(dtype=float)
            best = f"best {e.min():.2g}" if e.notna().any() else "no exact solution for this scene"
            out.append(
                {
                    "model": model,
                    "points": None,
                    "max_error": float(e.min()) if e.notna().any() else None,
                    "total_s": None,
                    "statement": f"no run within {ACCURACY:g} ({best})",
                }
            )
    return pd.DataFrame(out)


def work_precision(rows: pd.DataFrame) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Per model, (label, total seconds, max error) of its measured runs, by size."""
    groups = []
    if "max_error" not in rows:
        return groups
    ok = rows[rows["status"] == "ok"] if "status" in rows else rows
    ok = ok[pd.to_numeric(ok["max_error"], errors="coerce").notna()]
    for model, g in ok.groupby("model", sort=True):
        g = g.sort_values("points")
        # an exact error of 0 (the exact model itself) drawn at the plot's floor, 1e-17
        groups.append((model, g["total_s"].to_numpy(float), g["max_error"].to_numpy(float).clip(min=1e-17)))
    return groups


def work_precision_figure(groups, accuracy: float, title: str) -> str:
    """log-log max error (y) vs total seconds (x) per model, the accuracy line dashed (SVG)."""
    fig, ax = figures.plt.subplots(figsize=(6.4, 4.0))
    for label, t, e in groups:
        ax.loglog(t, e, "o-", ms=4, label=label)
    ax.axhline(accuracy, color="k", ls="--", lw=1, label=f"max error {accuracy:g}: counts toward targets below")
    return figures._finish(fig, ax, "total time (s)", "max rel. error vs exact (–)", title, which="both")


def build_performance(rows: list[dict], out: str | Path, slopes: dict[str, float], sharing=()) -> Path:
    """The performance page ``out/index.html`` and ``out/bench.jsonl``: the rows of ``pdverify bench``, their cost
    slopes, and ``sharing``, the factorisation-sharing rows of :func:`pdverify.apps.sharing.sharing_gain`."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame(rows)
    groups, limits = [], []
    if not df.empty and "total_s" in df:
        ok = df[df["status"] == "ok"] if "status" in df else df
        for model, g in ok.groupby("model", sort=True):
            g = g.sort_values("points")
            groups.append((model, g["points"].to_numpy(float), g["total_s"].to_numpy(float)))
            gl = g[g["limit_s"].notna()] if "limit_s" in g else g.iloc[0:0]
            limits.append((model, gl["points"].to_numpy(float), gl["limit_s"].to_numpy(float)))
    figs = (
        [Markup(figures.cost(groups, limits, "cost vs points (solid) and the banded-solve limit (dashed)"))]
        if groups
        else []
    )
    wp = work_precision(df) if not df.empty else []
    if wp:
        figs.append(
            Markup(
                work_precision_figure(
                    wp,
                    ACCURACY,
                    "work-precision: total seconds vs max error against the exact solution (one point per size)",
                )
            )
        )
    env = environment()
    meta = {
        "pdverify": __version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
    }
    page = env.get_template("performance.html.j2").render(
        meta=meta,
        generated=time.strftime("%Y-%m-%d %H:%M:%S"),
        figures=figs,
        targets=table(targets(df, slopes), row_class="verdict") if not df.empty else "",
        cheapest=table(cheapest(df)) if not df.empty else "",
        rows=table(
            df,
            [
                "model",
                "points",
                "dofs",
                "max_error",
                "error_bound",
                "assemble_s",
                "solve_s",
                "total_s",
                "limit_s",
                "ratio",
                "bandwidth",
                "peak_mem_mb",
                "mem_per_point_kb",
                "updates_per_s",
                "status",
                "message",
            ],
        ),
        slopes=table(pd.DataFrame([{"model": m, "cost_slope": s} for m, s in sorted(slopes.items())])),
        sharing=table(pd.DataFrame(list(sharing))) if sharing else "",
    )
    write(out / "bench.jsonl", "".join(json.dumps(r) + "\n" for r in [*rows, *sharing]))  # whole, renamed over
    index = out / "index.html"
    write(index, page)
    return index


LARGE_HORIZON_COLUMNS = [
    "model",
    "points",
    "horizon",
    "m",
    "krylov_s",
    "krylov_solve_s",
    "banded_s",
    "banded_solve_s",
    "assemble_s",
    "difference",
    "krylov_bound",
    "banded_bound",
    "agrees",
    "status",
    "message",
]


def build_large_horizon(rows: list[dict], out: str | Path) -> Path:
    """The page of ``bench --large-horizon``: the Krylov and the banded times of each row beside each other."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame(rows)
    meta = {
        "pdverify": __version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
    }
    page = (
        environment()
        .get_template("performance.html.j2")
        .render(
            meta=meta,
            generated=time.strftime("%Y-%m-%d %H:%M:%S"),
            large_horizon=table(df, [c for c in LARGE_HORIZON_COLUMNS if c in df]),
        )
    )
    write(out / "bench_large_horizon.jsonl", "".join(json.dumps(r) + "\n" for r in rows))
    index = out / "index.html"
    write(index, page)
    return index
