"""The judgements of a verification: each check reads the suite's results and returns a verdict.

Orders and slopes come from :mod:`pdverify.measure.metrics`. A verdict is ``pass``, ``fail``, ``info``
(measured, not judged) or ``n/a`` (the model does not declare what the check needs).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd

from ..measure.metrics import ROUND_OFF_LEVEL, errors, locking_slope, log_slope, observed_order
from ..measure.status import in_doubt
from ..numerics.linalg import BOUND_LIMIT

EXACT = 1e-9  # an error this small at every grid: the model reproduces the solution (orders meaningless)
ROUND = ROUND_OFF_LEVEL  # errors below this are round-off level: no order fitted there
ORDER_SLACK = 0.3  # a fitted order this far below the expected one still passes (pre-asymptotic grids)
ACCURACY = 1e-2  # error at the finest grid that passes
LOCKING_GROWTH = 10.0  # locking: the most slender scene's error above this times the error at L/h = 20 ...
LOCKING_ERROR = 1e-3  # ... and above this (at the finest grid)
ROUND_OFF = 10.0  # error at the finest floor grid more than this times the smallest: round-off grows
FLOOR = 1e-4  # ... which fails when it also exceeds this (a tenth of the 0.1 % a user may ask for)
IDENTITY = 1e-8  # symmetry and superposition: relative difference that passes (round-off of the solves)


# a "suspect" case (round-off bound > 1e-6, docs/trust.md) solved: its error against the exact solution is measured and
# judged (round-off is what the floor check measures); the card counts such cases (card.json "suspect_cases")
SOLVED = ("ok", "suspect")


def check(name: str, verdict: str, summary: str, **data) -> dict:
    return {"check": name, "verdict": verdict, "summary": summary, **data}


def reference_bound(rows) -> float:
    """The largest round-off bound of the reference solves behind these study rows that could decide their errors
    (:func:`pdverify.measure.status.in_doubt`; 0 when none: the column ``ref_error_bound``, docs/trust.md)."""
    if "ref_error_bound" not in rows:
        return 0.0
    doubt = [
        float(b)
        for b, e in zip(rows["ref_error_bound"], rows["err_max"], strict=True)
        if not pd.isna(b) and in_doubt(float(b), e)
    ]
    return max(doubt, default=0.0)


def reference_note(bounds) -> str:
    """What a check's summary adds when some of the errors it judged are against a reference whose round-off bound
    could decide them: the verdict holds only if that reference is better than its solve's bound can show."""
    bad = [b for b in bounds if b > 0]
    if not bad:
        return ""
    return (
        f"; {len(bad)} scene(s) measured against a reference whose round-off bound passes {BOUND_LIMIT:g} and a "
        f"tenth of their errors (up to {max(bad):.2g}): those errors may be the reference's"
    )


def series(df, files: list[str], column: str = "err_max") -> list[dict]:
    """Per scene file: grids, spacings, errors (``column``: err_max, or a quantity's err_max_<q>), costs, pair
    orders, fitted order (ok rows only)."""
    out = []
    wanted = set(files)
    by_file = {f: g for f, g in df[df["scene_file"].isin(wanted)].groupby("scene_file", sort=False)}
    for f in files:
        if f not in by_file:  # the model's check() declined the scene: skipped, not judged
            continue
        rows = by_file[f].sort_values("points", kind="stable")
        solved = rows["status"].isin(SOLVED).to_numpy()
        ok = rows[solved]
        h, e = ok["spacing"].to_numpy(float), ok[column].to_numpy(float)
        pair = [
            math.log(e[i] / e[i + 1]) / math.log(h[i] / h[i + 1]) if e[i] > 0 and e[i + 1] > 0 else float("nan")
            for i in range(len(e) - 1)
        ]
        above = e >= ROUND
        # the three finest grids above round-off level (a coarse grid may be pre-asymptotic)
        fitted = observed_order(h[above][-3:], e[above][-3:])[0] if above.sum() >= 3 else float("nan")
        if above.sum() == 2:
            fitted = (
                pair[int(np.flatnonzero(above)[0])]
                if np.flatnonzero(above)[1] - np.flatnonzero(above)[0] == 1
                else fitted
            )
        out.append(
            {
                "scene_file": f,
                "points": ok["points"].astype(int).tolist(),
                "errors": e.tolist(),
                "cost_s": ok["total_s"].to_numpy(float).tolist(),
                "pair_orders": pair,
                "order": fitted,
                "exact": bool(len(e) and above.sum() < 2 and np.nanmax(e) < ROUND),
                # at round-off on the last two grids or more and every grid after the first such: a series that
                # converges faster than any order (the grid resolves the solution); None otherwise
                "exact_from": _round_off_from(ok["points"].astype(int).tolist(), e),
                "failed": [
                    f"{int(n)} points: {m}"
                    for n, m in zip(rows["points"][~solved], rows["message"][~solved], strict=True)
                ]
                if not solved.all()
                else [],
                "reference_bound": reference_bound(ok),
                "warnings": str(ok["warnings"].iloc[-1])
                if len(ok) and "warnings" in ok and ok["warnings"].notna().iloc[-1]
                else "",
            }
        )
    return out


