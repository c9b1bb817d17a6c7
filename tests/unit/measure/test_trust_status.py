"""A result's round-off bound reaches every output: solve's table, CSV and JSON, a
study row's status (``suspect``), the report; NaN/inf never leaves with exit 0."""

import json
import math

import pandas as pd
import pytest

from pdverify.measure.status import case_status
from pdverify.numerics.linalg import BOUND_LIMIT

TOML = """name = "propped cantilever"
[beam]
length = 1.0
[section]
width = 0.01
height = 0.01
[material]
youngs_modulus = {E}
poissons_ratio = 0.3
[supports]
left = "clamped"
right = "pinned"
[[loads]]
type = "point_force"
position = 0.3
value = -50.0
"""


def test_case_status_from_the_bound():
    assert case_status({}) == {"error_bound": None}
    assert case_status({"error_bound": 0.5 * BOUND_LIMIT}) == {"error_bound": 0.5 * BOUND_LIMIT}
    s = case_status({"error_bound": 2 * BOUND_LIMIT})
    assert s["status"] == "suspect" and "2e-06" in s["message"]
    assert case_status({"error_bound": math.inf})["status"] == "suspect"


def test_a_bound_that_cannot_decide_the_error_leaves_the_row_ok():
    """A bound past the limit but below a tenth of the measured error cannot change that error's first digit: the
    row stays ok (the warning stays in its solve's output); at a tenth or more, or with no error measured, suspect."""
    bound = 2 * BOUND_LIMIT
    assert case_status({"error_bound": bound}, err=10.5 * bound) == {"error_bound": bound}
    at_tenth = case_status({"error_bound": bound}, err=10 * bound)
    assert at_tenth["status"] == "suspect" and "a tenth of the error" in at_tenth["message"]
    assert case_status({"error_bound": bound}, err=math.nan)["status"] == "suspect"
    assert case_status({"error_bound": math.inf}, err=1.0)["status"] == "suspect"


def test_a_bound_of_one_or_more_is_in_doubt_whatever_the_error():
    """A relative bound of 1 or more says the solution may be all round-off (pd-curved at L/h = 1e12: error 891, bound
    9.5, once ok): the row is suspect, however much larger the error."""
    assert case_status({"error_bound": 9.5}, err=891.0)["status"] == "suspect"
    assert case_status({"error_bound": 1.0}, err=1e6)["status"] == "suspect"
    assert case_status({"error_bound": 0.99}, err=10.0) == {"error_bound": 0.99}


def _cli(args, tmp_path, E="200e9"):
    from typer.testing import CliRunner

    from pdverify.apps.cli import app

    scene = tmp_path / "s.toml"
    scene.write_text(TOML.format(E=E))
    return CliRunner().invoke(app, ["solve", str(scene), *args])


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_every_format_shows_the_warning(tmp_path, fmt):
    """fem-eb's direct form at 20,001 nodes: round-off bound ~1e3 (error 7e-2 measured), in every format."""
    r = _cli(["-m", "fem-eb", "--form", "direct", "--points", "20001", "--format", fmt], tmp_path)
    assert r.exit_code == 0
    out = r.stdout
    if fmt == "json":
        info = json.loads(out)["info"]
        assert info["error_bound"] > BOUND_LIMIT and any("round-off bound" in w for w in info["warnings"])
    else:
        assert any(line.startswith("# warning: round-off bound") for line in out.splitlines())
    if fmt == "csv":
        df = pd.read_csv(__import__("io").StringIO(out), comment="#")
        assert list(df.columns) == ["x", "w", "rotation", "M", "V"] and len(df) == 20001


def test_no_warning_where_the_bound_holds(tmp_path):
    r = _cli(["-m", "fem-eb", "--points", "20001", "--format", "csv"], tmp_path)
    assert r.exit_code == 0 and not r.stdout.startswith("#")


@pytest.mark.parametrize("model", ["exact-eb", "fem-eb", "exact-timoshenko", "fem-timoshenko"])
def test_no_nan_with_exit_0(tmp_path, model):
    """E = 1e-300 on a 1 cm section: EI underflows to a subnormal float. The scene is refused before any model
    runs (exit 2, one line naming the modulus and the fix); never a NaN printed with exit 0."""
    r = _cli(["-m", model, "--points", "11"], tmp_path, E="1e-300")
    assert r.exit_code == 2
    assert "nan" not in r.stdout.lower()
    assert "youngs_modulus = 1e-300" in r.output and "error:" in r.output and "units" in r.output


