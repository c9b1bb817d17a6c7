"""pd-bond-pair's pair form: supports inside the span, springs, segments (O'Grady & Foster 2014's beams extend beyond
their supports, §3.2), against exact-eb."""

import copy

import numpy as np
import pytest
from helpers import BASE, STUDIES, own_grid, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.registry import run

UDL = [{"type": "distributed", "value": -500.0}]
MIXED = [
    {"type": "point_force", "position": 0.73, "value": -300.0},
    {"type": "point_moment", "position": 1.31, "value": 150.0},
    {"type": "distributed", "value": -500.0, "start": 0.2, "end": 1.1},
]

COUPLE = ": the deflection beside it is off"  # the line of the deflection beside a couple (test_couple_deflection.py)


def scene(left, right, inner=(), loads=UDL, segments=None):
    d = copy.deepcopy(BASE)
    d["supports"] = {"left": left, "right": right, "inner": list(inner)}
    d["loads"] = loads
    if segments:
        d["segments"] = segments
    return parse_scene(d)


SCENES = {
    "two spans": scene("pinned", "pinned", [{"position": 0.8, "type": "pinned"}], MIXED),
    "three spans": scene(
        "clamped", "pinned", [{"position": 0.6, "type": "pinned"}, {"position": 1.4, "type": "roller"}]
    ),
    "overhangs": scene(
        "free", "free", [{"position": 0.4, "type": "pinned"}, {"position": 1.6, "type": "pinned"}], MIXED
    ),
    "spring end": scene({"type": "spring", "stiffness": 2e5}, "clamped", loads=MIXED),
    "spring inside": scene("pinned", "pinned", [{"position": 1.0, "type": "spring", "stiffness": 5e5}]),
    "support between points": scene("pinned", "pinned", [{"position": 0.8123, "type": "pinned"}]),
    "stepped": scene(
        "clamped",
        "pinned",
        loads=MIXED,
        segments=[{"start": 0.0, "end": 0.8, "section": {"width": 0.1, "height": 0.1}}, {"start": 0.8, "end": 2.0}],
    ),
    "two materials": scene(
        "pinned",
        "guided",
        loads=MIXED,
        segments=[
            {"start": 0.0, "end": 1.2},
            {"start": 1.2, "end": 2.0, "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3}},
        ],
    ),
}


def err(sc, points, **opts):
    r = run(sc, "pd-bond-pair", points=points, **opts)
    ex = solve_straight(sc, False).fields(r.x)["w"]
    return np.abs(r.w - ex).max() / np.abs(ex).max(), r


@pytest.mark.parametrize("name", list(SCENES))
def test_second_order_against_exact_eb(name):
    """Measured 101 -> 201 points (m = 3, paper and corrected): orders 1.8-2.1, errors 1e-4 .. 2e-3 at 201 (an
    interface or a support between points inside a horizon costs no order: the pairs straddling an interface take
    the harmonic mean of EI over their span)."""
    sc = SCENES[name]
    for variant in ("paper", "corrected"):
        e1, _ = err(sc, 101, variant=variant)
        e2, r = err(sc, 201, variant=variant)
        assert e2 < 1e-2, (variant, e2)
        assert np.log2(e1 / e2) > 1.7, (variant, e1, e2)
        assert r.info["ends"] == "mirror"
        # rotation: first order; a couple's deflection: its estimate (test_couple_deflection.py); the solve's own
        # estimate from half the points (the rotation's, measured 1.6e-3 .. 6e-2 off where it speaks)
        lines = r.info.get("warnings", [])
        assert not [w for w in lines if not w.startswith("rotation") and COUPLE not in w and not own_grid(w)]


@pytest.mark.parametrize("name", ["two spans", "overhangs", "spring end", "spring inside", "stepped"])
def test_reactions_balance_the_loads(name):
    sc = SCENES[name]
    r = run(sc, "pd-bond-pair", points=201)
    R = r.info["reactions"]
    forces = sum(v for k, v in R.items() if k.startswith("force"))
    load = sum(
        ld.value * ((ld.end or 2.0) - (ld.start or 0.0)) if ld.type == "distributed" else ld.value
        for ld in sc.loads
        if ld.type != "point_moment"
    )
    # the pair forces meeting at a point are ~N^2 times its load (their differences carry it): their sums round to
    # ~N^2 eps of the load (measured 1e-15 .. 3e-13 relative at 201 points)
    assert abs(forces + load) < 201**2 * np.finfo(float).eps * abs(load), abs(forces + load) / abs(load)
    ex = solve_straight(sc, False).reactions()
    for k in ex:
        if k.startswith("force") and abs(ex[k]) > 1e-9 * abs(load):
            assert R[k] == pytest.approx(ex[k], rel=5e-2), k  # the PD reactions converge with the deflection


def test_overhang_mirror_image():
    d = copy.deepcopy(BASE)
    d["supports"] = {"left": "free", "right": "pinned", "inner": [{"position": 0.5, "type": "pinned"}]}
    d["loads"] = MIXED
    m = copy.deepcopy(d)
    m["supports"] = {"left": "pinned", "right": "free", "inner": [{"position": 1.5, "type": "pinned"}]}
    m["loads"] = [
        {"type": "point_force", "position": 2.0 - 0.73, "value": -300.0},
        {"type": "point_moment", "position": 2.0 - 1.31, "value": -150.0},
        {"type": "distributed", "value": -500.0, "start": 0.9, "end": 1.8},
    ]
    a, b = (run(parse_scene(s), "pd-bond-pair", points=161) for s in (d, m))
    # round-off of the mixed form (~N^2 eps; measured 3e-13)
    assert np.abs(a.w - b.w[::-1]).max() < 161**2 * np.finfo(float).eps * np.abs(a.w).max()


def test_the_pair_form_is_the_energy_form_on_end_supports():
    """ends = mirror on a scene with end supports only solves the energy form's tangent (u and w); the pair form of
    the same scene gives the same w: the same pairs, ghosts and end weights."""
    from pdverify.papers.ogrady.general import solve_pairs_linear

    sc = scene("clamped", "pinned", loads=MIXED)
    params = {"points": 121, "horizon": 3.0, "variant": "paper", "ends": "mirror"}
    _, w, _, _, _ = solve_pairs_linear(sc, params)
    r = run(sc, "pd-bond-pair", points=121, variant="paper", ends="mirror")
    assert "energy tangent" in r.info.get("form", "")
    assert np.abs(w - r.w).max() < 1e-9 * np.abs(r.w).max()


def test_taylor_ends_refuse_supports_inside_in_one_line():
    with pytest.raises(InputError, match="ends = taylor solves one elastic section between end supports"):
        run(SCENES["two spans"], "pd-bond-pair", points=101, ends="taylor")


def test_clamp_inside_the_span_is_first_order_and_says_so():
    sc = scene("pinned", "free", [{"position": 1.0, "type": "clamped"}])
    (e1, r), (e2, _) = err(sc, 101), err(sc, 201)
    assert 0.8 < np.log2(e1 / e2) < 1.2  # measured 0.99
    assert any("first order" in w for w in r.info["warnings"])


def test_ends_none_refuses_a_clamp():
    with pytest.raises(InputError, match="ends = none has no points outside the beam"):
        run(scene("clamped", "pinned"), "pd-bond-pair", points=101, ends="none")


def test_fig5_beam_of_the_paper():
    """O'Grady & Foster Fig. 5 (50 and 100 nodes on the span, delta = 0.2, beam extended two horizons): the paper's
    calibration with the paper's ends (none) is 1.24 % and 1.21 % too flexible at mid-span (measured); the authors
    publish -1.96 % and -0.77 % (docs/models/ogrady.md: the difference is not explained by the calibration, whose
    continuous reading gives -22.6 % and -12.0 %)."""
    sc = load_scene(STUDIES / "paper_ogrady_plastic" / "fig5_elastic.toml")
    exact = -5 * 5e-4 * 2.0**4 / 384
    for points, m, want in ((71, 5, 0.0124), (141, 10, 0.0121)):
        r = run(sc, "pd-bond-pair", points=points, horizon=m, variant="paper", ends="none")
        assert np.interp(1.4, r.x, r.w) / exact - 1 == pytest.approx(want, abs=5e-5)
        c = run(sc, "pd-bond-pair", points=points, horizon=m, variant="continuous-alpha", ends="mirror")
        assert np.interp(1.4, c.x, c.w) / exact - 1 < -0.1


@pytest.mark.parametrize("position, off", [(1.07, True), (1.075, False)])
def test_a_clamp_inside_between_grid_points_is_warned_that_m_does_not_converge(position, off):
    """An inner clamp between two grid points: the pair form spreads its couple over them, and M beside it stays
    30-50 % of max |M| off at every grid (sweep 12; pd-eb is at 5e-4 and falling). The warning says so, naming the
    grid; on a grid point the clamp is first order, as its own warning says."""
    d = scene_dict("pinned", "roller", [{"type": "point_force", "position": 1.24, "value": -1000.0}])
    d["supports"]["inner"] = [{"position": position, "type": "clamped"}]
    sc = parse_scene(d)
    for n in (161, 641):
        r = run(sc, "pd-bond-pair", points=n)
        said = [w for w in r.info.get("warnings", []) if w.startswith("supports.inner[0] (clamped)")]
        M, exact = r.measured("moment"), run(sc, "exact-eb", points=n).measured("moment")
        err = np.abs(M - exact).max() / np.abs(exact).max()
        if off:
            assert "lies between two points of the grid" in said[0] and err > 0.2, (n, err)
        else:
            assert "first order in the spacing" in said[0] and err < 0.02, (n, err)


def test_an_estimate_beside_an_off_grid_clamp_says_it_is_not_asymptotic():
    """`solve --estimate` read three grids' clean order 2.28 as asymptotic and printed 7.9 % where w was 54 % off
    (sweep 12, an inner clamp between grid points): the model's warning now marks the estimate not asymptotic."""
    from pdverify.measure.richardson import with_estimate
    from pdverify.registry import get_model

    d = scene_dict("pinned", "roller", [{"type": "point_force", "position": 1.24, "value": -1000.0}])
    d["supports"]["inner"] = [{"position": 1.07, "type": "clamped"}]
    r = with_estimate(parse_scene(d), get_model("pd-bond-pair"), {"points": 321}, run)
    est = r.info["estimate"]
    assert not est["asymptotic"] and "lies between two points of the grid" in est["why"]
