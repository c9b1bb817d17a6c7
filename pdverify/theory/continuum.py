"""A PD model's nonlocal continuum solution at a fixed horizon delta (the model's equations with its sums replaced by
integrals, its own boundary treatment): the limit of its discrete solutions as m = delta / dx grows at fixed delta
(docs/design/nonlocal.md, docs/nonlocal.md).

* **Closed form** where the model gives one (:meth:`~pdverify.core.contract.Model.continuum_series`: mirror ends, the
  series of :mod:`pdverify.theory.symbols`), used when its own estimate of the rest of the series is below
  :data:`SERIES_TOL`.
* **Extrapolation in m at fixed delta** elsewhere: the model solved on grids refined by whole factors of the asked
  grid (so its points are points of every level), m from at least :data:`M_MIN` up, and the values at the asked points
  extrapolated to dx -> 0 by Neville's scheme (polynomials in dx of every degree: the expansions of the models' sums
  have odd and even powers). The estimate is the change of the chosen column between the two finest rows; levels are
  added until it is below :data:`TOL` or the finest m reaches option ``continuum_m`` (default: the model's).
* **No limit**: a variant whose discrete rules exist only up to some m at fixed delta
  (:meth:`~pdverify.core.contract.Model.continuum_limit`) gets its own finest grid there, flagged in one line.

The model object is passed in and solved through its own ``resolve`` and ``solve`` (no model is imported here).
"""

from __future__ import annotations

import json
import math
from functools import lru_cache

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.result import Result, Timer, merge_info
from ..core.scene import Scene
from .symbols import series_solution

M_MIN = 8  # the coarsest level's m: below it the expansions in dx / delta are not yet asymptotic
TOL = 1e-9  # stop adding levels when the estimate (relative to the largest value) is below this
NOISE = 10.0  # ... or below this many times the levels' round-off bounds (pdverify.measure.richardson: NOISE)
ACHIEVED = 1e-8  # an estimate above this carries a warning with its number
SERIES_TOL = 1e-10  # the closed form is used when the rest of its series is below this


def horizon_of(model, scene: Scene, params: dict) -> float:
    """delta of ``params``: the horizon length given, else the one the model reports for its solve."""
    if params.get("horizon_length") is not None:
        return float(params["horizon_length"])
    solved = model.solve(scene, dict(params, continuum=False))
    return float(solved.info["horizon"])


def continuum_solution(model, scene: Scene, params: dict) -> Result:
    """The model's continuum at the horizon of ``params``, at the points of the grid of ``params`` (as a
    :class:`~pdverify.core.result.Result` with ``info``: the method, the levels, ``error_bound`` = its error estimate
    relative to the largest value, horizon, spacing and m of the asked grid)."""
    if scene.dynamics is not None and params.get("analysis", "auto") != "static":
        raise InputError(
            "continuum = true: the nonlocal continuum is a static solution, and this scene has a [dynamics] table; "
            "add -o static=true for its static part, or drop continuum"
        )
    timer = Timer()
    delta = horizon_of(model, scene, params)
    dx = model.spacing(scene, params)
    base = {k: v for k, v in params.items() if k not in ("horizon", "continuum")}
    base["horizon_length"] = delta
    x_user = None
    info = {"horizon": delta, "spacing": dx, "m": delta / dx}
    with timer("solve"):
        limit = model.continuum_limit(scene, base)
        series = None if limit else model.continuum_series(scene, params)
        solved = None
        if series is not None:
            x_user = _grid_of(model, scene, base, params["points"])
            got = series_solution(scene, series, x_user, need=SERIES_TOL)
            if got is not None and got[2] <= SERIES_TOL:
                q, rot, est = got
                info.update(continuum="closed form: series of the mirror modes", error_bound=est)
                fields = {} if series.quantity == "w" else {series.quantity: q}
                w = q if series.quantity == "w" else np.zeros_like(q)
                solved = (x_user, w, rot if series.quantity == "w" or series.slope is not None else None, fields)
        if solved is None:
            solved, more = _extrapolated(model, scene, base, delta, dx, limit)
            merge_info(info, more)
    x, w, rot, fields = solved
    whole = model.continuum_whole(params)
    if whole and "continuum_levels" in info and abs(info["m"] - round(info["m"])) > 1e-9 * info["m"]:
        info["error_bound"] = math.inf  # the levels keep one fraction of m: their limit is not the continuum's
        info["no_limit"] = f"m = {info['m']:.6g} is not whole and {whole}"  # a study flags its series
        info.setdefault("warnings", []).append(
            f"continuum of {model.name} at horizon {delta:g}: m = {info['m']:.6g} is not whole and {whole}: the "
            "extrapolation has no smooth limit to find; give points with (points - 1) delta / length whole"
        )
    est = info.get("error_bound", math.inf)
    if est > ACHIEVED and "no_limit" not in info:
        info.setdefault("warnings", []).append(
            f"continuum of {model.name} at horizon {delta:g}: estimated error {est:.2g} relative to the largest value "
            f"(above {ACHIEVED:g}; {info['continuum']})"
        )
    return model.new_result(scene, params, x, w, rotation=rot, fields=fields, dofs=0, timings=timer.timings, info=info)


