"""The round-off bound against the round-off a solve makes (benchmarks/trust_sweep.py, one case each).

The measured round-off of a case: the scene solved as given and with every length, the modulus and the loads scaled
by factors that are not powers of two (in exact arithmetic the relative deflections are one; their largest
difference samples the rounding of the assembled data), and once with every system refined in extended precision
(the solve's own error); differences below a few eps count as a few eps. The bound ``info["error_bound"]`` must
hold it (a bound below it misses), and the references' bound may exceed it by at most ~100x (a larger bound makes
a reference row ``suspect`` where its error is fine: docs/trust.md).

Measured (ratio bound / measured): fem-eb and fem-timoshenko at 10,001 points 5-22; exact-curved 21-63 (56 straight
cases) and 4.7-216 (84 arcs of 60, 120 and 270 degrees); pd-curved's mixed form 10-13 and
its primal form 21-155 at 41-321 particles; pd-bond-pair 5-1200.
"""

import importlib.util

import pytest
from helpers import ROOT

spec = importlib.util.spec_from_file_location("trust_sweep", ROOT / "benchmarks" / "trust_sweep.py")
sweep = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sweep)

REFERENCE_RATIO = 100  # a reference's bound within this factor of its round-off (module docstring)


@pytest.mark.parametrize("model", ["fem-eb", "fem-timoshenko"])
@pytest.mark.parametrize("pair", [("clamped", "pinned"), ("pinned", "guided"), ("clamped", "free")])
@pytest.mark.parametrize("slenderness", [20.0, 1e4])
def test_a_reference_bound_holds_its_round_off_without_crying_wolf(model, pair, slenderness):
    row = sweep.case(model, pair, 4001, slenderness)
    assert row["status"] == "ok", row
    assert row["measured"] <= row["bound"] <= REFERENCE_RATIO * row["measured"], row


@pytest.mark.parametrize(
    "pair", [("pinned", "clamped"), ("roller", "clamped"), ("clamped", "clamped"), ("guided", "pinned")]
)
@pytest.mark.parametrize("slenderness", [20.0, 1e4])
def test_exact_curved_bounds_its_round_off_without_crying_wolf(pair, slenderness):
    """exact-curved's bound (the cantilever states' quadrature and the amplitudes' Skeel bound, exact/curved.py) holds
    the round-off and stays within 100x of it; with 64 cond eps in its place pinned-clamped at L/h = 20 read 1e5 times
    its round-off (its end conditions' condition number 7.5e5, the amplitudes' error far below it)."""
    row = sweep.case("exact-curved", pair, 41, slenderness)
    assert row["status"] == "ok" and row["bound_kind"] == "error_bound", row
    assert row["measured"] <= row["bound"] <= REFERENCE_RATIO * row["measured"], row


@pytest.mark.parametrize(
    "model, points, pair",
    [
        ("pd-curved", 161, ("pinned", "guided")),
        ("pd-bond-pair", 401, ("guided", "pinned")),
        ("pd-eb", 401, ("clamped", "free")),
        ("pd-timoshenko", 401, ("clamped", "pinned")),
        ("pd-higher-order", 401, ("pinned", "guided")),  # its deflection's bound, not its w* = O(w / h^2)'s
    ],
)
def test_a_model_bound_holds_its_round_off(model, points, pair):
    row = sweep.case(model, pair, points, 1e4)
    assert row["status"] == "ok", row
    assert row["measured"] <= row["bound"], row


@pytest.mark.parametrize("pair", [("clamped", "free"), ("guided", "pinned")])
def test_the_mirror_ends_bound_is_the_element_residuals(pair):
    """pd-bond-pair with mirror ends refines against the element residual, whose terms round like second
    differences: its bound is Skeel's over those terms (dimensionless: the same at L/h = 20 and 10^4), holds the
    round-off and grows like eps N^2 (the inverse of a fourth-order operator applied to terms of a second
    difference's size; 0.4-1.7 eps N^2 measured here at 1,001 points), not like the assembled matrix's bound,
    ~ N^4 eps: 1.4e-4 and 2.4e-4 here, for a measured round-off of 1e-14 to 3e-14."""
    rows = [sweep.case("pd-bond-pair", pair, 1001, s, {"ends": "mirror"}) for s in (20.0, 1e4)]
    for row in rows:
        assert row["status"] == "ok", row
        assert row["measured"] <= row["bound"] <= 100 * 2.0**-52 * 1001**2, row
    assert 0.5 <= rows[0]["bound"] / rows[1]["bound"] <= 2.0, rows
