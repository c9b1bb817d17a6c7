"""pd-curved on a curved axis carries the estimate of its error from the same solve on about half the points
(pdverify/registry/grid_check.py): sweep 34 S34-6 found a 272.6-degree pinned-pinned arc with a patch and a couple
2.0 % off exact-curved in w and 5.9 % in N at 51 particles (degree 3) with no warning, its frame defect (3.7e-4) under
the degree's limit (1.5e-3)."""

import json
import tomllib

import numpy as np
import pandas as pd
import pytest
from helpers import scene_dict

from pdverify.apps.output import result_table
from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.measure.richardson import with_estimate
from pdverify.numerics.features import features
from pdverify.registry import get_model, run
from pdverify.registry.grid_check import fields_of, grid_difference
from pdverify.study.runner import run_study
from pdverify.study.spec import load_study

ARC_TOML = """name = "B3402_0128"
beam = {length = 0.000169319431247}
section = {width = 2.2717e-06, height = 4.5434e-06}
material = {youngs_modulus = 10183.0, poissons_ratio = 0.3}
supports = {left = "pinned", right = "pinned"}
axis = {type = "arc", radius = 3.5588e-05, opening_angle_deg = 272.6, start_angle_deg = 7.3284}
[[loads]]
type = "distributed"
value = 4.9705e-15
start = 7.2396e-05
end = 0.00012163
[[loads]]
type = "point_moment"
position = 0.00013867
value = -3.2035e-23
"""


def arc(**change):
    """Sweep 34's B3402_0128 (micrometres: the scale the sweep drew)."""
    return parse_scene({**tomllib.loads(ARC_TOML), **change})


def error(scene, r) -> float:
    """The largest error of the result's fields against exact-curved's on the same points, each relative to its own
    largest value."""
    a, b = fields_of(r), fields_of(run(scene, "exact-curved", points=len(r.x)))
    return max(float(np.abs(a[k] - b[k]).max() / np.abs(b[k]).max()) for k in a if k in b)


def said(r) -> list[str]:
    return [w for w in r.info.get("warnings", []) if "the same solve on" in w]


def test_a_coarse_grid_on_a_curved_axis_says_so():
    sc = arc()
    r = run(sc, "pd-curved", points=51, degree=3)
    assert error(sc, r) > 0.01  # the case (5.9 % in N measured)
    record = r.info["grid_estimate"]
    assert record["grids"] == [26, 51] and record["difference"] > error(sc, r)  # first order: the error's size
    (line,) = said(r)
    assert line.startswith("pd-curved: the same solve on 26 points differs from this one on 51 by ")
    assert not any("too coarsely" in w for w in r.info["warnings"])  # the frame defect's warning does not see it
    assert "# grid_estimate: the same solve on 26 points against 51: difference 0.345 in N" in result_table(r)
    assert "# grid_estimate: the same solve on 26 points against 51: difference 0.345 in N\n" in r.to_csv()  # S38-5


def test_the_check_warns_past_1e_3_and_leaves_the_result_as_it_is():
    sc = arc()
    for n in (101, 401):
        r = run(sc, "pd-curved", points=n, degree=3)
        quiet = run(sc, "pd-curved", points=n, degree=3, grid_check=False)
        assert len(said(r)) == (r.info["grid_estimate"]["difference"] > 1e-3)
        assert "grid_estimate" not in quiet.info and not said(quiet)
        np.testing.assert_array_equal(r.w, quiet.w)
    assert said(run(sc, "pd-curved", points=101, degree=3)) and not said(r)  # 401 particles: converged below 1e-3
    assert error(sc, r) < 1e-3


def test_a_grid_whose_half_is_refused_says_its_error_is_not_estimated():
    r = run(arc(), "pd-curved", points=7, degree=3)  # its half, 4 points, is below the least it takes (5)
    assert r.info["grid_estimate"]["note"] == "the same solve on 4 points is below the model's least, 5"
    assert any("the error on 7 points is not estimated" in w for w in r.info["warnings"])


