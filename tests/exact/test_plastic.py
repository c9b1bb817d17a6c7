"""exact-eb along a load path (pdverify/exact/plastic.py): the elastic-perfectly plastic and brittle Euler-Bernoulli
beam of the section's fibre law on statically determinate scenes, against closed forms."""

import copy

import numpy as np
import pytest

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.core.section import Section
from pdverify.registry import run

E, SY, L = 200e9, 250e6, 2.0
RECT = {"width": 0.1, "height": 0.1}
IPE = {"shape": "I", "height": 0.3, "flange_width": 0.15, "flange_thickness": 0.0107, "web_thickness": 0.0071}
BASE = {
    "name": "plastic",
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


def yield_moment(section=RECT) -> float:
    return SY * Section(**section).profile.elastic_modulus


def cantilever_tip_closed_form(P: float) -> tuple[float, float]:
    """(tip deflection loaded, after unloading) of a rectangular cantilever under the tip force |P| > My / L: elastic
    over u < u_y = My / P from the tip, kappa = kappa_y / sqrt(3 - 2 M / My) beyond; delta = ∫ kappa u du (Gere &
    Timoshenko, plastic bending of a rectangle)."""
    prof = Section(**RECT).profile
    EI, My = E * prof.inertia, yield_moment()
    uy, ky = My / P, SY / E / prof.extreme_fibre

    def F(t):  # ∫ t / sqrt(3 - 2 t) dt
        s = 3 - 2 * t
        return -1.5 * np.sqrt(s) + s**1.5 / 6

    tip = P * uy**3 / (3 * EI) + uy**2 * ky * (F(L / uy) - F(1.0))
    return tip, tip - P * L**3 / (3 * EI)


def test_a_plastic_cantilever_matches_its_closed_form_loaded_and_unloaded():
    """Loaded to 1.3 first yield: the tip deflection at the peak and the residual one to 1e-12 (the adaptive
    quadrature's tolerance is 1e-14 of the curvature's integral; measured 2e-16 and 1e-14), the plastic zone
    L - My / P, reactions from statics."""
    P = 1.3 * yield_moment() / L
    r = run(scene(loads=[{"type": "point_force", "position": L, "value": -P}]), "exact-eb", points=11)
    tip, residual = cantilever_tip_closed_form(P)
    peak = r.path[5]
    assert peak["factor"] == 1.0 and r.info["load_path"]["completed"]
    assert peak["w"][-1] == pytest.approx(-tip, rel=1e-12)
    assert r.w[-1] == pytest.approx(-residual, rel=1e-12)
    assert peak["plastic_zone"] == pytest.approx(L - L / 1.3, rel=1e-12)
    assert peak["reactions"]["force_left"] == pytest.approx(P, rel=1e-14)
    assert r.info["load_path"]["first_yield_factor"] == pytest.approx(1 / 1.3, rel=1e-14)
    assert r.info["load_path"]["collapse_factor"] == pytest.approx(1.5 / 1.3, rel=1e-13)
    assert r.fields["health"][0] == pytest.approx(np.sqrt(3 - 2 * 1.3), rel=1e-12)  # elastic core ye / c
    assert r.info["load_path"]["quadrature_error"] <= 1e-10 * tip


def test_an_elastic_path_is_the_linear_solution():
    sc = scene(
        material={"youngs_modulus": E, "poissons_ratio": 0.3},
        supports={"left": "pinned", "right": "pinned"},
        loads=[{"type": "distributed", "value": -1e4}],
    )
    lin = run(
        scene(
            supports={"left": "pinned", "right": "pinned"},
            loads=[{"type": "distributed", "value": -1e4}],
            material={"youngs_modulus": E, "poissons_ratio": 0.3},
            loading=None,
        ),
        "exact-eb",
        points=21,
    )
    r = run(sc, "exact-eb", points=21)
    assert np.abs(r.path[5]["w"] - lin.w).max() <= 1e-13 * np.abs(lin.w).max()
    assert np.abs(r.w).max() <= 1e-13 * np.abs(lin.w).max()


@pytest.mark.parametrize("section", [RECT, IPE], ids=["rectangle", "I"])
def test_load_control_past_collapse_stops_at_the_plastic_moment(section):
    """Simply supported under 1.6 q_y: one line naming the collapse factor 8 Mp / (q L²) (Z / S of the section), the
    steps before it kept."""
    My = yield_moment(section)
    sc = scene(
        section=section,
        supports={"left": "pinned", "right": "pinned"},
        loads=[{"type": "distributed", "value": -1.6 * 8 * My / L**2}],
    )
    r = run(sc, "exact-eb", points=21)
    lp = r.info["load_path"]
    shape = Section(**section).profile.shape_factor
    assert lp["collapse_factor"] == pytest.approx(shape / 1.6, rel=1e-13)
    assert not lp["completed"] and lp["last_factor"] < lp["collapse_factor"] < lp["last_factor"] + 0.2 + 1e-12
    assert sum("collapse load factor" in w for w in r.info["warnings"]) == 1
    assert r.info["load_path"]["peak_position"] == pytest.approx(L / 2, abs=1e-6 * L)  # flat top: sqrt(eps)


def test_the_first_fibre_fails_at_the_peak_moment():
    """Brittle (failure_strain only), simply supported, a force at L/4: M_f = EI eps_f / c at the force."""
    ef = 1e-3
    prof = Section(**RECT).profile
    Mf = E * prof.inertia * ef / prof.extreme_fibre
    P = 2 * Mf / (L / 4 * 3 / 4)
    sc = scene(
        material={"youngs_modulus": E, "poissons_ratio": 0.3, "failure_strain": ef},
        supports={"left": "pinned", "right": "pinned"},
        loads=[{"type": "point_force", "position": L / 4, "value": -P}],
        loading={"factors": [0.0, 1.0], "steps": 10},
    )
    lp = run(sc, "exact-eb", points=11).info["load_path"]
    assert lp["first_failure_factor"] == pytest.approx(0.5, rel=1e-13)
    assert lp["peak_position"] == pytest.approx(L / 4, rel=1e-14) and lp["last_factor"] == pytest.approx(0.4)


def test_mirror_and_scaled_paths():
    P = -1.2 * yield_moment() / L
    a = run(scene(loads=[{"type": "point_force", "position": L, "value": P}]), "exact-eb", points=41)
    b = run(
        scene(
            supports={"left": "free", "right": "clamped"}, loads=[{"type": "point_force", "position": 0.0, "value": P}]
        ),
        "exact-eb",
        points=41,
    )
    for sa, sb in zip(a.path, b.path, strict=True):
        assert np.abs(sa["w"] - sb["w"][::-1]).max() <= 1e-13 * np.abs(a.path[5]["w"]).max()
    s = 1e3
    c = run(
        scene(
            beam={"length": L * s},
            section={"width": 0.1 * s, "height": 0.1 * s},
            loads=[{"type": "point_force", "position": L * s, "value": P * s**2}],
        ),
        "exact-eb",
        points=41,
    )
    for sa, sc in zip(a.path, c.path, strict=True):
        assert np.abs(sa["w"] - sc["w"] / s).max() <= 1e-12 * np.abs(a.path[5]["w"]).max()


@pytest.mark.parametrize(
    "change,match",
    [
        ({"supports": {"left": "clamped", "right": "pinned"}}, "statically determinate .* use fem-eb"),
        (
            {"supports": {"left": "pinned", "right": "pinned", "inner": [{"position": 1.0, "type": "pinned"}]}},
            "indeterminate: use fem-eb",
        ),
        (
            {"loads": [{"type": "displacement", "position": 1.0, "value": -1e-3}]},
            "a prescribed deflection on an elastic or brittle beam only",
        ),
        ({"section": {"area": 0.01, "inertia": 1e-5}}, "symmetric about its centroid"),
        ({"loading": {"factors": [0.0, 1.0, -1.0], "steps": 2}}, "yields fibres in reverse.*use fem-eb"),
    ],
)
def test_what_exact_eb_cannot_follow_is_one_line(change, match):
    d = {"loads": [{"type": "point_force", "position": L, "value": -1.3 * yield_moment() / L}], **change}
    sc = scene(**d)
    if "reverse" in match:
        r = run(sc, "exact-eb", points=11)
        assert sum(bool(__import__("re").search(match, w)) for w in r.info["warnings"]) == 1
        return
    with pytest.raises(InputError, match=match):
        run(sc, "exact-eb", points=11)
