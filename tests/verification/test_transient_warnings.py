"""A transient carries its space discretisation's warnings: it integrates the static solve's operator and load
vector (the loads as steps at t = 0), so a load the static solve warns about (first order near a point load, a
model that does not converge to its theory) spoils the histories in the same way, and the transient says so.

Each case solves one scene with ``[dynamics]`` twice: its static part (``static=True``) and the transient. Every
static warning about w, u or the twist must be among the transient's (the transient adds its own: the time step,
the stabilising damping); with a smooth load the static solve warns of none, and the transient of none of them.
"""

import pytest
from transients import MATERIAL, transient_scene

from pdverify.registry import run

END_TIME = 1e-4  # a few dozen explicit steps at 41 points: the warnings depend on the space grid only
AXIAL_POINT = [{"type": "point_force", "value": 0.0, "axial": 3000.0, "position": 0.7}]
TORQUE_POINT = [{"type": "point_torque", "value": 30.0, "position": 0.7}]
FORCE_POINT = [{"type": "point_force", "value": -1000.0, "position": 0.7}]
SMOOTH_AXIAL = [{"type": "distributed", "value": 0.0, "axial": 3000.0, "shape": "sine"}]
SMOOTH_FORCE = [{"type": "distributed", "value": -1000.0, "shape": "sine"}]
SMOOTH_TORQUE = [{"type": "distributed", "value": 0.0, "torque": 30.0, "shape": "sine"}]

# (model, options, loads, a phrase of the static warning the point load gives)
POINT_CASES = [
    ("pd-rod", {}, AXIAL_POINT, "converges at first order near an axial point force"),
    ("pd-torsion", {}, TORQUE_POINT, "converges at first order near a point torque"),
    ("pd-timoshenko", {"variant": "corrected"}, FORCE_POINT, "converges at first order near a point force"),
]
SMOOTH_CASES = [
    ("pd-rod", {}, SMOOTH_AXIAL),
    ("pd-torsion", {}, SMOOTH_TORQUE),
    ("pd-timoshenko", {"variant": "corrected"}, SMOOTH_FORCE),
]


def _warnings(model, options, loads, static):
    scene = transient_scene("clamped", "clamped", loads=loads, end_time=END_TIME)
    assert scene.material.density == MATERIAL["density"]
    result = run(scene, model, points=41, static=static, **options)
    assert result.info["analysis"] == ("static" if static else "dynamic")
    return result.info.get("warnings", [])


@pytest.mark.parametrize(("model", "options", "loads", "phrase"), POINT_CASES, ids=[c[0] for c in POINT_CASES])
def test_a_transient_carries_the_static_solves_point_load_warnings(model, options, loads, phrase):
    static = _warnings(model, options, loads, static=True)
    dynamic = _warnings(model, options, loads, static=False)
    assert any(phrase in w for w in static), static  # the case is one the static solve warns of
    missing = [w for w in static if w not in dynamic]
    assert not missing, missing


@pytest.mark.parametrize(("model", "options", "loads"), SMOOTH_CASES, ids=[c[0] for c in SMOOTH_CASES])
def test_a_transient_under_a_smooth_load_has_no_discretisation_warning(model, options, loads):
    static = _warnings(model, options, loads, static=True)
    dynamic = _warnings(model, options, loads, static=False)
    assert static == []
    assert not [w for w in dynamic if "first order" in w or "converge" in w], dynamic
