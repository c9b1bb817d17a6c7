"""Refuse a solve that cannot fit in memory, with the estimate, before the large allocation.

Generic over models: a large grid is first solved at two small sizes with the same options, which gives the
unknowns per point and the bandwidth of the assembled system (``Result.dofs``, ``info["bandwidth_lower/upper"]``);
the banded LU needs ``dofs x (2 lower + upper + 1)`` float64 values. A whole static run also holds the band it
assembled, the copies of the round-off bound (residual in long double, Hager's solves) and the fields: its
peak resident set is up to ~6 x ``8 dofs (lower + upper + 1)`` bytes (fem-eb's two-field form; the tests give
each measured peak), and the estimate takes 6 x that.
"""

from __future__ import annotations

from ..core.errors import SolveError
from ..numerics.memory import BYTES_PER_BAND_ENTRY, available_bytes
from ..registry import run

PROBE_FROM = 200_001  # points; below this a run needs < ~1 GB for every model (bench.jsonl) and is not probed
PROBES = (201, 401)
BYTES_PER_POINT = 16 * 8  # the least any run holds per point: the grid and its output fields (x, w, rotation, the
# resultants, their references and errors in a study), float64; the whole need of an exact model's run


def probe_sizes(scene, model, params: dict) -> list[tuple[int, int, int]] | None:
    """(points, unknowns, bandwidth) of ``model`` on ``scene`` at the :data:`PROBES` sizes with resolved ``params``;
    None when the model assembles no banded system (exact, explicit dynamics) or a probe fails."""
    if params.get("horizon_length") is not None:  # the factor it resolved to is the full grid's: each probe its own
        params = {k: v for k, v in params.items() if k != "horizon"}
    sizes = []
    for n in PROBES:
        try:
            r = run(scene, model, **dict(params, points=n))
        except Exception:  # noqa: BLE001 - a probe that fails says nothing; the real run reports its own error
            return None
        lo, up = r.info.get("bandwidth_lower"), r.info.get("bandwidth_upper")
        if lo is None or up is None or not r.dofs:
            return None
        sizes.append((n, r.dofs, int(lo) + int(up) + 1))
    return sizes


def extrapolated(sizes, points: int) -> tuple[float, int]:
    """(unknowns, bandwidth) at ``points`` from the probes' (points, unknowns, bandwidth), each linear in the points:
    the unknowns always, the bandwidth where it grows (a horizon given as a length spans more points on a finer
    grid), else the probes' largest."""
    (n0, d0, b0), (n1, d1, b1) = sizes
    dofs = d1 + (d1 - d0) / (n1 - n0) * (points - n1)
    band = max(b0, b1, int(round(b1 + (b1 - b0) / (n1 - n0) * (points - n1))))
    return dofs, band


def need_bytes(sizes, points: int) -> int:
    """The run's estimated peak at ``points`` (module docstring)."""
    dofs, band = extrapolated(sizes, points)
    return int(BYTES_PER_BAND_ENTRY * dofs * band)


def estimate_bytes(scene, model, params: dict) -> tuple[int, float, int] | None:
    """(bytes, unknowns, bandwidth) of a run of ``model`` with resolved ``params`` on ``scene``, from two probe
    solves (:func:`probe_sizes`); None when there is no banded system to probe."""
    sizes = probe_sizes(scene, model, params)
    if sizes is None:
        return None
    dofs, band = extrapolated(sizes, params["points"])
    return int(BYTES_PER_BAND_ENTRY * dofs * band), dofs, band


def check_memory(scene, model, given: dict) -> None:
    """Raise SolveError (exit code 3) when the run would need more memory than the machine has available."""
    if model.option("points") is None:
        return
    try:
        params = model.resolve(scene, given)
    except Exception:  # noqa: BLE001 - invalid options are reported by the run itself
        return
    points = params.get("points")
    # at a fixed horizon_length the band widens with the grid: a few thousand points may already need gigabytes
    least = 2 * PROBES[-1] if params.get("horizon_length") is not None else PROBE_FROM
    if not isinstance(points, int) or points < least:
        return
    have = available_bytes()
    if have is not None and BYTES_PER_POINT * points > have:  # the output alone (exact models: all of it)
        raise SolveError(
            f"points = {points if points < 1e18 else format(points, '.3g')}: model {model.name} would need at least "
            f"{BYTES_PER_POINT * points / 2**30:.3g} GiB for "
            f"its grid and fields, {have / 2**30:.1f} GiB is available; use at most about {have // BYTES_PER_POINT} "
            "points"
        )
    sizes = probe_sizes(scene, model, params) if have is not None else None
    if sizes is None:
        return
    need = need_bytes(sizes, points)
    if need > have:
        dofs, band = extrapolated(sizes, points)
        lo, hi = PROBES[-1], points  # the largest grid that fits: need grows with the points
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if need_bytes(sizes, mid) <= have else (lo, mid)
        raise SolveError(
            f"points = {points}: model {model.name} would need about {need / 2**30:.1f} GiB ({dofs:.3g} unknowns x "
            f"bandwidth {band}), {have / 2**30:.1f} GiB is available; use at most about {lo} points"
        )
