import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.errors import InputError
from pdverify.core.geometry import AxisGeometry, axis_length
from pdverify.core.scene import Axis
from pdverify.core.scene_file import parse_scene


def test_arc_semicircle():
    ax = Axis(type="arc", radius=2.0, opening_angle_deg=180.0)
    g = AxisGeometry(ax, axis_length(ax))
    assert g.length == pytest.approx(2 * np.pi)
    s = np.array([0.0, np.pi, 2 * np.pi])
    assert np.allclose(g.position(s), [[2, 0], [0, 2], [-2, 0]], atol=1e-15)
    t, n = g.frame(np.array([0.0]))
    assert np.allclose(t, [[0, 1]]) and np.allclose(n, [[-1, 0]])  # n points to the centre
    assert np.allclose(g.curvature(s), 0.5)


@pytest.mark.slow
def test_polynomial_axis_arclength_and_curvature():
    # y = x^2 on [0, 1]: s(1) = (2 sqrt5 + asinh 2) / 4
    ax = Axis(type="polynomial", coefficients=[0.0, 0.0, 1.0], x_range=(0.0, 1.0))
    L = axis_length(ax)
    assert L == pytest.approx((2 * np.sqrt(5) + np.arcsinh(2)) / 4, rel=1e-14)
    g = AxisGeometry(ax, L)
    s = np.linspace(0, L, 7)
    p = g.position(s)
    assert np.allclose(p[:, 1], p[:, 0] ** 2, atol=1e-14)
    # arc length between consecutive points matches the requested spacing
    fine = g.position(np.linspace(0, L, 20001))
    assert np.sum(np.hypot(*np.diff(fine, axis=0).T)) == pytest.approx(L, rel=1e-8)
    x = p[:, 0]
    assert np.allclose(g.curvature(s), 2 / (1 + 4 * x**2) ** 1.5, rtol=1e-12)


def test_curved_scene_length_must_match_axis():
    d = scene_dict("clamped", "free")
    d["axis"] = {"type": "arc", "radius": 1.0, "opening_angle_deg": 180.0}
    d["beam"] = {"length": 3.0}
    with pytest.raises(InputError) as e:
        parse_scene(d)
    assert "beam.length = 3.0" in str(e.value) and "3.14159265359" in str(e.value)
    d["beam"] = {"length": np.pi}
    assert parse_scene(d).axis.type == "arc"


def test_straight_models_reject_curved_and_axial(make_scene):
    from pdverify.registry import get_model

    d = scene_dict("clamped", "free")
    d["axis"] = {"type": "arc", "radius": 1.0, "opening_angle_deg": 90.0}
    d["beam"] = {"length": np.pi / 2}
    reasons = get_model("exact-eb").check(parse_scene(d))
    assert reasons and "straight beams only" in reasons[0]
    s = make_scene("clamped", "free", [{"type": "point_force", "position": 1.0, "value": 0.0, "axial": 5.0}])
    assert "no axial displacement" in get_model("exact-eb").check(s)[0]
