"""The rotation beside a jump of the shear (pdverify/registry/jump_rotation.py): a point force near a support inside
that holds the deflection leaves pd-eb's, pd-timoshenko's and pd-bond-pair's rotation off by about c |J| h² / EI at
the points next to the support (J its reaction), large beside max |rotation| (sweep 17 N3, N4). Each warns with that
estimate where it passes 1e-3 of max |rotation|: the estimate is above the error wherever it warns, the error below
1e-3 wherever it does not, and a mirror image warns alike."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.registry import run
from pdverify.registry.jump_rotation import TOLERANCE, shear_jumps

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}
# every model, and pd-bond-pair's other variant and ends, whose constants were measured apart (sweep 20: its paper
# variant carried no estimate; mirror ends left the rotation at a clamp 7 times the Taylor ends' estimate)
SPECS = [*MODELS, "pd-bond-pair ends=mirror", "pd-bond-pair variant=paper", "pd-bond-pair variant=paper ends=mirror"]


def rotation_error(d: dict, model: str, points: int):
    """(the rotation's largest error against the exact beam relative to its largest value, the estimate the warning
    gives or 0) of the scene ``d`` on a 1 m steel beam, 20 x 50 mm."""
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    sc = parse_scene(d)
    name, *given = model.split()  # a spec: the model's name and its options key=value
    r = run(sc, name, points=points, **dict(kv.split("=") for kv in given))
    e = run(sc, MODELS[name], points=points)
    said = [w for w in r.info.get("warnings", []) if w.startswith("rotation beside")]
    estimate = float(said[0].split(" here ")[1].split()[0]) if said else 0.0
    return float(np.abs(r.rotation - e.rotation).max() / np.abs(e.rotation).max()), estimate


def beside(model: str, spacings: float, inner: dict, mirror: bool = False, points: int = 201):
    """:func:`rotation_error` of a pinned-pinned beam held inside at 0.5 + 0.41 spacings by ``inner``, a point force
    ``spacings`` spacings right of it (left in the ``mirror`` image), with a uniform load."""
    dx = 1.0 / (points - 1)
    at = 0.5 + 0.41 * dx
    force = at + spacings * dx
    loads = [{"type": "point_force", "position": 1.0 - force if mirror else force, "value": -700.0}]
    d = scene_dict("pinned", "pinned", loads + [{"type": "distributed", "value": -100.0}])
    d["supports"]["inner"] = [{"position": 1.0 - at if mirror else at, **inner}]
    return rotation_error(d, model, points)


@pytest.mark.parametrize("model", SPECS)
@pytest.mark.parametrize("inner", [{"type": "pinned"}, {"type": "spring", "stiffness": 1e9}], ids=["pin", "spring"])
def test_the_estimate_is_above_the_error_where_it_warns_and_the_error_is_small_where_it_does_not(model, inner):
    for spacings in (1.0, 3.5, 6.0, 12.4, 40.0):
        error, estimate = beside(model, spacings, inner)
        assert error <= max(estimate, TOLERANCE), (spacings, error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_mirror_image_warns_alike(model):
    """The old 5-spacing rule of pd-bond-pair warned a force 5 spacings right of a pin and not its mirror image, whose
    distance rounded above 5 spacings: the estimate is continuous in the distance and mirror images give it alike."""
    for spacings in (2.0, 5.0, 9.0):
        (e1, s1), (e2, s2) = (
            beside(model, spacings, {"type": "pinned"}),
            beside(model, spacings, {"type": "pinned"}, True),
        )
        assert (s1 > 0) == (s2 > 0) and abs(s1 - s2) <= 0.01 * s1, (spacings, s1, s2)
        assert abs(e1 - e2) <= 1e-6 * e1, (e1, e2)


def end_case(model: str, left: str, right: str, loads: list, points: int):
    """:func:`rotation_error` on ``left`` and ``right`` ends under ``loads``."""
    return rotation_error(scene_dict(left, right, loads), model, points)


@pytest.mark.parametrize("model", SPECS)
@pytest.mark.parametrize("points", [41, 101, 201])
def test_the_ends_reactions_are_jumps_too(model, points):
    """Sweep 18 H1: a clamped-clamped beam under a uniform load left pd-eb's rotation at the clamps 1.25e-2 of max
    |rotation| off at 41 points (2.05e-3 at 101), unwarned: the ends' reactions are jumps of the shear as a force
    inside is. Now counted: the estimate is above the error where it warns, the error below 1e-3 where it does not."""
    for ends in (("clamped", "clamped"), ("clamped", "pinned")):
        error, estimate = end_case(model, *ends, [{"type": "distributed", "value": -100.0}], points)
        assert error <= max(estimate, TOLERANCE), (ends, error, estimate)


def test_a_force_on_a_support_is_one_jump():
    """Sweep 18: a force on a pin inside was counted as a jump and the pin's reaction as another, though they largely
    cancel (estimates 25-35 times the error). Now one jump, their sum; the ends' forces are jumps too."""
    d = scene_dict("pinned", "pinned", [{"type": "point_force", "position": 0.5, "value": -700.0}])
    d["supports"]["inner"] = [{"type": "pinned", "position": 0.5}]
    reactions = {"force_left": 10.0, "force_right": 20.0, "force_inner_0": 670.0}
    jumps = shear_jumps(parse_scene(d), reactions, 0.01)
    assert [(at, J) for _, at, J in jumps] == [(0.0, 10.0), (0.5, -30.0), (d["beam"]["length"], 20.0)], jumps
    assert jumps[1][0] == "loads[0] (a point force at 0.5) and supports.inner[0] at 0.5"


