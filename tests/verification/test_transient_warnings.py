"""A transient carries its space discretisation's warnings: it integrates the static solve's operator and load
vector (the loads as steps at t = 0), so a load the static solve warns about (first order near a point load, a
model that does not converge to its theory) spoils the histories in the same way, and the transient says so.

Each case solves one scene with ``[dynamics]`` twice: its static part (``static=True``) and the transient. Every
static warning about w, u, the rotation or the twist must be among the transient's (the transient adds its own: the
time step, the stabilising damping; it recovers no moment and shear, so their warnings stay the static solve's);
with a smooth load neither warns of a first order.
"""

import re

import pytest
from transients import MATERIAL, transient_scene

from pdverify.registry import run

END_TIME = 1e-4  # a few dozen explicit steps at 41 points: the warnings depend on the space grid only
AXIAL_POINT = [{"type": "point_force", "value": 0.0, "axial": 3000.0, "position": 0.7}]
TORQUE_POINT = [{"type": "point_torque", "value": 30.0, "position": 0.7}]
FORCE_POINT = [{"type": "point_force", "value": -1000.0, "position": 0.7}]
# a force 0.013 m from the left end (inside every model's end layer at 41 points) and a couple inside the span
NEAR_END = [
    {"type": "point_force", "value": -1000.0, "position": 0.013},
    {"type": "point_moment", "value": 50.0, "position": 1.3},
]
# the recovered fields' warnings (the transient has no M, V) and the static rotation's beside a jump of the shear (its
# estimate takes the static reactions; docs/trust.md says the transient's is not estimated)
# the static solve's estimates from its own solution (max |rotation|, max |w|), which a transient does not make
RECOVERED = re.compile(r"\bmoment and shear\b|^rotation beside |: the deflection beside (it|them) is off ")
# a static solve's own estimate from the same solve on half the points (registry/grid_check.py); a transient makes its
# history's instead (registry/history_check.py)
OWN_ESTIMATE = re.compile(
    r": the same solve on \d+ points differs from this one|: the error on \d+ points is not estimated"
)
SMOOTH_AXIAL = [{"type": "distributed", "value": 0.0, "axial": 3000.0, "shape": "sine"}]
SMOOTH_FORCE = [{"type": "distributed", "value": -1000.0, "shape": "sine"}]
SMOOTH_TORQUE = [{"type": "distributed", "value": 0.0, "torque": 30.0, "shape": "sine"}]

# (model, options, loads, a phrase of the static warning the point load gives)
POINT_CASES = [
    ("pd-rod", {}, AXIAL_POINT, "converges at first order near an axial point force"),
    ("pd-torsion", {}, TORQUE_POINT, "converges at first order near a point torque"),
    ("pd-timoshenko", {"variant": "corrected"}, FORCE_POINT, "converges at first order near a point force"),
    ("pd-timoshenko", {"variant": "corrected"}, NEAR_END, "inside the boundary layer"),
    ("pd-eb", {}, NEAR_END, "inside the boundary layer"),
    ("pd-eb", {"variant": "paper"}, NEAR_END, "does not converge to the Euler-Bernoulli beam"),
    ("pd-bond-pair", {}, NEAR_END, "first order in the spacing near loads[1]"),
    ("pd-higher-order", {}, NEAR_END, "not on a cut grid point"),
]
SMOOTH_CASES = [
    ("pd-rod", {}, SMOOTH_AXIAL),
    ("pd-torsion", {}, SMOOTH_TORQUE),
    ("pd-timoshenko", {"variant": "corrected"}, SMOOTH_FORCE),
    ("pd-eb", {}, SMOOTH_FORCE),
    ("pd-bond-pair", {}, SMOOTH_FORCE),
    ("pd-higher-order", {}, SMOOTH_FORCE),
    ("fem-timoshenko", {}, SMOOTH_FORCE),
]


def _ids(cases):
    return [f"{c[0]}-{c[1].get('variant', 'default')}-{'near-end' if c[2] is NEAR_END else 'point'}" for c in cases]


def _warnings(model, options, loads, static):
    """The warnings of the transient, or (``static``) of the same scene without its [dynamics] table (with no end
    motion, its static part)."""
    scene = transient_scene("clamped", "clamped", loads=loads, end_time=END_TIME)
    assert scene.material.density == MATERIAL["density"]
    if static:
        scene = scene.model_copy(update={"dynamics": None})
    result = run(scene, model, points=41, **options)
    assert (result.info.get("analysis") == "dynamic") is not static
    return result.info.get("warnings", [])


@pytest.mark.parametrize(("model", "options", "loads", "phrase"), POINT_CASES, ids=_ids(POINT_CASES))
def test_a_transient_carries_the_static_solves_point_load_warnings(model, options, loads, phrase):
    static = _warnings(model, options, loads, static=True)
    dynamic = _warnings(model, options, loads, static=False)
    assert any(phrase in w for w in static), static  # the case is one the static solve warns of
    missing = [w for w in static if w not in dynamic and not RECOVERED.search(w) and not OWN_ESTIMATE.search(w)]
    assert not missing, missing


@pytest.mark.parametrize(("model", "options", "loads"), SMOOTH_CASES, ids=_ids(SMOOTH_CASES))
def test_a_transient_under_a_smooth_load_has_no_discretisation_warning(model, options, loads):
    static = _warnings(model, options, loads, static=True)
    dynamic = _warnings(model, options, loads, static=False)
    assert not [w for w in static if "first order" in w], static
    assert not [w for w in dynamic if "first order" in w], dynamic
    # pd-higher-order's clamp layer: both warn of it; the static rotation's estimate beside the ends is the static's
    assert [w for w in static if w not in dynamic and not RECOVERED.search(w) and not OWN_ESTIMATE.search(w)] == []


def test_a_pd_bond_pair_transient_on_a_rotational_spring_says_it_is_first_order():
    """Sweep 22 M3: a pd-bond-pair transient with a rotational spring end dropped the static solve's "first order"
    line (its final w 1.8e-3 off at 101 points, with only the rotation's line). The transient carries it."""
    spring = {"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e12}
    scene = transient_scene(spring, "pinned", loads=SMOOTH_FORCE, end_time=END_TIME)
    said = run(scene, "pd-bond-pair", points=41).info.get("warnings", [])
    assert any(w.startswith("supports.left: a rotational spring") and "first order" in w for w in said), said