def test_a_straight_axis_and_the_references_are_left_alone():
    straight = arc(axis={"type": "straight"})
    assert "grid_estimate" not in run(straight, "pd-curved", points=51).info
    assert "grid_estimate" not in run(arc(), "exact-curved", points=51).info


def test_an_estimate_takes_the_run_s_own_flags():
    r = with_estimate(arc(), get_model("pd-curved"), {"points": 51, "grid_check": True, "history_check": False}, run)
    assert r.info["estimate"]["grids"] == [26, 51, 101] and "grid_estimate" not in r.info  # the nested grids instead
    with pytest.raises(InputError, match="grid_check = 'maybe': give true or false"):  # sweep 36 S36-6: exit 0
        with_estimate(arc(), get_model("pd-curved"), {"points": 51, "grid_check": "maybe"}, run)


def test_a_study_run_may_leave_the_check_out(tmp_path):
    scene = tmp_path / "arc.toml"
    scene.write_text(ARC_TOML)
    study = tmp_path / "s.toml"
    study.write_text(
        f'name = "s"\nscenes = ["{scene}"]\nreference = "exact-curved"\n'
        '[[runs]]\nmodel = "pd-curved"\ndegree = 3\npoints = [51]\ngrid_check = [true, false]\n'
    )
    df = run_study(load_study(study), tmp_path / "out", workers=1, progress=False)
    said = {json.loads(o)["grid_check"]: str(w) for o, w in zip(df["options"], df["warnings"])}
    assert "the same solve on 26 points" in said[True] and "the same solve on" not in said[False]
    # the difference is a column of results.csv (sweep 38 S38-5: only the table and JSON formats carried it)
    made = {json.loads(o)["grid_check"]: d for o, d in zip(df["options"], df["grid_estimate"])}
    direct = run(arc(), "pd-curved", points=51, degree=3).info["grid_estimate"]["difference"]
    assert made[True] == direct and np.isnan(made[False])
    assert list(pd.read_csv(tmp_path / "out" / "results.csv")["grid_estimate"].isna()) == list(
        np.isnan(df["grid_estimate"])
    )


def audit_scene(name: str, L: float, width: float, height: float, E: float, supports: tuple, loads: list, axis: dict):
    return parse_scene(
        {
            "name": name,
            "beam": {"length": L},
            "section": {"width": width, "height": height},
            "material": {"youngs_modulus": E, "poissons_ratio": 0.3},
            "supports": dict(zip(("left", "right"), supports)),
            "loads": loads,
            "axis": {"type": "arc", **axis},
        }
    )


def test_an_even_grid_is_compared_between_the_jumps_not_across_them():
    """Sweep 36 S36-3: at 194 points the finer result, interpolated linearly across the jumps of M at a couple, read
    'differs by 1.2' where the result was 9e-12 off; at 193 and 195 no warning."""
    sc = audit_scene(
        "even_n_jump_false_alarm", 0.03180671653440414, 0.0009393845404413746, 0.0012047653794996674, 143914137618.4,
        ("pinned", "clamped"),
        [
            {"type": "point_force", "position": 0.006751932946121421, "value": -0.0157593812981, "axial": -0.0308329429,
             "frame": "global"},
            {"type": "point_moment", "position": 0.013885089902966217, "value": 0.0009472758613615269},
        ],
        {"radius": 0.14364917074932526, "opening_angle_deg": 12.686398453148673, "start_angle_deg": -101.30785719,
         "direction": "clockwise"},
    )  # fmt: skip
    for n in (193, 194, 195):
        r = run(sc, "pd-curved", points=n, degree=5)
        assert error(sc, r) < 1e-9 and not said(r), n
        assert r.info["grid_estimate"]["difference"] < 1e-6, n


