"""The bench command runs and reports ratios; no timing assertions (numbers belong in the report)."""

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
import scipy.sparse as sp
from helpers import ROOT

from pdverify.apps.bench import bench_case
from pdverify.measure.cost import cost_slope


@pytest.mark.slow
def test_bench_json_lines():
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "pdverify.apps.cli",
            "bench",
            "-m",
            "exact-eb",
            "--points",
            "101",
            "--points",
            "1001",
            "--format",
            "json",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    rows = [json.loads(l) for l in r.stdout.splitlines()]
    assert [row.get("points") for row in rows[:2]] == [101, 1001]
    assert all(row["status"] == "ok" and row["total_s"] > 0 for row in rows[:2])
    assert rows[-1]["model"] == "exact-eb" and "cost_slope" in rows[-1]


def test_limit_is_banded_solve_of_the_models_matrix(monkeypatch):
    """A model that declares ``assembles`` gets limit_s from the banded solve of exactly the System its
    assemble() returns; one that does not declare it gets none, whatever methods it has."""
    from pdverify import registry
    from pdverify.core.contract import System
    from pdverify.exact.beam import ExactBeam

    class Tridiag(ExactBeam):
        assembles = True

        def assemble(self, scene, params):
            n = params["points"]
            K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()
            return System(K, np.ones(n), np.arange(n), {})

    m = Tridiag("tridiag-test", False, "test")
    monkeypatch.setitem(registry.models(), "tridiag-test", m)
    row = bench_case("tridiag-test", 2001)
    assert row["bandwidth"] == 3 and row["limit_s"] > 0 and row["ratio"] == row["total_s"] / row["limit_s"]

    class Undeclared(Tridiag):
        assembles = False  # a method named assemble is not the contract: the declaration is

    monkeypatch.setitem(registry.models(), "undeclared-test", Undeclared("undeclared-test", False, "test"))
    row = bench_case("undeclared-test", 101)
    assert row["limit_s"] is None and row["bandwidth"] is None


def test_default_models_are_the_declared_ones():
    """bench's default list: models declaring an assembled system or a time integrator, nothing probed."""
    from pdverify.apps.bench import default_models
    from pdverify.registry import models

    got = set(default_models())
    assert {"pd-eb", "pd-bond-pair", "pd-timoshenko", "fem-eb", "pd-curved"} <= got
    assert not got & {n for n, m in models().items() if not m.assembles and "dynamic" not in m.analyses}
    assert "exact-eb" not in got


def test_every_default_model_runs_on_the_default_scene():
    """`pdverify bench` with no --model times every default model on the example cantilever: each row runs (an exact
    modal solution takes transient scenes only; an implicit FEM transient has no integrator to time: neither is a
    default), and a rate is given only by a model's own integrator."""
    from pdverify.apps.bench import default_models, times_dynamics
    from pdverify.registry import get_model

    assert "exact-modal-rod" not in default_models() and not times_dynamics(get_model("fem-timoshenko"))
    for name in default_models():
        row = bench_case(name, 101, repeat=1)
        assert row["total_s"] > 0, name


def test_cost_slope_recovers_power():
    rows = [
        {"model": "m", "status": "ok", "points": n, "total_s": 1e-6 * n**1.5, "max_error": 1e-9}
        for n in (10, 100, 1000)
    ]
    assert abs(cost_slope(rows)["m"] - 1.5) < 1e-12
    twice = [dict(rows[0]), dict(rows[0], total_s=2e-5)]  # one size timed twice: no slope (polyfit of one x)
    assert cost_slope(twice) == {}


def test_performance_page_states_targets_and_verdicts(tmp_path):
    from pdverify.report.perf import build_performance, targets

    rows = [
        {
            "model": "a",
            "points": 1000,
            "total_s": 0.01,
            "limit_s": 0.004,
            "ratio": 2.5,
            "peak_mem_mb": 5.0,
            "updates_per_s": None,
            "status": "ok",
            "max_error": 1e-9,
        },
        {
            "model": "a",
            "points": 1_000_000,
            "total_s": 3.0,
            "limit_s": 1.0,
            "ratio": 3.0,
            "peak_mem_mb": 900.0,
            "updates_per_s": None,
            "status": "ok",
            "max_error": 1e-9,
        },
        {
            "model": "b",
            "points": 1_000_000,
            "total_s": 1.0,
            "limit_s": 0.6,
            "ratio": 1.6,
            "peak_mem_mb": 2500.0,
            "updates_per_s": 6e7,
            "status": "ok",
            "max_error": 1e-9,
        },
    ]
    t = targets(pd.DataFrame(rows), {"a": 1.05})
    got = {(r.model, r.target.split()[0]): r.verdict for r in t.itertuples()}
    assert got[("a", "total")] == "fail" and got[("b", "total")] == "pass"  # 3.0 > 2, 1.6 <= 2
    assert got[("b", "updates/s")] == "pass" and got[("b", "peak")] == "fail" and got[("a", "cost")] == "pass"
    page = build_performance(rows, tmp_path, {"a": 1.05}).read_text()
    assert "<svg" in page and 'href="bench.jsonl"' in page and (tmp_path / "bench.jsonl").read_text().count("\n") == 3


