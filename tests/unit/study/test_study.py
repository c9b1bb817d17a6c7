"""Study runner: order by hand on a synthetic model, failures recorded, resume after SIGKILL, Dask = local."""

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from helpers import ROOT, start_in_own_group

from pdverify import registry
from pdverify.core.contract import Model, Option
from pdverify.core.errors import InputError
from pdverify.core.result import Result
from pdverify.exact.straight import solve_straight
from pdverify.measure.metrics import gci, observed_order, pareto
from pdverify.study import load_study, run_study

SCENE = ROOT / "studies/paper_diyaroglu/clamped_clamped.toml"


class Synthetic(Model):
    """Exact EB deflection times (1 + C dx^2): its max error is exactly C dx^2."""

    name = "synthetic-dx2"
    options = (
        Option("points", int, 11, minimum=2),
        Option("fail", bool, False),
        Option("fail_after", float, 0.0, minimum=0.0),
    )

    def solve(self, scene, params):
        if params["fail"]:
            time.sleep(params["fail_after"])  # a failure that costs time, as a singular system found late does
            raise np.linalg.LinAlgError("synthetic failure")
        x = np.linspace(0, scene.length, params["points"])
        dx = x[1] - x[0]
        w = solve_straight(scene, False).fields(x)["w"] * (1 + 3.0 * dx**2)
        return Result(
            scene.name, self.name, dict(params), x, w, dofs=len(x), timings={"assemble_s": 0.0, "solve_s": 0.0}
        )


@pytest.fixture
def synthetic(monkeypatch):
    monkeypatch.setitem(registry.models(), "synthetic-dx2", Synthetic())


def write_study(tmp_path, body, name="s"):
    p = tmp_path / f"{name}.toml"
    p.write_text(f'name = "{name}"\nscenes = ["{SCENE}"]\nreference = "exact-eb"\n' + body)
    return p


def test_observed_order_equals_hand_computation(tmp_path, synthetic):
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9, 17, 33, 65]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    dx = 1.0 / (np.array([5, 9, 17, 33, 65]) - 1)
    assert np.allclose(df.sort_values("points")["err_max"], 3.0 * dx**2, rtol=1e-9)
    conv = pd.read_csv(tmp_path / "out" / "convergence.csv")
    hand = np.polyfit(np.log(dx), np.log(3.0 * dx**2), 1)[0]
    assert conv["observed_order"].iloc[0] == pytest.approx(hand, abs=1e-9)
    assert conv["observed_order"].iloc[0] == pytest.approx(2.0, abs=1e-6)
    assert conv["r2"].iloc[0] == pytest.approx(1.0, abs=1e-12)
    assert conv["gci_order"].iloc[0] == pytest.approx(2.0, abs=1e-6)


def test_no_order_from_two_grids(tmp_path, synthetic):
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9]\n')
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    conv = tmp_path / "out" / "convergence.csv"
    assert conv.read_text().strip() in ("", '""') or pd.read_csv(conv).empty


def test_failure_is_recorded_and_the_study_goes_on(tmp_path, synthetic):
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9]\nfail = [false, true]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert sorted(df["status"]) == ["failed", "failed", "ok", "ok"]
    assert df[df["status"] == "failed"]["message"].str.contains("synthetic failure").all()


def test_a_study_whose_every_case_fails_still_has_its_report(tmp_path, synthetic):
    """results.csv has the measured columns even when no case was measured (it had none of them, and the report
    refused the folder as "not a pdverify results table"): the report lists the failed cases."""
    from pdverify.report import build_report

    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9]\nfail = true\n')
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    res = pd.read_csv(tmp_path / "out" / "results.csv")
    assert set(res["status"]) == {"failed"} and "err_max" in res and res["err_max"].isna().all()
    index = build_report(tmp_path / "out")
    assert "synthetic failure" in Path(index).read_text()


@pytest.mark.parametrize("workers", [1, 2])
def test_a_failed_case_records_what_it_cost(tmp_path, synthetic, workers):
    """A failed case's row carries the seconds its attempt took, and meta.json counts them as the models'
    time (before, a study with failures counted the failed solves as the runner's own time); a failed
    case never enters the speed-vs-error table."""
    p = write_study(
        tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9]\nfail = [false, true]\nfail_after = 0.1\n'
    )
    df = run_study(load_study(p), tmp_path / "out", workers=workers, progress=False)
    failed = df[df["status"] == "failed"]
    assert len(failed) == 2 and (failed["total_s"] >= 0.1).all() and (failed["total_s"] < 5).all()
    assert failed["err_max"].isna().all()
    timing = json.loads((tmp_path / "out" / "meta.json").read_text())["timing"]
    assert timing["solver_s"] >= failed["total_s"].sum()  # the solves' time, failed attempts included
    se = pd.read_csv(tmp_path / "out" / "speed_error.csv")
    assert set(se["case_id"]) == set(df[df["status"] == "ok"]["case_id"])


def test_metrics_units():
    assert observed_order([0.1, 0.05, 0.025], [1e-2, 2.5e-3, 6.25e-4])[0] == pytest.approx(2.0)
    assert np.isnan(observed_order([0.1, 0.05], [1e-2, 2.5e-3])[0])
    g = gci([0.1, 0.05, 0.025], [1 + 0.01, 1 + 0.0025, 1 + 0.000625])
    assert g["gci_order"] == pytest.approx(2.0) and g["richardson"] == pytest.approx(1.0)
    assert list(pareto([1, 2, 3, 4], [5, 1, 2, 0.5])) == [True, True, False, True]