def test_a_group_that_is_zero_but_for_round_off_is_measured_against_the_others():
    """Sweep 36 S36-4: two couples on a clamped-free arc leave N = Q = 0 but for round-off, and the check divided
    round-off by round-off (differences of 1.4 to 1460 at every grid)."""
    sc = audit_scene(
        "zero_NQ_moment_cantilever", 1.6191168669277785e-05, 8.36255784294396e-09, 5.16302238158653e-09,
        38251433373.76783, ("clamped", "free"),
        [
            {"type": "point_moment", "position": 1.2342205388307517e-05, "value": -1.4689406259427323e-22},
            {"type": "point_moment", "position": 1.1682576365265759e-05, "value": -8.002350603938326e-23},
        ],
        {"radius": 5.199965088040079e-06, "opening_angle_deg": 178.40228048217932, "start_angle_deg": -18.18321667},
    )  # fmt: skip
    for n in (59, 101):
        r = run(sc, "pd-curved", points=n, degree=4)
        assert r.info["grid_estimate"]["difference"] < 1e-3 and not said(r), n


def test_a_segment_whose_error_does_not_fall_is_not_estimated():
    """Sweep 36 S36-1: a segment of one family at every grid below N points (info["irregular"]) leaves both grids
    off alike: 0.25 % off in N at 85 points, the difference 1.4e-6, no warning."""
    sc = audit_scene(
        "silent_arc202_n85", 4.313195605400686e-05, 5.666920958248479e-09, 6.544432150365219e-09, 3672493.954591167,
        ("clamped", "pinned"),
        [
            {"type": "point_force", "position": 2.394243126157031e-06, "value": -1.4332854467025996e-22,
             "axial": 9.979375135891964e-23, "frame": "global"},
            {"type": "distributed", "value": -8.902999640127163e-18},
        ],
        {"radius": 1.2231911285685865e-05, "opening_angle_deg": 202.03539629414215, "start_angle_deg": -94.0798071},
    )  # fmt: skip
    r = run(sc, "pd-curved", points=85, degree=5)
    assert error(sc, r) > 1e-3 and r.info.get("irregular")
    assert r.info["grid_estimate"]["note"].startswith("the segment [")
    (line,) = [w for w in r.info["warnings"] if "the error on 85 points is not estimated: the segment [" in w]
    assert "the solves on 43 and 85 points can agree while both are off" in line


STEEL = {
    "beam": {"length": 1.0},
    "section": {"width": 0.02, "height": 0.02},
    "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3},
}


def straight(left: str, right: str, loads: list, name: str = "") -> object:
    """A 1 m steel beam of 20 mm square section."""
    return parse_scene(scene_dict(left, right, loads, name=name or f"{left}-{right}", **STEEL))


def member(model: str, shape: str):
    """Sweep 37 S37-2: a 1 m rod clamped at both ends (pd-rod) or bar pinned at both ends (pd-torsion) under a line
    load of ``shape``."""
    ends = "clamped" if model == "pd-rod" else "pinned"
    load = {"type": "distributed", "value": 0.0, "shape": shape, "axial" if model == "pd-rod" else "torque": 100.0}
    return straight(ends, ends, [load], f"{model} {shape}")


@pytest.mark.parametrize(
    "model, exact, field", [("pd-rod", "exact-rod", "u"), ("pd-torsion", "exact-torsion", "twist")]
)
def test_rods_and_bars_estimate_their_coarse_grids(model, exact, field):
    """A sine load at the default horizon: 0.93 % off at 21 points with no line (the model-error line speaks past
    1 %); the halves differ by more than the error, and the line goes where they agree to 1e-3."""
    sc = member(model, "sine")
    for n in (21, 41, 161):
        r, e = run(sc, model, points=n), run(sc, exact, points=n)
        err = np.abs(r.measured(field) - e.measured(field)).max() / np.abs(e.measured(field)).max()
        assert (err > 1e-3) == (n < 161) and bool(said(r)) == (n < 161), (n, err)
        assert r.info["grid_estimate"]["difference"] > err
    assert not said(run(member(model, "uniform"), model, points=21))  # the nonlocal operator is exact there
    continuum = run(sc, model, points=41, horizon_length=0.1, continuum=True)
    assert "grid_estimate" not in continuum.info  # no grid to estimate