def no_limit_warning(model, scene: Scene, params: dict) -> str:
    """The warning of a solve at a fixed horizon length (option ``horizon_length``, not its continuum) where the
    variant has no limit at fixed delta on ``scene`` (:meth:`~pdverify.core.contract.Model.continuum_limit`): refining
    such a grid at that horizon does not converge, so its result is one grid's; "" otherwise."""
    if params.get("horizon_length") is None or params.get("continuum"):
        return ""
    limit = model.continuum_limit(scene, params)
    if limit is None:
        return ""
    return (
        f"{model.name} at horizon_length = {float(params['horizon_length']):g}: {limit[0]}; more points at this "
        "horizon do not converge to a nonlocal solution, so this result is one grid's, not its continuum"
    )


MODEL_ERROR_LIMIT = 0.01  # the nonlocal model error on the first sine mode above which a result says so


def model_error_warning(model, scene: Scene, info: dict, params: dict | None = None) -> str:
    """The warning of a horizon long for the beam: the model's continuum is softer than the local theory by about
    g (k delta)^2 (stiffer where g < 0: pd-higher-order with Poisson's ratio below -1/2) on a mode of wave number k
    (:meth:`~pdverify.core.horizon.Horizon.gradient_coefficient`), which on the beam's first sine mode (k = pi / L)
    passes :data:`MODEL_ERROR_LIMIT` in size; "" otherwise. The estimate is the
    leading term only, and the first mode's: ends without a limit at fixed delta (docs/nonlocal.md) and shorter
    spans between inner supports lose more. ``params``: the solve's options, whose variant's ends may multiply it
    (:meth:`~pdverify.core.horizon.Horizon.model_error_ends`: measured, and said in the warning)."""
    g, delta = model.gradient_coefficient(scene, {}), info.get("horizon")
    if g is None or not delta:
        return ""
    size = g * (math.pi * float(delta) / scene.length) ** 2  # negative: stiffer than the local theory
    factor, why = model.model_error_ends(scene, params or {}, float(delta))
    if abs(size) * factor <= MODEL_ERROR_LIMIT:
        return ""
    ends = f"; {why} makes it up to {factor:g} times that, {100 * abs(size) * factor:.2g} %" if factor > 1 else ""
    return (
        f"{model.name}: the horizon {float(delta):.3g} is {100 * float(delta) / scene.length:.2g} % of the beam's "
        f"length: its nonlocal model error on the beam's first sine mode is about g (pi delta / L)^2 = "
        f"{100 * size:.2g} % (g = {g:.4g}, the model's gradient coefficient{ends}; more where its ends have no limit "
        "at fixed delta: docs/nonlocal.md); a shorter horizon comes nearer the local beam theory"
    )


