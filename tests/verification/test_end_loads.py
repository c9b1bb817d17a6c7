"""A load near an end that holds the deflection (pdverify/registry/end_loads.py): pd-eb's, pd-timoshenko's and
pd-bond-pair's deflection under it is off by about C (h / d)² of the load's own, d its distance from the end (sweep 18
H2: a cantilever loaded on its first 0.05 m was 13 % low at the tip at 101 points in pd-eb, 22 % in pd-bond-pair,
unwarned). Each warns with that estimate where it passes 1e-3: the estimate is above the error wherever it warns,
the error below 1e-3 wherever it does not, and a mirror image warns alike."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.registry import run
from pdverify.registry.end_loads import TOLERANCE

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}


def near_end(model: str, ends: tuple, load: dict, points: int = 201, mirror: bool = False):
    """(w's largest error against the exact beam relative to its largest value, the estimate or 0) of a 1 m steel
    beam, 20 x 50 mm, on ``ends`` under ``load`` (its mirror image: ends swapped, positions x -> 1 - x)."""
    if mirror:
        ends = ends[::-1]
        if load["type"] == "distributed":
            load = {**load, "start": 1.0 - load["end"], "end": 1.0 - load["start"]}
        else:
            load = {**load, "position": 1.0 - load["position"]}
    d = scene_dict(*ends, [load])
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    sc = parse_scene(d)
    r, e = run(sc, model, points=points), run(sc, MODELS[model], points=points)
    said = [w for w in r.info.get("warnings", []) if "(h / d)²" in w]
    # a load in the end's layer, or nearer than the estimate goes: a warning that expects large errors
    large = any("loads[0]" in w and "expect large errors" in w for w in r.info.get("warnings", []))
    estimate = float(said[0].split(", here ")[1].split(",")[0]) if said else (1.0 if large else 0.0)
    return float(np.abs(r.w - e.w).max() / np.abs(e.w).max()), estimate


@pytest.mark.parametrize("model", list(MODELS))
@pytest.mark.parametrize("ends", [("clamped", "free"), ("clamped", "clamped"), ("pinned", "pinned")])
def test_the_estimate_is_above_the_error_where_it_warns_and_the_error_is_small_where_it_does_not(model, ends):
    for a in (0.01, 0.025, 0.05, 0.1, 0.3):
        for load in (
            {"type": "distributed", "value": -5000.0, "start": 0.0, "end": a},
            {"type": "distributed", "value": -5000.0, "start": a / 4, "end": a},
            {"type": "point_force", "position": a, "value": -500.0},
        ):
            error, estimate = near_end(model, ends, load)
            assert error <= max(estimate, TOLERANCE) or estimate == 1.0, (load, error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_the_cantilever_loaded_beside_its_clamp_is_warned_and_a_mirror_image_alike(model):
    """Sweep 18 H2 at 101 points: the tip 13 % (pd-eb), 22 % (pd-bond-pair), 2.1 % (pd-timoshenko) off, now warned."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.05}
    (e1, s1), (e2, s2) = (near_end(model, ("clamped", "free"), load, 101, m) for m in (False, True))
    assert e1 > 1e-2 and e1 <= s1 and s1 == s2 and abs(e1 - e2) <= 1e-9, (e1, s1, e2, s2)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_stiff_spring_end_is_estimated_as_the_support_it_stands_for(model):
    """Sweep 19 I1: a spring end of 1e12 N/m under a patch on [0, 0.06] gave pd-eb's errors of the pinned end to the
    digit (w 4.34e-3 at 201 points) and no warning. A spring end that holds the deflection now takes the pinned end's
    constant (the clamped end's if it holds the rotation too): the same estimate as the pin, above both errors."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.06}
    (e1, s1), (e2, s2) = (
        near_end(model, (end, "pinned"), load) for end in ("pinned", {"type": "spring", "stiffness": 1e12})
    )
    assert s1 == s2 and max(e1, e2) <= max(s2, TOLERANCE), (e1, s1, e2, s2)


def test_a_load_edge_warning_does_not_hide_the_estimate():
    """Sweep 20 J1: a patch on [0, 0.0125] beside a stiff spring end (401 points, its edge 5 spacings in) carried only
    the edge warning, "errors of about 1e-2", where w was 4.4e-2 off: the estimate was skipped for a load another
    warning named. Only a point load in the end's layer leaves it to that warning now: the estimate is above w's
    error."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.0125}
    error, estimate = near_end("pd-eb", ({"type": "spring", "stiffness": 1e12}, "pinned"), load, 401)
    assert error > 1e-2 and error <= estimate, (error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_soft_or_rotational_spring_end_is_not_estimated(model):
    """Sweep 20: a spring end of 1e3 N/m (k L³ / EI = 0.024) took the pinned end's constant and warned "0.013" where
    w was 2.6e-5 off; a spring end that holds the rotation too took the clamped end's, 43 times below pd-bond-pair's
    first-order error there. A spring end is estimated as a pin from k L³ / EI = 100, translational only."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.06}
    for spring in (
        {"type": "spring", "stiffness": 1e3},
        {"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e12},
    ):
        _, estimate = near_end(model, (spring, "pinned"), load)
        assert estimate == 0.0, (spring, estimate)