def test_a_field_small_beside_its_partner_is_measured_on_its_own_scale():
    """Sweep 37 S37-3: on a shallow arc N is a twentieth of Q; measured against the larger Q the halves of a grid
    whose N was 2.1 % off its own largest value differed by 9.4e-4, unwarned."""
    sc = parse_scene(
        {
            "name": "R3703_1065",
            "beam": {"length": 0.0303638370799},
            "section": {"width": 0.0005218, "height": 0.00031113},
            "material": {"youngs_modulus": 829680000.0, "poissons_ratio": 0.3},
            "supports": {"left": "clamped", "right": "roller"},
            "loads": [
                {"type": "distributed", "value": 9.7409e-07},
                {"type": "point_force", "position": 0.0010588, "value": 3.3799e-08},
            ],
            "axis": {"type": "arc", "radius": 0.064695, "opening_angle_deg": 26.8911, "start_angle_deg": -74.617},
        }
    )
    r = run(sc, "pd-curved", points=201, degree=3)
    assert error(sc, r) > 0.01 and said(r)


def test_at_a_fixed_horizon_length_the_coarser_solve_keeps_the_horizon_factor():
    """Sweep 38 S38-1: at horizon_length = 0.07 L a rod under a sine load is 2.0e-3 off at every grid (its model error);
    two grids at that one horizon share it and differed by 9.8e-4, unwarned. The coarser solve keeps the factor."""
    sc = member("pd-rod", "sine")
    for n in (201, 801):
        r, e = run(sc, "pd-rod", points=n, horizon_length=0.07), run(sc, "exact-rod", points=n)
        err = np.abs(r.measured("u") - e.measured("u")).max() / np.abs(e.measured("u")).max()
        (line,) = said(r)
        assert err > 1e-3 and r.info["grid_estimate"]["difference"] > err
        m = round(0.07 * (n - 1))
        assert f"at the same horizon factor ({m} spacings: twice the horizon)" in line and "a shorter horizon" in line


def beam_error(scene, r) -> float:
    """The largest error of w and the rotation against exact-eb's, each relative to its own largest value."""
    e = run(scene, "exact-eb", points=len(r.x))
    return max(float(np.abs(a - b).max() / np.abs(b).max()) for a, b in ((r.w, e.w), (r.rotation, e.rotation)))


@pytest.mark.parametrize(
    "model, left, right, n",
    [
        ("pd-eb", "pinned", "guided", 41),
        ("pd-bond-pair", "pinned", "pinned", 81),
        ("pd-bond-pair", "roller", "guided", 81),
    ],
)
def test_pd_eb_and_bond_pair_estimate_their_coarse_grids(model, left, right, n):
    """Their verification suite's sine loads: pd-eb 2.4e-3 off at 41 points, pd-bond-pair (its mirror ends: the model
    error of its horizon, 3 spacings) 1.5e-3 and 1.1e-3 at 81 in w, with no line (their cards: 4 and 12 such rows;
    sweep 39: 29 silent rows of 16,830 random ones). Now warned; four times the points, the line goes."""
    sc = straight(left, right, [{"type": "distributed", "value": -1000.0, "shape": "sine"}])
    r = run(sc, model, points=n)
    err = beam_error(sc, r)
    assert err > 1e-3 and len(said(r)) == 1 and r.info["grid_estimate"]["difference"] > err
    assert [w for w in r.info["warnings"] if w not in said(r)] == []  # no other line told
    fine = run(sc, model, points=4 * n - 3)
    assert beam_error(sc, fine) < 1e-3 and not said(fine)


def test_a_load_the_coarser_grid_alone_puts_in_an_end_zone_is_not_estimated():
    """Sweep 39: a couple 10.4 spacings from a clamp at 201 points is outside pd-eb's end layer (10 spacings at horizon
    3), where its cantilever is exact; on 101 points it is 5.2 spacings from the clamp, inside, and that grid's shear
    is off by 70 times max |M| / L: the difference is the coarser grid's error, not this one's, so the check says it
    does not estimate it (its line, not a difference's)."""
    sc = straight("clamped", "free", [{"type": "point_moment", "position": 0.052, "value": 10.0}])
    r = run(sc, "pd-eb", points=201)
    assert beam_error(sc, r) < 1e-9  # exact
    coarse = run(sc, "pd-eb", points=101, grid_check=False)
    assert any("inside the boundary layer" in w for w in coarse.info["warnings"])
    (line,) = r.info["warnings"]
    assert (
        "the error on 201 points is not estimated: the same solve on 101 points puts loads[0] inside an end's zone"
        in line
    )
    assert r.info["grid_estimate"] == {"grids": [101, 201], "note": line.split("not estimated: ")[1].split("; use")[0]}
    assert not said(run(sc, "pd-eb", points=201, grid_check=False))


