"""core.result: merging a solve's info into what a model gathered before it."""

from pdverify.core.result import merge_info


def test_merge_info_keeps_the_warnings_of_both_and_updates_the_rest():
    """An update would keep only the solve's list: a model's own warning (gathered before the solve) would vanish
    whenever the solve also warns (a round-off bound), as pd-timoshenko's couple-on-two-points warning did."""
    info = {"warnings": ["the model's"], "cond": 1.0}
    solve = {"warnings": ["the solve's", "the model's"], "cond": 2.0}
    got = merge_info(info, solve, analysis="static")
    assert got is info and info["warnings"] == ["the model's", "the solve's"]
    assert info["cond"] == 2.0 and info["analysis"] == "static"
    assert "warnings" not in merge_info({}, {"cond": 3.0})