def coarsest_nested(model, scene: Scene, params: dict, x: np.ndarray) -> tuple[int, np.ndarray]:
    """(points, indices into ``x``) of the coarsest grid whose m = delta / dx is at least :data:`M_MIN` and whose
    points are points of the grid of ``params`` (its points ``x``; refined from it by a whole factor), the grid of
    ``params`` itself when none is coarser. Its continuum has every level from m = M_MIN up, and the continua of a
    series of grids at one horizon are one."""
    n, dx = params["points"], model.spacing(scene, params)
    base = {k: v for k, v in params.items() if k not in ("horizon", "continuum")}
    base["horizon_length"] = horizon_of(model, scene, params)
    m = base["horizon_length"] / dx
    best = (n, np.arange(n))
    for f in sorted({2**k for k in range(1, 31)} | {3**k for k in range(1, 20)}):
        if m / f < M_MIN * (1 - 1e-9):
            break
        for cand in sorted({(n - 1) // f + 1, n // f}):
            try:
                if cand < 3 or _refined(model, scene, dict(base, points=cand), f) != n:
                    continue
                idx = _indices(np.asarray(x, float), _grid_of(model, scene, base, cand), scene.length)
            except InputError:
                continue
            if idx is not None and cand < best[0]:
                best = (cand, idx)
    return best


def _grid_of(model, scene: Scene, base: dict, points: int) -> np.ndarray:
    """The points of the model's grid with ``points`` (its own solve's x, from a solve of the grid)."""
    return np.asarray(_level(model, scene, base, points)["x"])


def _refined(model, scene: Scene, base: dict, r: int) -> int:
    """The number of points of the grid of spacing dx / r (nodes with the ends: (n - 1) r + 1; cells: n r)."""
    n, dx = base["points"], model.spacing(scene, base)
    for cand in ((n - 1) * r + 1, n * r):
        if abs(model.spacing(scene, dict(base, points=cand)) * r / dx - 1.0) < 1e-12:
            return cand
    raise InputError(f"model {model.name}: no grid of spacing dx / {r} found for the continuum")


def _extrapolated(model, scene: Scene, base: dict, delta: float, dx: float, limit: tuple[str, int] | None):
    """((x, w, rotation, fields), info) of the extrapolation in m, or the finest grid of a variant without limit
    (``limit``: :meth:`~pdverify.core.contract.Model.continuum_limit`'s answer)."""
    m_user = delta / dx
    x_user = _grid_of(model, scene, base, base["points"])
    if limit is not None:
        why, m_top = limit
        r = max(1, int(math.floor(m_top / m_user + 1e-9)))
        levels = [r] if r == 1 else [max(1, r // 2), r]
        values = [_values_at(model, scene, base, _refined(model, scene, base, q), x_user) for q in levels]
        fine = values[-1]
        est = _relative(values[0][model.measures], fine[model.measures]) if len(values) > 1 else math.inf
        info = {
            "continuum": f"its own finest grid at this horizon, m = {m_user * r:g} ({why})",
            "continuum_levels": [m_user * q for q in levels],
            "error_bound": est,
            "no_limit": why,
            "warnings": [
                f"{model.name}: {why}; its continuum here is its own finest grid (m = {m_user * r:g}), "
                + (
                    f"which differs from the next coarser by {est:.2g}"
                    if len(values) > 1
                    else "the asked grid itself: no coarser grid to estimate its error from (error_bound inf)"
                )
                + ": m-convergence measured against it is flagged"
            ],
        }
        return _unpack(x_user, fine), info
    step = 2
    r0 = max(1, int(math.ceil(M_MIN / m_user - 1e-9)))
    if not _nested(model, scene, base, x_user, r0 * step):
        step = 3  # cell-centred grids nest under odd refinements only
        r0 = r0 if r0 % 2 else r0 + 1
    levels, values, bounds = [], [], []  # bounds: each level's round-off bound, as its solve reported it
    best, est, each = None, math.inf, {}
    key = model.measures
    r = r0
    top = base.get("continuum_m") or model.continuum_m
    stopped = ""
    while m_user * r <= top * (1 + 1e-9) or len(levels) < 2:
        try:
            points = _refined(model, scene, base, r)
            values.append(_values_at(model, scene, base, points, x_user))
        except (InputError, SolveError) as exc:  # the model refuses this grid (a memory or size limit) or cannot
            stopped = f"; the grid of m = {m_user * r:g} not solved: {exc.lines[0].split('; ')[0]}"  # solve it
            break
        bound = _bound_of(model, scene, base, points)
        if len(levels) >= 3 and bound > est:  # a level whose round-off passes the estimate adds only noise
            values.pop()
            stopped = f"; m = {m_user * r:g} not used: its round-off bound {bound:.2g} passes the estimate"
            break
        levels.append(r)
        bounds.append(bound)
        if len(levels) >= 3:
            best, est, each = neville(np.array([1.0 / q for q in levels]), values, key)
            if est <= max(TOL, NOISE * max(bounds)):  # converged, or to the levels' own round-off
                break
        r *= step
    if best is None:
        best, est, each = values[-1], _change(values[0], values[-1]) if len(values) > 1 else math.inf, {}
    if levels and m_user * levels[-1] > top * (1 + 1e-9):
        stopped += (
            f"; m = {m_user * levels[-1]:g} past continuum_m = {top:g}: two levels at least, each {step} times the last"
        )
    info = {
        "continuum": f"extrapolated in m at fixed delta from m = {', '.join(f'{m_user * q:g}' for q in levels)}"
        + stopped,
        "continuum_levels": [m_user * q for q in levels],
        "error_bound": est,
        "continuum_errors": each,
    }
    return _unpack(x_user, best), info


def _unpack(x: np.ndarray, values: dict):
    fields = {k: v for k, v in values.items() if k not in ("w", "rotation")}
    return x, values["w"], values.get("rotation"), fields


def _nested(model, scene, base, x_user, r) -> bool:
    x = np.asarray(_level(model, scene, base, _refined(model, scene, base, r))["x"])
    return _indices(x, x_user, scene.length) is not None


def _indices(x: np.ndarray, x_user: np.ndarray, L: float) -> np.ndarray | None:
    i = np.clip(np.searchsorted(x, x_user), 0, len(x) - 1)
    i = np.where((i > 0) & (np.abs(x[i - 1] - x_user) < np.abs(x[i] - x_user)), i - 1, i)
    return i if np.all(np.abs(x[i] - x_user) <= 1e-9 * L) else None


def _values_at(model, scene, base, points: int, x_user) -> dict:
    """w, rotation and every point field of the level with ``points`` at the asked points."""
    solved = _level(model, scene, base, points)
    idx = _indices(np.asarray(solved["x"]), x_user, scene.length)
    if idx is None:
        raise InputError(f"model {model.name}: the grid of {points} points does not hold the asked points")
    return {k: np.asarray(v)[idx] for k, v in solved.items() if k not in ("x", "bound")}


def _bound_of(model, scene, base, points: int) -> float:
    """The round-off bound (relative) of the level with ``points``, as its solve reported it (0 where none)."""
    return float(_level(model, scene, base, points)["bound"])


def _level(model, scene: Scene, base: dict, points: int) -> dict:
    """One level's solution (kept: the levels of the grids of one study overlap)."""
    key = json.dumps(dict(base, points=points), sort_keys=True, default=str)
    return _cached_level(model, scene.model_dump_json(), key)


@lru_cache(maxsize=32)
def _cached_level(model, scene_json: str, key: str) -> dict:
    scene = Scene.model_validate_json(scene_json)
    params = model.resolve(scene, json.loads(key))
    r = model.solve(scene, params)
    bound = r.info.get("error_bound")
    out = {"x": np.asarray(r.x, float), "w": np.asarray(r.w, float), "bound": float(bound or 0.0)}
    if r.rotation is not None:
        out["rotation"] = np.asarray(r.rotation, float)
    for k, v in r.fields.items():
        if np.shape(v) == np.shape(r.x):
            out[k] = np.asarray(v, float)
    return out


def _change(a: dict, b: dict) -> float:
    """The largest change between two levels' values, each field relative to its largest value."""
    return max(_relative(a[k], b[k]) for k in b if k in a)


def _relative(a, b) -> float:
    scale = float(np.abs(b).max())
    return float(np.abs(a - b).max() / scale) if scale > 0 else float(np.abs(a - b).max())


def neville(h: np.ndarray, values: list[dict], key: str = "w") -> tuple[dict, float, dict]:
    """(values at h = 0, estimate, the estimate of every field) of Neville's polynomial extrapolation of the levels'
    values (dicts of arrays) at spacings h (decreasing). Column j eliminates the terms h^1..h^j; the column whose two
    finest entries of ``key`` differ least (relative to its largest value) is taken, its finest entry returned, that
    difference its estimate."""
    K = len(h)
    keys = [k for k in values[-1] if all(k in v for v in values)]
    T = [[{k: np.asarray(values[i][k], float) for k in keys}] for i in range(K)]
    for i in range(1, K):
        for j in range(1, i + 1):
            f = h[i - j] / h[i] - 1.0
            T[i].append({k: T[i][j - 1][k] + (T[i][j - 1][k] - T[i - 1][j - 1][k]) / f for k in keys})
    best, est, col = T[K - 1][0], math.inf, 0
    for j in range(K - 1):
        e = _relative(T[K - 2][j][key], T[K - 1][j][key])
        if e < est:
            best, est, col = T[K - 1][j], e, j
    return best, est, {k: _relative(T[K - 2][col][k], T[K - 1][col][k]) for k in keys}
