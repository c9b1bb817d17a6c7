"""pd-curved on a curved axis carries the estimate of its error from the same solve on about half the points
(pdverify/registry/grid_check.py): sweep 34 S34-6 found a 272.6-degree pinned-pinned arc with a patch and a couple
2.0 % off exact-curved in w and 5.9 % in N at 51 particles (degree 3) with no warning, its frame defect (3.7e-4) under
the degree's limit (1.5e-3)."""

import json
import tomllib

import numpy as np

from pdverify.core.scene_file import parse_scene
from pdverify.measure.richardson import with_estimate
from pdverify.registry import get_model, run
from pdverify.registry.grid_check import fields_of
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
    assert r.info["grid_estimate"]["note"].startswith("no coarser grid")
    assert any("the error on 7 points is not estimated" in w for w in r.info["warnings"])


def test_a_straight_axis_and_the_references_are_left_alone():
    straight = arc(axis={"type": "straight"})
    assert "grid_estimate" not in run(straight, "pd-curved", points=51).info
    assert "grid_estimate" not in run(arc(), "exact-curved", points=51).info


def test_an_estimate_takes_the_run_s_own_flags():
    r = with_estimate(arc(), get_model("pd-curved"), {"points": 51, "grid_check": True, "history_check": False}, run)
    assert r.info["estimate"]["grids"] == [26, 51, 101] and "grid_estimate" not in r.info  # the nested grids instead


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
