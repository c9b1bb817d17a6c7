"""fem-eb along a load path (reference_fem/beam_plastic.py): Hermite elements with fibre sections against exact-eb's
load path (pdverify/exact/plastic.py) on determinate scenes, and what it does on the others."""

import copy
import re

import numpy as np
import pytest

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.core.section import Section
from pdverify.registry import get_model, run

E, SY, L = 200e9, 250e6, 2.0
RECT = {"width": 0.1, "height": 0.1}
IPE = {"shape": "I", "height": 0.3, "flange_width": 0.15, "flange_thickness": 0.0107, "web_thickness": 0.0071}
BASE = {
    "name": "fibres",
    "beam": {"length": L},
    "section": RECT,
    "material": {"youngs_modulus": E, "poissons_ratio": 0.3, "yield_stress": SY},
    "supports": {"left": "clamped", "right": "free"},
    "loads": [],
    "loading": {"factors": [0.0, 1.0, 0.0], "steps": 5},
}


def scene(**change):
    d = copy.deepcopy(BASE)
    d.update(change)
    return parse_scene(d)


def case(section, supports, factor):
    """The scene loaded to ``factor`` times first yield and unloaded: a uniform load (simply supported) or a tip
    force (cantilever)."""
    My = SY * Section(**section).profile.elastic_modulus
    if supports[1] == "free":
        load = {"type": "point_force", "position": L, "value": -factor * My / L}
    else:
        load = {"type": "distributed", "value": -factor * 8 * My / L**2}
    return scene(section=section, supports={"left": supports[0], "right": supports[1]}, loads=[load])


def errors(sc, points, fibres):
    """(peak, residual): max |w_fem - w_exact| over the nodes relative to the largest peak deflection."""
    ex = run(sc, "exact-eb", points=points)
    fe = run(sc, "fem-eb", points=points, fibres=fibres)
    assert np.allclose(fe.x, ex.x, rtol=0, atol=1e-15 * L) and fe.info["load_path"]["completed"]
    peak = np.abs(ex.path[5]["w"]).max()
    return np.abs(fe.path[5]["w"] - ex.path[5]["w"]).max() / peak, np.abs(fe.w - ex.w).max() / peak


def test_an_elastic_path_is_the_linear_element():
    """No yield stress: every step is the linear fem-eb (nodally exact) times the factor, to round-off."""
    mat = {"youngs_modulus": E, "poissons_ratio": 0.3}
    load = [{"type": "distributed", "value": -1e4}]
    sc = scene(material=mat, loads=load, supports={"left": "clamped", "right": "pinned"})
    lin = run(
        scene(material=mat, loads=load, supports={"left": "clamped", "right": "pinned"}, loading=None),
        "fem-eb",
        points=41,
    )
    r = run(sc, "fem-eb", points=41, fibres=20)
    assert np.abs(r.path[5]["w"] - lin.w).max() <= 1e-11 * np.abs(lin.w).max()
    assert np.abs(r.w).max() <= 1e-11 * np.abs(lin.w).max()
    assert r.path[5]["reactions"]["moment_left"] == pytest.approx(lin.info["reactions"]["moment_left"], rel=1e-10)


def test_the_fibre_beam_converges_to_exact_eb_with_the_elements():
    """Rectangular cantilever to 1.3 first yield and unloaded, 1600 layers: the error falls with the elements at
    order two or more (the curvature's kink at the plastic zone's edge; measured at the tip 6.6e-5, 1.7e-5, 1.4e-6,
    2.7e-8 at 11, 21, 41, 81 nodes; 400 layers put the fibres' part near 5e-8)."""
    sc = case(RECT, ("clamped", "free"), 1.3)
    e = np.array([errors(sc, n, 400) for n in (11, 21, 41)])
    orders = np.log2(e[:-1] / e[1:])
    assert np.all(orders > 1.8), (e, orders)


@pytest.mark.slow
@pytest.mark.parametrize(
    "section,supports,factor,points,fibres",
    [
        (RECT, ("pinned", "pinned"), 1.3, 321, 3200),
        (RECT, ("clamped", "free"), 1.3, 321, 3200),
        (IPE, ("pinned", "pinned"), 1.08, 321, 3200),
        (IPE, ("clamped", "free"), 1.08, 961, 1600),
    ],
    ids=["rectangle-ss", "rectangle-cantilever", "I-ss", "I-cantilever"],
)
def test_fem_eb_refined_agrees_with_exact_eb_loaded_and_unloaded(section, supports, factor, points, fibres):
    """Rectangle to 1.3 first yield, IPE 300 to 1.08 (its shape factor is 1.129: 1.3 is past collapse), and
    unloaded: fem-eb's nodes within 1e-8 of exact-eb's at the peak and after unloading (relative to the peak's
    largest deflection). The IPE cantilever's plastic zone (7 % of the span at the clamp) needs the finest grid; there
    the direct stiffness's round-off (N^4 eps) is 2e-8 of an elastic step's deflection."""
    peak, residual = errors(case(section, supports, factor), points, fibres)
    assert peak <= 1e-8 and residual <= 1e-8, (peak, residual)


