"""A load near an end that holds the deflection (pdverify/registry/end_loads.py): pd-eb's, pd-timoshenko's and
pd-bond-pair's deflection under it is off by about C (h / d)² of the load's own, d its distance from the end (sweep 18
H2: a cantilever loaded on its first 0.05 m was 13 % low at the tip at 101 points in pd-eb, 22 % in pd-bond-pair,
unwarned). Each warns with that estimate where it passes 1e-3: the estimate is above the error wherever it warns,
the error below 1e-3 wherever it does not, and a mirror image warns alike."""

import re

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.result import quantity_of
from pdverify.core.scene_file import parse_scene
from pdverify.registry import run
from pdverify.registry.end_loads import TOLERANCE

MODELS = {"pd-eb": "exact-eb", "pd-timoshenko": "exact-timoshenko", "pd-bond-pair": "exact-eb"}
# every model, and pd-bond-pair's paper variant, whose constants were measured apart (sweep 20: it had none)
SPECS = [*MODELS, "pd-bond-pair variant=paper"]  # (with mirror ends its own error passes 1e-3 at 201 points)


def near_end(model: str, ends: tuple, load: dict, points: int = 201, mirror: bool = False, more: tuple = ()):
    """(the larger of w's and M's largest errors against the exact beam, each relative to its largest value, the
    estimate or 0, the warnings) of a 1 m steel beam, 20 x 50 mm, on ``ends`` under ``load`` and ``more`` loads (its
    mirror image: ends swapped, positions x -> 1 - x). ``model``: its name and options key=value."""
    loads = [load, *more]
    if mirror:
        ends = ends[::-1]
        loads = [
            {**ld, "start": 1.0 - ld["end"], "end": 1.0 - ld["start"]}
            if ld["type"] == "distributed"
            else {**ld, "position": 1.0 - ld["position"]}
            for ld in loads
        ]
    d = scene_dict(*ends, loads)
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    sc = parse_scene(d)
    name, *given = model.split()
    r = run(sc, name, points=points, **dict(kv.split("=") for kv in given))
    e = run(sc, MODELS[name], points=points)
    said = [w for w in r.info.get("warnings", []) if "(h / d)²" in w and w.startswith(("loads[0]", "loads[0,"))]
    # a load in the end's layer, or nearer than the estimate goes: a warning that expects large errors
    large = any("loads[0]" in w and "expect large errors" in w for w in r.info.get("warnings", []))
    estimate = float(said[0].split(", here ")[1].split(",")[0]) if said else (1.0 if large else 0.0)
    M, Me = (quantity_of(x.w, x.rotation, x.fields, "moment") for x in (r, e))
    error = max(np.abs(r.w - e.w).max() / np.abs(e.w).max(), np.abs(M - Me).max() / np.abs(Me).max())
    return float(error), estimate, r.info.get("warnings", [])


