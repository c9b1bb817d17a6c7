"""Support reactions closed by statics (pdverify/numerics/statics.py): the two equations' unknowns are chosen by
whether they are independent, a force and a moment always, two forces when they are apart, at any length."""

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.numerics.statics import closed_reactions, statics_over


def scene(length: float, left="clamped", right="free"):
    return parse_scene(
        {
            "name": "beam",
            "beam": {"length": length},
            "section": {"width": 0.01 * length, "height": 0.01 * length},
            "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
            "supports": {"left": left, "right": right},
            "loads": [{"type": "point_force", "position": length, "value": -50.0}],
        }
    )


@pytest.mark.parametrize("length", [1e-6, 1.0, 1e9, 1e12])
def test_a_cantilever_is_statically_determinate_at_any_length(length):
    """A clamp's force and moment: a force and a moment are independent whatever the length (a moment's coefficient 1
    against a tolerance of 1e-9 L refused them from L = 1e9 on)."""
    out = closed_reactions(scene(length), {})
    assert out["force_left"] == pytest.approx(50.0, rel=1e-12)
    assert out["moment_left"] == pytest.approx(50.0 * length, rel=1e-12)
    assert "statically determinate" in out["method"]


@pytest.mark.parametrize("length", [1e-6, 1.0, 1e12])
def test_two_forces_apart_close_a_simply_supported_beam(length):
    out = closed_reactions(scene(length, "pinned", "roller"), {})
    assert out["force_left"] == pytest.approx(0.0, abs=1e-9) and out["force_right"] == pytest.approx(50.0, rel=1e-12)


@pytest.mark.parametrize("left,right", PAIRS)
def test_statics_continues_the_exact_resultants_over_spoiled_spans(left, right):
    """M and V spoiled in the 6 points next to each end and around x = 1 come back by statics from the points beside
    them, to round-off, with forces, a couple and partial and sine loads inside the spans (the end points' loads
    acting on the beam's side: the end point carries the value inside the beam)."""
    loads = MIXED_LOADS[:4] + [
        {"type": "point_force", "position": 0.13, "value": 70.0},
        {"type": "point_moment", "position": 1.9, "value": -40.0},
        {"type": "distributed", "value": 90.0, "start": 1.85, "end": 1.97},
    ]
    sc = parse_scene(scene_dict(left, right, loads))
    x = np.linspace(0.0, 2.0, 41)
    exact = solve_straight(sc, False).fields(x)
    M, V = exact["M"].copy(), exact["V"].copy()
    M[:6] += 5.0
    V[-6:] -= 3.0
    M[18:23] -= 2.0
    M2, V2, kept = statics_over(sc, x, M, V, [(0, 6), (35, 41), (18, 23)])
    assert kept == []
    on = np.isclose(x, 1.9)  # on the couple: the mean of its sides, which exact-eb does not give
    assert np.abs(M2 - exact["M"])[~on].max() < 1e-12 * np.abs(exact["M"]).max()
    assert np.abs(V2 - exact["V"]).max() < 1e-12 * np.abs(exact["V"]).max()