def test_load_control_past_collapse_stops_with_one_line():
    """Simply supported under 1.6 q_y: the path stops near the collapse factor Z / S / 1.6 = 0.9375 (the fibres'
    hinge), the steps before kept. Displacement elements bound the collapse load from above (a kinematic bound:
    measured 0.93766 at 40 elements), so the last factor may pass it by the elements' error (1 %, first order)."""
    My = SY * Section(**RECT).profile.elastic_modulus
    sc = scene(
        supports={"left": "pinned", "right": "pinned"}, loads=[{"type": "distributed", "value": -1.6 * 8 * My / L**2}]
    )
    r = run(sc, "fem-eb", points=41, fibres=50)
    lp = r.info["load_path"]
    assert not lp["completed"] and 0.9 <= lp["last_factor"] < 0.9375 * 1.01
    assert sum("the path stops at load factor" in w for w in r.info["warnings"]) == 1


def test_indeterminate_paths_mirror():
    """Clamped-pinned (exact-eb refuses it), a force at L/3 to past first yield and back: mirror images to round-off."""
    My = SY * Section(**RECT).profile.elastic_modulus
    P = -1.2 * 6 * My / L
    a = run(
        scene(
            supports={"left": "clamped", "right": "pinned"},
            loads=[{"type": "point_force", "position": L / 3, "value": P}],
        ),
        "fem-eb",
        points=31,
    )
    b = run(
        scene(
            supports={"left": "pinned", "right": "clamped"},
            loads=[{"type": "point_force", "position": 2 * L / 3, "value": P}],
        ),
        "fem-eb",
        points=31,
    )
    assert a.path[5]["plastic_zone"] > 0
    for sa, sb in zip(a.path, b.path, strict=True):
        assert np.abs(sa["w"] - sb["w"][::-1]).max() <= 1e-10 * np.abs(a.path[5]["w"]).max()


@pytest.mark.parametrize(
    "change,match",
    [
        ({"section": {"area": 0.01, "inertia": 1e-5}}, "section: fem-eb's fibres need the section's shape"),
        (
            {"material": {"youngs_modulus": E, "poissons_ratio": 0.3, "failure_strain": 1e-3}},
            "material.failure_strain: model fem-eb",
        ),
    ],
)
def test_what_fem_eb_cannot_follow_is_one_line(change, match):
    sc = scene(loads=[{"type": "point_force", "position": L, "value": -1e4}], **change)
    found = get_model("fem-eb").check(sc)
    if found:
        assert len(found) == 1 and re.search(match, found[0]), found
        return
    with pytest.raises(InputError, match=match):
        run(sc, "fem-eb", points=11)


@pytest.mark.parametrize("points", [101, 401])
def test_the_path_stops_at_collapse(points):
    """A cantilever loaded past its plastic collapse (a force at 1.5 m and a line load on 0.2 ... 1.2 m; exact-eb's
    collapse factor about 0.984): the discrete hinge keeps an elastic core at its element's other Gauss points, so
    Newton settled on 75 m (401 points) or 4e6 m (101) of deflection at factor 1 on a 2 m beam and called the path
    completed. The step whose stiffness falls below COLLAPSE of the first one stops it, warned, near the collapse."""
    loads = [
        {"type": "point_force", "position": 1.5, "value": -40000.0},
        {"type": "distributed", "value": -5000.0, "start": 0.2, "end": 1.2},
    ]
    r = run(scene(loads=loads, loading={"factors": [0.0, 1.0, 0.0], "steps": 10}), "fem-eb", points=points)
    path = r.info["load_path"]
    assert not path["completed"] and 0.975 < path["last_factor"] < 0.995
    assert np.abs(r.w).max() < 0.1 * L
    assert any("collapses" in w for w in r.info["warnings"])


