"""The card's nonlocal check (pdverify/verify/fixed_horizon.py): at a fixed horizon length the discretisation order
is judged against the order the variant's equations give there, the model-error order reported; a model without a
horizon and a curved-axis model are not measured, and a model without a limit at fixed delta there says so."""

import pytest

from pdverify.registry import get_model
from pdverify.verify.checks import ORDER_SLACK
from pdverify.verify.fixed_horizon import NAME, nonlocal_check
from pdverify.verify.suite import exact_reference


def card_check(name, opts=None):
    m = get_model(name)
    return nonlocal_check(m, opts or {}, exact_reference(m, opts or {}))


def test_the_rod_passes_with_second_order_and_reports_its_model_error():
    c = card_check("pd-rod")
    assert c["check"] == NAME and c["verdict"] == "pass"
    assert abs(c["discretisation_order"] - 2) < 0.1 and abs(c["model_error_order"] - 2) < 0.1
    assert "the model's nonlocality, not judged" in c["summary"]


def test_the_paper_variant_is_judged_at_the_first_order_of_its_full_volumes():
    """pd-eb paper: each bond a whole volume up to delta, a one-sided rule of the horizon's integral, first order at
    fixed delta (docs/nonlocal.md): the check expects 1 and says why."""
    c = card_check("pd-eb", {"variant": "paper"})
    assert c["verdict"] == "pass" and abs(c["discretisation_order"] - 1) < 0.1
    assert "expected discretisation order 1 (variant paper's sums give each bond a whole volume" in c["summary"]


def test_the_corrected_pd_eb_is_first_order_at_a_fixed_horizon():
    """pd-eb corrected normalises its weights by (m - 1/2) dx, the trapezoidal rule of the horizon without its node at
    xi = 0, so its nonlocal term is about 1 + 1/(2m) times the continuum's: first order at fixed delta
    (docs/nonlocal.md), the order the check expects of it. Its continuum, extrapolated from m = 8 to 64 on the m = 8
    grid, is settled well below the errors it judges; measured on the m = 32 grid's own continuum (two levels, m = 32
    and 64) the last error read half its size and the order about 1.45."""
    c = card_check("pd-eb")
    assert c["verdict"] == "pass" and abs(c["discretisation_order"] - 1) < 0.1
    assert abs(c["model_error_order"] - 2) < 0.1
    assert "expected discretisation order 1 (its weights are normalised by sum beta dx" in c["summary"]


def test_taylor_ends_fail_the_order_of_their_sums():
    """pd-bond-pair's default Taylor ends: the same bond pairs with mirror ends are second order at fixed delta; no
    first order is derived for the ends, so the check expects the model's 2 and fails them (docs/nonlocal.md)."""
    c = card_check("pd-bond-pair")
    assert c["verdict"] == "fail" and c["discretisation_order"] < 2 - ORDER_SLACK
    assert c["summary"].endswith("expected discretisation order 2")  # no reason: the model's order


@pytest.mark.parametrize(
    "name, options, order",
    [
        ("pd-eb", {}, 1.0),
        ("pd-eb", {"variant": "paper"}, 1.0),
        ("pd-bond-pair", {}, 2.0),
        ("pd-bond-pair", {"ends": "mirror"}, 2.0),
        ("pd-bond-pair", {"variant": "paper"}, 1.0),
        ("pd-bond-pair", {"variant": "continuous-alpha", "ends": "mirror"}, 1.0),
        ("pd-rod", {}, 2.0),
        ("pd-timoshenko", {"variant": "corrected"}, 2.0),
    ],
)
def test_each_variant_declares_its_fixed_horizon_order(name, options, order):
    got, why = get_model(name).fixed_horizon_order(options)
    assert got == order and bool(why) == (order == 1.0)


@pytest.mark.parametrize("name", ["exact-eb", "pd-curved"])
def test_not_measured(name):
    assert card_check(name)["verdict"] == "n/a"


def test_a_model_without_a_limit_at_fixed_delta_says_why():
    """pd-higher-order's default path measures at pinned ends (docs/nonlocal.md, a limit at fixed delta)."""
    c = card_check("pd-higher-order")
    assert (
        c["verdict"] == "info"
        and c["summary"].startswith("no limit at a fixed horizon")
        and "shear = path" in c["summary"]
    )


def test_a_card_s_horizon_factor_gives_way_to_the_check_s_horizon_length():
    """`pdverify verify pd-eb --horizon 1` gave "not measured: horizon and horizon_length both given" though the
    user gave only the factor: the check holds delta as a length and drops the card's factor (the same check as
    without it)."""
    assert card_check("pd-eb", {"horizon": 1.0}) == card_check("pd-eb")


def test_verify_order_sets_the_discretisation_order_it_expects():
    """`verify --order P` reaches this check too (it kept the model's own: pd-rod --order 1 printed "expected
    discretisation order 2", sweep 12): at P = 3 the rod's second order fails, at P = 1 it passes."""
    m = get_model("pd-rod")
    c = nonlocal_check(m, {}, exact_reference(m, {}), order=3.0)
    assert c["verdict"] == "fail" and "expected discretisation order 3 (--order)" in c["summary"]
    assert nonlocal_check(m, {}, exact_reference(m, {}), order=1.0)["verdict"] == "pass"
