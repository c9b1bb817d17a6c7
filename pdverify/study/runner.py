"""Run a study: cases in parallel (process pool or Dask), each written at once and atomically,
resumable, failures recorded; then the derived tables (convergence, locking, speed vs error).
"""

from __future__ import annotations

import json
import multiprocessing
import os
import platform
import shutil
import sys
import threading
import time
from collections import Counter
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from functools import lru_cache
from pathlib import Path

import numpy as np
import pandas as pd

try:  # imported with the runner (its one-time cost belongs to start-up, not to the first study's tables)
    import pyarrow as pa
    import pyarrow.csv as pa_csv
    import pyarrow.parquet as pa_parquet
    import pyarrow.pandas_compat  # noqa: F401 - else imported by the first pa.array(..., from_pandas=True): 2-12 ms
except ImportError:  # pragma: no cover - parquet is optional, the CSV tables are always written (by pandas)
    pa = None

from .. import __version__
from ..errors import OutputError, PdverifyError
from ..registry import get_model, run
from ..result import columns_csv
from .status import case_status
from .metrics import errors
from .spec import Case, Study, code_digest
from .recorder import Recorder, RecorderDied
from .store import SUFFIX, case_file, encode_record, read_case, read_curve, write_atomic
from .tables import (EMPTY_CONVERGENCE, Groups, convergence_rows, locking_rows, rows_of, speed_error_rows,
                     trust_rows, trust_table)  # noqa: F401 (trust_table: re-exported)

PARAM_COLUMNS = ("variant", "points", "horizon", "degree", "element", "layers", "form")


@lru_cache(maxsize=64)
def _reference_fn(scene_text: str, scene_file: str, slenderness, ref_items: tuple):
    """x -> reference deflection, built once per (scene, slenderness, reference options): the reference
    model's ``evaluator`` where it has one (exact models: exact at any x), else its own solution
    interpolated by a cubic spline."""
    from scipy.interpolate import CubicSpline

    ref = dict(ref_items)
    model = get_model(ref.pop("model"))
    scene = Case(scene_file, scene_text, slenderness, "", {}, {}).scene()
    ev = model.evaluator(scene, model.resolve(scene, ref))
    if ev is not None:
        return lambda x: np.asarray(ev(x)["w"], float)
    solved = run(scene, model, **ref)
    return CubicSpline(solved.x, solved.w)


REFERENCE_CACHE_POINTS = 20_000  # grids up to this size keep their reference values (64 grids: <= 10 MB)


@lru_cache(maxsize=64)
def _reference_values(scene_text: str, scene_file: str, slenderness, ref_items: tuple, x_bytes: bytes) -> np.ndarray:
    """The reference at one grid, kept: a sweep over horizon, variant or form solves many cases on the
    same points, and the exact solutions cost as much as the rest of a small case's bookkeeping
    (0.18 ms at 1,200 points). Read-only, so a caller cannot change the cached values."""
    w = np.array(_reference_fn(scene_text, scene_file, slenderness, ref_items)(np.frombuffer(x_bytes, "<f8")), float)
    w.flags.writeable = False
    return w


def reference_at(case: Case, scene, x: np.ndarray) -> np.ndarray:
    """The reference deflection at the model's points (see :func:`_reference_fn`); the values of grids of
    up to ``REFERENCE_CACHE_POINTS`` points are kept per (scene, slenderness, reference, grid)."""
    key = (case.scene_text, case.scene_file, case.slenderness, tuple(sorted(case.reference.items())))
    x = np.asarray(x, "<f8")
    if x.size <= REFERENCE_CACHE_POINTS:
        return _reference_values(*key, x.tobytes())
    return np.asarray(_reference_fn(*key)(x), float)


@lru_cache(maxsize=256)
def _reference_text(items: tuple) -> str:
    """The reference's options as the results table stores them (one per study, not one per case)."""
    return json.dumps(dict(items), sort_keys=True)


INFO_KEYS = ("horizon", "cond", "error_bound", "load_steps", "history")


