"""Section shapes (pdverify.core.section): the geometry of a width profile against handbook formulas."""

import copy

import numpy as np
import pytest
from helpers import BASE

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.core.section import Section
from pdverify.registry import get_model

IPE300 = {"shape": "I", "height": 0.3, "flange_width": 0.15, "flange_thickness": 0.0107, "web_thickness": 0.0071}


def test_rectangle():
    p = Section(width=0.1, height=0.2).profile
    assert p.area == pytest.approx(0.02, rel=1e-14)
    assert p.inertia == pytest.approx(0.1 * 0.2**3 / 12, rel=1e-14)
    assert p.shear_coefficient == pytest.approx(5 / 6, rel=1e-12)
    assert p.plastic_modulus == pytest.approx(0.1 * 0.2**2 / 4, rel=1e-12)
    assert p.shape_factor == pytest.approx(1.5, rel=1e-12)
    assert p.symmetric


def test_i_section_against_handbook_formulas():
    s = Section(**IPE300)
    h, bf, tf, tw = 0.3, 0.15, 0.0107, 0.0071
    hw = h - 2 * tf
    assert s.A == pytest.approx(2 * bf * tf + hw * tw, rel=1e-13)
    assert s.I == pytest.approx((bf * h**3 - (bf - tw) * hw**3) / 12, rel=1e-13)
    Z = bf * tf * (h - tf) + tw * hw**2 / 4
    assert s.profile.plastic_modulus == pytest.approx(Z, rel=1e-12)
    assert s.profile.elastic_modulus == pytest.approx(s.I / (h / 2), rel=1e-13)
    assert s.J == pytest.approx((2 * bf * tf**3 + hw * tw**3) / 3, rel=1e-13)
    # the energy shear coefficient of an I-section is close to the web's share of the area (Cowper's ~0.4 here)
    assert 0.35 < s.k < 0.45 and s.depth == h


def test_profile_triangle():
    s = Section(shape="profile", y=[0.0, 0.1], b=[0.2, 0.0])
    assert s.I == pytest.approx(0.2 * 0.1**3 / 36, rel=1e-12)
    assert s.profile.shape_factor == pytest.approx(2.343, abs=1e-3)  # 2 (2 - sqrt 2) ... the triangle's 2.343
    assert not s.profile.symmetric


def test_fibre_moment_curvature_limits():
    p = Section(**IPE300).profile
    E, sy = 200e9, 250e6
    ky = sy / E / p.extreme_fibre
    M = p.fibre_moment(np.array([0.5 * ky, ky, 1e4 * ky]), E, sy)
    assert M[0] == pytest.approx(0.5 * sy * p.elastic_modulus, rel=1e-13)
    assert M[1] == pytest.approx(sy * p.elastic_modulus, rel=1e-13)
    assert M[2] == pytest.approx(sy * p.plastic_modulus, rel=1e-7)


@pytest.mark.parametrize(
    "section,match",
    [
        ({"shape": "I", "height": 0.3, "flange_width": 0.15}, "needs height, flange_width, flange_thickness"),
        ({**IPE300, "flange_thickness": 0.2}, "two flanges must leave a web"),
        ({**IPE300, "width": 0.1}, "not keys of shape"),
        ({"shape": "profile", "y": [0.0, 0.1, 0.05], "b": [1.0, 1.0, 1.0]}, "non-decreasing"),
        ({"shape": "profile", "y": [0.0, 0.1], "b": [1.0]}, "as many widths as heights"),
        ({"width": 0.1, "height": 0.1, "web_thickness": 0.01}, 'keys of shape = "I"'),
    ],
)
def test_bad_sections_are_refused_in_one_line(section, match):
    d = copy.deepcopy(BASE)
    d["section"] = section
    with pytest.raises(InputError, match=match):
        parse_scene(d)


def test_a_model_of_rectangles_refuses_a_shape():
    d = copy.deepcopy(BASE)
    d["section"] = IPE300
    d["loads"] = [{"type": "point_force", "position": 2.0, "value": -1.0}]
    sc = parse_scene(d)
    assert get_model("pd-higher-order").check(sc) == [
        "section.shape = 'I': model pd-higher-order takes a rectangle (its equations use the section's depth and "
        "width); give width and height"
    ]
    assert not get_model("fem-eb").check(sc) and not get_model("pd-bond-pair").check(sc)
