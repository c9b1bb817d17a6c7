"""A static result's discretisation error estimated from the model itself: the same solve on about half the points.

For a model that asks for it (``Model.checks_own_grid``: pd-curved on a curved axis, whose PDDO derivative of the
axis frame strains a rigid motion, docs/models/curved.md; pd-rod and pd-torsion, whose horizon's error on coarse grids
has no other line), the solve on (n + 1) / 2 points differs from the one on n by about (2^p - 1) times the finer
one's error at order p (Richardson): the difference is the finer one's error at first order and above it at higher
orders, so a difference past 1e-3 says the finer grid's error may not be small. At a fixed horizon length the coarser
solve keeps the horizon factor (twice the horizon), so the difference carries the model error too, which two grids at
one horizon share. The fields are compared at the coarser grid's points, which an odd n shares with the finer grid;
with an even n the finer one is interpolated between the scene's features, never across a jump (:func:`on_coarse`),
and each field relative to its scale (:data:`GROUPS`). The result records the difference (``info["grid_estimate"]``)
and warns where it passes the tolerance; where it estimates nothing (the coarser grid refused, or the model's own
note that its error does not fall with the grid there) it says so. Grids that converge slowly, or to a locked answer,
can differ by less than their error: the difference is an estimate, not a bound.
"""

from __future__ import annotations

import numpy as np

from ..core.text import rounded_up
from ..numerics.features import features
from ..numerics.load_warnings import NEAR_TOLERANCE as TOLERANCE  # the estimates' threshold of a warning
from ..numerics.load_warnings import zoned
from .history_check import coarser_run

# each field is compared relative to the largest of its own largest value, SHARE of its group's and the size the next
# group gives it over the length L, so a component nearly zero beside its partner (N beside Q on a beam bent nearly
# straight) or a group that is zero but for round-off (N and Q under a pure couple) does not read its round-off as a
# difference: (names, the group whose largest value sets that size, that value's power of L, the size in words); any
# other field (a bar's twist and torque) is a group of its own
SHARE = 1e-2
GROUPS = (
    (("w", "u", "ux", "uy"), 1, 1, "max |rotation| L"),
    (("rotation",), 0, -1, "max |w, u| / L"),
    (("N", "Q", "V"), 3, -1, "max |M| / L"),
    (("M",), 2, 1, "max |N, Q| L"),
)


def fields_of(result) -> dict[str, np.ndarray]:
    """The result's output fields by name: w and rotation, then its other fields."""
    given = {"w": result.w, "rotation": result.rotation, **result.fields}
    out = {k: np.asarray(v, float) for k, v in given.items() if v is not None}
    return {k: v for k, v in out.items() if v.ndim == 1 and len(v) == len(result.x)}


def on_coarse(xf: np.ndarray, values: np.ndarray, xc: np.ndarray, breaks: np.ndarray) -> np.ndarray:
    """The fine grid's ``values`` at the coarse points ``xc``: where a fine point is there, its value; elsewhere a
    cubic spline through the fine points between the same two ``breaks`` (where the fields jump or kink: supports,
    loads; a point on a break holds the left limit, as the models give it), linear with fewer than 4 there; NaN
    with fewer than 2 (not compared)."""
    h = float(np.diff(xf).min()) if len(xf) > 1 else 1.0
    out = np.full(len(xc), np.nan)
    near = np.clip(np.searchsorted(xf, xc), 0, len(xf) - 1)
    near = np.where((near > 0) & (np.abs(xf[near - 1] - xc) < np.abs(xf[near] - xc)), near - 1, near)
    on = np.abs(xf[near] - xc) <= 1e-9 * h
    out[on] = values[near[on]]
    cut = breaks[(breaks > xf[0]) & (breaks < xf[-1])]
    piece_f, piece_c = np.searchsorted(cut, xf, side="left"), np.searchsorted(cut, xc, side="left")
    if np.all(on):  # nested grids (an odd n): nothing to interpolate
        return out
    from scipy.interpolate import CubicSpline  # here: its import takes 0.15 s, and an even n alone needs it

    for k in np.unique(piece_c[~on]):  # a loop over the pieces between breaks (a few), not over points
        xs, ys, at = xf[piece_f == k], values[piece_f == k], ~on & (piece_c == k)
        if len(xs) >= 4:
            out[at] = CubicSpline(xs, ys)(xc[at])
        elif len(xs) >= 2:
            out[at] = np.interp(xc[at], xs, ys)
    return out