def _round_off_from(points: list[int], e: np.ndarray) -> int | None:
    """The coarsest grid from which every error of the series is below round-off level, when that holds on at
    least the two finest grids; None otherwise."""
    below = np.asarray(e) < ROUND
    if len(below) < 2 or not below[-2:].all():
        return None
    first = len(below) - int(np.argmin(below[::-1])) if not below.all() else 0
    return int(points[first])


def convergence(rows: list[dict], expected: float, label: str) -> dict:
    if not rows:
        return check(label, "n/a", "the model declines every scene of this set")
    if all(r["exact"] and not r["failed"] for r in rows):
        return check(label, "pass", f"exact to round-off (every error < {ROUND:g}) on all {len(rows)} scenes")
    resolved = [r for r in rows if not r["exact"] and r["exact_from"] is not None]
    bad = [
        r
        for r in rows
        if r["failed"] or not (r["exact"] or r["exact_from"] is not None or r["order"] >= expected - ORDER_SLACK)
    ]
    worst = min((r["order"] for r in rows if not r["exact"] and not math.isnan(r["order"])), default=float("nan"))
    verdict = "pass" if not bad else "fail"
    text = (
        f"fitted order >= {expected - ORDER_SLACK:g} on every scene (lowest {worst:.2f})"
        if verdict == "pass"
        else f"{len(bad)} of {len(rows)} scenes below order {expected - ORDER_SLACK:g} or failed (lowest {worst:.2f})"
    )
    if resolved:  # converged past any order: the error drops to round-off level after the coarsest grids
        text += (
            f"; {len(resolved)} scene(s) at round-off (< {ROUND:g}) from "
            f"{min(r['exact_from'] for r in resolved)}-{max(r['exact_from'] for r in resolved)} points on"
        )
    text += order_warnings(bad)
    note = reference_note(r["reference_bound"] for r in rows)
    return check(
        label,
        verdict,
        text + note,
        expected_order=expected,
        lowest_order=worst,
        failing=[r["scene_file"] for r in bad],
        caveat=note,
    )


LOWER_ORDER = re.compile(r"\bfirst order\b|instead of falling at second order")  # a model's own warning of it


def order_warnings(bad: list[dict]) -> str:
    """Why scenes fall below the order, where the model says so: how many of ``bad`` carry its own warning about its
    order (first order near a load, a layer not yet resolved) at the finest grid, and the first such warning."""
    said = [next((w for w in r.get("warnings", "").split("; ") if LOWER_ORDER.search(w)), None) for r in bad]
    said = [w for w in said if w]
    return f"; {len(said)} of them warned by the model: {said[0]}" if said else ""


def accuracy(rows: list[dict]) -> dict:
    finest = [r["errors"][-1] if r["errors"] else float("inf") for r in rows]
    worst = max(finest)
    bad = [r for r, e in zip(rows, finest, strict=True) if not e <= ACCURACY]
    note = reference_note(r["reference_bound"] for r in rows)
    return check(
        "error at the finest grid",
        "pass" if not bad else "fail",
        f"largest error at the finest grid {worst:.2e} (limit {ACCURACY:g})"
        + (f"; {len(bad)} scene(s) above the limit{order_warnings(bad)}" if bad else "")
        + note,
        largest=worst,
        failing=[r["scene_file"] for r in bad],
        caveat=note,
    )