def solve_case(case: Case, artefacts: str | None = None, case_id: str | None = None) -> dict:
    """The solving half of a case: the model's result reduced to what :func:`measure_case` reads (arrays
    and numbers, picklable: it crosses to a worker's parent or to the recorder), or ``{"failure": message,
    "timings": {"total_s": seconds}}``.
    Never raises. ``artefacts``: a folder for the model's own files (a plane-stress VTU and its PNG, time
    histories as CSV), named by ``case_id``: they are written here, where the model's writers live.
    A failure's seconds are its cost: meta.json counts them as the models' time, not the runner's."""
    t0 = time.perf_counter()
    try:
        result = run(case.scene(), case.model, **case.given)
        solved = {"x": np.asarray(result.x, "<f8"), "w": np.asarray(result.w, "<f8"),
                  "rotation": None if result.rotation is None else np.asarray(result.rotation, "<f8"),
                  "fields": {k: np.asarray(v, "<f8") for k, v in result.fields.items() if np.shape(v) == np.shape(result.x)},
                  "timings": {k: result.timings.get(k) for k in ("assemble_s", "solve_s", "total_s")},
                  "dofs": int(result.dofs), "info": {k: _plain_scalar(result.info[k]) for k in INFO_KEYS if k in result.info}}
        hist = result.info.get("history")
        if artefacts and isinstance(hist, dict) and "t" in hist:  # the time histories as CSV, for other tools
            hdir = Path(artefacts).parent / "histories"
            hdir.mkdir(parents=True, exist_ok=True)
            write_atomic(hdir / f"{case_id or case.case_id}.csv", columns_csv({"t": hist["t"], **hist.get("series", {})}))
        if artefacts and ".vtu" in result.writers:
            base = Path(artefacts) / (case_id or case.case_id)
            base.parent.mkdir(parents=True, exist_ok=True)
            try:
                result.writers[".vtu"](str(base.with_suffix(".vtu")))
                if ".png" in result.writers:
                    result.writers[".png"](str(base.with_suffix(".png")))
            except PdverifyError as exc:  # a failed picture never fails the case
                solved["artefact_message"] = " ".join(exc.lines)
        return solved
    except Exception as exc:  # a bad case, a singular system, a bug in a model: recorded, the study goes on
        return {"failure": _failure_message(exc), "timings": {"total_s": time.perf_counter() - t0}}


def _failure_message(exc: Exception) -> str:
    """A failed case's message: a PdverifyError's lines, a replayed failure's text, else the exception's type
    and text (a bug)."""
    if isinstance(exc, PdverifyError):
        return " ".join(exc.lines)
    if isinstance(exc, _Failed):
        return str(exc)
    return f"{type(exc).__name__}: {exc}"


# The serial runner hands its solved cases to the recorder at most every HANDOFF_S seconds (and the last
# two one by one): each handoff costs the solving process ~0.1 ms whatever it carries (a pickle and a pipe write
# between two solves, caches cold), so cases of a few ms go by the handful. A killed runner (SIGKILL) loses
# at most the cases solved in the last HANDOFF_S beside the one being solved; Ctrl-C loses none.
HANDOFF_S = 0.02


def _handoff(i: int, solved: dict) -> tuple[tuple, list]:
    """The ``i``-th case's :func:`solve_case` result as it crosses to the recorder process: (message,
    arrays), its curves apart (written to the pipe as they are), the rest small (pickled: see
    ``recorder.encode``). :func:`_handback` undoes it."""
    names = [k for k in ("x", "w", "rotation") if solved.get(k) is not None]
    fields = solved.get("fields") or {}
    rest = {k: v for k, v in solved.items() if k not in ("x", "w", "rotation", "fields")}
    return (i, rest, names, list(fields)), [solved[k] for k in names] + list(fields.values())


def _handback(message: tuple, arrays: list) -> tuple[int, dict]:
    i, rest, names, fields = message
    solved = {**rest, **dict(zip(names, arrays))}
    if "failure" not in solved:
        solved.setdefault("rotation", None)
        solved["fields"] = dict(zip(fields, arrays[len(names):]))
    return i, solved


def _plain_scalar(v):
    """A numpy scalar as the Python number it equals (pickling a numpy scalar pickles its dtype: ~20 us)."""
    return v.item() if isinstance(v, np.generic) else v


def _describe(case: Case, row: dict):
    """The columns of a case's row known before it is solved: its scene's name, its options as resolved by
    the model (``options``: all but the grid, the key of a convergence series). Returns (scene, options)."""
    scene = case.scene()
    row["scene"] = scene.name
    params = get_model(case.model).resolve(scene, case.given)
    row.update({k: params.get(k, row.get(k)) for k in PARAM_COLUMNS})
    row["options"] = json.dumps({k: v for k, v in params.items() if k != "points"}, sort_keys=True)
    return scene, params


def predicted_row(case: Case, case_id: str) -> dict:
    """What the derived tables group a case by (scene, model, options, slenderness, points), before it is
    solved (tables.Groups); as far as it goes when the case cannot even be described (its row will fail)."""
    row = {"case_id": case_id, "model": case.model, "slenderness": case.slenderness,
           **{k: case.given.get(k) for k in PARAM_COLUMNS}}
    try:
        _describe(case, row)
    except Exception:  # noqa: BLE001 - its groups are then simply computed at the end
        pass
    return row


class _Failed(Exception):
    """A solve that failed, replayed where the case is measured so its row fills in as far as it would have."""


