"""A study case's status from its solve's round-off bound (docs/trust.md) and its reference's: ``suspect`` when either
passes :data:`pdverify.numerics.linalg.BOUND_LIMIT` and could decide the error the row measures (is not below a
tenth of it), so no table shows a row whose error may be round-off as a plain ``ok``. A bound past the limit that
cannot decide the error stays in the row's warnings, as in every output of the solve."""

from __future__ import annotations

import math

from ..numerics.linalg import BOUND_LIMIT


def _shown(bound: float) -> str:
    return f"{bound:.2g}" if math.isfinite(bound) else "unbounded"


def case_status(info: dict, err: float = math.nan) -> dict:
    """Columns for a solved case's row from the result's ``info``: ``error_bound`` (the relative round-off
    bound of its linear solve, None when the model made none) and, when that bound passes BOUND_LIMIT or
    is not finite and is not below REFERENCE_SHARE of the row's measured error ``err`` (NaN: none measured),
    ``status = "suspect"`` with a message naming it."""
    bound = info.get("error_bound")
    if bound is None:
        return {"error_bound": None}
    bound = float(bound)
    if not in_doubt(bound, err):
        return {"error_bound": bound}
    return {
        "error_bound": bound,
        "status": "suspect",
        "message": f"round-off bound {_shown(bound)} exceeds {BOUND_LIMIT:g}"
        + (": the error measured here" if math.isnan(err) else " and a tenth of the error measured here, which")
        + " may be the solve's",
    }


REFERENCE_SHARE = 0.1  # a bound below this share of the measured error cannot change its first digit


def in_doubt(bound: float, err: float) -> bool:
    """Whether a round-off bound (a solve's, or its reference's) could decide the error measured with it: past
    BOUND_LIMIT (or not finite) and not below REFERENCE_SHARE of the error (NaN: no error to compare, in doubt).
    A bound of 1 or more is in doubt whatever the error: a first-order bound (Higham, *Accuracy and Stability*,
    §7.1) holds only for perturbations small beside the solution, so past 1 it says the solution may be all
    round-off, not how large its error may be."""
    return not (bound <= BOUND_LIMIT or (bound < 1.0 and bound < REFERENCE_SHARE * float(err)))


def reference_status(bound: float | None, row: dict, what: str = "round-off bound") -> dict:
    """Columns for the error bound of the case's reference solve (a model solved as the reference, e.g. its own
    solution on a fine grid; None for exact references): ``ref_error_bound`` and, when it passes BOUND_LIMIT (or is
    not finite) and is not below REFERENCE_SHARE of the row's measured error ``err_max`` (so it could be a tenth of
    that error or more), ``status = "suspect"`` with a message naming it (added to the row's own). ``what`` the
    bound is: a solve's round-off bound, or a continuum's own error estimate."""
    if bound is None:
        return {"ref_error_bound": None}
    bound = float(bound)
    if not in_doubt(bound, row.get("err_max", math.nan)):
        return {"ref_error_bound": bound}
    said = (
        f"the reference's {what} {_shown(bound)} exceeds {BOUND_LIMIT:g} and a tenth of the error measured "
        "here, which may be the reference's"
    )
    return {
        "ref_error_bound": bound,
        "status": "suspect",
        "message": "; ".join(m for m in (row.get("message"), said) if m),
    }