def grid_difference(fine, coarse, breaks=()) -> tuple[float, str, str]:
    """(the largest difference of the two results' common fields at the coarser one's points (:func:`on_coarse`),
    relative to the field's scale on the finer one (:data:`GROUPS`); the field where it is; that scale in words and
    its value)."""
    a, b = fields_of(fine), fields_of(coarse)
    xf, xc = np.asarray(fine.x, float), np.asarray(coarse.x, float)
    L = float(xf[-1] - xf[0]) or 1.0
    common = [k for k in a if k in b]
    grouped = {k for g in GROUPS for k in g[0]}
    groups = [*GROUPS, *(((k,), None, 0, "") for k in common if k not in grouped)]  # others (twist, T): their own
    names = [[k for k in g[0] if k in common] for g in groups]
    tops = [max((float(np.abs(a[k]).max()) for k in ks), default=0.0) for ks in names]
    cuts = np.asarray(breaks, float)
    worst, field, against = 0.0, "", ""
    for (_, other, power, floor), ks, top in zip(groups, names, tops):
        across = 0.0 if other is None else tops[other] * L**power
        for k in ks:
            sizes = {f"max |{k}|": float(np.abs(a[k]).max()), f"{SHARE:g} max |{', '.join(ks)}|": SHARE * top}
            said, scale = max({**sizes, floor: across}.items(), key=lambda item: item[1])
            if not scale > 0.0:
                continue
            d = float(np.nanmax(np.abs(b[k] - on_coarse(xf, a[k], xc, cuts)), initial=0.0)) / scale
            if d > worst:
                worst, field, against = d, k, f"{said} = {scale:.3g}"
    return worst, field, against


def grid_check(m, scene, params: dict, result, solve) -> None:
    """Add ``info["grid_estimate"]`` ({"grids", "difference", "field"}, or a "note") to a static ``result`` of model
    ``m`` on ``scene`` on ``params["points"]`` points, from ``solve(points)`` (the same scene and options on
    (n + 1) / 2 points), and a warning where the difference passes the tolerance, or where it estimates nothing: the
    coarser grid refused, a model's own note that its error does not fall with the grid there (``info["irregular"]``:
    both grids can then agree and both be off), or grids that differ where the coarser one has a feature inside an
    end's zone (:data:`~pdverify.numerics.load_warnings.ZONES`): outside this grid's zone, or inside it at twice as
    many spacings from the end, where an end layer's error has fallen far more (pd-eb, a couple 8 spacings from a clamp:
    exact there, while the coarser grid's shear, at 4 spacings, differs by 51 times max |M| / L)."""
    n, coarse_n, record, coarse, least, refusal = coarser_run(m, params, result, "grid_estimate", solve)
    why = (
        ""
        if coarse is not None
        else f"the same solve on {coarse_n} points "
        + (f"does not run ({refusal})" if refusal else f"is below the model's least, {least}")
    )
    if coarse is not None and (irregular := result.info.get("irregular")):  # (a coarser grid's alone: its own error)
        why = irregular.removeprefix(m.name + ": ")
        why += f"; the solves on {coarse_n} and {n} points can agree while both are off"
    if not why:
        diff, field, against = grid_difference(result, coarse, features(scene))
        # grids that differ where the coarser one puts a feature inside an end's zone (its boundary layer, its fitted
        # ghosts, its cell averages: its own line) differ by that grid's error there, not this one's: this grid has
        # the feature outside its zone, or inside at twice the spacings from the end (then its own line says so)
        inside = zoned(coarse.info.get("warnings", []))
        if inside and diff > TOLERANCE:
            also = inside & zoned(result.info.get("warnings", []))
            where = (
                "where this grid does not"
                if not also
                else f"at half as many of its spacings from the end as this grid ({' and '.join(sorted(also))}: this "
                "grid's own line)"
            )
            why = (
                f"the same solve on {coarse_n} points puts {' and '.join(sorted(inside))} inside an end's zone (its "
                f"own warning), {where}, so their difference would be that grid's error, not this one's"
            )
    if why:
        record["note"] = why
        result.info.setdefault("warnings", []).append(
            f"{m.name}: the error on {n} points is not estimated: {why}; use more points, or check the result with "
            "`pdverify solve --estimate`"
        )
        return
    record.update(difference=diff, field=field)
    fixed = params.get("horizon_length") is not None  # the coarser solve at the same factor: twice the horizon
    same = f" at the same horizon factor ({result.info.get('m', 0):g} spacings: twice the horizon)" if fixed else ""
    if diff > TOLERANCE:
        result.info.setdefault("warnings", []).append(
            f"{m.name}: the same solve on {coarse_n} points{same} differs from this one on {n} by {rounded_up(diff)} "
            f"in {field} (relative to {against}), so this grid's error may pass {TOLERANCE:g} (the difference is "
            "about the error where it falls like the spacing, above it where it falls faster, and can be below it "
            "where the grids are not yet converging); "
            + ("a shorter horizon with more points" if fixed else "use more points and compare")
            + ", or check the result with `pdverify solve --estimate`"
        )