def measure_case(case: Case, solved: dict, case_id: str | None = None) -> dict:
    """The measuring half of a case: its row (parameters, errors against the reference at the model's
    points, timings, dofs, status) and its curves, from what :func:`solve_case` returned. Never raises."""
    case_id = case_id or case.case_id
    row = {"case_id": case_id, "code": code_digest(), "scene_file": case.scene_file, "model": case.model,
           "slenderness": case.slenderness, "reference": _reference_text(tuple(sorted(case.reference.items()))),
           "version": __version__}
    row.update({k: case.given.get(k) for k in PARAM_COLUMNS})
    curve = {}
    try:
        scene, params = _describe(case, row)
        if "failure" in solved:
            raise _Failed(solved["failure"])
        x, w, info = solved["x"], solved["w"], solved["info"]
        if case.reference.get("model") == "none":
            w_ref = np.full_like(x, np.nan)
            row.update(err_max=np.nan, err_l2=np.nan, err_at_max=np.nan,
                       w_at_max=float(w[np.argmax(np.abs(w))]), w_ref_at_max=np.nan)
        else:
            w_ref = reference_at(case, scene, x)
            row.update(errors(w, w_ref))
        row.update(solved["timings"])
        row["dofs"] = solved["dofs"]
        row["spacing"] = float(np.diff(x).max()) if len(x) > 1 else float("nan")
        row["horizon_factor"] = params.get("horizon")
        row["horizon"] = info.get("horizon", (params["horizon"] * row["spacing"]) if params.get("horizon") else None)
        row["cond"] = info.get("cond")
        row["status"], row["message"] = "ok", ""
        row.update(case_status(info))  # "suspect" when the round-off bound passes 1e-6 (issue 27)
        if "artefact_message" in solved:
            row["artefact_message"] = solved["artefact_message"]
        # arrays stay arrays here (compact to pickle from a worker); encode_record stores them exactly
        curve = {"x": x, "w": w, "w_ref": np.asarray(w_ref, "<f8")}
        if solved["rotation"] is not None:
            curve["rotation"] = solved["rotation"]
        if solved["fields"]:  # point fields (u, theta, N, Q, M ...): for positional benchmarks and other tools
            curve["fields"] = solved["fields"]
        if "load_steps" in info:  # deformed shapes of a nonlinear path, for the report
            curve["load_steps"] = info["load_steps"]
        hist = info.get("history")
        if isinstance(hist, dict) and "t" in hist:  # time histories of a dynamic run: {"t": [...], "series": {label: [...]}}
            curve["history"] = {"t": np.asarray(hist["t"], "<f8"),
                                "series": {k: np.asarray(v, "<f8") for k, v in hist.get("series", {}).items()},
                                "ylabel": hist.get("ylabel", "displacement")}
    except Exception as exc:  # a failed solve replayed (_Failed), a bad case, a bug: recorded, never raised
        for k, v in (solved.get("timings") or {}).items():  # what the attempt cost, as far as it went
            row.setdefault(k, v)
        row["status"], row["message"] = "failed", _failure_message(exc)
    return {"case": {"scene_file": case.scene_file, "model": case.model, "given": case.given,
                     "slenderness": case.slenderness, "reference": case.reference},
            "row": row, "curve": curve}


def run_case(case: Case, artefacts: str | None = None, case_id: str | None = None) -> dict:
    """Solve one case and measure it (:func:`solve_case`, then :func:`measure_case`). Never raises: a
    failure is a record with status 'failed'."""
    return measure_case(case, solve_case(case, artefacts, case_id), case_id)


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


class _Keeper:
    """Finished cases: each record cleaned, stored under the id this process computed and written at once
    and atomically (a killed run loses only the cases in flight); the rows kept for the tables. A worker
    with other code computes other ids: its record is kept under ours and the mismatch reported in
    meta.json instead of losing the case."""

    def __init__(self, out: Path, code: str):
        self.out, self.cases_dir, self.code = out, out / "cases", code
        self.rows: dict = {}
        self.mismatched: list[str] = []
        self.clock = {"solver_s": 0.0, "store_s": 0.0}  # the models' own time; cleaning, encoding, writing
        self.env: dict | None = None  # environment(), when the recorder reads it
        self.write = write_atomic  # as the module has it now (a test may replace it; the recorder is given it)

    def add(self, rec: dict, cid: str) -> bool:
        """Store one record; whether its case is ok. Raises OutputError when the file cannot be written."""
        t = time.perf_counter()
        rec = _clean(rec)
        row = rec["row"]
        if row.get("code") != self.code:
            self.mismatched.append(cid)
        row["case_id"] = cid
        try:
            self.write(self.cases_dir / f"{cid}{SUFFIX}", encode_record(rec))
        except OSError as exc:  # disk full, permissions: stop with one line; the cases written so far stay
            raise _output_error(self.out, exc) from None
        self.rows[cid] = row
        self.clock["solver_s"] += row.get("total_s") or 0.0
        self.clock["store_s"] += time.perf_counter() - t
        return row["status"] == "ok"

    def summary(self) -> tuple[dict, list, dict, dict | None]:
        return self.rows, self.mismatched, self.clock, self.env


