"""The tables a study writes from its rows: results (CSV and Parquet, written by Arrow), the derived
tables (convergence, locking, speed vs error, trust: pdverify/study/tables.py), the benchmark verdicts,
study.toml and meta.json.
"""

from __future__ import annotations

import json
import math
import os
import platform
import shutil
import time
from collections import Counter
from functools import lru_cache
from pathlib import Path

import numpy as np
import pandas as pd

try:  # imported with the runner (its one-time cost belongs to start-up, not to the first study's tables)
    import pyarrow as pa
    import pyarrow.csv as pa_csv
    import pyarrow.pandas_compat  # noqa: F401 - else imported by the first pa.array(..., from_pandas=True): 2-12 ms
    import pyarrow.parquet as pa_parquet
except ImportError:  # pragma: no cover - parquet is optional, the CSV tables are always written (by pandas)
    pa = None

from ..core.result import canonical, quantity_of
from ..core.version import __version__
from .checks import match_benchmark, skipped_note, write_checks
from .checks import verdict as _verdict
from .nonlocal_table import nonlocal_rows
from .spec import Study, code_digest
from .store import case_file, read_curve, write_atomic
from .tables import EMPTY_CONVERGENCE, convergence_rows, locking_rows, rows_of, speed_error_rows, trust_rows

TEXT_OPTIONS = ("variant", "element", "form")  # text options: a text column even when no case has them


def results_table(study: Study, rows: list[dict]):
    """The results as an Arrow table (:func:`_rows_table`): one row per case (``rows``, in the study's
    order), the study's name first, the text options text columns even when every value is missing; None
    without pyarrow or when a column's values are of mixed types (then pandas builds it: :func:`results_frame`)."""
    if not rows:
        return None
    missing = dict.fromkeys((c for c in MEASURED if not any(c in r for r in rows)), math.nan)  # every case failed
    return _rows_table([{"study": study.name, **r, **missing} for r in rows], ("study", *TEXT_OPTIONS))


def write_results(study: Study, out: Path, rows: list[dict], table=None) -> None:
    """results.csv and results.parquet from :func:`results_table` (``table``, when built already): the
    same bytes in every path, without a DataFrame's conversion."""
    table = table if table is not None else results_table(study, rows)
    if table is None:
        _save(results_frame(study, rows), out, "results")
        return
    _write(table, out, "results")


# the measured columns a results table always has (a study whose every case failed has them too, empty)
MEASURED = ("spacing", "err_max", "err_l2", "err_at_max", "w_at_max", "w_ref_at_max", "dofs", "total_s", "error_bound")


def results_frame(study: Study, rows: list[dict], table=None) -> pd.DataFrame:
    """The results DataFrame (what :func:`run_study` returns): :func:`results_table`'s (``table``, when built
    already) ``to_pandas`` (3.0-3.8 ms for 200 cases, 5.6-6.6 ms the first time in a process, against
    3.4-5.4 and 6.8-9.3 ms for pandas from the rows), else pandas' from the rows, the text options as
    pandas strings."""
    table = table if table is not None else results_table(study, rows)
    if table is not None:
        df = table.to_pandas()
    else:
        df = pd.DataFrame(rows)
        df.insert(0, "study", study.name)
        for col in TEXT_OPTIONS:
            if col in df:
                df[col] = df[col].astype("string")
    for col in MEASURED:  # every table has them, NaN where no case was measured (all failed)
        if col not in df:
            df[col] = np.nan
    return df


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
        return pa.table(
            {
                c: pa.array([r.get(c) for r in rows], pa.large_string() if c in text else None, from_pandas=True)
                for c in columns
            }
        )
    except (pa.ArrowException, TypeError, ValueError):
        return None


def _write(table, out: Path, name: str, parquet: bool = True) -> None:
    """``name``.csv and (``parquet``) ``name``.parquet from one Arrow table: Arrow's CSV writer is several times
    faster than pandas' ``to_csv`` (the tables are on a study's critical path). Arrow quotes every text value
    and writes an integral float without ``.0`` (``pandas.read_csv`` then reads such a column as integers); values
    are written exactly (shortest round-trip form)."""
    pa_csv.write_csv(table, out / f"{name}.csv")
    if parquet:
        pa_parquet.write_table(table, out / f"{name}.parquet")


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


