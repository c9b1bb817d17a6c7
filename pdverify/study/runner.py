"""Run a study: each case solved and measured (:func:`solve_case`, :func:`measure_case`) in this process, a process
pool or on a Dask cluster (execute.py), stored as soon as it finishes, atomically (outdir.py), so a run resumes where it
stopped; then the tables (derived.py)."""

from __future__ import annotations

import json
import operator
import os
import time
from contextlib import closing
from pathlib import Path

import numpy as np
import pandas as pd

from ..core.errors import InputError, OutputError, PdverifyError
from ..core.result import columns_csv
from ..core.version import __version__
from ..measure.metrics import errors
from ..measure.paths import peak_history
from ..measure.shapes import with_exact_shapes
from ..measure.status import case_status, reference_status
from ..numerics.timeint import ledger_columns
from ..registry import get_model, resolved
from . import execute, solves
from .derived import results_frame, results_table, write_tables
from .outdir import FolderLock, Keeper, claim, finished, output_error
from .progress import CaseProgress
from .reference import _reference_text, measured, reference_at, reference_bound, theory_gap_warning
from .spec import Case, Study, code_digest
from .split import continuum_at, split_errors
from .store import write_atomic
from .tables import trust_table  # noqa: F401 (re-exported)

PARAM_COLUMNS = ("variant", "points", "horizon", "horizon_length", "degree", "element", "layers", "form")


INFO_KEYS = ("horizon", "m", "cond", "error_bound", "load_steps", "history", "factorisation", "moment_curvature")
OWN_ESTIMATES = ("grid_estimate", "history_estimate")  # columns: the difference from the same run on half the points


def solve_case(case: Case, artefacts: str | None = None, case_id: str | None = None) -> dict:
    """The solving half of a case: the model's result reduced to what :func:`measure_case` reads (arrays
    and numbers), or ``{"failure": message, "timings": {"total_s": seconds}}``.
    Never raises. ``artefacts``: a folder for the model's own files (a plane-stress VTU and its PNG, time
    histories as CSV), named by ``case_id``: they are written here, where the model's writers live.
    A failure's seconds are its cost: meta.json counts them as the models' time, not the runner's."""
    t0 = time.perf_counter()
    try:
        result = solves.solve(case.scene_text, case.scene_file, case.slenderness, case.model, case.given)
        solved = {
            "x": np.asarray(result.x, "<f8"),
            "w": np.asarray(result.w, "<f8"),
            "rotation": None if result.rotation is None else np.asarray(result.rotation, "<f8"),
            "fields": {k: np.asarray(v, "<f8") for k, v in result.fields.items() if np.shape(v) == np.shape(result.x)},
            "timings": {k: result.timings.get(k) for k in ("assemble_s", "solve_s", "total_s")},
            "dofs": int(result.dofs),
            "info": {k: _plain_scalar(result.info[k]) for k in INFO_KEYS if k in result.info},
            **{k: result.info[k].get("difference") for k in OWN_ESTIMATES if k in result.info},
            "warnings": "; ".join(str(w) for w in result.info.get("warnings", [])),
        }
        if result.path:  # a load path: the load factor against the deflection at its peak point, for the report
            solved["load_path"] = peak_history(result.x, result.path)
        hist = result.info.get("history")
        if artefacts and isinstance(hist, dict) and "t" in hist:  # the time histories as CSV, for other tools
            hdir = Path(artefacts).parent / "histories"
            hdir.mkdir(parents=True, exist_ok=True)
            cols = {"t": hist["t"], **hist.get("series", {}), **ledger_columns(hist["t"], hist.get("energy", {}))}
            write_atomic(hdir / f"{case_id or case.case_id}.csv", columns_csv(cols))
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
    """A failed case's message: a PdverifyError's lines, a replayed failure's text, else the exception (a bug)."""
    if isinstance(exc, PdverifyError):
        return " ".join(exc.lines)
    if isinstance(exc, _Failed):
        return str(exc)
    return f"{type(exc).__name__}: {exc}"