class _Recording:
    """The serial run's work in its recorder process (:class:`~.recorder.Recorder`): measure each case
    from what its solve returned, store it (``keep``), and compute the derived tables' groups as the cases
    come in; once every case is in, the derived tables. A module-level class, so that it can be pickled
    for a recorder forked from the zygote; it carries the functions it calls that a caller may have
    replaced (``measure_case`` here, the keeper's ``write``), so the child runs what the runner would."""

    def __init__(self, study: Study, out: Path, ids: list[str], todo: list[Case], todo_ids: list[str],
                 done: dict, keep: _Keeper):
        self.study, self.out, self.ids, self.todo, self.todo_ids = study, out, ids, todo, todo_ids
        self.done, self.keep, self.measure, self.groups = done, keep, measure_case, None

    def start(self) -> None:
        """While the first case is solved: each case's groups in the derived tables, and the environment."""
        keep = self.keep
        t = time.perf_counter()
        expected = [self.done.get(cid) or predicted_row(case, cid) for case, cid in zip(self.study.cases, self.ids)]
        self.groups = Groups(list({r["case_id"]: r for r in expected}.values()))
        for row in self.done.values():
            self.groups.add(row)
        keep.clock["groups_s"] = time.perf_counter() - t
        keep.env = environment()  # read here, off the solver's core (~18 ms the first time in a process)
        warm_up()  # a fork of a runner that has not written a table yet: for the derived tables at the end

    def record(self, batch, arrays) -> None:
        """The cases of one handoff (:data:`HANDOFF_S`), in order: :meth:`record_case` each."""
        k = 0
        for message in batch:
            n = len(message[2]) + len(message[3])
            self.record_case(message, arrays[k:k + n])
            k += n

    def record_case(self, message, arrays) -> None:
        """Measure the i-th case from what the solve returned, store it."""
        keep = self.keep
        i, solved = _handback(message, arrays)
        cid = self.todo_ids[i]
        t = time.perf_counter()
        rec = self.measure(self.todo[i], solved, cid)
        keep.clock["measure_s"] = keep.clock.get("measure_s", 0.0) + time.perf_counter() - t
        keep.add(rec, cid)
        if i < len(self.todo) - 1:  # the last one's after its row has gone back to the runner (derived_tables)
            t = time.perf_counter()
            self.groups.add(keep.rows[cid])  # the derived tables' groups this case completes
            keep.clock["groups_s"] += time.perf_counter() - t

    def summary(self):
        return self.keep.summary()

    def derived_tables(self) -> float:
        """Once every case is in, while the runner writes the results: the derived tables; their seconds."""
        t = time.perf_counter()
        self.groups.add(self.keep.rows[self.todo_ids[-1]])  # the last case's groups: after the rows went back
        rows = {**self.done, **self.keep.rows}
        write_derived(self.study, self.out, [rows[cid] for cid in dict.fromkeys(self.ids)], RECORDER_WRITES,
                      self.groups.memo)
        return time.perf_counter() - t


def run_study(study: Study, out: Path, workers: int | None = None, scheduler: str | None = None,
              progress: bool = True) -> pd.DataFrame:
    """Run the study's cases not yet done in ``out`` (resumed from their case files), write every table and
    meta.json there; the results table. Raises OutputError (one line, nothing lost that was stored) when
    ``out`` cannot be written or when a process storing or solving cases (recorder, worker) dies."""
    out = Path(out)
    try:
        return _run_study(study, out, workers, scheduler, progress)
    except RecorderDied as exc:  # killed by the system (out of memory, a signal): what it stored is kept
        raise OutputError(f"{exc}; the cases it stored are kept in {out / 'cases'}: run the study again to "
                          "resume") from None
    except BrokenProcessPool:  # a worker killed: the cases it solved before were stored here
        raise OutputError(f"a worker process ended abruptly (killed: out of memory, a signal); the cases "
                          f"finished before are kept in {out / 'cases'}: run the study again to resume") from None


