"""Error metrics, observed order of convergence, grid convergence index, locking slope, Pareto front."""

from __future__ import annotations

import math

import numpy as np

ROUND_OFF_LEVEL = 1e-7  # relative errors below this are round-off (eps x N^3 at a few thousand points): no order there


def at_round_off(err) -> bool:
    """True when every finite error (at least one) is below :data:`ROUND_OFF_LEVEL`: the model is exact for the
    load, and the errors' scatter is round-off, with no order to fit."""
    err = np.asarray(err, float)
    finite = err[np.isfinite(err)]
    return bool(finite.size and np.all(np.abs(finite) < ROUND_OFF_LEVEL))


def _norm(v: np.ndarray) -> float:
    """Euclidean norm by numpy's pairwise sum, not BLAS: the same bits whatever the number of BLAS threads,
    and no BLAS thread left spinning. (OpenBLAS threads a dot product above ~10,000 entries, and its
    threads then spin for a while, taking the other core from the solver in a serial run.)"""
    return math.sqrt(float(np.add.reduce(v * v)))


def errors(w: np.ndarray, w_ref: np.ndarray) -> dict[str, float]:
    """Max error relative to max|ref|, relative L2, relative error at the point of largest |ref|."""
    w, w_ref = np.asarray(w, float), np.asarray(w_ref, float)
    a = np.abs(w_ref)
    i = int(np.argmax(a))
    scale = float(a[i])
    if scale == 0:
        return {
            "err_max": float(np.abs(w).max()),
            "err_l2": _norm(w),
            "err_at_max": float(abs(w[i])),
            "w_at_max": float(w[i]),
            "w_ref_at_max": 0.0,
        }
    d = w - w_ref
    return {
        "err_max": float(np.abs(d).max() / scale),
        "err_l2": _norm(d) / _norm(w_ref),
        "err_at_max": float(abs(d[i]) / scale),
        "w_at_max": float(w[i]),
        "w_ref_at_max": float(w_ref[i]),
    }


def log_slope(x, y, min_points: int = 2) -> tuple[float, float]:
    """Least-squares slope of log(y) vs log(x) and its R^2, over the points with x > 0 and finite y > 0
    (nan, nan below ``min_points`` such points, or when the x values are all equal). Closed form: the same
    line as ``np.polyfit(log x, log y, 1)``, at a fraction of its cost (a study fits hundreds of series)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x > 0) & (y > 0) & np.isfinite(y)
    lx, ly = np.log(x[ok]), np.log(y[ok])
    if len(lx) < max(min_points, 2):
        return float("nan"), float("nan")
    dx, dy = lx - lx.mean(), ly - ly.mean()
    sxx = dx @ dx
    if sxx == 0:
        return float("nan"), float("nan")
    p = (dx @ dy) / sxx
    ss = dy @ dy
    res = dy - p * dx
    r2 = 1 - (res @ res) / ss if ss > 0 else float("nan")
    return float(p), float(r2)


def observed_order(spacing, error) -> tuple[float, float]:
    """Least-squares slope of log(error) vs log(spacing) and its R^2 (needs >= 3 grids)."""
    return log_slope(spacing, error, min_points=3)


def gci(spacing, value, safety: float = 1.25) -> dict[str, float]:
    """Roache's grid convergence index of the three finest grids (value: a solution functional).
    Unequal refinement ratios by Celik et al.'s (2008) fixed-point iteration, in Python floats (numpy
    scalars made it the convergence table's main cost)."""
    h, f = np.asarray(spacing, float), np.asarray(value, float)
    order = np.argsort(h)[:3]
    nan = {"gci_order": float("nan"), "gci_fine": float("nan"), "richardson": float("nan")}
    if len(order) < 3:
        return nan
    (h1, h2, h3), (f1, f2, f3) = h[order].tolist(), f[order].tolist()
    r21, r32 = h2 / h1, h3 / h2
    e21, e32 = f2 - f1, f3 - f2
    if not (r21 > 1 and r32 > 1):  # a grid twice among the three finest (the same case listed twice)
        return nan
    if e21 == 0 or e32 == 0 or (e21 > 0) != (e32 > 0) or not (math.isfinite(e21) and math.isfinite(e32)):
        return nan
    ratio = abs(e32 / e21)
    p = abs(math.log(ratio)) / math.log(r21)
    for _ in range(50):
        try:
            a, b = r21**p - 1, r32**p - 1
            q = a / b
        except (OverflowError, ZeroDivisionError):
            q = float("nan")
        if not (q > 0 and math.isfinite(q)):  # the iteration diverged (numpy's inf/nan path): no order
            return nan
        p_new = abs(math.log(ratio) + math.log(q)) / math.log(r21)
        if abs(p_new - p) < 1e-12:
            break
        p = p_new
    try:
        rich = (r21**p * f1 - f2) / (r21**p - 1)
    except (OverflowError, ZeroDivisionError):
        return nan
    return {
        "gci_order": float(p),
        "gci_fine": float(safety * abs(e21 / f1) / (r21**p - 1)) if f1 else float("nan"),
        "richardson": float(rich),
    }


def locking_slope(slenderness, error) -> tuple[float, float]:
    """Slope of log(error) vs log(slenderness) (0: locking-free) and the slenderness where error > 1 %."""
    s, e = np.asarray(slenderness, float), np.asarray(error, float)
    o = np.argsort(s)
    s, e = s[o], e[o]
    slope = log_slope(s, e)[0]
    over = s[e > 0.01]
    return slope, float(over[0]) if len(over) else float("nan")


def pareto(cost, error) -> np.ndarray:
    """Mask of the cases no other case beats in both cost and error."""
    c, e = np.asarray(cost, float), np.asarray(error, float)
    o = np.lexsort((e, c))
    mask = np.zeros(len(c), bool)
    best = np.inf
    for i in o:  # sorted by cost: a case is on the front when its error beats every cheaper one
        if e[i] < best:
            mask[i] = True
            best = e[i]
    return mask
