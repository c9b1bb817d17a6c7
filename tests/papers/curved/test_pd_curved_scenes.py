"""pd-curved on straight beams with supports inside the span, springs and segments: each support and segment end a
break of the axis with its own conditions (pdverify/papers/curved/supports.py), against exact-timoshenko (w, the
rotation, M, the reactions) and exact-rod (u, N); mirror scenes and the one-line refusals."""

import sys
from pathlib import Path

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "exact"))
from test_continuous_beams import CASES, mirrored, scene  # noqa: E402

HELD_AXIALLY = [c for c in CASES if c[0] not in ("on springs", "stepped on springs")]


def _errors(sc, points):
    r = run(sc, "pd-curved", points=points)
    ex = get_model("exact-timoshenko").evaluate(sc, {}, r.x)
    out = [np.abs(getattr(r, f) - ex[f]).max() / np.abs(ex[f]).max() for f in ("w", "rotation")]
    re = run(sc, "exact-timoshenko", points=3).info["reactions"]
    rr = r.info["reactions"]
    out.append(max(abs(rr[k] - v) for k, v in re.items()) / max(abs(v) for v in re.values()))
    return np.array(out)


@pytest.mark.parametrize("name,supports,segments", HELD_AXIALLY, ids=[c[0] for c in HELD_AXIALLY])
def test_converges_at_the_degree_on_continuous_overhanging_spring_and_segmented_beams(name, supports, segments):
    """Degree 4 (the default): w and the rotation at order >= 3.5 between 41 and 81 points (measured 4.0 to 5.6;
    two spans 3.7e-4, 1.5e-5, 4.9e-7 at 21, 41, 81), every support's force and moment at >= 2.5."""
    sc = scene(supports, segments)
    coarse, fine = _errors(sc, 41), _errors(sc, 81)
    assert np.all(fine <= 1e-5), fine
    order = np.log2(coarse / fine)
    # the reactions from the resultants' jumps: order >= 2.5 (the overhangs' determinate ones 2.9, 6.7e-7 at 41)
    assert np.all(order[:2] >= 3.5) and order[2] >= 2.5, (coarse, fine)


@pytest.mark.parametrize("name,supports,segments", HELD_AXIALLY[:3], ids=[c[0] for c in HELD_AXIALLY[:3]])
def test_a_mirror_scene_gives_the_mirror_result(name, supports, segments):
    a = run(scene(supports, segments), "pd-curved", points=41)
    b = run(mirrored(supports, segments), "pd-curved", points=41)
    back = np.interp(a.x, (2.0 - b.x)[::-1], b.w[::-1])
    assert np.abs(back - a.w).max() <= 1e-11 * np.abs(a.w).max()


def test_an_inner_pinned_support_holds_the_axial_displacement_as_exact_rod_reads_it():
    """The axial part of a two-span beam (pinned, pinned inside, roller) is exact for piecewise-polynomial loads:
    u against exact-rod to round-off, the axial reactions -63.3 and -336.7 N carrying the 400 N of axial load."""
    d = {
        "name": "two spans, axial loads",
        "beam": {"length": 2.0},
        "section": {"width": 0.05, "height": 0.1},
        "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.3},
        "supports": {"left": "pinned", "right": "roller", "inner": [{"position": 1.2, "type": "pinned"}]},
        "loads": [
            {"type": "distributed", "value": 0.0, "axial": 300.0},
            {"type": "point_force", "position": 0.5, "value": 0.0, "axial": -200.0},
        ],
    }
    sc = parse_scene(d)
    r = run(sc, "pd-curved", points=41)
    ex = get_model("exact-rod").evaluate(sc, {}, r.x)
    assert np.abs(r.fields["u"] - ex["u"]).max() <= 1e-12 * np.abs(ex["u"]).max()
    re, rr = run(sc, "exact-rod", points=3).info["reactions"], r.info["reactions"]
    assert rr["axial_left"] == pytest.approx(re["axial_left"], rel=1e-10)
    assert rr["axial_inner_0"] == pytest.approx(re["axial_inner_0"], rel=1e-10)


@pytest.mark.parametrize("name", ["on springs", "stepped on springs"])
def test_a_beam_on_springs_alone_slides_along_its_axis_and_is_refused_in_one_line(name):
    """The springs resist w and the rotation, not u: pd-curved, which has the axial unknown, names the mechanism."""
    supports, segments = next((s, g) for n, s, g in CASES if n == name)
    with pytest.raises(InputError) as err:
        run(scene(supports, segments), "pd-curved", points=41)
    assert len(err.value.lines) == 1 and "along its axis" in err.value.lines[0]


def test_the_manufactured_harness_refuses_supports_inside_the_span():
    sc = scene(CASES[0][1])
    assert any(p.startswith("supports.inner") for p in get_model("pd-curved-mms").check(sc))


@pytest.mark.parametrize("offset, said", [(0.0, False), (1e-9, True), (1e-6, False)])
def test_a_load_merged_with_a_support_says_so(offset, said):
    """pd-curved takes breaks within 1e-9 L as one: a couple 1e-9 m beside an inner pin was put on the pin, 3.7e-9
    off (round-off bound 6e-13) and not mirror-symmetric, unwarned. It says so where the two lie further apart than
    the positions' rounding and within the merge; on the support or clearly beside it, nothing."""
    d = scene_dict("pinned", "roller", [{"type": "point_moment", "position": 0.8 + offset, "value": 500.0}])
    d["supports"]["inner"] = [{"position": 0.8, "type": "pinned"}]
    r = run(parse_scene(d), "pd-curved", points=41)
    assert any("takes them as one break" in w for w in r.info.get("warnings", [])) == said
