"""nonlocal.csv (pdverify/study/nonlocal_table.py): orders fitted against the model's continuum only where the
continuum's own error estimate cannot decide them."""

import numpy as np

from pdverify.study.nonlocal_table import CONTINUUM_SHARE, nonlocal_rows


def _rows(continuum_error):
    """A second-order m-convergence series at delta = 0.1: err_disc = 0.1 (dx / 0.0125)^2 on four grids."""
    out = []
    for n in (81, 161, 321, 641):
        dx = 1.0 / (n - 1)
        e = 1e-3 * (dx / 0.0125) ** 2
        out.append(
            {
                "status": "ok", "scene": "s", "model": "pd-x", "options": '{"horizon_length": 0.1}',
                "slenderness": None, "points": n, "spacing": dx, "horizon": 0.1, "m": 0.1 / dx, "err_disc": e,
                "err_model": 1e-2, "err_max": 1e-2 + e, "continuum_error": continuum_error,
            }
        )  # fmt: skip
    return out


def test_an_order_against_a_continuum_that_knows_its_error_is_fitted():
    (row,) = [r for r in nonlocal_rows(_rows(None)) if r["path"] == "m-convergence"]
    assert abs(row["observed_order"] - 2) < 1e-9 and not row["continuum_in_doubt"]


def test_a_continuum_whose_own_error_could_decide_the_order_gives_none():
    smallest = 1e-3 * ((1 / 640) / 0.0125) ** 2
    (row,) = [r for r in nonlocal_rows(_rows(2 * CONTINUUM_SHARE * smallest)) if r["path"] == "m-convergence"]
    assert row["continuum_in_doubt"] and np.isnan(row["observed_order"]) and np.isnan(row["finest_order"])
    assert len(row["errors"].split()) == 4  # the errors are still listed
    (ok,) = [r for r in nonlocal_rows(_rows(0.5 * CONTINUUM_SHARE * smallest)) if r["path"] == "m-convergence"]
    assert not ok["continuum_in_doubt"] and abs(ok["observed_order"] - 2) < 1e-9


def test_the_plane_figure_says_when_the_continuum_is_in_doubt():
    """The δ–Δx plane title (pdverify/report/planes.py) names a path without an order instead of dropping it."""
    import pandas as pd

    from pdverify.report.planes import _orders

    smallest = 1e-3 * ((1 / 640) / 0.0125) ** 2
    table = pd.DataFrame(nonlocal_rows(_rows(2 * CONTINUUM_SHARE * smallest)))
    title = _orders(table, "s", "pd-x", "{}")
    assert title == "orders: m none (continuum in doubt) (δ = 0.1)", title


def test_errors_at_round_off_give_no_order():
    """A variant exact for the load (every error below metrics.ROUND_OFF_LEVEL) has no order to fit: the scatter of
    round-off (1e-13 to 1e-15) would read as any order; as in convergence.csv, the row says at_round_off."""
    import pandas as pd

    from pdverify.report.planes import _orders

    rows = _rows(None)
    for r, e in zip(rows, (9.4e-13, 8.5e-14, 8.3e-15, 2.0e-13)):
        r["err_disc"] = r["err_max"] = e
    found = {r["path"]: r for r in nonlocal_rows(rows)}
    m = found["m-convergence"]
    assert m["at_round_off"] and np.isnan(m["observed_order"]) and np.isnan(m["finest_order"])
    assert not any(r["at_round_off"] for r in nonlocal_rows(_rows(None)))  # errors of 1e-3 ... 1.6e-5: an order
    assert _orders(pd.DataFrame([m]), "s", "pd-x", "{}") == "orders: m none (exact to round-off) (δ = 0.1)"