BAD_STUDIES = {
    "unknown model": ('[[runs]]\nmodel = "pd-nothing"\n', "runs[0]: model = 'pd-nothing': unknown model"),
    "option not taken": ('[[runs]]\nmodel = "exact-eb"\nhorizon = 3\n', "takes no option 'horizon'"),
    "empty sweep": ('[[runs]]\nmodel = "pd-eb"\npoints = []\n', "runs[0].points = []: an empty sweep"),
    "no runs": ("", "runs: missing or empty"),
    "horizon below spacing": ('[[runs]]\nmodel = "pd-eb"\nhorizon = 0.5\n', "horizon = 0.5"),
    "bad reference": ('reference2 = 1\n[[runs]]\nmodel = "pd-eb"\n', "unknown key 'reference2'"),
    "typo key": ('[[runs]]\nmodel = "pd-eb"\nvariant = "papr"\n', "variant = 'papr'"),
    "check flag not a boolean": (
        '[[runs]]\nmodel = "pd-eb"\ngrid_check = "no"\n',
        "grid_check = 'no': give true or false",
    ),
    "bad slenderness": ('[sweep]\nslenderness = [-3]\n[[runs]]\nmodel = "pd-eb"\n', "slenderness value -3"),
    # a model or name of the wrong type was called "missing"
    "model a number": ("[[runs]]\nmodel = 3\n", "runs[0]: model = 3: not a model name"),
}


@pytest.mark.parametrize("what", list(BAD_STUDIES))
@pytest.mark.slow
def test_bad_study_one_line_exit_2(tmp_path, what):
    body, msg = BAD_STUDIES[what]
    p = write_study(tmp_path, body)
    r = subprocess.run(
        [sys.executable, "-m", "pdverify.apps.cli", "study", str(p), "--out", str(tmp_path / "o")],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr and msg in r.stderr, r.stderr
    assert not (tmp_path / "o").exists()  # validated before running anything


def test_a_name_that_is_not_a_text_is_named_as_such(tmp_path):
    """Sweep 25 O6: name = {a = 1} was reported as "name: missing"."""
    p = tmp_path / "s.toml"
    p.write_text(f'name = {{a = 1}}\nscenes = ["{SCENE}"]\n[[runs]]\nmodel = "pd-eb"\n')
    with pytest.raises(InputError, match=r"name = \{'a': 1\}: not a text"):
        load_study(p)


def test_a_write_that_failed_names_the_fix_its_cause_calls_for():
    """Sweep 25 O6: --out /proc was told to "free disk space"; only a full disk is."""
    import errno

    from pdverify.study.outdir import output_error

    full = str(output_error(Path("o"), OSError(errno.ENOSPC, "No space left on device")))
    missing = str(output_error(Path("/proc"), OSError(errno.ENOENT, "No such file or directory")))
    assert "free disk space" in full and "free disk space" not in missing and "give a writable --out" in missing


def test_missing_scene_and_syntax_error(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('name = "s"\nscenes = ["nope.toml"]\n[[runs]]\nmodel = "pd-eb"\n')
    with pytest.raises(InputError, match="no such scene file"):
        load_study(p)
    p.write_text('name = "s"\nscenes = [\n')
    with pytest.raises(InputError, match="TOML syntax error"):
        load_study(p)


def _cols(df):
    return df.sort_values("case_id")[["case_id", "err_max", "err_l2", "w_at_max"]].reset_index(drop=True)


def _signal_mid_run(p, out, sig):
    """Start ``pdverify study`` serially in its own process group, send ``sig`` to the group once 5 case
    files are on disk (as a terminal sends Ctrl-C to the whole group) and wait; the process, its stderr
    and the CLI command (to run the study again). Case files are counted as ``[!.]*.case``: a case being written is
    ``.tmp-...-<id>.case`` until its rename, which ``*.case`` matches too (a run stopped then kept 4 of the 5 it
    had counted)."""
    cmd = [sys.executable, "-m", "pdverify.apps.cli", "study", str(p), "--out", str(out), "--workers", "1", "--quiet"]
    proc = start_in_own_group(cmd)
    deadline = time.time() + 60
    while time.time() < deadline and len(list((out / "cases").glob("[!.]*.case"))) < 5:
        time.sleep(0.02)
    os.killpg(proc.pid, sig)
    _, err = proc.communicate(timeout=60)
    return proc, err, cmd


@pytest.mark.slow
def test_resume_after_sigkill(tmp_path):
    p = write_study(
        tmp_path,
        '[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\n'
        "points = [101, 151, 201, 301, 401, 601, 801]\nhorizon = [2, 3, 4]\n",
    )
    out = tmp_path / "out"
    _, _, cmd = _signal_mid_run(p, out, signal.SIGKILL)
    partial = len(list((out / "cases").glob("[!.]*.case")))
    assert 5 <= partial < 42, partial
    # corrupt files are detected and recomputed: one truncated (killed mid-write elsewhere), one with a
    # single flipped bit inside its curve data (caught by the checksum, not by parsing)
    truncated, flipped = sorted((out / "cases").glob("[!.]*.case"))[:2]
    truncated.write_bytes(truncated.read_bytes()[:-100])
    raw = bytearray(flipped.read_bytes())
    raw[-9] ^= 0x01
    flipped.write_bytes(bytes(raw))
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    meta = json.loads((out / "meta.json").read_text())
    assert meta["resumed_cases"] == partial - 2
    fresh = run_study(load_study(p), tmp_path / "fresh", workers=1, progress=False)
    assert np.allclose(
        _cols(pd.read_csv(out / "results.csv"))[["err_max", "err_l2", "w_at_max"]],
        _cols(fresh)[["err_max", "err_l2", "w_at_max"]],
        rtol=1e-12,
    )
    # the derived tables of the resumed run cover the resumed cases too
    from pdverify.study.derived import write_derived

    again = tmp_path / "again"
    again.mkdir()
    write_derived(load_study(p), again, pd.read_parquet(out / "results.parquet"))
    for name in ("convergence.csv", "trust.csv", "speed_error.csv"):
        assert (out / name).read_bytes() == (again / name).read_bytes(), name
    assert len(pd.read_csv(out / "convergence.csv")) == 6  # 2 variants x 3 horizons, 7 grids each


@pytest.mark.slow
def test_ctrl_c_keeps_the_finished_cases_and_leaves_no_process(tmp_path):
    """Ctrl-C (SIGINT to the whole process group, as a terminal sends it) in a serial run: exit 130 without
    a traceback, every case that was finished is on disk, no half-written file, no tables for a partial
    study, no process left behind, and a second run resumes every finished case."""
    # grids up to 8001 points (~1.5 s in all): the run must still be solving when 5 case files are on disk
    # (60 cases of <= 2001 points once ran to the end before the signal, in a full suite on a busy machine)
    p = write_study(
        tmp_path,
        '[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\n'
        "points = [101, 151, 201, 301, 401, 601, 801, 1201, 1601, 2001, 3001, 4001, 6001, 8001]\n"
        "horizon = [2, 3, 4]\n",
    )
    out = tmp_path / "out"
    proc, err, cmd = _signal_mid_run(p, out, signal.SIGINT)
    finished = len(list((out / "cases").glob("*.case")))
    assert proc.returncode == 130 and b"Traceback" not in err, err
    assert 5 <= finished < 84 and not list((out / "cases").glob(".tmp-*")) and not (out / "results.csv").exists()
    left = []  # processes whose command line names this run's output
    for cmdline in Path("/proc").glob("[0-9]*/cmdline"):
        try:
            if str(out).encode() in cmdline.read_bytes():
                left.append(cmdline.parent.name)
        except OSError:  # the process ended meanwhile
            pass
    assert left == [], left
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "meta.json").read_text())["resumed_cases"] == finished


