"""`pdverify solve --estimate`: the Richardson estimate of a result's discretisation error (pdverify.measure.richardson)
against its true error, on a sweep of straight scenes (every support pair, mixed loads: point forces and moments
anywhere, partial and sine distributed loads) for each corrected PD model and grid. Where the estimate calls its
grids asymptotic it is within a factor ESTIMATE_FACTOR of the true error on at least SHARE of the cases; where they
are not, it says so (and the result carries the warning)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.measure.richardson import nested_grids, richardson, with_estimate
from pdverify.registry import get_model, run

ESTIMATE_FACTOR = 3.0  # the estimate within this factor of the true error
SHARE = 0.9  # ... on at least this share of the asymptotic cases
MODELS = {"pd-eb": "exact-eb", "pd-bond-pair": "exact-eb", "pd-timoshenko": "exact-timoshenko"}
LOAD_SETS = [MIXED_LOADS[:1], MIXED_LOADS[2:4], MIXED_LOADS]


def cases():
    for name in MODELS:
        for (left, right), loads in zip(PAIRS, LOAD_SETS * len(PAIRS)):
            for n in (41, 161):
                yield name, left, right, loads, n


def true_error(scene, name, result) -> float:
    exact = get_model(MODELS[name]).evaluator(scene, {})(result.x)["w"]
    return float(np.abs(result.w - exact).max() / np.abs(exact).max())


@pytest.mark.slow
def test_the_estimate_is_within_a_factor_3_where_it_says_its_grids_are_asymptotic():
    within, asymptotic, rows = 0, 0, []
    for name, left, right, loads, n in cases():
        scene = parse_scene(scene_dict(left, right, loads))
        result = with_estimate(scene, get_model(name), {"points": n}, run)
        est, err = result.info["estimate"], true_error(scene, name, result)
        rows.append((name, left, right, len(loads), n, est["error"], err, est["asymptotic"]))
        if est["asymptotic"] and err > 1e-9:  # above the round-off floor
            asymptotic += 1
            within += 1 / ESTIMATE_FACTOR <= est["error"] / err <= ESTIMATE_FACTOR
        else:
            assert est["asymptotic"] or any(w.startswith("estimate:") for w in result.info["warnings"])
    assert asymptotic >= len(rows) // 2, rows  # the sweep is mostly asymptotic: the check has cases to judge
    assert within >= SHARE * asymptotic, [r for r in rows if r[-1]]


def test_nested_grids_halve_the_spacing():
    assert nested_grids(101, 5) == ((26, 51, 101), 2)
    assert nested_grids(103, 5) == ((52, 103, 205), 1)
    assert nested_grids(104, 5) == ((104, 207, 413), 0)
    assert nested_grids(9, 5) == ((5, 9, 17), 1)


def test_a_model_exact_for_the_scene_is_at_its_round_off():
    """fem-eb is nodally exact: its grids agree to round-off, and the estimate says so (no order)."""
    scene = parse_scene(scene_dict("clamped", "pinned", MIXED_LOADS))
    est = with_estimate(scene, get_model("fem-eb"), {"points": 41}, run).info["estimate"]
    assert est["asymptotic"] and est["error"] < 1e-12 and "round-off" in est["why"]


def test_the_estimate_of_a_second_order_model_from_three_grids():
    """On a sine load the error of pd-eb (corrected) is C dx^2 from about 41 points (orders 1.84, 1.93, 1.97 from 21
    to 161): three grids give the order 2 and the error at the middle one within the factor."""
    scene = parse_scene(scene_dict("pinned", "pinned", [{"type": "distributed", "value": -1.0, "shape": "sine"}]))
    results = [run(scene, "pd-eb", points=n) for n in (41, 81, 161)]
    est = richardson(results, 1, "w", 2.0)
    assert est.asymptotic and abs(est.order - 2) < 0.1
    assert 1 / ESTIMATE_FACTOR <= est.error / true_error(scene, "pd-eb", results[1]) <= ESTIMATE_FACTOR