def _run_study(study: Study, out: Path, workers: int | None, scheduler: str | None, progress: bool) -> pd.DataFrame:
    cases_dir = out / "cases"
    try:
        cases_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise _output_error(out, exc) from None
    t0 = time.perf_counter()
    ids = [c.case_id for c in study.cases]  # hashed once: the key covers the scene text and the code digest
    id_of = {id(c): cid for c, cid in zip(study.cases, ids)}
    done, todo = {}, []  # done: case id -> row (the curves stay on disk)
    seen = set()
    on_disk = {e.name for e in os.scandir(cases_dir)}  # one listing instead of a look-up per case
    for case, cid in zip(study.cases, ids):
        if cid in seen:
            continue
        seen.add(cid)
        path = case_file(cases_dir, cid, on_disk)
        rec = read_case(path) if path is not None else None
        if rec is not None:
            done[cid] = rec["row"]
        else:
            todo.append(case)
    resumed = len(done)

    keep = _Keeper(out, code_digest())
    # Serial runs solve here and measure + store in a child on the other core (recorder.Recorder: a fork of
    # the zygote when it is up, else of this process); with workers or Dask this process collects the
    # measured records and writes them itself.
    serial = not scheduler and ((workers or os.cpu_count() or 1) <= 1 or len(todo) <= 1)
    recorder = None
    if serial and len(todo) > 1 and Recorder.available:
        work = _Recording(study, out, ids, todo, [id_of[id(c)] for c in todo], done, keep)
        try:
            recorder = Recorder(work.record, work.summary, work.derived_tables, start=work.start)
        except OSError:  # no process to be had (limits): measure and store here instead
            pass
    env = None  # environment(), when the recorder reads it
    bar = _progress(len(todo), progress)  # after the fork: the bar's thread stays in this process
    warming = None
    # This process's first tables: Arrow's and pandas' first use (5-15 ms) in a thread while the first cases
    # are solved. The other core is the recorder's, idle most of the time; the warm-up holds the GIL little
    # (one-row tables, written by Arrow's C++). First runs in a fresh process, 8 pairs: 4.0-5.7 % runner
    # overhead, median 4.6 %, against 4.1-6.5 %, median 5.5 %, without it.
    if recorder is not None and not _warm:
        warming = threading.Thread(target=warm_up, name="pdverify-warm-up", daemon=True)
        warming.start()
    batch, batch_arrays = [], []  # solved, not yet handed to the recorder (HANDOFF_S)
    artefacts = str(out / "vtu")  # once: a path joined and made a string cost ~35 us a case between solves
    try:
        if scheduler:
            from dask.distributed import Client, as_completed as dask_completed

            with Client(scheduler) as client:
                futures = client.map(run_case, todo, [None] * len(todo), [id_of[id(c)] for c in todo],
                                     pure=False)  # remote workers: no artefact files
                by_key = {f.key: c for f, c in zip(futures, todo)}
                for fut in dask_completed(futures):
                    bar.advance(failed=not keep.add(fut.result(), id_of[id(by_key[fut.key])]))
        elif recorder is not None:
            handoff = 0.0  # the solving process's time to hand the cases over
            last = len(todo) - 1
            sent = time.perf_counter()
            for i, case in enumerate(todo):
                solved = solve_case(case, artefacts, id_of[id(case)])
                t = time.perf_counter()
                message, arrays = _handoff(i, solved)
                batch.append(message)
                batch_arrays += arrays
                # the last case alone: what the recorder has left to do when the solves end is one case
                if t - sent >= HANDOFF_S or i >= last - 1:
                    full, batch, batch_arrays = (batch, batch_arrays), [], []  # emptied first: never sent
                    recorder.put(*full)  # twice, even when Ctrl-C comes in the middle of this write
                    sent = time.perf_counter()
                handoff += time.perf_counter() - t
                bar.advance(failed="failure" in solved)
            keep.clock["handoff_s"] = handoff
        elif serial:
            for case in todo:
                bar.advance(failed=not keep.add(run_case(case, artefacts, id_of[id(case)]), id_of[id(case)]))
        else:
            # fork on Linux whatever the Python version (3.14 made forkserver the default): workers start in
            # milliseconds with the models already imported, as the recorder does
            ctx = multiprocessing.get_context("fork") if sys.platform.startswith("linux") else None
            with ProcessPoolExecutor(max_workers=workers or os.cpu_count(), mp_context=ctx) as pool:
                futs = {pool.submit(run_case, c, artefacts, id_of[id(c)]): c for c in todo}
                for fut in as_completed(futs):
                    bar.advance(failed=not keep.add(fut.result(), id_of[id(futs[fut])]))
    except BaseException:  # Ctrl-C, a failed write: the child records the cases it was given, no tables
        bar.close()
        if warming is not None:
            warming.join()
        if recorder is not None:
            if batch and not recorder.closed:  # Ctrl-C: the cases solved since the last handoff are kept too
                try:
                    recorder.put(batch, batch_arrays)
                except Exception:  # the recorder failed: its error is the one being raised, or will be
                    pass
            recorder.abort()
        raise
    try:
        if recorder is not None:
            t = time.perf_counter()
            (rows, mismatched, clock, env), _ = recorder.close()  # the child's OutputError, if any, is raised here
            # the bar counted the failed solves as they came; a case can also fail where it is measured
            # (its reference): the final count is the rows'
            bar.set_failed(sum(r["status"] != "ok" for r in rows.values()))
    finally:
        bar.close()
    derived = None
    if recorder is not None:
        keep.rows.update(rows)
        keep.mismatched += mismatched
        keep.clock.update(clock, recorder_wait_s=time.perf_counter() - t)

        def derived():  # written by the child meanwhile: its time for them, and its CPU time in all
            tables_s, cpu = recorder.join()
            return {"recorder_tables_s": tables_s, "recorder_cpu_s": cpu}

    if warming is not None:
        warming.join()
    done.update(keep.rows)
    rows = [done[cid] for cid in dict.fromkeys(ids)]
    table = results_table(study, rows)
    df = results_frame(study, rows, table)
    cases_s = time.perf_counter() - t0
    try:
        write_tables(study, out, rows, table=table, env=env, wall=cases_s, resumed=resumed,
                     mismatched=keep.mismatched, derived=derived,
                     timing={"cases_s": cases_s, "computed_cases": len(todo),
                             "recorder": "process" if recorder else "inline",
                             **({"recorder_start": recorder.started} if recorder else {}), **keep.clock})
    except OSError as exc:
        if recorder is not None:
            recorder.abort()
        raise _output_error(out, exc, "a table") from None
    return df


