"""Support reactions closed by statics (pdverify/numerics/statics.py): the two equations' unknowns are chosen by
whether they are independent, a force and a moment always, two forces when they are apart, at any length."""

import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.numerics.statics import closed_reactions


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
