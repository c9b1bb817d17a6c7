"""The convergence table flags a series whose observed order falls far below the order its model promises
(``below_order``, beside ``promised_order``), on errors above round-off only."""

import pytest

from pdverify.study.tables import FAR_BELOW, convergence_rows


def series(model: str, errors, bound: float = 1e-15) -> list[dict]:
    spacings = [0.1, 0.05, 0.025, 0.0125][: len(errors)]
    return [
        {
            "scene": "s",
            "model": model,
            "options": "{}",
            "slenderness": 20.0,
            "status": "ok",
            "spacing": h,
            "err_max": e,
            "w_at_max": 1.0 + e,
            "error_bound": bound,
        }
        for h, e in zip(spacings, errors, strict=True)
    ]


@pytest.mark.parametrize(
    "errors, bound, flagged",
    [
        ([1e-2, 2.5e-3, 6.25e-4, 1.5625e-4], 1e-15, False),  # order 2, as promised
        ([1e-2, 8e-3, 6.4e-3, 5.12e-3], 1e-15, True),  # order 0.32: far below 2
        ([1e-2, 4.9e-3, 2.4e-3, 1.17e-3], 1e-15, False),  # order 1.03: half the promised, not below it
        ([3e-15, 2e-15, 3e-15, 2.5e-15], 1e-15, False),  # round-off: no order to flag
        ([1e-6, 8e-7, 6.4e-7, 5.12e-7], 1e-7, False),  # within 10x of the solve's round-off bound
    ],
)
def test_a_series_far_below_its_promised_order_is_flagged(errors, bound, flagged):
    (row,) = convergence_rows(series("pd-timoshenko", errors, bound))
    assert row["promised_order"] == 2.0 and FAR_BELOW * 2.0 == 1.0
    assert row["below_order"] is flagged, row


def test_pd_curved_s_series_are_held_to_its_degree_s_order():
    """pd-curved promises 2 ceil(P / 2) in the mixed form (Model.promised_order): a degree-4 series at order 1.03 is
    far below its 4, where against the 2 every model declared it was not flagged."""
    rows = series("pd-curved", [1e-2, 4.9e-3, 2.4e-3, 1.17e-3])
    for r in rows:
        r["options"] = '{"degree": 4, "form": "mixed"}'
    (row,) = convergence_rows(rows)
    assert row["promised_order"] == 4.0 and row["below_order"] is True
