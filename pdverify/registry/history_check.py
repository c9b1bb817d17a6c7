"""A transient's discretisation error estimated from the model itself: the same history on about half the points.

A time history on a grid carries the spatial error of the operator and the dispersion of the waves the grid cannot
carry (a load applied at once excites them all), neither of which a static line sees: pd-timoshenko's history on a
clamped-clamped beam with a patch and a couple was 13.7 % of its largest value off exact-modal-timoshenko at 161
points, 7.0 % at 321 (first order), with no warning (sweep 34). The history on (n + 1) / 2 points differs from the
one on n by about (2^p - 1) times the finer one's error at order p (Richardson), so that difference, taken as the
estimate, is the error's at first order and above it at higher orders (beside a travelling front, whose largest error
need not fall with the spacing, it says only that the error is of that size); the result records it
(``info["history_estimate"]``) and warns where it passes 1e-3 of a series' largest value, or where the coarser run
does not run (blows up, or is refused). The closed-form references (``Model.reference``: exact-modal-*) are left
out; fem-timoshenko's transient, a discretised reference, is checked too (its history was 5.6 % off at 161 points)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.text import rounded_up
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning


class Coarser(NamedTuple):
    """The same run on (n + 1) / 2 points: ``result`` None where the grid is below the model's least (``least``) or
    refused (``refusal``: the first line of the model's error)."""

    n: int
    points: int
    record: dict
    result: object
    least: int
    refusal: str


def coarser_run(m, params: dict, result, key: str, solve) -> Coarser:
    """:class:`Coarser` from ``solve((n + 1) / 2)`` for ``params["points"]`` = n; its record ({"grids"}) is put in
    ``result.info[key]``."""
    n = int(params["points"])
    least = int(m.option("points").minimum or 2)
    coarse_n = (n + 1) // 2
    record: dict = {"grids": [coarse_n, n]}
    result.info[key] = record
    if coarse_n < least:
        return Coarser(n, coarse_n, record, None, least, "")
    try:
        return Coarser(n, coarse_n, record, solve(coarse_n), least, "")
    except (InputError, SolveError) as exc:  # the model's rules refuse the coarser grid, or it blows up
        return Coarser(n, coarse_n, record, None, least, str(exc).splitlines()[0])


def history_difference(fine: dict, coarse: dict) -> tuple[float, str]:
    """(the largest difference of the two histories' common series at the finer one's times, relative to each series'
    largest value on the finer one; the series where it is): the coarser history interpolated in time."""
    t, tc = np.asarray(fine["t"], float), np.asarray(coarse["t"], float)
    worst, where = 0.0, ""
    for name, values in fine["series"].items():
        if name not in coarse["series"]:
            continue
        a = np.asarray(values, float)
        top = float(np.abs(a).max()) if a.size else 0.0
        if top > 0.0:
            d = float(np.abs(a - np.interp(t, tc, np.asarray(coarse["series"][name], float))).max() / top)
            if d > worst:
                worst, where = d, name
    return worst, where


def history_check(scene, m, params: dict, result, solve) -> None:
    """Add ``info["history_estimate"]`` ({"grids", "difference", "series"}) to a transient ``result`` of model ``m``
    on ``params["points"]`` points, from ``solve(points)`` (the same scene and options on (n + 1) / 2 points), and a
    warning where the difference passes the tolerance. Nothing where the coarser grid is refused or does not run (a
    note in the record says why)."""
    n, coarse_n, record, coarse, least, refusal = coarser_run(m, params, result, "history_estimate", solve)
    if coarse is None and not refusal:
        record["note"] = f"no coarser grid: {coarse_n} points is below the model's {least}"
        return
    if coarse is None:  # the model's rules refuse the coarser grid, or its transient blows up
        record["note"] = f"the coarser grid does not run: {refusal}"
        result.info.setdefault("warnings", []).append(
            f"the history's error is not estimated: the same run on {coarse_n} points does not run ({refusal}); "
            "refine and compare, or measure it against a reference history (exact-modal-*) in a study"
        )
        return
    if "history" not in coarse.info:
        record["note"] = "the coarser grid gives no history"
        return
    diff, where = history_difference(result.info["history"], coarse.info["history"])
    record.update(difference=diff, series=where)
    if diff > TOLERANCE:
        result.info.setdefault("warnings", []).append(
            f"the history on {coarse_n} points differs from this one on {n} by {rounded_up(diff)} of its largest "
            f"value ({where}): its error on this grid is of about that size (a load or an end motion applied at once "
            "sends waves the grid cannot carry; beside a travelling front the largest difference need not fall with "
            "the spacing); refine and compare, or measure it against a reference history (exact-modal-*) in a study"
        )