def history_errors(case: Case, scene, hist) -> dict | None:
    """The errors of a case's time histories (every probe's translation, stacked) against a reference model
    that gives histories (``history_at(scene, params, probes, t)``: exact-modal-rod) at the case's own
    sample times, as :func:`~.metrics.errors` measures w; None when either has none."""
    if not isinstance(hist, dict) or "t" not in hist or scene.dynamics is None:
        return None
    ref = dict(case.reference)
    model = get_model(ref.pop("model"))
    if not model.histories:
        return None
    probes = list(scene.dynamics.probes) or [scene.length / 2]  # the integrators' default probe
    got = np.column_stack(list(hist["series"].values())[: len(probes)])  # translations first, then rotations
    want = model.history_at(scene, model.resolve(scene, ref), probes, np.asarray(hist["t"], float))
    return errors(got.ravel(), want.ravel())


def _plain_scalar(v):
    """A numpy scalar as the Python number it equals (pickling a numpy scalar pickles its dtype: ~20 us)."""
    return v.item() if isinstance(v, np.generic) else v


def _describe(case: Case, row: dict):
    """The columns of a case's row known before it is solved: its scene's name, its options as resolved by
    the model (``options``: all but the grid, the key of a convergence series). Returns (scene, options)."""
    scene = case.scene()
    row["scene"] = scene.name
    row["units"] = scene.units  # labels the report's axes (m or in)
    params = resolved(get_model(case.model), scene, case.given)
    row.update({k: params.get(k, row.get(k)) for k in PARAM_COLUMNS})
    # the option is the horizon factor; the horizon in length units is known once solved (a failed case has none)
    row["horizon_factor"], row["horizon"] = row.get("horizon"), None
    drop = {"points"} | ({"horizon"} if params.get("horizon_length") is not None else set())  # (derived from it)
    row["options"] = json.dumps({k: v for k, v in params.items() if k not in drop}, sort_keys=True)
    return scene, params


class _Failed(Exception):
    """A solve that failed, replayed where the case is measured so its row fills in as far as it would have."""


def measure_case(case: Case, solved: dict, case_id: str | None = None) -> dict:
    """The measuring half of a case: its row (parameters, errors against the reference at the model's
    points, timings, dofs, status) and its curves, from what :func:`solve_case` returned. Never raises: a
    failure is the row's status, and the row and curves are filled as far as the measuring went."""
    case_id = case_id or case.case_id
    row = _row_skeleton(case, case_id)
    curve: dict = {}
    try:
        scene, params = _describe(case, row)
        if "failure" in solved:
            raise _Failed(solved["failure"])
        w_ref = _measure_errors(case, scene, solved, row)
        split_errors(case, scene, solved, w_ref, row)
        references = _measure_quantities(case, scene, solved, row)
        _measure_status(case, solved, params, row)
        _fill_curves(curve, scene, solved, w_ref, row["quantity"])
        if references:  # the reference of each other quantity at the model's points: the report's error curves
            curve["references"] = references
    except Exception as exc:  # a failed solve replayed (_Failed), a bad case, a bug: recorded, never raised
        for k, v in (solved.get("timings") or {}).items():  # what the attempt cost, as far as it went
            row.setdefault(k, v)
        row["status"], row["message"] = "failed", _failure_message(exc)
    return {
        "case": {
            "scene_file": case.scene_file,
            "model": case.model,
            "given": case.given,
            "slenderness": case.slenderness,
            "reference": case.reference,
        },
        "row": row,
        "curve": curve,
    }


def _row_skeleton(case: Case, case_id: str) -> dict:
    """The row's columns known from the case alone: key, code, scene file, model, slenderness, reference, version,
    options as given."""
    row = {
        "case_id": case_id,
        "code": code_digest(),
        "scene_file": case.scene_file,
        "model": case.model,
        "slenderness": case.slenderness,
        "reference": _reference_text(tuple(sorted(case.reference.items()))),
        "version": __version__,
    }
    row.update({k: case.given.get(k) for k in PARAM_COLUMNS})
    return row