@pytest.mark.parametrize("model", SPECS)
@pytest.mark.parametrize("ends", [("clamped", "free"), ("clamped", "clamped"), ("pinned", "pinned")])
def test_the_estimate_is_above_the_error_where_it_warns_and_the_error_is_small_where_it_does_not(model, ends):
    for a in (0.01, 0.025, 0.05, 0.1, 0.3):
        for load in (
            {"type": "distributed", "value": -5000.0, "start": 0.0, "end": a},
            {"type": "distributed", "value": -5000.0, "start": a / 4, "end": a},
            {"type": "point_force", "position": a, "value": -500.0},
        ):
            error, estimate, _ = near_end(model, ends, load)
            assert error <= max(estimate, TOLERANCE) or estimate == 1.0, (load, error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_the_cantilever_loaded_beside_its_clamp_is_warned_and_a_mirror_image_alike(model):
    """Sweep 18 H2 at 101 points: the tip 13 % (pd-eb), 22 % (pd-bond-pair), 2.1 % (pd-timoshenko) off, now warned."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.05}
    (e1, s1, _), (e2, s2, _) = (near_end(model, ("clamped", "free"), load, 101, m) for m in (False, True))
    assert e1 > 1e-2 and e1 <= s1 and s1 == s2 and abs(e1 - e2) <= 1e-9, (e1, s1, e2, s2)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_stiff_spring_end_is_estimated_as_the_support_it_stands_for(model):
    """Sweep 19 I1: a spring end of 1e12 N/m under a patch on [0, 0.06] gave pd-eb's errors of the pinned end to the
    digit (w 4.34e-3 at 201 points) and no warning. A spring end that holds the deflection now takes the pinned end's
    constant (the clamped end's if it holds the rotation too): the same estimate as the pin, above both errors."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.06}
    (e1, s1, _), (e2, s2, _) = (
        near_end(model, (end, "pinned"), load) for end in ("pinned", {"type": "spring", "stiffness": 1e12})
    )
    assert s1 == s2 and max(e1, e2) <= max(s2, TOLERANCE), (e1, s1, e2, s2)


def test_a_load_edge_warning_does_not_hide_the_estimate():
    """Sweep 20 J1: a patch on [0, 0.0125] beside a stiff spring end (401 points, its edge 5 spacings in) carried only
    the edge warning, "errors of about 1e-2", where w was 4.4e-2 off: the estimate was skipped for a load another
    warning named. Only a point load in the end's layer leaves it to that warning now: the estimate is above w's
    error."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.0125}
    error, estimate, _ = near_end("pd-eb", ({"type": "spring", "stiffness": 1e12}, "pinned"), load, 401)
    assert error > 1e-2 and error <= estimate, (error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
@pytest.mark.parametrize("points", [101, 401])
def test_a_spring_end_is_estimated_as_a_pin_and_with_a_rotational_stiffness_as_a_clamp(model, points):
    """Sweep 21 K1, K2: a spring end with a rotational stiffness (k = 1e12, kr = 1e4 N m/rad, q on [0, 0.02]) left
    pd-eb's w 9.9e-3 off at 401 points and a clamp-like one pd-timoshenko's 0.10 at 101, and a soft spring (k L³ / EI
    24) pd-eb's M at the end 1.9e-2 at 101 (the pin's, whatever k), unwarned. A spring end now takes the pin's
    constant (w and M), with a rotational stiffness the clamp's: the estimate is above the error. pd-bond-pair takes
    none at a rotational spring, where its end slope is first order and its own warning says so."""
    for spring, end in (
        ({"type": "spring", "stiffness": 1e3}, 0.02),
        ({"type": "spring", "stiffness": 1e6}, 0.06),
        ({"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e4}, 0.02),
        ({"type": "spring", "stiffness": 1e12, "rotational_stiffness": 1e12}, 0.02),
    ):
        load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": end}
        error, estimate, said = near_end(model, (spring, "pinned"), load, points)
        if model == "pd-bond-pair" and "rotational_stiffness" in spring:
            assert estimate == 0.0 and any("first order" in w for w in said), (spring, said)
        else:
            assert error <= max(estimate, TOLERANCE), (spring, error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_load_beside_an_opposing_one_is_estimated_beside_the_whole(model):
    """Sweep 21 K3: q = -5000 on [0, 0.05] and +2500 on [0.06, 0.1] of a pinned-pinned beam: the second load halves
    the whole's deflection and the first's error near the end stays its own, so the estimate relative to the load's
    own deflection was 2-3.4 times below pd-eb's and pd-bond-pair's errors and at 801 points pd-eb printed nothing with
    w 1.5e-3 off. The estimate now takes the load's response beside the whole's (exact beams): above the error."""
    load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.05}
    more = ({"type": "distributed", "value": 2500.0, "start": 0.06, "end": 0.1},)
    for points in (201, 801):
        error, estimate, _ = near_end(model, ("pinned", "pinned"), load, points, more=more)
        assert error <= max(estimate, TOLERANCE), (points, error, estimate)


@pytest.mark.parametrize("model", list(MODELS))
def test_a_patch_cut_into_pieces_is_estimated_as_the_patch(model):
    """Sweep 22 M1: q on [0.04, 0.14] of a clamped-clamped beam cut into 10 patches gives pd-bond-pair the errors of
    the whole patch, but each piece's estimate was its own share: 0.0016 printed for w 3.6e-3 off at 201 points, and
    nothing at 401 with the rotation 1.1e-3 off. The pieces near one end add up: the estimate is above the error."""
    pieces = [
        {"type": "distributed", "value": -5000.0, "start": 0.04 + k / 100, "end": 0.05 + k / 100} for k in range(10)
    ]
    for points in (201, 401):
        error, estimate, _ = near_end(model, ("clamped", "clamped"), pieces[0], points, more=tuple(pieces[1:]))
        assert error <= max(estimate, TOLERANCE), (points, error, estimate)


@pytest.mark.parametrize("scale", [1e-3, 1e3])
def test_a_load_at_the_closest_bound_is_judged_alike_on_a_scaled_beam(scale):
    """Sweep 23 N3: a piece whose centroid sits exactly 2.5 spacings from the end turned "not estimated" on the beam
    scaled by 1e-3 (its positions' rounding), one line more and the sum 0.049 -> 0.038. The bound holds whatever the
    rounding: the same lines on the scaled beam."""

    def said(k: float):
        loads = [
            {"type": "distributed", "value": -5000.0, "start": 0.0, "end": 0.05 * k},
            {"type": "distributed", "value": -5000.0, "start": 0.05 * k, "end": 0.1 * k},
        ]
        d = scene_dict("clamped", "pinned", loads)
        d.update(beam={"length": 1.0 * k}, section={"width": 0.02 * k, "height": 0.05 * k})
        d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
        return [w for w in run(parse_scene(d), "pd-eb", points=101).info.get("warnings", []) if "end (" in w]

    base, scaled = said(1.0), said(scale)
    numbers = [re.sub(r"[0-9.e+-]+", "#", w) for w in base]  # the same lines, whatever their numbers' rounding
    assert numbers == [re.sub(r"[0-9.e+-]+", "#", w) for w in scaled], (base, scaled)


def rotation_estimate(line: str) -> float:
    """The rotation's estimate a load-near-an-end line gives: its own number where it names the rotation beside
    the deflection and the moment, else "the rotation up to F times that (Y)": Y."""
    if "the deflection, the rotation and the moment" in line:
        return float(line.split(", here ")[1].split(",")[0])
    return float(line.split("the rotation up to ")[1].split("(")[1].split(")")[0])


@pytest.mark.parametrize("model", sorted(MODELS))
@pytest.mark.parametrize("ends", [("clamped", "free"), ("pinned", "pinned"), ("clamped", "clamped")])
def test_the_rotation_near_an_end_load_is_estimated_too(model, ends):
    """Sweep 25 O5: a patch 3 spacings from a pinned end left pd-timoshenko's rotation 4.5 times its jump line's
    estimate, beside an end-load line that spoke of w and M only. Each default model's line now covers the rotation
    (pd-eb within its estimate; pd-timoshenko and pd-bond-pair up to 3 and 2 times it, measured 2.53 and 1.58 by
    benchmarks/end_loads.py)."""
    checked = 0
    for a in (0.01, 0.025, 0.05, 0.1):
        for load in (
            {"type": "distributed", "value": -5000.0, "start": a / 4, "end": a},
            {"type": "point_force", "position": a, "value": -500.0},
        ):
            d = scene_dict(*ends, [load])
            d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
            d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
            sc = parse_scene(d)
            r, e = run(sc, model, points=201), run(sc, MODELS[model], points=201)
            lines = [w for w in r.info.get("warnings", []) if "(h / d)²" in w and w.startswith("loads[0]")]
            if not lines:
                continue
            error = float(np.abs(r.rotation - e.rotation).max() / np.abs(e.rotation).max())
            assert error <= rotation_estimate(lines[0]), (a, load["type"], error, lines[0])
            checked += 1
    assert checked  # each end pair warns on some of these loads


def test_the_rotation_s_part_does_not_make_the_line_speak_alone():
    """Sweep 30 T3: the rotation's factor (3 for pd-timoshenko, 2 for pd-bond-pair) made the line speak from an
    estimate of 3.3e-4 (297 new lines on errors all below 1e-3, no unwarned row mended): a patch on [0, 0.2] of a
    pinned-pinned beam, pd-timoshenko at 201 points, rotation 4.2e-4 against "here 0.00038, the rotation up to 3 times
    that". The line speaks where w and M need it."""
    d = scene_dict("pinned", "pinned", [{"type": "distributed", "value": -1000.0, "start": 0.0, "end": 0.2}])
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    r = run(parse_scene(d), "pd-timoshenko", points=201)
    assert not [w for w in r.info.get("warnings", []) if "(h / d)²" in w]


@pytest.mark.parametrize("model", ["pd-eb", "pd-bond-pair"])
@pytest.mark.parametrize("ends", [("free", "clamped"), ("guided", "clamped")])
@pytest.mark.parametrize("points", [101, 201])
def test_a_patch_on_the_last_spacings_of_a_free_or_guided_end_is_warned(model, ends, points):
    """A patch on the last 0.5 ... 5 spacings of a free or guided end: the ends' Taylor ghosts, fitted to M = V = 0
    there, carry it (up to 1.3 and 3.2 times max |w| on half a spacing, at any grid): nearer than 2.5 h the line expects
    large errors; farther the error is small or the ghosts' own line names it (sweep 43, finding 1)."""
    dx = 1.0 / (points - 1)
    for spacings in (0.5, 1, 2, 3, 5, 8):
        load = {"type": "distributed", "value": -5000.0, "start": 0.0, "end": spacings * dx}
        error, estimate, said = near_end(model, ends, load, points=points)
        ghosts = any("its ghosts are fitted on: errors of about 1e-2" in w for w in said)
        assert error <= max(estimate, TOLERANCE) or estimate == 1.0 or (ghosts and error < 1e-2), (spacings, error)
