"""The study runner's processes and its output folder: pool workers die with the main process, a folder is
locked by the run using it and belongs to one study, a bad --scheduler or --workers is one line."""

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from helpers import ROOT, pdverify_process, start_in_own_group

from pdverify.core.errors import InputError, OutputError
from pdverify.study import load_study, run_study
from pdverify.study.outdir import LOCK_NAME, FolderLock

SCENE = ROOT / "studies/paper_diyaroglu/clamped_clamped.toml"


def write_study(tmp_path, body, name="s"):
    p = tmp_path / f"{name}.toml"
    p.write_text(f'name = "{name}"\nscenes = ["{SCENE}"]\nreference = "exact-eb"\n' + body)
    return p


# twelve batches (one per slenderness: an operator group; the grid options, points and horizon, are not) of three grids,
# cases of similar cost (each a banded solve of about a tenth of a second and its grid check): a pool of two runs two
# batches and holds at most three queued when it is stopped, and it hands a batch's records back when the batch ends,
# so a stop soon after the first stored cases (two batches may end together) leaves batches unstarted whatever the
# machine's speed (with one batch, every case was stored at its end, and only a stop among the store's writes kept
# fewer than all)
SLOW_RUNS = (
    '[[runs]]\nmodel = "pd-eb"\nvariant = "corrected"\npoints = [16001, 20001, 24001]\n'
    "slenderness = [10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120]\n"
)
SLOW_CASES = 36


def one_error_line(r, code):
    assert r.returncode == code and "Traceback" not in r.stderr, r.stderr
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    return lines[0]


def _children(pid: int) -> list[int]:
    """The live (not zombie) processes whose parent is ``pid``."""
    kids = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[1]) == pid and fields[0] != "Z":
            kids.append(int(stat.parent.name))
    return kids


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_kill_9_of_a_pool_run_leaves_no_worker(tmp_path):
    """``kill -9`` of a study's main process while two pool workers solve: no worker is left after 5 s
    (they were left stuck on their queues for over 60 s before), and the cases stored so far resume."""
    p = write_study(tmp_path, SLOW_RUNS)
    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "pdverify.apps.cli", "study", str(p), "--out", str(out), "--workers", "2", "--quiet"],
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    deadline = time.time() + 300  # a wait for the machine, not a check: a loaded one stores its first case later
    workers = []
    while time.time() < deadline and (len(workers) < 2 or not list((out / "cases").glob("[!.]*.case"))):
        workers = _children(proc.pid)
        time.sleep(0.05)
    assert len(workers) == 2, workers  # both pool workers up and at least one case stored
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=10)
    time.sleep(5)
    left = [w for w in workers if _alive(w)]
    for w in left:  # not to leave them running when the test fails
        os.kill(w, signal.SIGKILL)
    assert left == []
    kept = len(list((out / "cases").glob("[!.]*.case")))
    assert 1 <= kept < SLOW_CASES and not (out / "results.csv").exists()
    assert FolderLock(out).release() is None  # the kernel dropped the dead run's lock


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_of_a_pool_run_keeps_the_finished_cases_and_leaves_no_process(tmp_path):
    """Ctrl-C (SIGINT to the whole process group, as a terminal sends it) in a run with two pool workers:
    exit 130 without a traceback, the workers ended (they ignore SIGINT; the main process stops them), no
    tables for a partial study, and the next run resumes every stored case."""
    p = write_study(tmp_path, SLOW_RUNS)
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "pdverify.apps.cli", "study", str(p), "--out", str(out), "--workers", "2", "--quiet"]
    proc = start_in_own_group(cmd)
    deadline = time.time() + 300  # a wait for the machine, not a check: a loaded one stores its cases later
    workers, stored = [], 0
    while time.time() < deadline and (len(workers) < 2 or stored < 3):
        workers = _children(proc.pid)
        stored = len(list((out / "cases").glob("[!.]*.case")))
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and b"Traceback" not in err, err
    time.sleep(0.5)
    assert len(workers) == 2 and [w for w in workers if _alive(w)] == []
    kept = len(list((out / "cases").glob("[!.]*.case")))
    assert stored >= 3, f"only {stored} cases stored in 300 s"
    assert stored <= kept < SLOW_CASES  # every case stored before the signal is kept, and the run was cut short
    assert not list((out / "cases").glob(".tmp-*")) and not (out / "results.csv").exists()
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "meta.json").read_text())["resumed_cases"] == kept


