"""The convergence check's reading of a series (pdverify/verify/checks.py): an order fitted above round-off level,
and a series whose error drops to round-off level after its coarsest grids passes as converged past any order."""

import numpy as np
import pandas as pd

from pdverify.verify import checks as C

GRIDS = [21, 41, 81, 161]


def _rows(errors_by_scene: dict) -> pd.DataFrame:
    rows = []
    for scene, errors in errors_by_scene.items():
        for n, e in zip(GRIDS, errors):
            rows.append({"scene_file": scene, "points": n, "spacing": 1.0 / (n - 1), "err_max": e, "status": "ok"})
            rows[-1].update(total_s=1e-3, message="", error_bound=0.0, ref_error_bound=None)
    return pd.DataFrame(rows)


def _second_order(c):
    return [c * (20 / (n - 1)) ** 2 for n in GRIDS]


def test_a_series_at_round_off_after_its_coarsest_grid_passes_and_is_named():
    errors = {"a": _second_order(1e-2), "b": [7e-2, 1e-12, 2e-12, 3e-12]}
    rows = C.series(_rows(errors), list(errors))
    assert [r["exact_from"] for r in rows] == [None, 41]
    check = C.convergence(rows, 2.0, "convergence (straight)")
    assert check["verdict"] == "pass", check
    assert "1 scene(s) at round-off" in check["summary"] and "41-41 points" in check["summary"], check


def test_a_series_that_stalls_above_round_off_still_fails():
    errors = {"a": _second_order(1e-2), "b": [7e-2, 3e-2, 2e-2, 1.5e-2]}
    check = C.convergence(C.series(_rows(errors), list(errors)), 2.0, "convergence (straight)")
    assert check["verdict"] == "fail" and check["failing"] == ["b"], check


def test_round_off_on_one_grid_only_is_no_pass():
    """Round-off on the finest grid alone (the one before it above) is not a resolved series."""
    rows = C.series(_rows({"b": [7e-2, 3e-2, 2e-2, 1e-12]}), ["b"])
    assert rows[0]["exact_from"] is None
    assert np.isnan(rows[0]["order"]) or rows[0]["order"] < 1.7


def test_a_scene_below_the_order_that_the_model_warns_of_is_explained_and_still_fails():
    """The card says why where the model does: the failing scenes carrying the model's own first-order warning at the
    finest grid are counted and the warning quoted; the verdict is the same."""
    errors = {"a": _second_order(1e-2), "b": [4e-2, 2e-2, 1e-2, 5e-3], "c": [4e-2, 2e-2, 1e-2, 5e-3]}
    df = _rows(errors)
    said = "model x converges at first order near a point load (x = 0.5): 2e-2, 1e-2 at 41, 81 points"
    df["warnings"] = np.where(df["scene_file"] == "b", "a load in a boundary layer; " + said, "")
    check = C.convergence(C.series(df, list(errors)), 2.0, "convergence (straight)")
    assert check["verdict"] == "fail" and check["failing"] == ["b", "c"], check
    assert check["summary"].endswith("; 1 of them warned by the model: " + said), check
    assert C.convergence(C.series(_rows(errors), list(errors)), 2.0, "c")["summary"].count("warned") == 0
