"""exact-rod and exact-torsion on scenes with supports inside the span, springs and segments: the piecewise closed
form with the supports' forces as unknowns against the one-span closed form, textbook values, statics and mirror
images."""

import numpy as np
import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run

L, E, NU, B = 2.0, 70e9, 0.3, 0.05
EA = E * B * B
LOADS = [  # axial loads in every span: a force, a partial and a sine load
    {"type": "point_force", "position": 0.7, "value": 0.0, "axial": -300.0},
    {"type": "distributed", "value": 0.0, "axial": -500.0, "start": 0.2, "end": 1.1},
    {"type": "distributed", "value": 0.0, "axial": 400.0, "shape": "sine"},
    {"type": "point_force", "position": 1.85, "value": 0.0, "axial": 120.0},
]
STEPPED = [{"start": 0.0, "end": 0.9, "section": {"width": 0.07, "height": 0.05}}, {"start": 0.9, "end": L}]
SCENES = {
    "two spans": ({"left": "pinned", "right": "pinned", "inner": [{"position": 1.0, "type": "pinned"}]}, []),
    "overhangs": (
        {
            "left": "free",
            "right": "free",
            "inner": [{"position": 0.4, "type": "clamped"}, {"position": 1.6, "type": "pinned"}],
        },
        [],
    ),
    "on springs": ({"left": {"type": "spring", "stiffness": 2e7}, "right": {"type": "spring", "stiffness": 5e7}}, []),
    "inner spring": (
        {"left": "free", "right": "clamped", "inner": [{"position": 0.55, "type": "spring", "stiffness": 1e8}]},
        [],
    ),
    "stepped two spans": (
        {"left": "clamped", "right": "free", "inner": [{"position": 1.3, "type": "pinned"}]},
        STEPPED,
    ),
}


def _scene(supports, segments=(), loads=LOADS):
    d = {
        "name": "rod",
        "beam": {"length": L},
        "section": {"width": B, "height": B},
        "material": {"youngs_modulus": E, "poissons_ratio": NU},
        "supports": supports,
        "loads": loads,
    }
    if segments:
        d["segments"] = list(segments)
    return parse_scene(d)


def _axial_total(scene) -> float:
    """The axial loads' resultant (+x), exactly: the sine's integral 2 L / pi."""
    out = 0.0
    for ld in scene.loads:
        if ld.type == "point_force":
            out += ld.axial
        else:
            a, b = scene.span(ld)
            out += ld.axial * (2 * L / np.pi if ld.shape == "sine" else b - a)
    return out


@pytest.mark.parametrize("pair", [("clamped", "free"), ("pinned", "clamped"), ("free", "pinned")])
def test_segments_of_one_section_give_the_one_span_closed_form(pair):
    """Two segments of the scene's own section and material take the piecewise path: it gives the closed form."""
    sup = {"left": pair[0], "right": pair[1]}
    x = np.linspace(0.0, L, 41)
    one = get_model("exact-rod").evaluator(_scene(sup), {})(x)
    two = get_model("exact-rod").evaluator(_scene(sup, [{"start": 0.0, "end": 0.77}, {"start": 0.77, "end": L}]), {})(x)
    assert np.abs(two["u"] - one["u"]).max() <= 1e-13 * np.abs(one["u"]).max()
    assert np.abs(two["N"] - one["N"]).max() <= 1e-12 * np.abs(one["N"]).max()


def test_an_inner_support_splits_the_rod_into_two_held_rods():
    """Both ends and a support at a hold u: each part is a rod held at both ends, u = p x (a - x) / (2 EA) on
    [0, a]; the reactions -p a / 2, -p L / 2 (inner), -p (L - a) / 2."""
    p, a = 300.0, 0.8
    sc = _scene(
        {"left": "pinned", "right": "clamped", "inner": [{"position": a, "type": "pinned"}]},
        loads=[{"type": "distributed", "value": 0.0, "axial": p}],
    )
    x = np.linspace(0.0, L, 41)
    f = get_model("exact-rod").evaluator(sc, {})(x)
    left = np.where(x <= a, p * x * (a - x), p * (x - a) * (L - x)) / (2 * EA)
    assert np.allclose(f["u"], left, rtol=0, atol=1e-14 * np.abs(left).max())
    r = run(sc, "exact-rod", points=5).info["reactions"]
    assert r["axial_left"] == pytest.approx(-p * a / 2, rel=1e-12)
    assert r["axial_inner_0"] == pytest.approx(-p * L / 2, rel=1e-12)
    assert r["axial_right"] == pytest.approx(-p * (L - a) / 2, rel=1e-12)


def test_a_rod_on_an_end_spring_and_a_stepped_rod():
    """u = P / k + P x / EA on a spring end; a stepped cantilever's tip u = P (a / EA_1 + (L - a) / EA_2)."""
    P, k = 1000.0, 3e7
    tip = [{"type": "point_force", "position": L, "value": 0.0, "axial": P}]
    x = np.linspace(0.0, L, 21)
    f = get_model("exact-rod").evaluator(
        _scene({"left": {"type": "spring", "stiffness": k}, "right": "free"}, loads=tip), {}
    )(x)
    assert np.allclose(f["u"], P / k + P * x / EA, rtol=1e-13, atol=0)
    stepped = run(_scene({"left": "clamped", "right": "free"}, STEPPED, tip), "exact-rod", points=3)
    assert stepped.fields["u"][-1] == pytest.approx(P * (0.9 / (E * 0.07 * B) + (L - 0.9) / EA), rel=1e-13)


def test_torsion_bar_over_an_inner_roller():
    """A roller holds the twist (a fork): a torque T at c between a held end and the roller at a goes to them as
    on a bar held at both ends, T (a - c) / a and T c / a; the span beyond carries none."""
    T, c, a = 60.0, 0.3, 1.2
    sc = _scene(
        {"left": "clamped", "right": "free", "inner": [{"position": a, "type": "roller"}]},
        loads=[{"type": "point_torque", "position": c, "value": T}],
    )
    r = run(sc, "exact-torsion", points=5).info["reactions"]
    assert r["torque_left"] == pytest.approx(-T * (a - c) / a, rel=1e-12)
    assert r["torque_inner_0"] == pytest.approx(-T * c / a, rel=1e-12)
    assert abs(r["torque_right"]) <= 1e-12 * T


@pytest.mark.parametrize("name", list(SCENES))
def test_reactions_balance_and_mirror_scenes_mirror(name):
    supports, segments = SCENES[name]
    sc = _scene(supports, segments)
    r = run(sc, "exact-rod", points=41)
    assert abs(sum(r.info["reactions"].values()) + _axial_total(sc)) <= 1e-12 * 1000.0
    inner = [dict(s, position=L - s["position"]) for s in supports.get("inner", [])][::-1]
    mirror_sup = {"left": supports["right"], "right": supports["left"], "inner": inner}
    mirror_seg = [dict(g, start=L - g["end"], end=L - g["start"]) for g in segments][::-1]
    loads = []
    for ld in LOADS:  # x -> L - x turns the axial components around
        d = dict(ld, axial=-ld["axial"])
        if "position" in d:
            d["position"] = L - d["position"]
        if "start" in d:
            d["start"], d["end"] = L - d["end"], L - d["start"]
        loads.append(d)
    m = run(_scene(mirror_sup, mirror_seg, loads), "exact-rod", points=41)
    assert np.abs(-m.fields["u"][::-1] - r.fields["u"]).max() <= 1e-12 * np.abs(r.fields["u"]).max()