def _measure_errors(case: Case, scene, solved: dict, row: dict) -> np.ndarray:
    """Fill the row's measured quantity and its errors against the reference at the model's points (NaN with
    ``reference = "none"``; a transient against a transient reference: the errors of the histories); the
    reference's values at those points."""
    x, info = solved["x"], solved["info"]
    row["quantity"] = quantity = get_model(case.model).measures  # w, or a field (pd-rod: u)
    w = measured(solved, quantity, case.model)
    if case.reference.get("model") == "none":
        w_ref = np.full_like(x, np.nan)
        row.update(
            err_max=np.nan,
            err_l2=np.nan,
            err_at_max=np.nan,
            w_at_max=float(w[np.argmax(np.abs(w))]),
            w_ref_at_max=np.nan,
        )
        return w_ref
    w_ref = continuum_at(case, scene, x)[0] if case.reference.get("continuum") else reference_at(case, scene, x)
    row.update(errors(w, w_ref))
    hist_err = history_errors(case, scene, info.get("history"))
    if hist_err is not None:  # a transient against a transient reference: the histories, not the final w
        row.update(hist_err)
    return w_ref


def jumps(scene, x: np.ndarray, quantity: str) -> np.ndarray:
    """The points where ``quantity`` jumps (within 1e-9 of the length): the shear at point forces and at supports
    inside the span, the moment at couples and at inner clamped supports. There the value depends on the side a
    model reports, so an error there says nothing."""
    tol = 1e-9 * scene.length
    at = []
    for load in scene.loads:
        kind = getattr(load, "type", "")
        if (quantity == "shear" and kind == "point_force") or (quantity == "moment" and kind == "point_moment"):
            at.append(load.position)
        if quantity == "axial" and kind == "point_force" and getattr(load, "axial", 0.0):
            at.append(load.position)
    for s in scene.supports.inner:
        if (quantity == "shear" and s.holds_deflection) or (quantity == "moment" and s.holds_rotation):
            at.append(s.position)
    x = np.asarray(x, float)
    return np.any(np.abs(x[:, None] - np.asarray(at, float)[None, :]) <= tol, axis=1) if at else np.zeros(len(x), bool)


def _measure_quantities(case: Case, scene, solved: dict, row: dict) -> dict:
    """The errors of every other quantity the study measures (``quantities``: rotation, moment, shear, axial),
    ``err_max_<q>`` and ``err_l2_<q>`` (relative to the reference's largest value of that quantity), NaN where the
    model or the reference gives none (named in ``missing_quantities``). Returns the reference's values of each
    quantity measured, at the model's points."""
    main = row["quantity"]
    missing, references = [], {}
    for q in case.quantities:
        if q == main:
            continue
        row[f"err_max_{q}"] = row[f"err_l2_{q}"] = np.nan
        if case.reference.get("model") == "none":
            continue
        try:
            values = measured(solved, q, case.model)
            at = continuum_at if case.reference.get("continuum") else reference_at
            ref = np.asarray(
                at(case, scene, solved["x"], q)[0] if at is continuum_at else at(case, scene, solved["x"], q)
            )
        except (InputError, KeyError):
            missing.append(q)
            continue
        keep = ~jumps(scene, solved["x"], q)  # a jump's two values are both right there: not compared
        e = errors(values[keep], ref[keep])
        row[f"err_max_{q}"], row[f"err_l2_{q}"] = e["err_max"], e["err_l2"]
        references[q] = np.asarray(ref, "<f8")
    if missing:
        row["missing_quantities"] = " ".join(missing)
    return references


