"""A static result's discretisation error estimated from the model itself: the same solve on about half the points.

For a model that asks for it (``Model.checks_own_grid``: pd-curved on a curved axis, whose PDDO derivative of the
axis frame strains a rigid motion, docs/models/curved.md), the solve on (n + 1) / 2 points differs from the one on n
by about (2^p - 1) times the finer one's error at order p (Richardson): the difference is the finer one's error at
first order and above it at higher orders, so a difference past 1e-3 of a field's largest value says the finer
grid's error may not be small. The result records it (``info["grid_estimate"]``) and
warns where it passes the tolerance, or where the coarser solve is refused (the grid is then near the least the
model takes). Grids that converge slowly, or to a locked answer, can differ by less than their error: the
difference is an estimate, not a bound.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.text import rounded_up
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning

# fields compared relative to their group's largest value, so a component that is nearly zero beside its partner
# (N beside Q on a beam bent nearly straight) does not read its round-off as a difference
GROUPS = (("w", "u", "ux", "uy"), ("rotation",), ("N", "Q", "V"), ("M",))


def fields_of(result) -> dict[str, np.ndarray]:
    """The result's output fields by name: w and rotation, then its other fields."""
    out = {"w": np.asarray(result.w, float), "rotation": np.asarray(result.rotation, float)}
    out.update({k: np.asarray(v, float) for k, v in result.fields.items() if k not in out})
    return out


def grid_difference(fine, coarse) -> tuple[float, str]:
    """(the largest difference of the two results' common fields at the coarser one's points, relative to the
    largest value of the field's group on the finer one; where it is, "field (relative to the largest of a, b)"):
    the finer one interpolated linearly where the grids are not nested (an even number of points)."""
    a, b = fields_of(fine), fields_of(coarse)
    xf, xc = np.asarray(fine.x, float), np.asarray(coarse.x, float)
    worst, where = 0.0, ""
    for group in GROUPS:
        names = [k for k in group if k in a and k in b and len(a[k]) == len(xf) and len(b[k]) == len(xc)]
        top = max((float(np.abs(a[k]).max()) for k in names), default=0.0)
        if top <= 0.0:
            continue
        for k in names:
            d = float(np.abs(b[k] - np.interp(xc, xf, a[k])).max() / top)
            if d > worst:
                worst, where = d, k if len(names) == 1 else f"{k}, relative to the largest of {', '.join(names)}"
    return worst, where


def grid_check(m, params: dict, result, solve) -> None:
    """Add ``info["grid_estimate"]`` ({"grids", "difference", "field"}) to a static ``result`` of model ``m`` on
    ``params["points"]`` points, from ``solve(points)`` (the same scene and options on (n + 1) / 2 points), and a
    warning where the difference passes the tolerance or where the coarser grid is refused."""
    n = int(params["points"])
    least = int(m.option("points").minimum or 2)
    coarse_n = (n + 1) // 2
    record: dict = {"grids": [coarse_n, n]}
    result.info["grid_estimate"] = record
    why = f"{coarse_n} points is below the model's {least}" if coarse_n < least else ""
    coarse = None
    if not why:
        try:
            coarse = solve(coarse_n)
        except (InputError, SolveError) as exc:  # the model's rules refuse the coarser grid (a segment too short)
            why = str(exc).splitlines()[0][:160]
    if coarse is None:
        record["note"] = f"no coarser grid: {why}"
        result.info.setdefault("warnings", []).append(
            f"{m.name}: the error on {n} points is not estimated: the same solve on {coarse_n} points does not run "
            f"({why}), so this grid is near the coarsest the model takes; use more points, or check the result with "
            "`pdverify solve --estimate`"
        )
        return
    diff, where = grid_difference(result, coarse)
    record.update(difference=diff, field=where)
    p = m.promised_order(params)
    if diff > TOLERANCE:
        result.info.setdefault("warnings", []).append(
            f"{m.name}: the same solve on {coarse_n} points differs from this one on {n} by {rounded_up(diff)} of "
            f"its largest value ({where}), so this grid's error may pass {TOLERANCE:g}: it is about that difference "
            f"at first order, about {rounded_up(diff / (2**p - 1))} once the model's order {p:g} holds, and grids "
            "that converge slowly can differ by less than their error; use more points and compare, or check the "
            "result with `pdverify solve --estimate`"
        )