@pytest.mark.slow
def test_dask_local_cluster_matches_local_run(tmp_path):
    from dask.distributed import LocalCluster

    p = write_study(
        tmp_path,
        '[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\npoints = [51, 101]\n'
        '[[runs]]\nmodel = "fem-eb"\npoints = [11]\n',
    )
    local = run_study(load_study(p), tmp_path / "local", workers=2, progress=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        dist = run_study(load_study(p), tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False)
    a, b = _cols(local), _cols(dist)
    assert list(a["case_id"]) == list(b["case_id"])
    assert np.array_equal(
        a[["err_max", "err_l2", "w_at_max"]].to_numpy(), b[["err_max", "err_l2", "w_at_max"]].to_numpy()
    )
    timing = ["assemble_s", "solve_s", "total_s"]
    pd.testing.assert_frame_equal(local.drop(columns=timing), dist.drop(columns=timing))
    for name in ("convergence.csv", "locking.csv", "trust.csv"):  # the tables without timings: same bytes
        assert (tmp_path / "local" / name).read_bytes() == (tmp_path / "dask" / name).read_bytes(), name
    assert json.loads((tmp_path / "dask" / "meta.json").read_text())["timing"]["path"] == "dask"


def test_case_record_round_trips_exactly_and_rejects_damage(tmp_path):
    """Case files: arrays come back bit for bit (NaN, -0.0, subnormal, huge), nested curves (fields, time
    histories, load steps) keep their structure, and any damage reads as None (the case is recomputed)."""
    from pdverify.study.store import decode_record, encode_record, read_case, write_atomic

    a = np.array([0.1, -1e-300, 1e300, np.pi, -0.0, np.nan, 5e-324])
    rec = {
        "case": {"model": "m", "given": {"points": 7}},
        "row": {"status": "ok", "err_max": 0.5, "n": 3},
        "curve": {
            "x": a,
            "w": a[::-1].copy(),
            "fields": {"M": 2 * a},
            "history": {"t": a, "series": {"p": a}},
            "load_steps": [{"factor": 0.5, "x": [0.0, 1.0]}],
            "grid": np.arange(6.0).reshape(2, 3),
        },
    }
    back = decode_record(encode_record(rec))
    assert back["row"] == rec["row"] and back["case"] == rec["case"]
    for got, want in (
        (back["curve"]["x"], a),
        (back["curve"]["w"], a[::-1]),
        (back["curve"]["fields"]["M"], 2 * a),
        (back["curve"]["history"]["series"]["p"], a),
        (back["curve"]["grid"], np.arange(6.0).reshape(2, 3)),
    ):
        assert got.tobytes() == np.ascontiguousarray(want).tobytes() and got.shape == want.shape
    assert back["curve"]["load_steps"] == rec["curve"]["load_steps"]
    raw = encode_record(rec)
    for k in range(len(raw)):  # every single-bit flip, anywhere in the file, is caught
        bad = bytearray(raw)
        bad[k] ^= 0x10
        assert decode_record(bytes(bad)) is None, k
    assert decode_record(raw[:-1]) is None and decode_record(raw + b"x") is None and decode_record(b"") is None
    p = tmp_path / "c.case"
    write_atomic(p, encode_record(rec))
    assert read_case(p)["row"] == rec["row"] and read_case(tmp_path / "missing.case") is None
    fifo = tmp_path / "fifo.case"  # a FIFO under a case's name: reading it blocked the resume and the report
    os.mkfifo(fifo)
    assert read_case(fifo) is None


def test_a_write_stopped_by_ctrl_c_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    """Ctrl-C while a case file is written (the main process stores records as they come): the old file is
    intact and no ``.tmp-*`` file is left in the directory (a CI run once found one after Ctrl-C)."""
    from pdverify.study import store

    p = tmp_path / "c.case"
    store.write_atomic(p, b"old")

    def interrupted(fd, parts):
        os.write(fd, b"ne")
        raise KeyboardInterrupt

    monkeypatch.setattr(store, "write_all", interrupted)
    with pytest.raises(KeyboardInterrupt):
        store.write_atomic(p, b"new")
    assert p.read_bytes() == b"old" and sorted(f.name for f in tmp_path.iterdir()) == ["c.case"]


def test_first_format_case_files_still_read(tmp_path):
    """Studies run before the binary records (``<id>.json``, arrays as base64) still build reports."""
    import base64

    from pdverify.study.store import case_file, read_curve

    a = np.array([0.0, 0.5, 1.0])
    b64 = {"dtype": "<f8", "shape": [3], "b64": base64.b64encode(a.tobytes()).decode()}
    (tmp_path / "abc.json").write_text(
        json.dumps(
            {"case": {}, "row": {"status": "ok"}, "curve": {"x": b64, "w": [1.0, 2.5, 3.0], "fields": {"u": b64}}}
        )
    )
    c = read_curve(case_file(tmp_path, "abc"))
    assert np.array_equal(c["x"], a) and np.array_equal(c["w"], [1.0, 2.5, 3.0]) and np.array_equal(c["fields"]["u"], a)
    assert case_file(tmp_path, "nope") is None


def test_case_key_changes_with_the_code(monkeypatch):
    """Editing a model must recompute its cases, not resume stale ones: the key holds a code digest."""
    from pdverify.study import spec

    case = spec.Case("s.toml", "x = 1", None, "pd-eb", {"points": 11}, {"model": "exact-eb"})
    before = case.case_id
    assert len(spec.code_digest()) == 16
    monkeypatch.setattr(spec, "code_digest", lambda: "0" * 16)
    assert case.case_id != before


def test_trust_table_states_ranges_and_the_round_off_grid():
    from pdverify.study.runner import trust_table

    ref = json.dumps({"model": "exact-eb"})
    rows = []
    moderate = [1e-2 * 4, 1e-3, 2e-4, 5e-3]
    for s, errs in ((10, moderate), (20, moderate), (1000, [0.5, 0.2, 0.1, 0.3])):
        for n, e in zip([11, 21, 41, 81], errs):
            rows.append(
                dict(
                    model="m",
                    options="{}",
                    scene="a",
                    slenderness=s,
                    points=n,
                    err_max=e,
                    status="ok",
                    reference=ref,
                    cond=1e12 if n == 81 else 1e8,
                )
            )  # cond·eps 2.2e-4 at 81 points
    table = trust_table(pd.DataFrame(rows), tol=0.01)
    t, slender = table.iloc[0], table.iloc[1]  # thick and slender scenes are judged apart, by band
    assert t["slenderness_band"].startswith("moderate") and slender["slenderness_band"].startswith("slender")
    assert t["slenderness_trusted"] == "10 – 20" and t["slenderness_not"] == ""
    assert slender["slenderness_trusted"] == "" and slender["slenderness_not"] == "1000"
    assert t["points_trusted"] == "21 – 81" and t["points_not"] == "11"
    # 2e-4 -> 5e-3 at L/h 10: within 100 cond·eps (2.2e-4), so round-off; 0.1 -> 0.3 at 1000 is far above it
    assert t["round_off_from_points"] == 81 and pd.isna(t["growth_from_points"])
    assert slender["growth_from_points"] == 81 and pd.isna(slender["round_off_from_points"])
    assert "L/h 10 – 20" in t["statement"] and "from 81 points" in t["statement"] and "round-off" in t["statement"]
    assert "not round-off" in slender["statement"]
    small = pd.DataFrame([dict(r, err_max=r["err_max"] * 1e-6) for r in rows])  # growth below 1e-6 is not trouble
    assert pd.isna(trust_table(small).iloc[0]["round_off_from_points"])


def test_trust_calls_a_growth_round_off_only_where_cond_eps_explains_it():
    """The pd-eb paper variant's case: its error grows to 6e-3 under refinement while cond·eps is
    4e-7: a discretisation defect, not round-off. Without a condition estimate the cause is not claimed."""
    from pdverify.study.runner import trust_table

    ref = json.dumps({"model": "exact-eb"})
    eps = np.finfo(float).eps
    rows = [
        dict(
            model="pd-eb",
            options='{"variant": "paper"}',
            scene="a",
            slenderness=20,
            points=n,
            err_max=e,
            status="ok",
            reference=ref,
            cond=c / eps,
        )
        for n, e, c in ((21, 1e-3, 1e-10), (41, 1.5e-3, 1e-8), (81, 6e-3, 4e-7))
    ]
    t = trust_table(pd.DataFrame(rows)).iloc[0]
    assert pd.isna(t["round_off_from_points"]) and t["growth_from_points"] == 81
    assert "error 0.006, far above cond·eps = 4e-07: not round-off" in t["statement"]
    t = trust_table(pd.DataFrame([dict(r, cond=None) for r in rows])).iloc[0]
    assert t["growth_from_points"] == 81 and "no condition estimate" in t["statement"]
    explained = [dict(r, cond=0.1 * r["err_max"] / eps) for r in rows]  # error = 10 cond·eps: explained
    t = trust_table(pd.DataFrame(explained)).iloc[0]
    assert t["round_off_from_points"] == 81 and pd.isna(t["growth_from_points"])


def test_benchmark_at_a_position_of_a_field(tmp_path, synthetic):
    """A benchmark row may name a position and a quantity: the case's curve is interpolated there."""
    p = write_study(
        tmp_path,
        f"""[[runs]]
model = "synthetic-dx2"
points = 11
[[benchmarks]]
name = "quarter point"
scene = "{SCENE}"
model = "synthetic-dx2"
points = 11
position = 0.5
""",
    )
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    b = pd.read_csv(tmp_path / "out" / "benchmarks.csv").iloc[0]
    sc = load_study(p).cases[0].scene()
    x = np.linspace(0, sc.length, 11)
    want = np.interp(0.5, x, solve_straight(sc, False).fields(x)["w"] * (1 + 3.0 * (x[1] - x[0]) ** 2))
    assert b["computed"] == pytest.approx(want, rel=1e-12) and b["position"] == 0.5
    assert b["target"] == pytest.approx(np.interp(0.5, x, solve_straight(sc, False).fields(x)["w"]), rel=1e-12)
    bad = write_study(
        tmp_path,
        f'[[runs]]\nmodel = "synthetic-dx2"\n[[benchmarks]]\nname = "b"\nscene = "{SCENE}"\n'
        'model = "synthetic-dx2"\nquantity = "u"\nposition = 99.0\n',
        name="bad",
    )
    with pytest.raises(InputError) as e:
        load_study(bad)
    assert any("position = 99.0" in l for l in e.value.lines) and any(
        "position" in l or "target" in l for l in e.value.lines
    )


def test_a_benchmark_of_an_output_the_case_lacks_names_those_it_has(tmp_path, synthetic):
    """An unknown quantity is known only once the case has run: its row is "missing" and names the case's outputs."""
    p = write_study(
        tmp_path,
        f'[[runs]]\nmodel = "synthetic-dx2"\npoints = 11\n[[benchmarks]]\nname = "b"\nscene = "{SCENE}"\n'
        'model = "synthetic-dx2"\npoints = 11\nquantity = "zz"\nposition = 0.5\ntarget = 1.0\n',
    )
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    b = pd.read_csv(tmp_path / "out" / "benchmarks.csv").iloc[0]
    assert b["verdict"] == "missing" and b["message"].startswith("quantity 'zz' not among the case's outputs (w")


def test_expected_fail_verdicts():
    from pdverify.study.checks import verdict

    assert [verdict(True, "pass"), verdict(False, "pass"), verdict(False, "fail"), verdict(True, "fail")] == [
        "pass",
        "fail",
        "expected-fail",
        "unexpected-pass",
    ]


def test_records_from_other_code_are_kept_and_reported(tmp_path, synthetic, monkeypatch):
    """A worker running other code computes other case ids; the runner stores each record under the id
    it computed itself and lists the mismatch in meta.json (a study never loses a finished case)."""
    from pdverify.study import runner

    real = runner.measure_case

    def other_code(case, solved, case_id=None):
        rec = real(case, solved, case_id)
        rec["row"]["case_id"], rec["row"]["code"] = "0" * 16, "f" * 16
        return rec

    monkeypatch.setattr(runner, "measure_case", other_code)
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [11, 21, 31]\n')
    for workers in (1, 2):  # measured in this process, and in pool workers
        out = tmp_path / f"out{workers}"
        df = run_study(load_study(p), out, workers=workers, progress=False)
        meta = json.loads((out / "meta.json").read_text())
        assert (
            len(df) == 3
            and set(df["case_id"]) == set(meta["cases_from_other_code"])
            and "0" * 16 not in set(df["case_id"])
        )


def test_csv_tables_hold_the_exact_values(tmp_path):
    """The CSV tables (written by Arrow) read back to the same numbers, bit for bit, as the Parquet ones."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\npoints = [51, 101, 201]\n')
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    for name in ("results", "convergence", "speed_error"):
        csv, parquet = (
            pd.read_csv(tmp_path / "out" / f"{name}.csv"),
            pd.read_parquet(tmp_path / "out" / f"{name}.parquet"),
        )
        assert list(csv.columns) == list(parquet.columns) and len(csv) == len(parquet) > 0
        for col in parquet.select_dtypes("number").columns:
            assert np.array_equal(csv[col].to_numpy(float), parquet[col].to_numpy(float), equal_nan=True), (name, col)


def test_serial_and_pool_runs_write_the_same_tables(tmp_path):
    """A serial run and a run with two pool workers give the same results but for the timings, meta.json
    records the same environment and counts, and each run's derived tables are, byte for byte, those
    written again from the results table beside them."""
    from pdverify.study.derived import write_derived

    p = write_study(
        tmp_path,
        '[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\npoints = [51, 101, 201]\n'
        'horizon = [2, 3]\n[[runs]]\nmodel = "fem-eb"\npoints = [5, 9, 17]\n'
        '[[benchmarks]]\nname = "centre"\nscene = "' + str(SCENE) + '"\nmodel = "fem-eb"\npoints = 17\n',
    )
    frames, metas = {}, {}
    for workers in (1, 2):
        frames[workers] = run_study(load_study(p), tmp_path / f"out-{workers}", workers=workers, progress=False)
        metas[workers] = json.loads((tmp_path / f"out-{workers}" / "meta.json").read_text())
        assert metas[workers]["timing"]["path"] == ("serial" if workers == 1 else "pool")
    for key in ("python", "platform", "machine", "versions", "counts", "code", "skipped"):
        assert metas[1][key] == metas[2][key], key
    assert metas[1]["versions"]["numpy"] == np.__version__ and metas[1]["counts"] == {"ok": len(frames[1])}
    timing = ["assemble_s", "solve_s", "total_s"]
    pd.testing.assert_frame_equal(frames[1].drop(columns=timing), frames[2].drop(columns=timing))
    for name in ("convergence.csv", "locking.csv", "trust.csv", "benchmarks.csv"):  # no timings in them
        assert (tmp_path / "out-1" / name).read_bytes() == (tmp_path / "out-2" / name).read_bytes(), name
    for workers in (1, 2):
        out, again = tmp_path / f"out-{workers}", tmp_path / f"again-{workers}"
        again.mkdir()
        write_derived(load_study(p), again, pd.read_parquet(out / "results.parquet"))
        names = sorted(f.name for f in again.iterdir() if f.suffix == ".csv")
        assert {"convergence.csv", "locking.csv", "speed_error.csv", "trust.csv", "benchmarks.csv"} <= set(names)
        for name in names:
            assert (out / name).read_bytes() == (again / name).read_bytes(), name


def test_meta_json_reports_the_runner_overhead(tmp_path):
    """meta.json's timing: the solves' time (each case's seconds in its solve, this run), the runner's own time
    (the wall time of cases and tables less the solves' time) and its fraction of the wall time. In one process the
    solves are parts of the cases' wall time, so the fraction lies in (0, 1) whatever the machine: a solve kept from
    another case (pd-eb's grid check on nested grids) counts once, though its rows' total_s both report its making."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101, 201]\nhorizon = [2, 3]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    t = json.loads((tmp_path / "out" / "meta.json").read_text())["timing"]
    assert 0 < t["solver_s"] < t["cases_s"] and len(df) == 6
    wall = t["cases_s"] + t["tables_s"]
    assert t["runner_overhead_s"] == pytest.approx(wall - t["solver_s"], rel=1e-9)
    assert t["runner_overhead_fraction"] == pytest.approx(t["runner_overhead_s"] / wall, rel=1e-9)
    assert 0 < t["runner_overhead_fraction"] < 1 and t["workers"] == 1 and t["computed_cases"] == 6


def test_solver_s_is_the_time_spent_not_the_rows_claims(tmp_path, synthetic, monkeypatch):
    """A row's total_s is what making its solve cost, also when the solve was kept from another case and taken
    again in no time; meta.json's solver_s adds the seconds spent (here: rows claiming 100 s each, taken in
    milliseconds)."""
    from pdverify.study import solves  # noqa: PLC0415 - patched where the runner calls it

    made = solves.solve

    def kept(*args, **kwargs):
        result = made(*args, **kwargs)
        result.timings["total_s"] = 100.0  # as a kept solve whose making took 100 s reports
        return result

    monkeypatch.setattr(solves, "solve", kept)
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9, 17]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    t = json.loads((tmp_path / "out" / "meta.json").read_text())["timing"]
    assert (df["total_s"] == 100.0).all()
    assert 0 < t["solver_s"] < t["cases_s"] < 100.0
    assert 0 < t["runner_overhead_fraction"] < 1


def _run_case_or_die(case, artefacts=None, case_id=None):
    """runner.run_case, but a pool worker given the 201-point grid is killed (as by the out-of-memory killer)."""
    from pdverify.study import runner

    if case.given.get("points") == 201:
        os.kill(os.getpid(), signal.SIGKILL)
    return runner.measure_case(case, runner.solve_case(case, artefacts, case_id), case_id)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the pool forks its workers on Linux only")
def test_pool_worker_killed_is_one_output_error_and_the_run_resumes(tmp_path, monkeypatch):
    """A pool worker killed mid-run: one OutputError (no BrokenProcessPool traceback) saying how to resume;
    the cases finished before are kept, and the next run computes only the others."""
    from pdverify.core.errors import OutputError
    from pdverify.study import runner

    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101, 201]\nhorizon = [2, 3]\n')
    with monkeypatch.context() as m:
        m.setattr(runner, "run_case", _run_case_or_die)
        with pytest.raises(OutputError) as exc:
            run_study(load_study(p), tmp_path / "out", workers=2, progress=False)
    msg = str(exc.value)
    assert "worker process ended abruptly" in msg and "run the study again to resume" in msg
    kept = len(list((tmp_path / "out" / "cases").iterdir()))
    assert kept < 6
    df = run_study(load_study(p), tmp_path / "out", workers=2, progress=False)
    assert len(df) == 6 and (df["status"] == "ok").all()
    assert json.loads((tmp_path / "out" / "meta.json").read_text())["resumed_cases"] == kept


@pytest.mark.slow
def test_unwritable_output_is_one_line_exit_4(tmp_path):
    """An output directory that cannot be made (here a file stands where it should go; permissions or a
    full disk end the same way) stops the study with one line naming the directory and the fix."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [11, 21]\n')
    blocker = tmp_path / "taken"
    blocker.write_text("a file, not a directory")
    r = subprocess.run(
        [sys.executable, "-m", "pdverify.apps.cli", "study", str(p), "--out", str(blocker / "out"), "--quiet"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 4 and "Traceback" not in r.stderr, r.stderr
    line = r.stderr.strip()
    assert "\n" not in line and f"--out {blocker / 'out'}" in line and "choose another path" in line, line


@pytest.mark.parametrize("workers", [1, 2])
def test_full_disk_during_a_run_is_an_output_error(tmp_path, synthetic, monkeypatch, workers):
    """A case file that cannot be written in the middle of a run (a full disk, simulated) stops the study
    with OutputError naming the directory and the fix, in a serial run and with pool workers (the main
    process writes every case file); the cases written before it stay."""
    from pdverify.core.errors import OutputError
    from pdverify.study import outdir

    real = outdir.write_atomic

    def full_disk(path, data):  # the disk fills up after two case files
        if len(list(Path(path).parent.glob("*.case"))) >= 2:
            raise OSError(28, "No space left on device")
        real(path, data)

    monkeypatch.setattr(outdir, "write_atomic", full_disk)
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [11, 21, 31, 41, 51]\n')
    with pytest.raises(OutputError, match="No space left on device.*free disk space or give another --out"):
        run_study(load_study(p), tmp_path / "out", workers=workers, progress=False)
    assert len(list((tmp_path / "out" / "cases").glob("*.case"))) == 2


@pytest.mark.parametrize("workers", [1, 2])
def test_unwritable_table_is_an_output_error_and_the_cases_stay(tmp_path, synthetic, workers):
    """A table that cannot be written (here a directory stands where results.csv goes) stops the study with
    OutputError naming the directory, after every case file is written (a rerun only redoes the tables)."""
    from pdverify.core.errors import OutputError

    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [11, 21, 31]\n')
    (tmp_path / "out" / "results.csv").mkdir(parents=True)
    with pytest.raises(OutputError, match="output directory .*: a table could not be written"):
        run_study(load_study(p), tmp_path / "out", workers=workers, progress=False)
    assert len(list((tmp_path / "out" / "cases").glob("*.case"))) == 3


def test_ctrl_c_keeps_every_case_solved_before_it(tmp_path, monkeypatch):
    """Ctrl-C during the sixth solve of a serial run: the five solved before it are stored (each is
    written as it finishes), and the next run resumes them and completes with the numbers of an
    uninterrupted run."""
    from pdverify.study import runner

    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101, 201, 401]\nhorizon = [2, 3]\n')
    solve, calls = runner.solve_case, []

    def interrupted(case, *args):
        calls.append(case)
        if len(calls) == 6:
            raise KeyboardInterrupt
        return solve(case, *args)

    with monkeypatch.context() as m:
        m.setattr(runner, "solve_case", interrupted)
        with pytest.raises(KeyboardInterrupt):
            run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert len(list((tmp_path / "out" / "cases").glob("*.case"))) == 5
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert json.loads((tmp_path / "out" / "meta.json").read_text())["resumed_cases"] == 5
    fresh = run_study(load_study(p), tmp_path / "fresh", workers=1, progress=False)
    assert len(df) == 8 and (df["status"] == "ok").all()
    assert np.array_equal(_cols(df)[["err_max", "err_l2"]].to_numpy(), _cols(fresh)[["err_max", "err_l2"]].to_numpy())


def test_a_run_sweeps_its_own_slenderness(tmp_path):
    """runs[i].slenderness replaces [sweep]'s list for that run only (the main job sweeps the locking of one
    model without multiplying the others); a bad value is one error line naming the run."""
    body = (
        "[sweep]\nslenderness = [20]\n"
        '[[runs]]\nmodel = "pd-eb"\npoints = [21, 41]\nslenderness = [10, 100, 1000]\n'
        '[[runs]]\nmodel = "fem-eb"\npoints = 21\n'
    )
    st = load_study(write_study(tmp_path, body))
    got = sorted((c.model, c.slenderness) for c in st.cases)
    assert got == sorted([("pd-eb", s) for s in (10, 100, 1000) for _ in (21, 41)] + [("fem-eb", 20)])
    for bad in ("[]", "[10, -1]", '["10"]'):
        p = write_study(tmp_path, f'[[runs]]\nmodel = "pd-eb"\nslenderness = {bad}\n')
        with pytest.raises(InputError) as exc:
            load_study(p)
        assert len(exc.value.lines) == 1 and "runs[0].slenderness" in exc.value.lines[0], exc.value.lines


@pytest.mark.slow
def test_a_models_warnings_reach_its_row_and_the_report(tmp_path):
    """A locking q4 run warns (reference_fem.plane_stress): the warning is in results.csv and in the report's
    results table, beside the number it qualifies; a run without warnings has an empty cell."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "fem-plane-stress"\nelement = ["q4", "q8"]\npoints = 21\nlayers = 2\n')
    run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    res = pd.read_csv(tmp_path / "out/results.csv").set_index("element")
    assert "locks in bending" in res.loc["q4", "warnings"]
    assert pd.isna(res.loc["q8", "warnings"]) or "locks" not in res.loc["q8", "warnings"]
    from pdverify.report.build import build_report

    html_text = build_report(tmp_path / "out").read_text()
    assert "element = q4: full integration locks in bending" in html_text


def test_scenes_that_share_a_name_are_refused(tmp_path):
    """The tables group a convergence series by the scene's name: two scene files of different content under one name
    merged into one series (17 support pairs of a transient gave a single 'observed order', and a duplicated grid
    crashed the GCI with a ZeroDivisionError). One line names both files and the fix; the same file twice is fine."""
    text = SCENE.read_text()
    other = tmp_path / "other.toml"
    other.write_text(text.replace('left = "clamped"', 'left = "pinned"'))
    p = tmp_path / "s.toml"
    p.write_text(f'name = "s"\nscenes = ["{SCENE}", "{other}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "exact-eb"\n')
    with pytest.raises(InputError, match=r"are both named .*give each scene its own name") as exc:
        load_study(p)
    assert len(exc.value.lines) == 1 and str(other) in exc.value.lines[0]
    same = tmp_path / "same.toml"
    same.write_text(text)
    p.write_text(f'name = "s"\nscenes = ["{SCENE}", "{same}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "exact-eb"\n')
    load_study(p)


def test_gci_of_a_repeated_grid_is_nan():
    """Three finest spacings with one repeated (the same case listed twice) have no refinement ratio: NaN, not a
    ZeroDivisionError."""
    assert all(np.isnan(v) for v in gci([0.1, 0.1, 0.2, 0.4], [1.0, 1.1, 1.2, 1.3]).values())
    assert gci([0.1, 0.2, 0.4], [1.0, 1.01, 1.04])["gci_order"] == pytest.approx(np.log2(3))


def test_a_case_file_copied_over_another_is_computed_again(tmp_path):
    """Resuming reads a stored case only if its record is that case's: a file copied over another case's name (a
    careless copy between folders) is computed again, so no case vanishes from results.csv."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [11, 21]\n')
    first = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    by_points = first.set_index("points")["case_id"]
    cases = tmp_path / "out" / "cases"
    src, dst = (next(cases.glob(f"{by_points[n]}.*")) for n in (11, 21))
    dst.write_bytes(src.read_bytes())
    again = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert sorted(again["points"]) == [11, 21]
    assert again.set_index("points")["err_max"].to_dict() == first.set_index("points")["err_max"].to_dict()


def test_a_run_on_a_scene_its_model_cannot_solve_is_said(tmp_path, capsys):
    """A run listing a scene its model refuses (pd-eb on a scene with a yield stress) expands to no case for it: the
    study's output says how many and why, beside meta.json's ``skipped`` (it said nothing)."""
    from helpers import cli

    elastic, plastic = tmp_path / "elastic.toml", tmp_path / "plastic.toml"
    text = (ROOT / "studies/examples/cantilever_tip_load.toml").read_text()
    elastic.write_text(text)
    plastic.write_text(
        re.sub(r'^name = ".*"', 'name = "plastic"', text, flags=re.M).replace(
            "[material]\n", "[material]\nyield_stress = 250e6\n"
        )
    )
    study = tmp_path / "s.toml"
    study.write_text(
        f'name = "skips"\nscenes = ["{elastic.as_posix()}", "{plastic.as_posix()}"]\nreference = "exact-eb"\n'
        '[[runs]]\nmodel = "pd-eb"\npoints = [21, 41]\n'
    )
    code, _, err = cli(["study", study, "--out", tmp_path / "out", "--workers", "1", "--quiet"], capsys)
    assert code == 0, err
    assert "skipped: 2 cases of pd-eb on " in err and "plastic.toml: material.yield_stress" in err
    assert len(json.loads((tmp_path / "out" / "meta.json").read_text())["skipped"]) == 2


INNER_PIN = '\n[[supports.inner]]\nposition = 0.5\ntype = "pinned"'
SEGMENTS = (
    "\n[[segments]]\nstart = 0.0\nend = 0.5\n[[segments]]\nstart = 0.5\nend = 1.0\n"
    "[segments.section]\nwidth = 0.01\nheight = 0.008"
)


@pytest.mark.parametrize(
    "model, options, why, extra",
    [
        (
            "pd-bond-pair",
            'ends = ["taylor", "mirror"]',
            "supports inside the span: ends = taylor solves one",
            INNER_PIN,
        ),
        ("pd-eb", 'variant = ["paper", "corrected"]', "variant = paper (the paper's equations hold a beam", INNER_PIN),
        ("pd-higher-order", 'variant = ["paper", "corrected"]', "Appendix B's fictitious layers hold", INNER_PIN),
        (
            "pd-timoshenko",
            'variant = ["corrected", "energy"]',
            "variant corrected of pd-timoshenko takes one",
            SEGMENTS,
        ),
        (  # sweep 32 B1: a section weight on segments was a failed case
            "pd-bond-pair",
            'weight = ["fibre", "uniform"]',
            "a section weight takes one section along the beam",
            SEGMENTS,
        ),
    ],
)
def test_a_run_whose_options_a_scene_refuses_skips_those_cases(tmp_path, capsys, model, options, why, extra):
    """Options a scene cannot be solved with (pd-bond-pair's Taylor ends, the paper variants of pd-eb and
    pd-higher-order, and a support inside the span; pd-timoshenko's corrected variant and pd-bond-pair's section
    weights, and segments) are skipped with
    the reason, as a scene its model refuses is: they were failed cases, and the study exited 1."""
    from helpers import cli

    two_spans = tmp_path / "two_spans.toml"
    two_spans.write_text(
        (ROOT / "studies/examples/cantilever_tip_load.toml")
        .read_text()
        .replace('right = "free"', 'right = "free"' + extra)
    )
    study = tmp_path / "s.toml"
    study.write_text(
        f'name = "skips"\nscenes = ["{two_spans.as_posix()}"]\nreference = "exact-eb"\n'
        f'[[runs]]\nmodel = "{model}"\npoints = [21, 41]\n{options}\n'
    )
    code, _, err = cli(["study", study, "--out", tmp_path / "out", "--workers", "1", "--quiet"], capsys)
    assert code == 0, err
    assert f"skipped: 2 cases of {model} on " in err and why in err
    df = pd.read_csv(tmp_path / "out" / "results.csv")
    assert len(df) == 2 and (df["status"] == "ok").all()


def test_a_report_whose_every_order_check_is_missing_is_written(tmp_path, capsys):
    """Every order check missing (its variant's cases all skipped) left checks.csv without a scene column, and the
    report failed on it (exit 70, no index.html, the study's verdict lost): now written, exit 1 for the check."""
    from helpers import cli

    two_spans = tmp_path / "two_spans.toml"
    two_spans.write_text(
        (ROOT / "studies/examples/cantilever_tip_load.toml")
        .read_text()
        .replace('right = "free"', 'right = "free"\n[[supports.inner]]\nposition = 0.5\ntype = "pinned"')
    )
    study = tmp_path / "s.toml"
    study.write_text(
        f'name = "missing"\nscenes = ["{two_spans.as_posix()}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "pd-eb"\n'
        'points = [21, 41, 81]\nvariant = ["paper", "corrected"]\n'
        '[[checks]]\nmodel = "pd-eb"\nvariant = "paper"\nobserved_order = { min = 1.5 }\n'
    )
    code, _, err = cli(["study", study, "--out", tmp_path / "out", "--workers", "1", "--quiet", "--report"], capsys)
    assert code == 1 and "internal error" not in err, err
    assert (tmp_path / "out" / "index.html").is_file()
    assert "the study skipped 3 combinations its models refuse" in err  # the check may name one of them


@pytest.mark.parametrize(
    "options, refused",
    [
        ("horizon = 3\npoints = [5, 6, 11]", ["does not fit in 5 points", "does not fit in 6 points"]),
        ('variant = "energy"\nhorizon_length = 0.1\npoints = [41, 161]', ["horizon = 16 spacings of 0.00625"]),
    ],
)
def test_a_grid_the_model_refuses_is_refused_with_the_study(tmp_path, options, refused):
    """A run whose grids the model refuses (Model.grid_problems: pd-eb's family of 3 points each side in 5 or 6
    points; pd-timoshenko energy at m = 16) is refused when the study is loaded, one line per grid naming the run,
    exit 2 like ``pdverify solve`` on the same input; before, those grids ran as failed cases (exit 1). Nothing
    is run: the output folder is not made."""
    model = "pd-timoshenko" if "energy" in options else "pd-eb"
    p = write_study(tmp_path, f'[[runs]]\nmodel = "{model}"\n{options}\n')
    with pytest.raises(InputError) as e:
        load_study(p)
    assert len(e.value.lines) == len(refused)
    for line, want in zip(e.value.lines, refused):
        assert line.startswith(f"{p}: runs[0]: ") and want in line, line
    import pdverify

    out = tmp_path / "out"
    with pytest.raises(InputError):
        pdverify.run_study(p, out=out)
    assert not out.exists()


def test_the_api_refuses_an_output_file_before_any_case(tmp_path):
    """pdverify.run_study(..., out=<a file>): OutputError naming it before a case is solved (it solved one, then
    blamed the disk), and the file as it was."""
    import pdverify
    from pdverify.core.errors import OutputError

    target = tmp_path / "notes.txt"
    target.write_text("keep me\n")
    with pytest.raises(OutputError, match="is a file, not a folder"):
        pdverify.run_study(ROOT / "studies/convergence.toml", out=target)
    assert target.read_text() == "keep me\n"


def test_a_run_can_leave_out_the_solves_own_estimate(tmp_path):
    """``grid_check = false`` in a run: its rows carry no grid_estimate (the second solve on half the points is not
    made); the same run without it carries one on every row (pd-eb checks its own grid)."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [41, 81]\ngrid_check = [true, false]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    checked = df["options"].str.contains('"grid_check": true')
    assert checked.sum() == 2 and df.loc[checked, "grid_estimate"].notna().all()
    assert (~checked).sum() == 2 and df.loc[~checked, "grid_estimate"].isna().all()