def _measure_status(case: Case, solved: dict, params: dict, row: dict) -> None:
    """Fill the row's timings, dofs, spacing, horizon (length units), condition number, status (``suspect`` when
    the model's or the reference's round-off bound is too large), message, warnings (also a reference theory's gap)."""
    x, info = solved["x"], solved["info"]
    row.update(solved["timings"])
    row["dofs"] = solved["dofs"]
    row["spacing"] = float(np.diff(x).max()) if len(x) > 1 else float("nan")
    row["horizon"] = info.get("horizon", (params["horizon"] * row["spacing"]) if params.get("horizon") else None)
    row["m"], row["cond"] = info.get("m"), info.get("cond")
    # the digest of the factorised operator: the cases with the same one in a process share its LU
    # (numerics/factorcache.py); whether this case made it or took it depends on the run's order, not recorded
    row["factorisation"] = info.get("factorisation")
    row.update({k: solved[k] for k in OWN_ESTIMATES if solved.get(k) is not None})
    row["status"], row["message"] = "ok", ""
    row.update(case_status(info, row.get("err_max", np.nan)))  # suspect: a bound that could decide it (trust.md)
    if case.reference.get("continuum"):  # ... or the reference's: the error is measured against it
        row.update(reference_status(continuum_at(case, case.scene(), x)[1], row, "continuum's error estimate"))
    elif case.reference.get("model") != "none":
        row.update(reference_status(reference_bound(case), row))
    gap = theory_gap_warning(case, x, row.get("err_max", np.nan))
    row["warnings"] = "; ".join(w for w in (solved.get("warnings", ""), gap) if w)
    if "artefact_message" in solved:
        row["artefact_message"] = solved["artefact_message"]


def _fill_curves(curve: dict, scene, solved: dict, w_ref: np.ndarray, quantity: str) -> None:
    """Fill ``curve`` in place: the model's points, deflection and reference of the measured quantity, rotation,
    point fields, a nonlinear path's load steps beside the exact shapes, a dynamic run's histories and energy."""
    info = solved["info"]
    # arrays stay arrays here (compact to pickle from a worker); encode_record stores them exactly
    # w_ref: the reference of the measured quantity (named by "quantity" when it is not w)
    curve.update({"x": solved["x"], "w": solved["w"], "w_ref": np.asarray(w_ref, "<f8")})
    if quantity != "w":
        curve["quantity"] = quantity
    if solved["rotation"] is not None:
        curve["rotation"] = solved["rotation"]
    if solved["fields"]:  # point fields (u, theta, N, Q, M ...): for positional benchmarks and other tools
        curve["fields"] = solved["fields"]
    if solved.get("load_path"):  # a load path's load factor against its peak deflection (measure/paths.py)
        curve["load_path"] = solved["load_path"]
    if "moment_curvature" in info:  # the section law a model's load path follows (pd-bond-pair's pairs)
        curve["moment_curvature"] = {k: np.asarray(v, "<f8") for k, v in info["moment_curvature"].items()}
    if "load_steps" in info:  # deformed shapes of a nonlinear path and the exact ones, for the report
        curve["load_steps"] = with_exact_shapes(scene, info["load_steps"])
    hist = info.get("history")
    if isinstance(hist, dict) and "t" in hist:  # time histories of a dynamic run: {"t": [...], "series": {...}}
        curve["history"] = {
            "t": np.asarray(hist["t"], "<f8"),
            "series": {k: np.asarray(v, "<f8") for k, v in hist.get("series", {}).items()},
            "ylabel": hist.get("ylabel", "displacement"),
        }
        if hist.get("energy"):  # the energy ledger (kinetic, strain, work, dissipation, balance)
            curve["history"]["energy"] = {k: np.asarray(v, "<f8") for k, v in hist["energy"].items()}


def run_case(case: Case, artefacts: str | None = None, case_id: str | None = None) -> dict:
    """Solve one case and measure it (:func:`solve_case`, :func:`measure_case`); a failure is a record, never raised.
    ``spent_s``: this process's seconds in the solve, what meta.json's ``solver_s`` adds up (a kept solve costs almost
    none again, though its row's ``total_s`` is that of its making)."""
    t0 = time.perf_counter()
    solved = solve_case(case, artefacts, case_id)
    return {**measure_case(case, solved, case_id), "spent_s": time.perf_counter() - t0}