@pytest.mark.slow
def test_a_locked_folder_is_one_line_exit_4_naming_it_and_the_other_run(tmp_path):
    """A second run into a folder another run holds stops at once (exit 4) naming the folder and the
    holder's pid, and computes nothing; once the holder ends, the run goes through."""
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n')
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import fcntl, os, sys, time\n"
            f"fd = os.open({str(out / LOCK_NAME)!r}, os.O_RDWR | os.O_CREAT)\n"
            "fcntl.flock(fd, fcntl.LOCK_EX)\nos.write(fd, f'{os.getpid()}\\n'.encode())\n"
            "print('held', flush=True)\ntime.sleep(60)\n",
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "held"
        line = one_error_line(pdverify_process("study", p, "--out", out, "--quiet"), 4)
        assert str(out) in line and f"pid {holder.pid}" in line and "another --out" in line, line
        assert not list((out / "cases").glob("*.case"))
        with pytest.raises(OutputError, match=f"in use by another pdverify run \\(pid {holder.pid}\\)"):
            run_study(load_study(p), out, workers=1, progress=False)
    finally:
        holder.kill()
        holder.wait()
    assert len(run_study(load_study(p), out, workers=1, progress=False)) == 2  # the holder gone: the run goes through
    assert (out / "results.csv").exists()


def test_the_lock_is_held_during_a_run_and_released_after(tmp_path, monkeypatch):
    """While its cases run the folder's lock is taken (another taker is refused); after the run, and after
    a run that failed, it is free again."""
    from pdverify.study import runner

    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n')
    out = tmp_path / "out"
    seen = []
    solve = runner.solve_case

    def probing(case, *args):
        with pytest.raises(OutputError, match=f"{out} is in use by another pdverify run \\(pid {os.getpid()}\\)"):
            FolderLock(out)
        seen.append(case)
        if len(seen) == 2:
            raise KeyboardInterrupt
        return solve(case, *args)

    with monkeypatch.context() as m:
        m.setattr(runner, "solve_case", probing)
        with pytest.raises(KeyboardInterrupt):
            run_study(load_study(p), out, workers=1, progress=False)
    FolderLock(out).release()  # free after the interrupted run
    run_study(load_study(p), out, workers=1, progress=False)
    FolderLock(out).release()  # and after a whole one


@pytest.mark.slow
def test_another_study_never_overwrites_a_folders_tables(tmp_path):
    """A different study file run into a folder that holds a study's results stops (exit 4, one line naming
    the folder, the other study and the fix) before writing anything; the same study resumes there."""
    a = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n', "first")
    b = write_study(tmp_path, '[[runs]]\nmodel = "fem-eb"\npoints = [5, 9]\n', "second")
    out = tmp_path / "out"
    run_study(load_study(a), out, workers=1, progress=False)
    before = {f.name: f.read_bytes() for f in out.iterdir() if f.is_file() and f.name != LOCK_NAME}
    line = one_error_line(pdverify_process("study", b, "--out", out, "--quiet"), 4)
    assert str(out) in line and "'first'" in line and "another --out" in line and f"remove {out}" in line, line
    assert {f.name: f.read_bytes() for f in out.iterdir() if f.is_file() and f.name != LOCK_NAME} == before
    assert len(list((out / "cases").glob("[!.]*.case"))) == 2
    assert run_study(load_study(a), out, workers=1, progress=False)["status"].eq("ok").all()  # the same study
    assert json.loads((out / "meta.json").read_text())["resumed_cases"] == 2


