"""The zygote (pdverify/zygote.py): a serial run's recorder forked from it gives the same results as one
forked from the runner, without the runner ever forking; code it does not run (a model registered at run
time, work that cannot be pickled) is recorded by a fork of the runner as before; it exits with the
process that started it."""

import json
import operator
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdverify import zygote
from pdverify.study import load_study, recorder, run_study

from test_study import SCENE, Synthetic, synthetic, write_study  # noqa: F401  (synthetic: a fixture)

pytestmark = pytest.mark.skipif(not (zygote.available and recorder.Recorder.available),
                                reason="the zygote and the recorder need Linux and two CPUs")

STUDY = ('[[runs]]\nmodel = "pd-eb"\nvariant = ["paper", "corrected"]\npoints = [51, 101, 201]\nhorizon = [2, 3]\n'
         '[[runs]]\nmodel = "fem-eb"\npoints = [5, 9, 17]\n')


@pytest.fixture
def running():
    """A zygote started and ready for the test, stopped after it (other tests fork, as the CLI does)."""
    assert zygote.start()
    assert zygote.ready(wait=120), "the zygote did not come up"
    proc = zygote._zygote.proc
    yield proc
    zygote.stop()
    assert proc.returncode is not None  # it exited when its socket closed


def _timing(out):
    return json.loads((out / "meta.json").read_text())["timing"]


def test_recorder_from_the_zygote_records_what_a_fork_records(tmp_path, running, monkeypatch):
    """Same rows (but the timings) and byte-identical error tables whether the recorder is a fork of the
    zygote or of the runner; with the zygote the runner does not fork at all (os.fork fails here)."""
    p = write_study(tmp_path, STUDY)
    with monkeypatch.context() as m:
        m.setattr(recorder.os, "fork", lambda: pytest.fail("the runner forked"))
        zyg = run_study(load_study(p), tmp_path / "zygote", workers=1, progress=False)
    assert _timing(tmp_path / "zygote")["recorder_start"] == "zygote"
    monkeypatch.setattr(zygote, "ready", lambda wait=0.0: False)
    forked = run_study(load_study(p), tmp_path / "fork", workers=1, progress=False)
    assert _timing(tmp_path / "fork")["recorder_start"] == "fork"
    timing = ["assemble_s", "solve_s", "total_s"]
    assert (zyg["status"] == "ok").all() and len(zyg) == 15
    pd.testing.assert_frame_equal(zyg.drop(columns=timing), forked.drop(columns=timing))
    for name in ("convergence.csv", "locking.csv", "trust.csv"):  # (speed_error holds each run's seconds)
        assert (tmp_path / "zygote" / name).read_bytes() == (tmp_path / "fork" / name).read_bytes(), name
    assert sorted(os.listdir(tmp_path / "zygote" / "cases")) == sorted(os.listdir(tmp_path / "fork" / "cases"))


def test_zygote_recorder_writes_where_the_runner_is(tmp_path, running, monkeypatch):
    """A relative output directory is the runner's, not the zygote's: the recorder works in the runner's
    working directory (changed here after the zygote started)."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n')
    monkeypatch.chdir(tmp_path)
    run_study(load_study(p), Path("relative-out"), workers=1, progress=False)
    assert _timing(tmp_path / "relative-out")["recorder_start"] == "zygote"
    assert len(list((tmp_path / "relative-out" / "cases").glob("*.case"))) == 2
    assert (tmp_path / "relative-out" / "convergence.csv").exists()  # written by the recorder


def test_code_the_zygote_does_not_run_is_recorded_by_a_fork(tmp_path, running, synthetic):  # noqa: F811
    """A model registered at run time is unknown to the zygote: the runner forks its recorder, and the
    synthetic model's error (exactly 3 dx^2) comes out right. Work that cannot be pickled (closures) is
    forked too."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "synthetic-dx2"\npoints = [5, 9, 17]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert _timing(tmp_path / "out")["recorder_start"] == "fork"
    dx = load_study(p).cases[0].scene().length / (df["points"] - 1)
    assert np.allclose(df["err_max"], 3.0 * dx**2, rtol=1e-9)
    seen = []
    rec = recorder.Recorder(lambda m, a: seen.append(m), lambda: len(seen))
    assert rec.started == "fork"
    rec.put("x", [np.zeros(2)])
    assert rec.close()[0] == 1


def test_zygote_child_sends_back_its_value_and_its_failure(running):
    """Picklable work runs in a child of the zygote: ``close`` returns its ``finish()``; an exception in its
    ``handle`` is raised in the runner, not lost."""
    rec = recorder.Recorder(print, dict)  # print to the zygote's /dev/null; finish: an empty dict
    assert rec.started == "zygote"
    rec.put("a message", [np.arange(3.0)])
    value, cpu = rec.close()
    assert value == {} and cpu >= 0.0
    rec = recorder.Recorder(operator.truediv, dict)  # "text" / [arrays]: a TypeError in the child
    assert rec.started == "zygote"
    with pytest.raises(TypeError, match="unsupported operand"):
        for _ in range(100):
            rec.put("text", [np.zeros(8192)])
        rec.close()


def test_zygote_exits_when_its_starter_is_killed(tmp_path):
    """SIGKILL to the process that started the zygote: the zygote sees its socket close and exits."""
    code = ("import sys, time; from pdverify import zygote; zygote.start(); "
            "assert zygote.ready(wait=120); print(zygote._zygote.proc.pid, flush=True); time.sleep(600)")
    starter = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    pid = int(starter.stdout.readline())
    os.kill(pid, 0)  # running
    starter.kill()
    starter.wait()
    deadline = time.time() + 30
    while time.time() < deadline and _alive(pid):
        time.sleep(0.05)
    assert not _alive(pid), "the zygote outlived the process that started it"


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, exited but not yet reaped by init, does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_a_zygote_that_cannot_fork_leaves_the_run_whole(tmp_path, monkeypatch):
    """The zygote took the request but made no child (its fork failed: it closed the pipes): the runner's
    first write finds no reader, the recorder's pipes are closed (none leaks) and the run measures and
    stores its cases in its own process, with the same results."""
    p = write_study(tmp_path, STUDY)
    ref = run_study(load_study(p), tmp_path / "ref", workers=1, progress=False)
    monkeypatch.setattr(zygote, "ready", lambda wait=0.0: True)
    monkeypatch.setattr(zygote, "fork", lambda fds: True)  # accepted; the caller then closes its copies
    before = set(os.listdir("/proc/self/fd"))
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert _timing(tmp_path / "out")["recorder"] == "inline"
    assert set(os.listdir("/proc/self/fd")) <= before
    timing = ["assemble_s", "solve_s", "total_s"]
    pd.testing.assert_frame_equal(df.drop(columns=timing), ref.drop(columns=timing))