def test_a_study_row_is_suspect_and_the_report_marks_it(tmp_path):
    from pdverify.study import spec
    from pdverify.study.runner import run_case

    text = TOML.format(E="200e9")
    bad = run_case(
        spec.Case("s.toml", text, None, "fem-eb", {"points": 20001, "form": "direct"}, {"model": "exact-eb"})
    )["row"]
    good = run_case(spec.Case("s.toml", text, None, "fem-eb", {"points": 20001}, {"model": "exact-eb"}))["row"]
    assert bad["status"] == "suspect" and bad["error_bound"] > BOUND_LIMIT and bad["error_bound"] >= bad["err_max"] / 2
    assert good["status"] == "ok" and good["error_bound"] < BOUND_LIMIT and good["err_max"] < 1e-10

    from pdverify.report.build import table

    html = table(pd.DataFrame([bad, good]), ["model", "err_max", "error_bound", "status"], row_class="status")
    assert '<tr class="suspect">' in html and '<tr class="ok">' in html


def test_a_row_against_a_reference_with_a_large_bound_is_suspect():
    """The error is measured against the reference, so the reference's round-off bound is the row's too: fem-eb at
    101 nodes (exact at its nodes) against fem-eb's direct form at 20,001 nodes (bound ~1e3) is suspect, with a message
    naming the reference; against the two-field form (bound < 1e-6) it is ok. exact-eb's bound is its closed form's
    rounding (pdverify/exact/straight.py: rounding), near eps on this scene."""
    from pdverify.measure.status import reference_status
    from pdverify.study import spec
    from pdverify.study.runner import run_case

    assert reference_status(None, {}) == {"ref_error_bound": None}
    assert reference_status(0.5 * BOUND_LIMIT, {}) == {"ref_error_bound": 0.5 * BOUND_LIMIT}
    both = reference_status(2 * BOUND_LIMIT, {"message": "own"})
    assert both["status"] == "suspect" and both["message"].startswith("own; the reference's round-off bound 2e-06")
    text = TOML.format(E="200e9")
    ref = {"model": "fem-eb", "points": 20001}
    bad = run_case(spec.Case("s.toml", text, None, "fem-eb", {"points": 101}, dict(ref, form="direct")))["row"]
    good = run_case(spec.Case("s.toml", text, None, "fem-eb", {"points": 101}, ref))["row"]
    exact = run_case(spec.Case("s.toml", text, None, "fem-eb", {"points": 101}, {"model": "exact-eb"}))["row"]
    assert bad["status"] == "suspect" and bad["ref_error_bound"] > BOUND_LIMIT and "reference's" in bad["message"]
    assert bad["error_bound"] < BOUND_LIMIT  # the model's own solve is fine: only the reference is in doubt
    assert good["status"] == "ok" and good["ref_error_bound"] < BOUND_LIMIT
    assert exact["status"] == "ok" and exact["ref_error_bound"] < 1e-12


def test_a_card_check_on_such_rows_carries_the_caveat(tmp_path):
    """A verify check that judged errors against such a reference says so in its summary (card HTML, JSON, JUnit)
    and the study report's summary marks its verdict with * (the caveat in the cell's title)."""
    from pdverify.report.summary import _check_cell
    from pdverify.verify import checks as C

    df = pd.DataFrame(
        {
            "scene_file": ["a", "a", "a", "b", "b", "b"],
            "points": [21, 41, 81] * 2,
            "spacing": [1 / 20, 1 / 40, 1 / 80] * 2,
            "err_max": [4e-3, 1e-3, 2.5e-4] * 2,
            "total_s": [0.01] * 6,
            "status": ["ok"] * 3 + ["suspect"] * 3,
            "message": [""] * 6,
            "ref_error_bound": [1e-9] * 3 + [0.36] * 3,
        }
    )
    rows = C.series(df, ["a", "b"])
    conv = C.convergence(rows, 2.0, "convergence")
    assert (
        conv["verdict"] == "pass" and conv["caveat"] and "1 scene(s)" in conv["summary"] and "0.36" in conv["summary"]
    )
    assert not C.convergence(rows[:1], 2.0, "convergence")["caveat"]
    cell = _check_cell("pass", conv["caveat"])
    assert cell.endswith(">pass*</td>") and 'title="1 scene(s) measured against a reference' in cell
    assert _check_cell("pass", "") == '<td class="chk-pass">pass</td>'
