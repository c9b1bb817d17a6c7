"""A study's output folder: locked by the run that uses it, owned by one study, its finished cases read
back (resume) and each new one stored at once and atomically.

- **Lock.** A run holds an exclusive ``fcntl`` lock on ``OUT/.pdverify.lock`` (the file holds its pid)
  from before it reads the folder until its last table is written (POSIX only: elsewhere nothing is
  locked). A second run into the same folder does not wait: it stops at once with exit code 4 and one
  line naming the folder and the other run's pid. The kernel drops the lock when the process ends,
  however it ends (``kill -9`` included); the file itself stays (removing it would race with a run
  taking it).
- **One study per folder.** ``OUT/study.toml`` is a copy of the study file, written when the run starts, with
  ``OUT/scenes.json`` (each scene file's text as run).
  A run of another study (its ``name`` differs from the copy's) stops with exit code 4 before anything is
  computed or written: give another ``--out`` or remove the folder. The same study edited (same name: a
  run added, a grid refined) takes the folder over: its copy is replaced, the cases it shares with the
  earlier run are resumed (case files are keyed by their content) and every table is written anew.
"""

from __future__ import annotations

import errno
import json
import os
import time
from pathlib import Path

import numpy as np

from ..core.errors import OutputError

try:
    import fcntl
except ImportError:  # pragma: no cover - not POSIX: folders are not locked there
    fcntl = None
from .spec import Study
from .store import SUFFIX, case_file, encode_record, read_case, write_atomic

LOCK_NAME = ".pdverify.lock"


def output_error(out: Path, exc: OSError, what: str = "a case file") -> OutputError:
    """The one line of a write that failed: the fix the error's cause calls for (a full disk: space; else another
    folder), and that the cases written are kept."""
    fix = (
        "free disk space or give another --out"
        if exc.errno in (errno.ENOSPC, errno.EDQUOT)
        else "give a writable --out"
    )
    return OutputError(
        f"output directory {out}: {what} could not be written ({exc}); {fix}. The cases already written are kept: "
        "run the study again to resume."
    )


class FolderLock:
    """The exclusive lock on an output folder (module docstring); :meth:`release` or the process's end
    frees it."""

    def __init__(self, out: Path):
        self.path, self.fd = Path(out) / LOCK_NAME, None
        if fcntl is None:  # pragma: no cover - not POSIX
            return
        try:
            self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise output_error(out, exc, "the lock file") from None
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            other = os.pread(self.fd, 32, 0).decode("ascii", "replace").strip() or "unknown"
            os.close(self.fd)
            raise OutputError(
                f"output directory {out} is in use by another pdverify run (pid {other}); wait for "
                "it to end or give another --out"
            ) from None
        os.ftruncate(self.fd, 0)
        os.pwrite(self.fd, f"{os.getpid()}\n".encode(), 0)

    def release(self) -> None:
        if self.fd is not None:
            os.close(self.fd)  # closing the descriptor drops the flock
            self.fd = None


SCENES = "scenes.json"


def claim(out: Path, study: Study) -> None:
    """Make ``out`` this study's folder: refuse it when its study.toml names another study (module
    docstring), else write (or replace) the copy. Raises OutputError."""
    mine = Path(study.path).read_bytes()
    there = Path(out) / "study.toml"
    try:
        theirs = there.read_bytes()
    except FileNotFoundError:
        theirs = None
    except OSError as exc:
        raise OutputError(
            f"output directory {out}: {there.name} could not be read ({exc}); give another --out"
        ) from None
    if theirs is not None and _name(theirs) != repr(study.name):
        raise OutputError(
            f"output directory {out} holds the results of another study ({_name(theirs)}, not "
            f"{study.name!r}): give another --out or remove {out}"
        )
    scenes = json.dumps({c.scene_file: c.scene_text for c in study.cases}, indent=1, sort_keys=True) + "\n"
    try:
        if theirs != mine:
            write_atomic(there, mine)
        write_atomic(Path(out) / SCENES, scenes)  # the scene files as run: the report reads them (no path needed)
    except OSError as exc:
        raise output_error(out, exc, "study.toml") from None


def _name(toml: bytes) -> str:
    """The other study's name as its study.toml gives it, for the message."""
    import tomllib

    try:
        return repr(tomllib.loads(toml.decode("utf-8")).get("name", "unnamed"))
    except (ValueError, UnicodeDecodeError):
        return "an unreadable study.toml"


def finished(cases_dir: Path, ids: list[str]) -> dict[str, dict]:
    """The rows of the cases already stored (case id -> row); a missing, partial or corrupt file is not
    among them (store.read_case), nor one whose record is another case's (a file copied over this case's name),
    so its case is computed again."""
    on_disk = {e.name for e in os.scandir(cases_dir)}  # one listing instead of a look-up per case
    done = {}
    for cid in dict.fromkeys(ids):
        path = case_file(cases_dir, cid, on_disk)
        rec = read_case(path) if path is not None else None
        if rec is not None and rec["row"].get("case_id", cid) == cid:
            done[cid] = rec["row"]
    return done


def _clean(rec: dict) -> dict:
    """The record with its row's numpy scalars as Python numbers and NaN / inf as None (the tables'
    missing value)."""
    row = {}
    for k, v in rec["row"].items():
        t = type(v)
        if t is float or isinstance(v, np.floating):
            v = float(v) if v - v == 0 else None  # finite
        elif isinstance(v, np.integer):
            v = int(v)
        row[k] = v
    return {**rec, "row": row}


class Keeper:
    """Finished cases: each record cleaned, stored under the id this process computed and written at once
    and atomically (a killed run loses only the cases in flight); the rows kept for the tables. A worker
    with other code computes other ids: its record is kept under ours and the mismatch reported in
    meta.json instead of losing the case."""

    def __init__(self, out: Path, code: str):
        self.out, self.cases_dir, self.code = out, out / "cases", code
        self.rows: dict = {}
        self.mismatched: list[str] = []
        self.clock = {"solver_s": 0.0, "store_s": 0.0}  # the solves' time this run; cleaning, encoding, writing

    def add(self, rec: dict, cid: str) -> bool:
        """Store one record; whether its case failed (a suspect case solved: the progress bar does not count it).
        Raises OutputError when the file cannot be written."""
        t = time.perf_counter()
        spent = rec.pop("spent_s", None)  # this run's seconds in the solve (runner.run_case), not stored
        rec = _clean(rec)
        row = rec["row"]
        if row.get("code") != self.code:
            self.mismatched.append(cid)
        row["case_id"] = cid
        try:
            write_atomic(self.cases_dir / f"{cid}{SUFFIX}", encode_record(rec))
        except OSError as exc:  # disk full, permissions: stop with one line; the cases written so far stay
            raise output_error(self.out, exc) from None
        self.rows[cid] = row
        self.clock["solver_s"] += spent if spent is not None else row.get("total_s") or 0.0
        self.clock["store_s"] += time.perf_counter() - t
        return row["status"] == "failed"
