"""The performance page: ``pdverify bench --out DIR`` writes ``DIR/bench.jsonl`` (one object per
line, as printed) and ``DIR/index.html`` (cost vs points per model against the banded-solve limit of
the same matrix, the ratio table and the targets of the performance issue with their verdicts)."""

from __future__ import annotations

import json
import os
import platform
import time
from pathlib import Path

import pandas as pd
from markupsafe import Markup

from .. import __version__
from . import figures
from .build import environment, table

RATIO_TARGET = 2.0  # total time / banded solve of the same matrix, at the largest size
UPDATES_TARGET = 5e7  # point-updates per second of explicit dynamics at 10^6 points
MEMORY_TARGET_MB = 2048.0  # peak memory of a 10^6-point static run


def targets(rows: pd.DataFrame, slopes: dict[str, float]) -> pd.DataFrame:
    """One row per (model, target): measured value at the model's largest size and the verdict."""
    out = []
    ok = rows[rows.get("status", "ok") == "ok"] if "status" in rows else rows
    for model, g in ok.groupby("model", sort=True):
        big = g.loc[g["points"].idxmax()]
        if pd.notna(big.get("ratio")):
            out.append({"model": model, "target": f"total / limit <= {RATIO_TARGET:g}", "points": int(big["points"]),
                        "measured": float(big["ratio"]), "verdict": "pass" if big["ratio"] <= RATIO_TARGET else "fail"})
        if pd.notna(big.get("updates_per_s")):
            out.append({"model": model, "target": f"updates/s >= {UPDATES_TARGET:.0e}", "points": int(big["points"]),
                        "measured": float(big["updates_per_s"]),
                        "verdict": "pass" if big["updates_per_s"] >= UPDATES_TARGET else "fail"})
        if pd.notna(big.get("peak_mem_mb")) and big["points"] >= 1_000_000:
            out.append({"model": model, "target": f"peak memory < {MEMORY_TARGET_MB:g} MB", "points": int(big["points"]),
                        "measured": float(big["peak_mem_mb"]),
                        "verdict": "pass" if big["peak_mem_mb"] < MEMORY_TARGET_MB else "fail"})
        if model in slopes:
            out.append({"model": model, "target": "cost ~ N^1 (slope <= 1.2)", "points": int(big["points"]),
                        "measured": slopes[model], "verdict": "pass" if slopes[model] <= 1.2 else "fail"})
    return pd.DataFrame(out)


def build_performance(rows: list[dict], out: str | Path, slopes: dict[str, float]) -> Path:
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
    title = "cost vs points (solid) and the banded-solve limit (dashed)"
    figs = [Markup(figures.cost(groups, limits, title))] if groups else []
    env = environment()
    meta = {"pdverify": __version__, "python": platform.python_version(), "platform": platform.platform(),
            "cpu_count": os.cpu_count()}
    page = env.get_template("performance.html.j2").render(
        meta=meta, generated=time.strftime("%Y-%m-%d %H:%M:%S"), figures=figs,
        targets=table(targets(df, slopes), row_class="verdict") if not df.empty else "",
        rows=table(df, ["model", "points", "dofs", "assemble_s", "solve_s", "total_s", "limit_s", "ratio", "bandwidth",
                        "peak_mem_mb", "mem_per_point_kb", "updates_per_s", "status", "message"]),
        slopes=table(pd.DataFrame([{"model": m, "cost_slope": s} for m, s in sorted(slopes.items())])))
    (out / "bench.jsonl").write_text("".join(json.dumps(r) + "\n" for r in rows))
    index = out / "index.html"
    index.write_text(page, encoding="utf-8")
    return index