def test_no_second_order_estimate_beside_a_support_the_model_holds_at_first_order():
    """Sweeps 21-22: beside an inner clamp pd-bond-pair is first order (w 8.5e-3 off at 1401 points), its own warning
    says so, yet its rotation line promised 1e-3 "at 1370 points" (the rotation 1.5e-2 off there), and beside a
    rotational spring end its estimate was 3.8-14.5 times below the rotation's error. Beside a support the model's
    own warning holds at first order (with its size), no second-order rotation line."""
    d = scene_dict("pinned", "pinned", [{"type": "point_force", "position": 0.51, "value": -700.0}])
    d["supports"]["inner"] = [{"type": "clamped", "position": 0.5}]
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    said = run(parse_scene(d), "pd-bond-pair", points=401).info["warnings"]
    assert any(w.startswith("supports.inner[0]") and "first order in the spacing" in w for w in said), said
    assert not [w for w in said if w.startswith("rotation beside")], said


@pytest.mark.parametrize("model", SPECS)
def test_a_load_over_an_end_is_estimated(model):
    """Sweep 19 I4: q on [0, 0.7] of a pinned-pinned beam left the rotation at the loaded pin 1.19 (pd-eb) and 1.66
    (pd-bond-pair) times the estimate at 401 points (1.15 and 1.61 at 41 and 61). The ends' constants now come from
    benchmarks/jump_rotation.py with such patches, on 41 to 401 points: the estimate is above the error."""
    for points in (41, 61, 401):
        d = scene_dict("pinned", "pinned", [{"type": "distributed", "value": -100.0, "start": 0.0, "end": 0.7}])
        error, estimate = rotation_error(d, model, points)
        assert error <= max(estimate, TOLERANCE), (points, error, estimate)


def test_a_rotation_line_elsewhere_gives_the_jumps_part_only():
    """Sweep 23 N1: with the jump beside a first-order support left out, the line named the next one ("rotation
    beside the right end ... here 0.026" on a pinned-pinned beam clamped at mid-span, a force at 0.515 and a uniform
    load, 101 points) while the rotation was 0.133 off beside the clamp, and read as the rotation's error. Sweep 25
    O2: saying that it did not hold within L / 4 of that support was not enough: the support's first-order error
    turns the whole span (a pinned-pinned beam clamped at 0.5 under a force at 0.4: the rotation at x = 0 off by
    2.55e-2 at 201 points, 3.2e-3 at 1601, against a line of 0.002 "use at least 311 points for 1e-3"). The line
    says that its number is the jump's own part, that the rotation everywhere also carries that support's error,
    and gives no count of points."""
    loads = [{"type": "point_force", "position": 0.515, "value": -700.0}, {"type": "distributed", "value": -100.0}]
    d = scene_dict("pinned", "pinned", loads)
    d["supports"]["inner"] = [{"type": "clamped", "position": 0.5}]
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    said = run(parse_scene(d), "pd-bond-pair", points=101).info["warnings"]
    assert any(w.startswith("supports.inner[0]") and "the rotation too" in w for w in said), said
    lines = [w for w in said if w.startswith("rotation beside")]
    assert lines and all("everywhere also carries the first-order error of supports.inner[0]" in w for w in lines), said
    assert not any("points for 1e-3" in w for w in lines), said


@pytest.mark.parametrize("points", [101, 201, 401])
def test_a_jump_far_from_a_support_held_at_first_order_is_estimated(points):
    """Sweep 24 N5: one rule for the whole result dropped every rotation line once a support was held at first order:
    with a soft rotational spring end (kr 1e4) and a clamped far end, a force at 0.93 left the rotation at x = 1 off by
    0.125, 3.1e-2, 7.8e-3 at 101-401 points with no line. The jumps far from that support keep their estimate."""
    spring = {"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e4}
    d = scene_dict(spring, "clamped", [{"type": "point_force", "position": 0.93, "value": -700.0}])
    error, estimate = rotation_error(d, "pd-bond-pair", points)
    assert error > TOLERANCE and error <= estimate, (error, estimate)


@pytest.mark.parametrize("scale", [1.0, 0.7])
def test_a_symmetric_scene_names_both_ends(scale):
    """Sweep 35 S35-7: a clamped-clamped beam under a uniform load named its left end, and a copy scaled by 0.7 its
    right, by the rounding of two equal reactions."""
    L = 2.92564 * scale
    d = scene_dict("clamped", "clamped", [{"type": "distributed", "value": -1000.0}])
    d.update(beam={"length": L}, section={"width": 0.02 * L, "height": 0.1 * L})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    r = run(parse_scene(d), "pd-eb", points=51, horizon_length=2.5 * L / 50)
    (line,) = [w for w in r.info["warnings"] if w.startswith("rotation beside")]
    assert line.startswith("rotation beside the left end and the right end: the shear jumps by ")
