"""``pdverify advise``: the cheapest model and grid that is accurate enough for one scene.

1. What the scene needs. Curved axis -> models with ``curved``; shear: the exact Euler–Bernoulli and
   Timoshenko solutions of the scene are compared; when the shear deflection is below half the tolerance,
   Euler–Bernoulli models qualify, else only models whose ``theory`` includes shear. 2D effects: when
   (h/L)^2 exceeds half the tolerance, a q8 plane-stress solve is compared with exact Timoshenko; if they
   differ by more than half the tolerance only the continuum model qualifies. Dynamics: the scene format
   has no time-dependent loading yet, so the answer is always a static model.
2. The grid, per candidate: earlier studies' results (reports/*/results.csv, clean convergence series of
   the same model and options) predict the points needed; the ladder of nested grids N, 2N-1, 4N-3 starts
   two refinements below that prediction and stops when the a-posteriori estimate on this very scene
   (observed order p from three grids, Richardson |w_2 - w_3| / (2^p - 1), relative to max|w|) is below
   the tolerance.
3. The cheapest candidate whose estimate is below the tolerance wins (cost = its measured solve time);
   the runner-up is the next cheapest. On straight scenes the exact error is printed as a check.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import InputError, SolveError
from .exact.straight import solve_straight
from .registry import models, run
from .scene import Scene


@dataclass
class Candidate:
    model: str
    options: dict
    points: int
    estimate: float
    order: float
    seconds: float
    exact_error: float | None = None
    basis: str = ""


@dataclass
class Advice:
    scene: str
    tolerance: float
    needs: list[str]
    choice: Candidate | None
    runner_up: Candidate | None
    rejected: list[str] = field(default_factory=list)


def shear_gap(scene: Scene) -> float:
    x = np.linspace(0, scene.length, 201)
    eb = solve_straight(scene, False).fields(x)["w"]
    ti = solve_straight(scene, True).fields(x)["w"]
    scale = np.abs(ti).max()
    return float(np.abs(ti - eb).max() / scale) if scale > 0 else 0.0


def prior_order(model: str, options: dict, root: Path = Path("reports")) -> str:
    """Observed orders measured by earlier studies for this model with these options."""
    import json

    import pandas as pd

    orders = []
    for f in sorted(root.glob("*/convergence.csv")):
        try:
            c = pd.read_csv(f)
        except Exception:
            continue
        if not {"model", "observed_order", "options"} <= set(c.columns):
            continue
        for _, r in c[c["model"] == model].iterrows():
            opts = json.loads(r["options"]) if isinstance(r["options"], str) else {}
            if all(opts.get(k) == v for k, v in options.items()) and np.isfinite(r["observed_order"]):
                orders.append(r["observed_order"])
    if not orders:
        return "no earlier study"
    return f"earlier studies: median observed order {np.median(orders):.2f} over {len(orders)} series"


def predicted_points(model: str, options: dict, tol: float, root: Path = Path("reports")) -> tuple[int | None, str]:
    """Points an earlier study says this model needs for tol: fit err = C (dx / L)^p over its ok rows
    with these options (all scenes), take the most pessimistic scene's C. (None, why) without data."""
    import json

    import pandas as pd

    rows = []
    for f in sorted(root.glob("*/results.csv")):
        try:
            df = pd.read_csv(f)
        except Exception:
            continue
        if not {"model", "options", "points", "err_max", "status"} <= set(df.columns):
            continue
        df = df[(df["model"] == model) & (df["status"] == "ok") & df["err_max"].notna() & (df["err_max"] > 1e-12)]
        for _, r in df.iterrows():
            opts = json.loads(r["options"]) if isinstance(r["options"], str) else {}
            if all(opts.get(k) == v for k, v in options.items()) and pd.isna(r.get("slenderness")):
                rows.append((f"{r['scene']}|{r['options']}", float(r["points"]), float(r["err_max"])))
    data = pd.DataFrame(rows, columns=["series", "n", "err"])
    needs, used = [], 0
    for _, g in data.groupby("series"):  # one convergence series (scene + every option)
        if g["n"].nunique() < 3:
            continue
        lh, le = np.log(1.0 / (g["n"] - 1)), np.log(g["err"])
        p, c = np.polyfit(lh, le, 1)
        r2 = 1 - np.sum((le - (p * lh + c)) ** 2) / max(np.sum((le - le.mean()) ** 2), 1e-300)
        if p > 0.5 and r2 > 0.9:  # a clean discretisation-error series (not round-off, not a plateau)
            needs.append(int(np.ceil((tol / np.exp(c)) ** (-1.0 / p))) + 1)
            used += 1
    if not needs:
        return None, "no clean convergence series in earlier studies for these options"
    n = max(needs)
    return n, f"earlier studies: {used} convergence series predict up to {n} points"