def test_the_same_study_edited_takes_its_folder_over_and_resumes(tmp_path):
    """An edited study (same name, a grid added) is the same study: the run resumes the cases it shares with
    the earlier one, solves the new grid and writes every table anew, with the new study file's copy."""
    a = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n', "first")
    out = tmp_path / "out"
    run_study(load_study(a), out, workers=1, progress=False)
    a.write_text(a.read_text().replace("[51, 101]", "[51, 101, 201]"))
    df = run_study(load_study(a), out, workers=1, progress=False)
    assert sorted(df["points"]) == [51, 101, 201] and df["status"].eq("ok").all()
    assert json.loads((out / "meta.json").read_text())["resumed_cases"] == 2
    assert (out / "study.toml").read_bytes() == a.read_bytes()
    assert sorted(pd.read_csv(out / "results.csv")["points"]) == [51, 101, 201]


def test_a_killed_runs_folder_still_belongs_to_its_study(tmp_path, monkeypatch):
    """study.toml is written when a run starts: a run stopped before its tables still marks the folder as
    its study's, so another study is refused there."""
    from pdverify.study import runner

    a = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n', "first")
    b = write_study(tmp_path, '[[runs]]\nmodel = "fem-eb"\npoints = [5, 9]\n', "second")

    def interrupted(case, *args):
        raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(runner, "solve_case", interrupted)
        with pytest.raises(KeyboardInterrupt):
            run_study(load_study(a), tmp_path / "out", workers=1, progress=False)
    assert (tmp_path / "out" / "study.toml").read_bytes() == a.read_bytes()
    with pytest.raises(OutputError, match="holds the results of another study \\('first'"):
        run_study(load_study(b), tmp_path / "out", workers=1, progress=False)


@pytest.mark.parametrize(
    "address", ["nonsense", "tcp://127.0.0.1", "tcp://127.0.0.1:99999", "http://h:1:2", "tcp://127.0.0.1:80 x"]
)
def test_a_malformed_scheduler_address_is_one_line_exit_2(tmp_path, address):
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51]\n')
    with pytest.raises(InputError, match="not a Dask scheduler address; write tcp://HOST:PORT"):
        run_study(load_study(p), tmp_path / "out", scheduler=address, progress=False)
    assert not (tmp_path / "out").exists()  # refused before the folder is touched


@pytest.mark.slow
def test_a_malformed_scheduler_address_from_the_cli(tmp_path):
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51]\n')
    line = one_error_line(
        pdverify_process("study", p, "--out", tmp_path / "out", "--scheduler", "nonsense", "--quiet"), 2
    )
    assert "--scheduler 'nonsense'" in line and "tcp://HOST:PORT" in line, line


@pytest.mark.slow
def test_an_unreachable_scheduler_is_one_line_exit_2_after_the_connect_timeout(tmp_path, monkeypatch):
    """No scheduler at the address (a port nothing listens on): one line naming the connect timeout the client
    was given (execute.SCHEDULER_TIMEOUT_S, not Dask's 30 s), exit 2, no case computed."""
    from pdverify.study.execute import SCHEDULER_TIMEOUT_S

    with socket.socket() as s:  # a port that was free a moment ago
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51, 101]\n')
    r = pdverify_process("study", p, "--out", tmp_path / "out", "--scheduler", f"tcp://127.0.0.1:{port}", "--quiet")
    line = one_error_line(r, 2)
    assert f"tcp://127.0.0.1:{port}" in line and "no Dask scheduler reached" in line, line
    assert f"connect timeout {SCHEDULER_TIMEOUT_S} s" in line, line
    assert not list((tmp_path / "out" / "cases").glob("*.case"))


@pytest.mark.parametrize("workers", [0, -1])
@pytest.mark.slow
def test_workers_below_one_is_one_line_exit_2(tmp_path, workers):
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51]\n')
    line = one_error_line(pdverify_process("study", p, "--out", tmp_path / "out", "--workers", workers, "--quiet"), 2)
    assert f"--workers {workers}" in line and "1 or more" in line, line


@pytest.mark.parametrize("workers", [0, -3, True, 2.5, "2"])
def test_run_study_refuses_workers_that_are_not_a_whole_number_from_1(tmp_path, workers):
    p = write_study(tmp_path, '[[runs]]\nmodel = "pd-eb"\npoints = [51]\n')
    with pytest.raises(InputError, match=f"--workers {workers!r}: give a whole number of processes, 1 or more"):
        run_study(load_study(p), tmp_path / "out", workers=workers, progress=False)
    assert not (tmp_path / "out").exists()