TEXT_OPTIONS = ("variant", "element", "form")  # text options: a text column even when no case has them


def results_table(study: Study, rows: list[dict]):
    """The results as an Arrow table (:func:`_rows_table`): one row per case (``rows``, in the study's
    order), the study's name first, the text options text columns even when every value is missing; None
    without pyarrow or when a column's values are of mixed types (then pandas builds it: :func:`results_frame`)."""
    if not rows:
        return None
    return _rows_table([{"study": study.name, **r} for r in rows], ("study", *TEXT_OPTIONS))


def write_results(study: Study, out: Path, rows: list[dict], table=None) -> None:
    """results.csv and results.parquet from :func:`results_table` (``table``, when built already): the
    same bytes in every path, ~6 ms for 200 cases where the DataFrame's conversion and writes took ~9 ms."""
    table = table if table is not None else results_table(study, rows)
    if table is None:
        _save(results_frame(study, rows), out, "results")
        return
    _write(table, out, "results")


def results_frame(study: Study, rows: list[dict], table=None) -> pd.DataFrame:
    """The results DataFrame (what :func:`run_study` returns): :func:`results_table`'s (``table``, when built
    already) ``to_pandas`` (3.0-3.8 ms for 200 cases, 5.6-6.6 ms the first time in a process, against
    3.4-5.4 and 6.8-9.3 ms for pandas from the rows), else pandas' from the rows, the text options as
    pandas strings."""
    table = table if table is not None else results_table(study, rows)
    if table is not None:
        return table.to_pandas()
    df = pd.DataFrame(rows)
    df.insert(0, "study", study.name)
    for col in TEXT_OPTIONS:
        if col in df:
            df[col] = df[col].astype("string")
    return df


def _output_error(out: Path, exc: OSError, what: str = "a case file") -> OutputError:
    return OutputError(f"output directory {out}: {what} could not be written ({exc}); free disk space or "
                       "give a writable --out. The cases already written are kept: run the study again to resume.")


class _progress:
    """rich progress bar: cases done, failures, time left (silent when disabled)."""

    def __init__(self, total, enabled):
        self.enabled = enabled and total > 0
        self.failed = 0
        if self.enabled:
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self.p = Progress(TextColumn("cases"), BarColumn(), MofNCompleteColumn(), TextColumn("failed {task.fields[failed]}"),
                              TimeRemainingColumn(), transient=False)
            self.p.start()
            self.task = self.p.add_task("cases", total=total, failed=0)

    def advance(self, failed=False):
        self.failed += int(failed)
        if self.enabled:
            self.p.update(self.task, advance=1, failed=self.failed)

    def set_failed(self, n: int):
        self.failed = n
        if self.enabled:
            self.p.update(self.task, failed=n)

    def close(self):
        if self.enabled:
            self.p.stop()


def _arrow(df: pd.DataFrame):
    """``df`` as an Arrow table (what ``to_parquet`` writes), or None without pyarrow, without columns, or
    when a column does not convert (mixed types): then pandas writes the CSV and there is no Parquet."""
    if pa is None or df.columns.empty:
        return None
    try:
        return pa.Table.from_pandas(df, preserve_index=False)
    except (pa.ArrowException, TypeError, ValueError):
        return None


def _rows_table(rows: list[dict], text=()):
    """The table of ``rows`` (dicts) as Arrow builds it from them: columns in order of first appearance (as
    pandas makes them), missing values (None, NaN) as nulls (as pandas' are), the columns named in ``text``
    text even when every value is missing; None without pyarrow, without columns, or when a column's values
    are of mixed types."""
    columns = list(dict.fromkeys(k for r in rows for k in r))
    if pa is None or not columns:
        return None
    try:
        return pa.table({c: pa.array([r.get(c) for r in rows], pa.large_string() if c in text else None,
                                     from_pandas=True) for c in columns})
    except (pa.ArrowException, TypeError, ValueError):
        return None


def _write(table, out: Path, name: str, parquet: bool = True) -> None:
    """``name``.csv and (``parquet``) ``name``.parquet from one Arrow table: Arrow's CSV writer takes ~1 ms
    where pandas' ``to_csv`` took 8-11 ms on a 200-case results table (the tables are on a study's critical
    path). Arrow quotes every text value and writes an integral float without ``.0`` (``pandas.read_csv``
    then reads such a column as integers); values are written exactly (shortest round-trip form)."""
    pa_csv.write_csv(table, out / f"{name}.csv")
    if parquet:
        pa_parquet.write_table(table, out / f"{name}.parquet")


_warm = False  # whether this process has used Arrow's writers and the table's conversion to pandas


