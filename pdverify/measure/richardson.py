"""The discretisation error of a result estimated from the model itself: Richardson extrapolation on nested grids.

Three solves on grids whose spacings halve (n, 2n - 1, 4n - 3 points, or the two coarser ones below n) give the
differences d_coarse and d_fine of successive grids at the coarser grid's points, the observed order
p = log2(d_coarse / d_fine) and the error of each grid, e_i = d_(i,i+1) 2^p / (2^p - 1), and of the finest,
d_fine / (2^p - 1) (Richardson 1911; Roache 1998, ch. 5). The estimate is trusted only in the asymptotic range:
the observed order within ASYMPTOTIC of the order the model's equations promise (``Model.promised_order``), and the
coarsest grid fine enough to place the scene's features apart (:func:`feature_gap`: a load, support or break within one
spacing of another is not resolved, and grids that do not resolve it can converge to each other with a clean order
while all of them are far from the solution), and no result saying that its model's error does not fall regularly
on its grid (``info["irregular"]``: a layer in transition, whose errors can cancel between grids). Where the grids
agree to their round-off (the solves' own bounds) the model is exact on the scene up to that round-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..core.errors import InputError
from ..numerics.features import features
from ..registry import CHECK_FLAGS, as_flag, model_options

ASYMPTOTIC = (0.75, 1.5)  # the observed order's band around the promised one, as fractions of it
NOISE = 10.0  # grids closer than this many times their round-off bounds agree to round-off


@dataclass(frozen=True)
class Estimate:
    """The estimated relative error (of max |quantity|) of the result on ``grids[at]``."""

    error: float
    order: float
    grids: tuple[int, ...]
    at: int
    asymptotic: bool
    why: str  # how the estimate was made, or why it is not to be trusted
    resolved: bool = True  # the coarsest grid places the scene's features apart (False: the estimate means nothing)
    note: str = ""  # what the estimate leaves out (at a fixed horizon length: the model error)

    def line(self) -> str:
        """One line for every output format."""
        head = f"estimate: discretisation error ~{self.error:.2g} (relative; Richardson on {self.grids}"
        head += f", observed order {self.order:.2f})" if math.isfinite(self.order) else ")"
        return (
            head
            + ("" if self.asymptotic else f"; not asymptotic: {self.why}")
            + (f"; {self.note}" if self.note else "")
        )


def nested_grids(n: int, least: int) -> tuple[tuple[int, ...], int]:
    """(three grids whose spacings halve, the index of n among them): the two coarser ones below n where the
    intervals divide and the coarsest has at least ``least`` points, else n with finer ones."""
    if (n - 1) % 4 == 0 and (n - 1) // 4 + 1 >= least:
        return ((n - 1) // 4 + 1, (n - 1) // 2 + 1, n), 2
    if (n - 1) % 2 == 0 and (n - 1) // 2 + 1 >= least:
        return ((n - 1) // 2 + 1, n, 2 * n - 1), 1
    return (n, 2 * n - 1, 4 * n - 3), 0


def feature_gap(scene) -> float:
    """The shortest distance along the axis between two of the scene's features
    (:func:`~pdverify.numerics.features.features`: its ends, the supports inside, the positions of point loads and
    prescribed displacements, the ends of distributed loads and of segments; within 1e-9 of the length, one)."""
    gaps = np.diff(features(scene))
    return float(gaps.min()) if len(gaps) else float(scene.length)


def difference(coarse, fine, quantity: str, scale: float) -> float:
    """max |coarse - fine| at the coarser grid's points, relative to ``scale`` (nested grids: the finer one's
    values there, interpolated where a model adds points of its own, such as FE load nodes)."""
    a, b = coarse.measured(quantity), fine.measured(quantity)
    return float(np.abs(a - np.interp(coarse.x, fine.x, b)).max() / scale)


def richardson(results: list, at: int, quantity: str = "w", promised: float | None = None, scene=None) -> Estimate:
    """The estimate for ``results[at]`` from three results on nested grids (coarse to fine); with ``scene``, not
    asymptotic while the coarsest grid's spacing is wider than the scene's :func:`feature_gap`."""
    grids = tuple(len(r.x) for r in results)
    scale = float(np.abs(results[-1].measured(quantity)).max()) or 1.0
    d1, d2 = difference(results[0], results[1], quantity, scale), difference(results[1], results[2], quantity, scale)
    noise = NOISE * max(float(r.info.get("error_bound") or 0.0) for r in results)
    # the floor of any grid's own rounding: a sum over its n points rounds by about n eps (Higham 2002, ch. 4), which
    # a bound that leaves out a path (a prescribed deflection's) may miss: exact grids 4e-14 apart then read as a
    # converging series whose order turned with the units (0.37, 3.17, -4.9)
    if max(d1, d2) <= max(noise, 16 * np.finfo(float).eps * max(grids)):
        return Estimate(max(d1, d2), math.inf, grids, at, True, "the grids agree to their round-off")
    p = math.log2(d1 / d2) if d1 > 0 and d2 > 0 else math.nan
    unresolved = ""
    if scene is not None:
        spacing, gap = float(np.diff(results[0].x).max()), feature_gap(scene)
        if spacing > gap * (1 + 1e-9):
            unresolved = (
                f"the coarsest grid's spacing ({spacing:.3g}) is wider than the distance between the scene's closest "
                f"features ({gap:.3g}; ends, supports, loads, breaks): refine the grid"
            )
    if not p > 0:
        why = "; ".join(filter(None, ["the grids do not converge in themselves", unresolved]))
        return Estimate(max(d1, d2), p, grids, at, False, why, resolved=not unresolved)
    q = 2.0**p
    error = (d1, d2)[at] * q / (q - 1) if at < 2 else d2 / (q - 1)
    if unresolved:
        return Estimate(max(error, d2), p, grids, at, False, unresolved, resolved=False)
    irregular = next((r.info["irregular"] for r in results if r.info.get("irregular")), "")
    if irregular:  # the model knows its error does not fall at its order on these grids
        return Estimate(max(error, d2), p, grids, at, False, f"the model's own warning: {irregular}")
    if promised is None:
        return Estimate(error, p, grids, at, True, "")
    lo, hi = (f * promised for f in ASYMPTOTIC)
    if lo <= p <= hi:
        return Estimate(error, p, grids, at, True, "")
    return Estimate(
        max(error, d2), p, grids, at, False, f"observed order {p:.2f}, the model's {promised:g}: refine the grid"
    )


def with_estimate(scene, model, options: dict, run) -> object:
    """The result of ``run(scene, model, **options)`` with ``info["estimate"]`` (the :class:`Estimate` as a dict,
    its ``line`` included), from two more solves on nested grids; a model without a grid gets none."""
    grid = model.option("points")
    params = model.resolve(scene, model_options(options))
    for k in CHECK_FLAGS:  # a bad value is refused here as run would (this run leaves the grid check out)
        if k in options:
            as_flag(options[k], k)
    options = dict(options, grid_check=False)  # the nested grids are the better estimate
    if grid is None:
        return run(scene, model, **options)
    n = params["points"]
    if params.get("continuum"):  # no grid to refine: the continuum carries its own estimate
        result = run(scene, model, **options)
        bound = float(result.info.get("error_bound", math.inf))
        line = (
            f"estimate: the model's continuum has no discretisation error; its own estimate (of its series or its "
            f"extrapolation in m) is {bound:.2g}"
        )
        result.info["estimate"] = {
            **Estimate(bound, math.nan, (n,), 0, True, "the continuum's own estimate").__dict__,
            "grids": [n],
            "line": line,
        }
        return result
    grids, at = nested_grids(n, int(grid.minimum or 2))
    options = {k: v for k, v in options.items() if k != "spacing"}  # a grid given as a spacing: n points (params)
    try:
        results = [run(scene, model, **dict(options, points=g)) for g in grids]
    except InputError:  # a coarser grid than the model's rules allow (e.g. its ends' families would overlap)
        grids, at = nested_grids(n, n + 1)
        results = [run(scene, model, **dict(options, points=g)) for g in grids]
    est = richardson(results, at, model.measures, model.promised_order(params), scene)
    if params.get("horizon_length") is not None and not params.get("continuum"):
        est = replace(est, note=fixed_horizon_note(scene, model, float(params["horizon_length"])))
    result = results[at]
    result.info["estimate"] = {**est.__dict__, "grids": list(est.grids), "line": est.line()}
    if not est.asymptotic or est.note:
        result.info.setdefault("warnings", []).append(est.line())
    return result


def fixed_horizon_note(scene, model, delta: float) -> str:
    """What an estimate on grids that share the horizon length ``delta`` leaves out: they converge to the model's
    continuum at that horizon, not to the local beam theory, whose difference (the model error) is about
    g (pi delta / L)^2 on the first sine mode (g the model's gradient coefficient, docs/nonlocal.md)."""
    g = model.gradient_coefficient(scene, {})
    size = "" if g is None else f", about {abs(g) * (math.pi * delta / scene.length) ** 2:.2g} on the first sine mode"
    return (
        f"the grids share horizon_length = {delta:g}, so this is the error to the model's own continuum at that "
        f"horizon, not to the local beam theory: the model error{size}{',' if size else ''} comes on top (more "
        "with supports inside, partial or point loads: docs/nonlocal.md)"
    )
