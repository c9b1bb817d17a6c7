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
from pdverify.measure.richardson import feature_gap, nested_grids, richardson, with_estimate
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


def moment_near_the_clamp(position: float):
    """A 1 m clamped-roller strip, 20 x 20 mm (L/h = 50), a couple of 100 N m at ``position``."""
    d = scene_dict("clamped", "roller", [{"type": "point_moment", "position": position, "value": 100.0}])
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.02})
    return parse_scene(d)


def test_grids_that_do_not_resolve_the_scene_are_not_asymptotic():
    """A couple 0.01 L from the clamp: fem-plane-stress's grids of 21, 41 and 81 stations (spacings 0.05 ... 0.0125 L)
    all put it inside the clamp's first element, converge to each other at about order 2 and give an estimate tens of
    times below the error of the finest (against 321 stations, itself still 1e-3 off). Their coarsest spacing is
    wider than the couple's distance to the clamp, so the estimate is not asymptotic and says why; at 0.3 L the same
    grids resolve the scene."""
    scene = moment_near_the_clamp(0.01)
    results = [run(scene, "fem-plane-stress", points=n) for n in (21, 41, 81)]
    fine = run(scene, "fem-plane-stress", points=321)
    err = float(np.abs(results[-1].w - np.interp(results[-1].x, fine.x, fine.w)).max() / np.abs(fine.w).max())
    blind = richardson(results, 2, "w", 2.0)  # without the scene: the danger the rule is for
    assert blind.asymptotic and blind.error < err / 10, (blind, err)
    est = richardson(results, 2, "w", 2.0, scene)
    assert not est.asymptotic and not est.resolved and "closest features (0.01" in est.why
    assert feature_gap(moment_near_the_clamp(0.3)) == pytest.approx(0.3)
    no_order = richardson(results[::-1], 2, "w", 2.0, scene)  # differences that grow: no order, and still unresolved
    assert not no_order.resolved and "do not converge" in no_order.why and "closest features" in no_order.why
    assert richardson(results, 2, "w", 2.0, moment_near_the_clamp(0.3)).resolved


def test_the_feature_gap_counts_every_position_of_the_scene():
    """Ends, inner supports, point loads, distributed loads' ends and segments' ends; coincident ones count once."""
    d = scene_dict(
        "clamped",
        "free",
        [
            {"type": "point_force", "position": 0.5, "value": 1.0},
            {"type": "distributed", "value": -1.0, "start": 0.5, "end": 1.3},
        ],
        supports={"left": "clamped", "right": "free", "inner": [{"position": 1.2, "type": "pinned"}]},
    )
    assert feature_gap(parse_scene(d)) == pytest.approx(0.1)  # 1.2 to 1.3 on a 2 m beam
    assert feature_gap(parse_scene(scene_dict("pinned", "pinned"))) == pytest.approx(2.0)


def test_a_model_that_says_its_error_is_irregular_gets_no_trusted_estimate():
    """pd-higher-order's cantilever with its clamp's layer in transition (spacing 2.8-11 widths of the layer): the
    grids 81, 161, 321 give a clean order 2.1 and an estimate 33 times below the error at 321 points (2.9e-6 against
    9.8e-5, measured against exact-higher-order). The model says so in info["irregular"], and the estimate is not
    asymptotic."""
    d = scene_dict("clamped", "free", [{"type": "point_force", "position": 1.0, "value": 50.0}])
    d.update(beam={"length": 1.0}, section={"width": 0.01, "height": 0.01})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    scene = parse_scene(d)
    result = with_estimate(scene, get_model("pd-higher-order"), {"points": 321}, run)
    est = result.info["estimate"]
    assert result.info["irregular"] and not est["asymptotic"] and "the model's own warning" in est["why"]
    assert est["line"] in result.info["warnings"]