@pytest.mark.parametrize("points", [41, pytest.param(81, marks=pytest.mark.slow)])
def test_the_collapse_overshoot_is_within_what_the_stop_says(points):
    """Clamped-clamped, uniform load to 1.2 times 16 Mp / L^2 in 240 steps: the elements' Gauss points miss the
    clamps' peak moment, so the last converged factor is above the beam's collapse (1.0313 and 1.0154 of it at 40
    and 80 elements: first order in h), and the stop's warning gives the excess it may have, 1.3 h / L."""
    import re

    Mp = SY * RECT["width"] * RECT["height"] ** 2 / 4
    q = 1.2 * 16 * Mp / L**2
    sc = scene(supports={"left": "clamped", "right": "clamped"}, loads=[{"type": "distributed", "value": -q}])
    sc = sc.model_copy(update={"loading": sc.loading.model_copy(update={"factors": [0.0, 1.0], "steps": 240})})
    r = run(sc, "fem-eb", points=points)
    excess = r.info["load_path"]["last_factor"] * 1.2 - 1
    (line,) = [w for w in r.info["warnings"] if "collapses" in w]
    said = float(re.search(r"by up to about ([0-9.]+)%", line).group(1)) / 100
    assert 0 < excess <= said, (excess, said)


H = RECT["height"]
EI = E * RECT["width"] * H**3 / 12
DELTA_Y = SY * L**2 / (6 * E * H)  # the centre deflection at first yield under a centre force: M_y L^2 / (12 EI)


def centre_held(fraction, steps=10):
    """Simply supported, the centre deflection prescribed to ``fraction`` of first yield's in ``steps`` steps (the
    audit's yd_small, y9 and lp/yield_1.0_0.0002 scenes of O'Grady Fig. 6 and 9, in units of first yield)."""
    return scene(
        supports={"left": "pinned", "right": "pinned"},
        loads=[{"type": "displacement", "position": L / 2, "value": -fraction * DELTA_Y}],
        loading={"factors": [0.0, 1.0], "steps": steps},
    )


@pytest.mark.parametrize("points", [41, 401])
def test_an_elastic_prescribed_deflection_takes_its_steps_uncut(points):
    """The centre held at 0.3 of first yield: every step is linear, so Newton's first solve (linearised at the last
    state, the held increment inside it) is the step's solution, and iterative refinement of the direct solve (error
    ~N^4 eps, below 1e-5 here) reaches the residual's round-off in at most two more, where the halving test stops it:
    3 tangent solves a step at most, no step cut. Setting the held node first made a one-element kink (curvature
    6 du / l^2) whose fibres yielded: every step was cut, 188 steps for 10 at 41 points, past 120 s at 101."""
    r = run(centre_held(0.3), "fem-eb", points=points)
    lp = r.info["load_path"]
    assert lp["completed"] and lp["steps"] == 11 and lp["newton_iterations"] <= 3 * 10, lp
    assert all(s["cut_back"] == 0 and s["plastic_zone"] == 0 for s in r.path)


@pytest.mark.parametrize("points", [41, 201])
def test_a_plastic_prescribed_deflection_takes_its_steps_uncut(points):
    """The centre held to 2.4 first yield in 30 steps (the audit's y9: Fig. 9's scene with yield_stress = 250e6):
    the plastic law is piecewise linear and each step's Newton, started from the linearised step, settles without a
    cut, so the path has the scene's 30 steps. The kink start cut them (263 steps at 21 points, 1111 at 41, over
    600 s at 101)."""
    r = run(centre_held(0.02 / DELTA_Y, steps=30), "fem-eb", points=points)
    lp = r.info["load_path"]
    assert lp["completed"] and lp["steps"] == 31, lp
    assert all(s["cut_back"] == 0 for s in r.path) and r.path[-1]["plastic_zone"] > 0


@pytest.mark.parametrize("points", [61, 101, 201])
def test_the_first_step_of_a_prescribed_deflection_is_elastic(points):
    """The centre held to 3.16 first yield in 10 steps (the audit's lp/yield_1.0_0.0002): the first step, 0.316 of
    first yield, is elastic. The kink start's curvature is 0.158 n_el^2 times first yield's in the kinked element
    whatever the step, so even the eighth halving yielded whole sections at 61 points and up: the path stopped at
    load factor 0, 'singular'. Now it completes uncut and the first step's force is 48 EI delta / L^3 (Hermite
    elements are nodally exact); its round-off is the element forces' cancellation, 12 EI delta / l^3 summed to
    48 EI delta / L^3: n_el^3 / 4 eps, bounded here by n_el^3 eps."""
    r = run(centre_held(3.16), "fem-eb", points=points)
    lp = r.info["load_path"]
    assert lp["completed"] and lp["steps"] == 11 and all(s["cut_back"] == 0 for s in r.path), lp
    first = r.path[1]
    assert first["factor"] == pytest.approx(0.1) and first["plastic_zone"] == 0
    exact = -48 * EI * 0.316 * DELTA_Y / L**3
    n_el = points - 1
    assert abs(first["reactions"]["force_displacement_0"] / exact - 1) <= n_el**3 * np.finfo(float).eps
    assert r.path[-1]["plastic_zone"] > 0