def test_rows_carry_their_error_against_the_exact_solution():
    """Speed is never reported without accuracy. fem-eb's two-field form at 1001 nodes is at
    round-off (measured 1e-15 on the example cantilever); exact-eb is the exact solution itself."""
    row = bench_case("fem-eb", 1001)
    assert 0 <= row["max_error"] < 1e-12 and row["error_bound"] < 1e-6
    assert bench_case("exact-eb", 101)["max_error"] == 0.0


def test_no_error_against_the_elastic_solution_past_elasticity():
    """A scene with a yield stress (O'Grady & Foster's Fig. 6 beam) has no elastic exact solution: bench's error is
    unknown ("-"), not the distance from the elastic beam (it printed 0.12 for fem-eb, whose error against the
    plastic reference is 5e-8)."""
    from pdverify.apps.bench import max_error
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import get_model, run

    scene = load_scene(ROOT / "studies/paper_ogrady_plastic/fig6_loaded.toml")
    assert max_error(scene, get_model("fem-eb"), run(scene, "fem-eb", points=101)) is None


def test_no_error_against_the_static_solution_of_a_transient():
    """A transient's w is its state at the end time: bench's error is unknown, not its distance from the static
    deflection (it printed 1.0 for pd-timoshenko on Moyer's Example 2)."""
    from pdverify.apps.bench import max_error
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import get_model, run

    scene = load_scene(ROOT / "studies/paper_moyer/beam_transient.toml")
    result = run(scene, "pd-timoshenko", points=21)
    assert result.info["analysis"] == "dynamic" and np.any(result.w)
    assert max_error(scene, get_model("pd-timoshenko"), result) is None


def test_inaccurate_runs_count_toward_no_target(tmp_path):
    """A run whose error is above 1e-6 is left out of every target, the slope and the cheapest run; a
    model with no accurate run fails the accuracy target instead of passing on speed."""
    from pdverify.measure.cost import accurate
    from pdverify.report.perf import build_performance, cheapest, targets

    rows = [
        {
            "model": "a",
            "points": 1000,
            "total_s": 0.01,
            "limit_s": 0.008,
            "ratio": 1.25,
            "peak_mem_mb": 5.0,
            "status": "ok",
            "max_error": 1e-9,
        },
        {
            "model": "a",
            "points": 10_000,
            "total_s": 0.05,
            "limit_s": 0.04,
            "ratio": 1.25,
            "peak_mem_mb": 9.0,
            "status": "ok",
            "max_error": 2e-7,
        },
        {
            "model": "a",
            "points": 1_000_000,
            "total_s": 1.0,
            "limit_s": 0.1,
            "ratio": 10.0,
            "peak_mem_mb": 900.0,
            "status": "ok",
            "max_error": 0.5,
        },
        {
            "model": "c",
            "points": 1_000_000,
            "total_s": 0.5,
            "limit_s": 0.5,
            "ratio": 1.0,
            "peak_mem_mb": 90.0,
            "status": "ok",
            "max_error": 1.6,
        },
        {"model": "d", "points": 1000, "total_s": 0.5, "limit_s": 0.5, "ratio": 1.0, "status": "ok", "max_error": None},
    ]
    assert [accurate(r) for r in rows] == [True, True, False, False, False]
    assert set(cost_slope(rows)) == {"a"}  # two accurate sizes of a; none of c or d
    t = targets(pd.DataFrame(rows), cost_slope(rows))
    ratio_a = t[(t.model == "a") & t.target.str.startswith("total")].iloc[0]
    assert ratio_a.points == 10_000 and ratio_a.verdict == "pass"  # the 10^6 run (ratio 10, error 0.5) is out
    for m in ("c", "d"):
        assert list(t[t.model == m].verdict) == ["fail"] and "max error" in t[t.model == m].target.iloc[0]
    ch = cheapest(pd.DataFrame(rows)).set_index("model")
    assert ch.loc["a", "points"] == 1000 and ch.loc["a", "total_s"] == 0.01
    assert "no run within" in ch.loc["c", "statement"] and "1.6" in ch.loc["c", "statement"]
    page = build_performance(rows, tmp_path, cost_slope(rows)).read_text()
    assert page.count("<svg") == 2 and "work-precision" in page and "cheapest run within 1e-06" in page


@pytest.mark.parametrize("text, n", [("4.1e1", 41), ("1e3", 1000), ("101", 101), ("9007199254740993", 2**53 + 1)])
def test_points_read_as_solve_reads_them(text, n):
    """Sweep 13: `bench --points 4.1e1` was refused (an integer option) where `solve --points 4.1e1` solves 41
    points; both read a whole number in any notation now (pdverify.core.contract.whole_number)."""
    from pdverify.apps.bench_command import _points

    assert _points(text) == n