@pytest.mark.parametrize("k", [1.0, 1e3, 1e-3])
def test_an_exact_model_agrees_to_round_off_in_any_units(k):
    """fem-eb is exact at its nodes with a prescribed deflection and a force: its nested grids differ by ~4e-14 and
    now agree to round-off at every scale (its bound leaves the prescribed path out: before, the verdict was
    observed order 0.37, 3.17 or -4.9 with the units)."""
    d = scene_dict(
        "clamped",
        "pinned",
        [
            {"type": "displacement", "position": 0.8 * k, "value": -0.003 * k},
            {"type": "point_force", "position": 1.5 * k, "value": 200.0},
        ],
    )
    d.update(beam={"length": 2.0 * k}, section={"width": 0.05 * k, "height": 0.1 * k})
    r = with_estimate(parse_scene(d), get_model("fem-eb"), {"points": 21}, run)
    assert r.info["estimate"]["asymptotic"] and r.info["estimate"]["why"] == "the grids agree to their round-off"


@pytest.mark.parametrize("degree, form, order", [(4, "mixed", 4.0), (3, "mixed", 4.0), (2, "mixed", 2.0)])
def test_pd_curved_s_estimate_holds_the_order_its_degree_promises(degree, form, order):
    """pd-curved converges at order 2 ceil(P / 2) (mixed) or 2 floor(P / 2) (primal), not the 2 every model declares
    by default: its default degree 4 observed 4.4 on a clamped-pinned beam under mixed loads and the estimate called
    that "not asymptotic" (26 of 28 cases of benchmarks/estimate_sweep.py; now 26 trusted, all within 3x)."""
    m = get_model("pd-curved")
    assert m.promised_order({"degree": degree, "form": form}) == order
    assert m.promised_order({"degree": degree, "form": "primal"}) == 2 * (degree // 2)
    scene = parse_scene(scene_dict("clamped", "pinned", MIXED_LOADS[2:4]))
    result = with_estimate(scene, m, {"points": 41, "degree": degree, "form": form}, run)
    est = result.info["estimate"]
    exact = get_model("exact-timoshenko").evaluator(scene, {})(result.x)["w"]
    err = float(np.abs(result.w - exact).max() / np.abs(exact).max())
    assert est["asymptotic"], est["why"]
    assert 1 / ESTIMATE_FACTOR <= est["error"] / err <= ESTIMATE_FACTOR, (est["error"], err)


def test_an_estimate_at_a_fixed_horizon_length_says_it_leaves_out_the_model_error():
    """Grids that share a horizon length converge to the model's continuum at it, not to the local beam (sweep 28 R3:
    pd-eb on a pinned-pinned sine load, delta = 0.05 L, 161 points: the estimate 5.5e-5, the error against exact-eb
    1.48e-3). The line says so, with the model error g (pi delta / L)^2, and it is a warning."""
    s = parse_scene(scene_dict("pinned", "pinned", [{"type": "distributed", "shape": "sine", "value": -1e3}]))
    r = with_estimate(s, get_model("pd-eb"), {"points": 161, "horizon_length": 0.05}, run)
    line = r.info["estimate"]["line"]
    assert "not to the local beam theory" in line and line in r.info["warnings"]
    g = get_model("pd-eb").gradient_coefficient(s, {})
    assert f"{g * (np.pi * 0.05 / s.length) ** 2:.2g}" in line
    plain = with_estimate(s, get_model("pd-eb"), {"points": 161}, run)
    assert "local beam theory" not in plain.info["estimate"]["line"]


def test_an_estimate_of_a_continuum_is_its_own():
    """A continuum has no grid to refine: three continua of one function agree, and the Richardson line read
    "discretisation error ~0" (sweep 28 R8). The estimate is the continuum's own (its series' or extrapolation's)."""
    s = parse_scene(scene_dict("pinned", "pinned", [{"type": "distributed", "shape": "sine", "value": -1e3}]))
    r = with_estimate(s, get_model("pd-eb"), {"points": 41, "horizon_length": 0.1, "continuum": True}, run)
    assert r.info["estimate"]["error"] == r.info["error_bound"] > 0
    assert "continuum has no discretisation error" in r.info["estimate"]["line"]