def warm_up() -> bool:
    """Write a one-row table (:func:`_save_rows`) to a temporary folder and convert it to pandas, once per
    process: the first use of Arrow's CSV and Parquet writers and of ``to_pandas`` in a process costs 5-15 ms
    (the libraries' code paged in), paid on a study's critical path when its tables are written. Never
    raises (a failure, say no writable temporary folder, only leaves the first tables slower); whether this
    process is warm."""
    global _warm
    import tempfile

    if not _warm:
        try:
            with tempfile.TemporaryDirectory() as d:
                _save_rows([{"a": 1.0, "b": "x"}], Path(d), "warm")
                if pa is not None:
                    _rows_table([{"a": 1.0, "b": "x"}], ("b",)).to_pandas()
            _warm = True
        except Exception:  # noqa: BLE001 - an optimisation only: the tables are written (and checked) later
            pass
    return _warm


def _write_empty(out: Path, name: str) -> None:
    """What pandas writes for a table with neither rows nor columns, without building one and waking its
    CSV writer (~2-5 ms the first time)."""
    (out / f"{name}.csv").write_bytes(b"\n")


def _save_rows(rows: list[dict], out: Path, name: str, parquet: bool = True) -> None:
    """:func:`_save` of the table of ``rows``, built by Arrow directly (:func:`_rows_table`; a derived table:
    ~1 ms each where going through a DataFrame cost 2-6 ms); through pandas when a column's values are of
    mixed types."""
    if not rows:
        _write_empty(out, name)
        return
    table = _rows_table(rows)
    if table is None:
        _save(pd.DataFrame(rows), out, name, parquet)
        return
    _write(table, out, name, parquet)


def _save(df: pd.DataFrame, out: Path, name: str, parquet: bool = True) -> None:
    """``name``.csv and (``parquet``) ``name``.parquet of ``df`` (:func:`_write`); pandas' CSV alone when it
    does not convert to Arrow."""
    if df.columns.empty:
        _write_empty(out, name)
        return
    table = _arrow(df)
    if table is None:
        df.to_csv(out / f"{name}.csv", index=False)
        return
    _write(table, out, name, parquet)


def _verdict(ok: bool, expected: str) -> str:
    """pass / fail, or for a row that documents a known defect (expected = fail): 'expected-fail' when it
    still fails and 'unexpected-pass' when it no longer does (then the row's text needs a look)."""
    if expected == "fail":
        return "unexpected-pass" if ok else "expected-fail"
    return "pass" if ok else "fail"


def benchmark_table(study: Study, df: pd.DataFrame, conv: pd.DataFrame, cases_dir: Path | None = None) -> pd.DataFrame:
    """Verification rows. Default quantity: the deflection at the point of largest reference deflection
    (``w_at_max``); with ``position`` (m along the axis) and optional ``quantity`` (w, rotation or a
    point field such as u, theta, M), the case's curve interpolated there (the case file holds it)."""
    rows = []
    for b in study.benchmarks:
        opts = {k: v for k, v in b.items() if k not in ("name", "scene", "model", "target", "tolerance", "quantity", "position", "expected")}
        m = (df["scene_file"] == b["scene"]) & (df["model"] == b["model"]) & (df["status"] == "ok")

        def matches(r):
            have = dict(json.loads(r["options"]), points=r["points"])
            return all(k in have and have[k] == v for k, v in opts.items())

        cand = df[m]
        hit = cand[cand.apply(matches, axis=1)] if len(cand) else cand
        if hit.empty:
            rows.append({"name": b["name"], "scene": b["scene"], "model": b["model"], "verdict": "missing"})
            continue
        r = hit.iloc[0]
        target = b.get("target", r["w_ref_at_max"])
        computed = r["w_at_max"]
        quantity = b.get("quantity", "w")
        if "position" in b:
            path = case_file(cases_dir, r["case_id"]) if cases_dir else None
            c = read_curve(path) if path is not None else {}
            arr = c.get(quantity) if quantity in ("w", "rotation") else c.get("fields", {}).get(quantity)
            if arr is None:
                rows.append({"name": b["name"], "scene": b["scene"], "model": b["model"], "verdict": "missing",
                             "message": f"quantity {quantity!r} not among the case's outputs"})
                continue
            computed = float(np.interp(float(b["position"]), c["x"], arr))
            if "target" not in b:
                target = float(np.interp(float(b["position"]), c["x"], c["w_ref"])) if quantity == "w" else float("nan")
        rel = abs(computed - target) / abs(target) if target else float("nan")
        tol = b.get("tolerance", 0.01)
        order = float("nan")
        if not conv.empty:
            c = conv[(conv["scene"] == r["scene"]) & (conv["model"] == r["model"]) & (conv["options"] == r["options"])
                     & (conv["slenderness"].fillna(-1) == (r["slenderness"] if pd.notna(r["slenderness"]) else -1))]
            if len(c):
                order = c["observed_order"].iloc[0]
        rows.append({"name": b["name"], "scene": r["scene"], "scene_file": b["scene"], "model": b["model"],
                     "variant": r.get("variant"), "reference": r["reference"], "target": target,
                     "computed": computed, "ratio": computed / target if target else float("nan"), "rel_error": rel,
                     "err_max": r["err_max"], "tolerance": tol, "verdict": _verdict(rel <= tol, b.get("expected", "pass")),
                     "quantity": quantity if "position" in b else "w at max", "position": b.get("position"),
                     "observed_order": order, "case_id": r["case_id"]})
    return pd.DataFrame(rows)


