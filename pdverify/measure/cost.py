"""What a benchmark row's time is worth: a row counts toward a performance target only when its error is known
and small (a fast wrong answer says nothing about cost), and the cost slope of a model over its sizes."""

from __future__ import annotations

import numpy as np

ACCURACY = 1e-6  # a row counts toward a performance target only when its max error is at most this


def accurate(row: dict) -> bool:
    """Whether a bench row may count toward a performance target: measured, and within ``ACCURACY``."""
    e = row.get("max_error")
    return row.get("status", "ok") == "ok" and e is not None and e == e and e <= ACCURACY


def cost_slope(rows: list[dict]) -> dict[str, float]:
    """Per model: slope of log(total_s) vs log(points) (1 = linear cost), over its accurate rows only
    (:func:`accurate`: a fast wrong answer says nothing about cost)."""
    out = {}
    by: dict[str, list] = {}
    for r in rows:
        if accurate(r) and r.get("total_s"):
            by.setdefault(r["model"], []).append((r["points"], r["total_s"]))
    for m, pts in by.items():
        if len({p for p, _ in pts}) >= 2:  # a slope needs two sizes (one size timed twice fits nothing)
            n, t = np.log(np.array(pts, float)).T
            out[m] = float(np.polyfit(n, t, 1)[0])
    return out