def estimate(scene: Scene, name: str, options: dict, tol: float, budget: float, start: int = 11,
             max_points: int = 20_001) -> Candidate | None:
    """Refine nested grids until the Richardson estimate is below tol (or the budget/size runs out)."""
    if name == "fem-plane-stress":
        max_points = min(max_points, 401)
    sols, n, spent = [], start, 0.0
    est, order = np.inf, float("nan")
    while n <= max_points:
        t0 = time.perf_counter()
        r = run(scene, name, points=n, **options)
        dt = time.perf_counter() - t0
        spent += dt
        sols.append((n, r, dt))
        if len(sols) >= 3:
            (_, r1, _), (_, r2, _), (_, r3, _) = sols[-3:]
            scale = np.abs(r3.w).max() or 1.0
            # differences on the coarser grid's points (interpolated: FE meshes carry extra load nodes)
            d12 = np.abs(r1.w - np.interp(r1.x, r2.x, r2.w)).max() / scale
            d23 = np.abs(r2.w - np.interp(r2.x, r3.x, r3.w)).max() / scale
            if d23 <= 1e-10:  # converged to round-off (the model is exact for this scene)
                est, order = max(d12, d23), float("inf")
            else:
                order = float(np.log2(d12 / d23))
                est = d23 / (2**order - 1) if order > 0.1 else np.inf
            if est < tol:
                break
        if spent > budget:
            break
        n = 2 * n - 1
    if not np.isfinite(est) or est >= tol:
        return None
    n_best, r_best, dt_best = sols[-1]
    ex = None
    prior = prior_order(name, options)
    if scene.is_straight and models()[name].theory in ("euler-bernoulli", "timoshenko"):
        exw = solve_straight(scene, models()[name].theory != "euler-bernoulli").fields(r_best.x)["w"]
        ex = float(np.abs(r_best.w - exw).max() / np.abs(exw).max())
    return Candidate(name, options, n_best, float(est), order, dt_best, ex,
                     f"three-grid Richardson on this scene (N = {sols[-3][0]}, {sols[-2][0]}, {n_best}; "
                     f"p = {order:.2f}); {prior}")


def continuum_gap(scene: Scene) -> float:
    """Relative difference, at the largest deflection, between exact Timoshenko and a q8 plane-stress solve."""
    r = run(scene, "fem-plane-stress", element="q8", points=161, layers=8)
    ex = solve_straight(scene, True).fields(r.x)["w"]
    i = int(np.argmax(np.abs(ex)))
    return float(abs(r.w[i] / ex[i] - 1)) if ex[i] else 0.0