def benchmark_table(study: Study, df: pd.DataFrame, conv: pd.DataFrame, cases_dir: Path | None = None) -> pd.DataFrame:
    """Verification rows. Default quantity: what the model is measured on (its deflection, pd-rod's u) at the
    point of largest reference value (``w_at_max``); with ``position`` (m along the axis) and optional
    ``quantity`` (w, rotation or a point field such as u, theta, M), the case's curve interpolated there (the
    case file holds it)."""
    rows = []
    for b in study.benchmarks:
        r, unmatched = match_benchmark(b, df)  # its case, or the row of a missing / failed case
        if unmatched is not None:
            if unmatched["verdict"] == "missing":
                unmatched = dict(unmatched, message=unmatched["message"] + skipped_note(study.skipped))
            rows.append(unmatched)
            continue
        target = b.get("target", r["w_ref_at_max"])
        scale, note = abs(target), ""
        computed = r["w_at_max"]
        measures = r.get("quantity") if isinstance(r.get("quantity"), str) else "w"  # what the row's errors are on
        quantity = b.get("quantity", measures)
        if "position" in b:
            path = case_file(cases_dir, r["case_id"]) if cases_dir else None
            c = read_curve(path) if path is not None else {}
            arr = quantity_of(c.get("w"), c.get("rotation"), c.get("fields", {}), quantity) if c else None
            if arr is None:
                rows.append(_missing(b, f"quantity {quantity!r} not among the case's outputs ({_outputs(c)})"))
                continue
            computed = float(np.interp(float(b["position"]), c["x"], arr))
            if "target" not in b:
                ref = c["w_ref"] if quantity == measures else c.get("references", {}).get(canonical(quantity))
                if ref is None:  # the reference gives none, or the case's run does not measure it
                    q = canonical(quantity)
                    gives_none = q in str(r.get("missing_quantities") or "").split()
                    why = f"the reference gives no {q}" if gives_none else f"the run of its case does not measure {q}"
                    why += "" if gives_none else f" (add {q} to its quantities)"
                    rows.append(_missing(b, why + "; give a target"))
                    continue
                target = float(np.interp(float(b["position"]), c["x"], ref))
                top = float(np.abs(ref).max())
                scale = abs(target)
                if scale <= ZERO_TARGET * top:  # zero to round-off (a moment at a pin): no relative error of it
                    scale = top
                    note = f"the reference's {quantity} is zero here to round-off ({target:.2g}): the error is "
                    note += f"relative to its largest value on the beam, {top:.3g}"
        rel = abs(computed - target) / scale if scale else float("nan")
        tol = b.get("tolerance", 0.01)
        order = float("nan")
        if not conv.empty:
            c = conv[
                (conv["scene"] == r["scene"])
                & (conv["model"] == r["model"])
                & (conv["options"] == r["options"])
                & (conv["slenderness"].fillna(-1) == (r["slenderness"] if pd.notna(r["slenderness"]) else -1))
            ]
            if len(c):
                order = c["observed_order"].iloc[0]
        rows.append(
            {
                "name": b["name"],
                "scene": r["scene"],
                "scene_file": b["scene"],
                "model": b["model"],
                "variant": r.get("variant"),
                "reference": r["reference"],
                "target": target,
                "computed": computed,
                "ratio": computed / target if target else float("nan"),
                "rel_error": rel,
                "err_max": r["err_max"],
                "tolerance": tol,
                "verdict": _verdict(rel <= tol, b.get("expected", "pass")),
                "quantity": quantity if "position" in b else f"{measures} at max",
                "position": b.get("position"),
                "observed_order": order,
                "case_id": r["case_id"],
                **({"message": note} if note else {}),
            }
        )
    return pd.DataFrame(rows)


ZERO_TARGET = 1e-9  # a reference value below this share of its largest is zero to round-off for a benchmark's
# relative error (far below the tolerances benchmarks give, 1e-6 and up)


def _missing(b: dict, message: str) -> dict:
    """A benchmark's row when its case gives it nothing to read: verdict missing, with why."""
    return {"name": b["name"], "scene": b["scene"], "model": b["model"], "verdict": "missing", "message": message}


def _outputs(curve: dict) -> str:
    """The names a benchmark's ``quantity`` can take on a case's curve: w, rotation and its fields."""
    names = [q for q in ("w", "rotation") if curve.get(q) is not None] + sorted(curve.get("fields", {}))
    return ", ".join(names) or "none"


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
    return {
        "python": platform.python_version(),
        "platform": platform.platform(),
        "machine": platform.machine(),
        "versions": package_versions(),
    }