def within(rows: list[dict]) -> dict:
    """The coarsest grid at which every scene is within 1 % and within 0.1 %."""
    out = {}
    for tol in (1e-2, 1e-3):
        need = []
        for r in rows:
            hit = [p for p, e in zip(r["points"], r["errors"], strict=True) if e <= tol]
            need.append(hit[0] if hit and all(e <= tol for e in r["errors"][r["points"].index(hit[0]) :]) else None)
        out[f"{tol:g}"] = max(need) if need and None not in need else None
    text = ", ".join(
        f"within {float(k) * 100:g} %: " + (f"{v} points" if v else "not on these grids") for k, v in out.items()
    )
    return check("grids within 1 % and 0.1 %", "info", text, points=out)


def locking(df, files: list[str], meta: dict) -> dict:
    """Error vs slenderness at each grid (slope of log error vs log slenderness, reported). Judged at the finest
    grid: locking when the most slender scene's error exceeds both 10x the error at slenderness 20 and 0.1 %."""
    slopes, bad, ref_bounds = [], [], []
    for pair in sorted({meta[f]["pair"] for f in files}):
        fs = [f for f in files if meta[f]["pair"] == pair]
        rows = df[df["scene_file"].isin(fs)]
        if (~rows["status"].isin(SOLVED)).any():
            bad.append(f"{pair}: failed solves")
        rows = rows[rows["status"].isin(SOLVED)]
        ref_bounds += [reference_bound(rows[rows["scene_file"] == f]) for f in fs]
        for points, g in rows.groupby("points"):
            s = [meta[f]["slenderness"] for f in g["scene_file"]]
            e = g["err_max"].to_numpy(float)
            slope = 0.0 if np.nanmax(e) < EXACT else locking_slope(s, e)[0]
            slopes.append(
                {
                    "pair": pair,
                    "points": int(points),
                    "slope": slope,
                    "errors": dict(zip(map(float, s), e.tolist(), strict=True)),
                }
            )
        if slopes and slopes[-1]["pair"] == pair:
            errs = slopes[-1]["errors"]
            slender, base = errs.get(max(errs), float("nan")), errs.get(20.0, min(errs.values()))
            if not slender <= max(LOCKING_GROWTH * base, LOCKING_ERROR):
                at = rows[(rows["points"] == slopes[-1]["points"]) & (rows["status"] == "suspect")]
                bound = float(at["error_bound"].max()) if len(at) else 0.0
                bad.append(
                    f"{pair}: {slender:.1e} at L/h = {max(errs):g} vs {base:.1e} at 20 ({slopes[-1]['points']} points)"
                    + (f"; round-off bound of {len(at)} of those solves up to {bound:.1e}" if len(at) else "")
                )
    finest = [s for s in slopes if s["points"] == max((t["points"] for t in slopes), default=0)]
    text = "; ".join(f"{s['pair']}: slope {s['slope']:.2f}, {max(s['errors'].values()):.1e} at most" for s in finest)
    note = reference_note(ref_bounds)
    return check(
        "locking (error vs slenderness 5 ... 10000)",
        "pass" if slopes and not bad else "fail",
        ((text + " at the finest grid") if not bad else "locks: " + "; ".join(bad)) + note,
        caveat=note,
        slopes=slopes,
    )


def floor(rows: list[dict]) -> dict:
    """Round-off: the fine-grid scene's error should keep falling; where it rises (the condition number grows
    as N^4 for a fourth-order operator), it must stay below FLOOR at the finest grid."""
    if not rows:  # the model with these options declines the fine-grid scene (a variant's refusal)
        return check("accuracy floor (round-off)", "n/a", "the model declines the fine-grid scene (Scenes it declines)")
    r = rows[0]
    if r["failed"]:
        return check("accuracy floor (round-off)", "fail", "the fine-grid solves failed: " + "; ".join(r["failed"][:2]))
    e, n = np.asarray(r["errors"]), np.asarray(r["points"], float)
    i = int(np.argmin(e))
    growth = log_slope(n[i:], e[i:])[0] if len(e) - i >= 2 else float("nan")
    ok = e[-1] <= max(ROUND_OFF * e[i], FLOOR, EXACT)
    rise = f"; rises ~N^{growth:.1f} beyond {int(n[i])} points" if not math.isnan(growth) else ""
    note = reference_note([r["reference_bound"]])
    return check(
        "accuracy floor (round-off)",
        "pass" if ok else "fail",
        f"error {e[-1]:.2e} at {int(n[-1])} points, smallest {e[i]:.2e} at {int(n[i])}{rise}"
        + ("" if ok else f": above {FLOOR:g} from round-off")
        + note,
        caveat=note,
        floor=float(e[i]),
        finest=float(e[-1]),
        growth=growth,
    )