@lru_cache(maxsize=1)
def package_versions() -> dict:
    """Versions of the packages whose code can change a number (read once per process: 20 ms)."""
    import importlib.metadata as md

    versions = {}
    for pkg in ("numpy", "scipy", "scikit-fem", "pandas", "pyvista", "matplotlib", "dask"):
        try:
            versions[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            versions[pkg] = None
    return dict(versions)


def environment() -> dict:
    """Python, platform, machine and the versions of the packages whose code can change a number, as
    meta.json records them (the first call in a process reads package metadata: ~18 ms)."""
    return {"python": platform.python_version(), "platform": platform.platform(), "machine": platform.machine(),
            "versions": package_versions()}


def _write_convergence(study: Study, out: Path, rows: list[dict], memo: dict | None) -> None:
    conv = convergence_rows(rows, memo)
    if not conv and not any(r.get("status") == "ok" for r in rows):
        _save(pd.DataFrame(columns=EMPTY_CONVERGENCE), out, "convergence")  # the header: no case is ok
    else:
        _save_rows(conv, out, "convergence")
    if study.benchmarks:  # the verification rows quote the observed order
        _save(benchmark_table(study, pd.DataFrame(rows), pd.DataFrame(conv), out / "cases"), out, "benchmarks",
              parquet=False)


def _write_speed_error(study: Study, out: Path, rows: list[dict], memo: dict | None) -> None:
    se, summary = speed_error_rows(rows, memo)
    _save_rows(se, out, "speed_error")
    _save_rows(summary, out, "speed_error_summary", parquet=False)


DERIVED = {  # the derived tables (pdverify/study/tables.py), by the part of the work that writes them together
    "convergence": _write_convergence,  # convergence.csv/.parquet and benchmarks.csv
    "locking": lambda study, out, rows, memo: _save_rows(locking_rows(rows, memo), out, "locking"),
    "speed_error": _write_speed_error,  # speed_error.csv/.parquet and speed_error_summary.csv
    "trust": lambda study, out, rows, memo: _save_rows(trust_rows(rows, memo=memo), out, "trust", parquet=False),
}
RECORDER_WRITES = tuple(DERIVED)  # by a serial run's recorder (computed along the way); the runner writes results


def write_derived(study: Study, out: Path, results, parts=tuple(DERIVED), memo: dict | None = None) -> None:
    """The derived tables (``parts`` of :data:`DERIVED`: all by default) from the results (a DataFrame, or
    its rows as dicts with None for a missing value). ``memo``: groups already computed (tables.Groups)."""
    rows = rows_of(results) if isinstance(results, pd.DataFrame) else results
    for name in parts:
        DERIVED[name](study, out, rows, memo)


def write_tables(study: Study, out: Path, rows: list[dict], wall: float, resumed: int,
                 mismatched: list[str] | None = None, timing: dict | None = None, derived=None,
                 env: dict | None = None, table=None) -> None:
    """results (:func:`write_results` from ``rows``, or ``table`` when built already) and the derived
    tables (:func:`write_derived`; or, when ``derived`` is given, those not in :data:`RECORDER_WRITES`, then
    ``derived()`` waits for the process that writes those and returns timings to record); then study.toml
    and meta.json, last (``env``: :func:`environment`, when read elsewhere). ``timing`` (from
    :func:`run_study`): where the run's time went; meta.json adds the tables' own time."""
    t_tables = time.perf_counter()
    write_results(study, out, rows, table)
    if derived is None:
        write_derived(study, out, rows)
    else:  # the other process writes RECORDER_WRITES meanwhile
        write_derived(study, out, rows, [k for k in DERIVED if k not in RECORDER_WRITES])
        timing = {**(timing or {}), "runner_tables_s": time.perf_counter() - t_tables, **derived()}
    shutil.copyfile(study.path, out / "study.toml")
    meta = {"study": study.name, "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "pdverify": __version__,
            **(env or environment()), "cpu_count": os.cpu_count(), "wall_s": wall, "resumed_cases": resumed,
            "counts": dict(Counter(r.get("status") for r in rows).most_common()),  # (pandas' value_counts: ~15 ms
            "skipped": study.skipped, "code": code_digest(),                      # on its first call in a process)
            "cases_from_other_code": mismatched or []}
    if timing is not None:
        meta["timing"] = {**timing, "tables_s": time.perf_counter() - t_tables}
    write_atomic(out / "meta.json", json.dumps(meta, indent=2, default=str))