def test_a_fractional_factor_at_a_horizon_length_is_estimated_where_the_variant_takes_the_length():
    """Sweep 39: pd-eb's paper variant defines a fractional m only through a horizon length (Eq. 11a with delta given),
    and its coarser solve was given the factor (4.44) and refused it: "not estimated" on 127 of 148 such rows. The
    coarser solve takes the same factor as a length."""
    sc = straight("pinned", "pinned", [{"type": "distributed", "value": -1000.0, "shape": "sine"}])
    r = run(sc, "pd-eb", points=21, horizon_length=0.222, variant="paper")
    assert abs(r.info["m"] - 4.44) < 1e-9 and "difference" in r.info["grid_estimate"]
    twice = run(sc, "pd-eb", points=11, horizon_length=0.444, variant="paper", grid_check=False)
    assert r.info["grid_estimate"]["difference"] == grid_difference(r, twice)[0]


def test_a_series_finest_first_solves_each_grid_once_and_gives_the_same_results():
    """The coarser solve of the grid check is kept (registry._unchecked): on a series solved finest first, as a card
    does, a grid's own solve is the finer grid's check, given back as a copy, bit for bit the result made apart."""
    from pdverify import registry

    sc = straight("pinned", "guided", [{"type": "distributed", "value": -1000.0, "shape": "sine"}])
    registry._unchecked_kept.clear()
    made = [run(sc, "pd-eb", points=n) for n in (161, 81, 41)]  # 81 and 41 were the checks of 161 and 81
    assert len(registry._unchecked_kept) == 4  # 161, 81, 41, 21: four solves for three grids and their checks
    registry._unchecked_kept.clear()
    apart = [run(sc, "pd-eb", points=n) for n in (41, 81, 161)][::-1]
    for a, b in zip(made, apart, strict=True):
        assert np.array_equal(a.w, b.w) and np.array_equal(a.rotation, b.rotation)
        assert a.info.get("warnings") == b.info.get("warnings") and a.info["grid_estimate"] == b.info["grid_estimate"]
    made[2].info.setdefault("warnings", []).append("changed by the caller")
    assert "changed by the caller" not in run(sc, "pd-eb", points=41).info.get("warnings", [])  # a copy


def test_a_load_both_grids_put_in_an_end_zone_is_not_estimated_from_the_coarser_one():
    """A couple 8.07 spacings from a clamp at 101 points is inside pd-eb's end layer (10 spacings at horizon 3) on both
    grids, and exact on this one; on 51 points it is 4.04 spacings from the clamp, where that grid's shear is far
    off, and the check read their difference as this grid's possible error (a sweep of random straight scenes:
    "differs ... by 52 in V relative to max |M| / L" on a clamped-spring beam; here 51). The layer's error falls
    steeply with the spacings from the end, so the coarser grid's error is the larger: not estimated, and this grid's
    own layer line stays."""
    sc = straight("clamped", "free", [{"type": "point_moment", "position": 0.0807, "value": 10.0}])
    r = run(sc, "pd-eb", points=101)
    assert beam_error(sc, r) < 1e-9  # exact
    coarse = run(sc, "pd-eb", points=51, grid_check=False)
    assert grid_difference(r, coarse, features(sc))[0] > 1e-3  # what was read as this grid's error
    lines = r.info["warnings"]
    assert any("inside the boundary layer" in w for w in lines)  # this grid's own line
    (line,) = [w for w in lines if "points" in w and "estimated" in w]
    assert "not estimated: the same solve on 51 points puts loads[0] inside an end's zone" in line
    assert "half as many of its spacings from the end as this grid" in line
