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


def estimate_bytes(scene, model, params: dict) -> tuple[int, float, int] | None:
    """(bytes, unknowns, bandwidth) of a run of ``model`` with resolved ``params`` on ``scene``, from two probe
    solves; None when the model assembles no banded system (exact, explicit dynamics) or a probe fails."""

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
    (n0, d0, b0), (n1, d1, b1) = sizes
    per_point = (d1 - d0) / (n1 - n0)
    dofs = d1 + per_point * (params["points"] - n1)
    band = max(b0, b1)
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
    if not isinstance(points, int) or points < PROBE_FROM:
        return
    have = available_bytes()
    if have is not None and BYTES_PER_POINT * points > have:  # the output alone (exact models: all of it)
        raise SolveError(
            f"points = {points if points < 1e15 else format(points, '.3g')}: model {model.name} would need at least "
            f"{BYTES_PER_POINT * points / 2**30:.3g} GiB for "
            f"its grid and fields, {have / 2**30:.1f} GiB is available; use at most about {have // BYTES_PER_POINT} "
            "points"
        )
    est = estimate_bytes(scene, model, params) if have is not None else None
    if est is None:
        return
    need, dofs, band = est
    if need > have:
        fits = int(have / (BYTES_PER_BAND_ENTRY * band * dofs / points))
        raise SolveError(
            f"points = {points}: model {model.name} would need about {need / 2**30:.1f} GiB ({dofs:.3g} unknowns x "
            f"bandwidth {band}), {have / 2**30:.1f} GiB is available; use at most about {fits} points"
        )