def advise(scene: Scene, tolerance: float, budget: float = 30.0, include_reference: bool = False) -> Advice:
    if not 0 < tolerance < 1:
        raise InputError(f"tolerance = {tolerance!r}: give a relative tolerance between 0 and 1, e.g. 1e-3")
    needs, rejected = [], []
    cands = [m for m in models().values() if m.kind == "static" and not m.check(scene)
             and (include_reference or not m.reference)]
    if not scene.is_straight:
        needs.append("curved axis: models that solve curved beams")
    else:
        gap = shear_gap(scene)
        if gap <= tolerance / 2:
            needs.append(f"Euler–Bernoulli is enough: the shear deflection is {gap:.2e} of the deflection (tolerance {tolerance:g})")
        else:
            needs.append(f"shear matters: Timoshenko and EB differ by {gap:.2e} > tolerance/2; EB models excluded")
            for m in cands:
                if m.theory == "euler-bernoulli":
                    rejected.append(f"{m.name}: Euler–Bernoulli theory misses the shear deflection ({gap:.1e})")
            cands = [m for m in cands if m.theory != "euler-bernoulli"]
        twod = (1.0 / scene.slenderness) ** 2  # order of the 2D corrections to beam theory
        if twod <= tolerance / 2:
            needs.append(f"beam theory is enough: 2D corrections are of order (h/L)^2 = {twod:.1e} <= tolerance/2")
        elif "fem-plane-stress" in models() and not models()["fem-plane-stress"].check(scene):
            gap2 = continuum_gap(scene)
            if gap2 > tolerance / 2:
                needs.append(f"2D effects matter: Timoshenko and a q8 plane-stress solution differ by {gap2:.2e} > "
                             "tolerance/2; only the continuum model qualifies")
                for m in cands:
                    rejected.append(f"{m.name}: beam theory misses 2D effects ({gap2:.1e})")
                cands = [models()["fem-plane-stress"]]
            else:
                needs.append(f"beam theory is enough: Timoshenko and q8 plane stress differ by {gap2:.2e}")
    needs.append("static: the scene format has no time-dependent loading yet, so no time integration is chosen")
    options = {"pd-eb": {"variant": "corrected"}, "pd-bond-pair": {"variant": "corrected", "ends": "taylor"},
               "fem-plane-stress": {"element": "q8"}}
    found = []
    for m in cands:
        if m.option("points") is None:
            continue
        opts = options.get(m.name, {})
        n_pred, why = predicted_points(m.name, opts, tolerance)
        # start the ladder two refinements below the prediction, so the three grids end near it
        start = 11 if n_pred is None else max(11, min(5001, (n_pred - 1) // 4 + 1))
        try:
            c = estimate(scene, m.name, opts, tolerance, budget, start=start)
            if c is not None:
                c.basis += f"; start N = {start} ({why})"
        except (InputError, SolveError) as exc:
            rejected.append(f"{m.name}: {exc.lines[0]}")
            continue
        if c is None:
            rejected.append(f"{m.name}: did not reach {tolerance:g} within the budget ({budget:g} s) / grid limit")
        else:
            found.append(c)
    found.sort(key=lambda c: c.seconds)
    if not found:
        raise SolveError(f"tolerance = {tolerance:g}: no installed model reaches it on this scene within "
                         f"{budget:g} s; " + "; ".join(rejected[:3]))
    return Advice(scene.name, tolerance, needs, found[0], found[1] if len(found) > 1 else None, rejected)


def format_advice(a: Advice) -> str:
    lines = [f"scene: {a.scene}   tolerance: {a.tolerance:g}"]
    lines += [f"  needs: {n}" for n in a.needs]
    for label, c in (("choice", a.choice), ("runner-up", a.runner_up)):
        if c is None:
            continue
        opts = " ".join(f"--{k} {v}" for k, v in c.options.items())
        lines.append(f"{label}: {c.model} --points {c.points} {opts}".rstrip())
        lines.append(f"  estimated error {c.estimate:.2e} ({c.basis})")
        if c.exact_error is not None:
            lines.append(f"  check against the exact solution: {c.exact_error:.2e}")
        lines.append(f"  expected cost {c.seconds:.3g} s")
    lines += [f"  not chosen: {r}" for r in a.rejected]
    return "\n".join(lines)