def run_study(
    study: Study,
    out: Path,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = True,
    artefacts: bool = True,
) -> pd.DataFrame:
    """Run the study's cases not yet done in ``out`` (resumed from their case files), write every table and
    meta.json there; the results table. ``workers``: local processes (default: every core; 1 runs the
    cases in this process); ``scheduler``: a Dask scheduler's address (then ``workers`` is not used).
    Raises InputError for a bad ``workers`` or ``scheduler`` (exit 2), OutputError (exit 4; nothing stored
    is lost) when ``out`` cannot be written, is in use by another run or holds another study's results, or
    when a process solving cases dies. ``artefacts``: write the models' own files (plane-stress VTU and PNG, time
    histories as CSV) under ``out``; the verification suite's cases skip them."""
    workers = whole_workers(workers)
    if scheduler is not None:
        execute.check_scheduler(scheduler)
    out = Path(out)
    try:
        (out / "cases").mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise output_error(out, exc) from None
    lock = FolderLock(out)
    try:
        claim(out, study)
        return _run_study(study, out, workers, scheduler, progress, artefacts)
    except execute.BrokenProcessPool:  # a worker killed: the cases it solved before were stored here
        raise OutputError(
            f"a worker process ended abruptly (killed: out of memory, a signal); the cases "
            f"finished before are kept in {out / 'cases'}: run the study again to resume"
        ) from None
    except execute.ClusterLost as exc:
        raise OutputError(
            f"--scheduler {scheduler}: the Dask cluster lost a case ({exc}); the cases finished "
            f"before are kept in {out / 'cases'}: run the study again to resume"
        ) from None
    finally:
        lock.release()


def whole_workers(workers):
    """``workers`` as a number of processes (None: every core; numpy integers too); InputError (exit 2)
    unless a whole number of at least 1."""
    if workers is None:
        return None
    try:
        n = 0 if isinstance(workers, bool) else operator.index(workers)
    except TypeError:
        n = 0
    if n < 1:
        raise InputError(f"--workers {workers!r}: give a whole number of processes, 1 or more")
    return n


def _run_study(
    study: Study, out: Path, workers: int | None, scheduler: str | None, progress: bool, artefacts: bool = True
) -> pd.DataFrame:
    t0 = time.perf_counter()
    ids = [c.case_id for c in study.cases]  # hashed once: the key covers the scene text and the code digest
    done = finished(out / "cases", ids)  # case id -> row (the curves stay on disk)
    resumed = len(done)
    todo = list({cid: c for c, cid in zip(study.cases, ids) if cid not in done}.items())  # each id once
    todo_ids, todo_cases = [cid for cid, _ in todo], [c for _, c in todo]
    n = 1 if scheduler else min(workers or os.cpu_count() or 1, max(1, len(todo)))
    files = str(out / "vtu") if artefacts else None
    if scheduler and todo:
        loop = execute.on_dask(run_case, todo_cases, todo_ids, scheduler)
    else:
        groups, sizes = [c.operator_group for c in todo_cases], [c.size for c in todo_cases]
        order = [c.batch_order for c in todo_cases]
        if n > 1:
            loop = execute.pool(run_case, todo_cases, todo_ids, files, n, groups, sizes, order)
        else:
            loop = execute.serial(run_case, todo_cases, todo_ids, files, groups, sizes, order)
    keep = Keeper(out, code_digest())
    bar = CaseProgress(len(todo), progress)
    try:
        with closing(loop):  # closed on any way out: a pool's workers are ended
            for cid, rec in loop:
                bar.advance(failed=keep.add(rec, cid))
    finally:
        bar.close()
    done.update(keep.rows)
    rows = [done[cid] for cid in dict.fromkeys(ids)]
    table = results_table(study, rows)
    df = results_frame(study, rows, table)
    cases_s = time.perf_counter() - t0
    timing = {
        "cases_s": cases_s,
        "computed_cases": len(todo),
        "workers": n,
        "path": "dask" if scheduler else ("pool" if n > 1 else "serial"),
        **keep.clock,
    }
    try:
        write_tables(
            study, out, rows, table=table, wall=cases_s, resumed=resumed, mismatched=keep.mismatched, timing=timing
        )
    except OSError as exc:
        raise output_error(out, exc, "a table") from None
    return df