COST_GROWTH = 1.5  # the finest grid must cost this many times the next one for an error-cost slope to mean anything


def cost(rows: list[dict]) -> dict:
    """Seconds per solve at the finest grid and the slope of log(error) vs log(seconds) between the two finest
    grids (median over the scenes where the finest solve costs at least COST_GROWTH times the next one: where
    it does not, fixed costs (start-up, an external command's process) time the solve, not the grid)."""
    live = [r for r in rows if not r["exact"] and len(r["errors"]) >= 2 and min(r["cost_s"][-2:]) > 0]
    slopes = [
        math.log(r["errors"][-1] / r["errors"][-2]) / math.log(r["cost_s"][-1] / r["cost_s"][-2])
        for r in live
        if r["errors"][-1] > 0 and r["cost_s"][-1] >= COST_GROWTH * r["cost_s"][-2]
    ]
    secs = [r["cost_s"][-1] for r in rows if r["cost_s"]]
    p = float(np.median(slopes)) if slopes else float("nan")
    t = float(np.median(secs)) if secs else float("nan")
    trend = (
        f"error ~ cost^{p:.2f} between the two finest grids ({len(slopes)} scenes)"
        if slopes and t >= 0.01
        else "no error-cost slope: the solves are timed by their fixed costs (under 10 ms, or the finest grid "
        f"costs less than {COST_GROWTH:g}x the next)"
    )
    return check(
        "cost vs error", "info", f"{t:.3g} s per solve at the finest grid (median); {trend}", seconds=t, slope=p
    )


def mirrored(a, b, quantity: str = "w", sign: float = 1.0) -> float:
    """max |sign f_b(L - x) - f_a(x)| / max |f_a| of the measured quantity f (w; a rod's u has sign -1): the
    mirror scene's solution read back on the first one's points."""
    L = a.x[-1]
    fa, fb = a.measured(quantity), b.measured(quantity)
    back = sign * np.interp(a.x, (L - b.x)[::-1], fb[::-1])
    return float(np.abs(back - fa).max() / max(np.abs(fa).max(), 1e-300))


def identity(name: str, diffs: list[tuple[str, float]]) -> dict:
    if not diffs:
        return check(name, "n/a", "no scene: the model declines or refuses every scene of this check")
    worst = max(d for _, d in diffs)
    failed = [label for label, _ in diffs if label.startswith("failed:")]
    summary = (
        f"the solve failed ({failed[0][len('failed: ') :]})"
        if failed
        else f"largest relative difference {worst:.1e} (limit {IDENTITY:g})"
    )
    return check(name, "pass" if worst <= IDENTITY else "fail", summary, cases=dict(diffs))


def theory_gap(df, meta: dict, reference: str, points: int) -> dict:
    """Info for a model judged by self-convergence: how far its solution on the reference grid is from
    ``reference`` (another theory's exact solution) on the convergence scenes. Not judged: the distance between
    two theories (plus that grid's discretisation error), which only a reference of the model's own theory
    (e.g. plane stress against a beam theory) can tell apart."""
    ok = df[df["status"].isin(SOLVED)]
    if ok.empty:
        return check("theory gap", "info", f"no solve at {points} points succeeded")
    gaps = dict(zip(ok["scene_file"], ok["err_max"].astype(float), strict=True))
    worst = max(gaps, key=gaps.get)
    return check(
        "theory gap",
        "info",
        f"distance of the {points}-point solution from {reference}: median {np.median(list(gaps.values())):.1e}, "
        f"largest {gaps[worst]:.1e} ({meta[worst]['name']}); the theories' difference, not judged",
        reference=reference,
        points=points,
        scenes={meta[f]["name"]: e for f, e in gaps.items()},
    )


def superposition_diff(a, b, ab, quantity: str = "w") -> float:
    return errors(a.measured(quantity) + b.measured(quantity), ab.measured(quantity))["err_max"]