def _write_convergence(study: Study, out: Path, rows: list[dict]) -> None:
    conv = convergence_rows(rows)
    if not conv and not any(r.get("status") == "ok" for r in rows):
        _save(pd.DataFrame(columns=EMPTY_CONVERGENCE), out, "convergence")  # the header: no case is ok
    else:
        _save_rows(conv, out, "convergence")
    if study.benchmarks:  # the verification rows quote the observed order
        _save(
            benchmark_table(study, pd.DataFrame(rows), pd.DataFrame(conv), out / "cases"),
            out,
            "benchmarks",
            parquet=False,
        )
    write_checks(study, out, rows)  # checks.csv: the study's order checks on the convergence series


def _write_speed_error(study: Study, out: Path, rows: list[dict]) -> None:
    se, summary = speed_error_rows(rows)
    _save_rows(se, out, "speed_error")
    _save_rows(summary, out, "speed_error_summary", parquet=False)


DERIVED = {  # the derived tables (pdverify/study/tables.py), by the part of the work that writes them together
    "convergence": _write_convergence,  # convergence.csv/.parquet and benchmarks.csv
    "locking": lambda study, out, rows: _save_rows(locking_rows(rows), out, "locking"),
    "speed_error": _write_speed_error,  # speed_error.csv/.parquet and speed_error_summary.csv
    "trust": lambda study, out, rows: _save_rows(trust_rows(rows), out, "trust", parquet=False),
    "nonlocal": lambda study, out, rows: _write_nonlocal(out, rows),  # nonlocal.csv: with split errors only
}


def _write_nonlocal(out: Path, rows: list[dict]) -> None:
    """nonlocal.csv (:mod:`.nonlocal_table`), when a row carries the split errors."""
    if any(r.get("err_disc") is not None for r in rows):
        _save_rows(nonlocal_rows(rows), out, "nonlocal", parquet=False)


def write_derived(study: Study, out: Path, results, parts=tuple(DERIVED)) -> None:
    """The derived tables (``parts`` of :data:`DERIVED`: all by default) from the results (a DataFrame, or
    its rows as dicts with None for a missing value)."""
    rows = rows_of(results) if isinstance(results, pd.DataFrame) else results
    for name in parts:
        DERIVED[name](study, out, rows)


def write_tables(
    study: Study,
    out: Path,
    rows: list[dict],
    wall: float,
    resumed: int,
    mismatched: list[str] | None = None,
    timing: dict | None = None,
    table=None,
) -> None:
    """results (:func:`write_results` from ``rows``, or ``table`` when built already) and the derived
    tables (:func:`write_derived`); then study.toml and meta.json, last. ``timing`` (from
    :func:`~.runner.run_study`): where the run's time went; meta.json adds the tables' own time and the
    runner's overhead (:func:`overhead`)."""
    t_tables = time.perf_counter()
    write_results(study, out, rows, table)
    write_derived(study, out, rows)
    shutil.copyfile(study.path, out / "study.toml")
    meta = {
        "study": study.name,
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "pdverify": __version__,
        **environment(),
        "cpu_count": os.cpu_count(),
        "wall_s": wall,
        "resumed_cases": resumed,
        "counts": dict(Counter(r.get("status") for r in rows).most_common()),
        "skipped": study.skipped,
        "code": code_digest(),
        "cases_from_other_code": mismatched or [],
    }
    if timing is not None:
        timing = {**timing, "tables_s": time.perf_counter() - t_tables}
        meta["timing"] = {**timing, **overhead(timing)}
    write_atomic(out / "meta.json", json.dumps(meta, indent=2, default=str))


def overhead(timing: dict) -> dict:
    """The runner's own time: the run's wall time (cases and tables) less the models' time shared among the
    processes that solved (``solver_s / workers``: perfect sharing, so with workers the figure also holds
    any imbalance between them and the pool's start-up); and that as a fraction of the wall time. Reported,
    not a target."""
    wall = timing.get("cases_s", 0.0) + timing.get("tables_s", 0.0)
    own = wall - timing.get("solver_s", 0.0) / max(1, timing.get("workers", 1))
    return {"runner_overhead_s": own, "runner_overhead_fraction": own / wall if wall > 0 else None}
