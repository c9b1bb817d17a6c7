"""Order checks of a study file, and the verdict of a finished study (its exit code and summary line).

```toml
[[checks]]                          # the observed order of convergence of every matching series
name = "pd-eb corrected is second order"   # optional
model = "pd-eb"
variant = "corrected"               # filters: any option of the model, scene, slenderness
observed_order = { min = 1.9, max = 2.1 }  # min, max or both
expected = "fail"                   # optional: a known defect the check documents
```

A series is what the convergence table groups (tables.GROUP: scene, model, every option but the grid,
slenderness). Each series a check matches is one row of ``checks.csv``: its grids, errors, pairwise observed
orders and the least-squares order of the convergence table, which the bounds are applied to. A series with
fewer than three grids whose cases ran, or a check matching no series, is ``missing`` (a failure), unless the
check documents a defect (``expected = "fail"``) and the series' cases failed: then ``expected-fail``. A series
whose every error is below the round-off level (``metrics.ROUND_OFF_LEVEL``: the model reproduces the
solution) has no order to measure and passes with "exact to round-off", as ``pdverify verify`` judges it.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from pathlib import Path

import numpy as np
import pandas as pd

from ..core.errors import InputError
from ..core.result import QUANTITIES
from ..core.text import close_match
from ..measure.metrics import ROUND_OFF_LEVEL, log_slope
from ..registry import get_model
from .store import write_atomic
from .tables import GROUPINGS, grouped

CHECK_KEYS = {"name", "model", "observed_order", "expected", "scene", "slenderness", "quantity"}
FAILING = ("fail", "missing")  # verdicts that fail a study (exit 1)
MIN_GRIDS = 3


def finite_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def strict_type(option, value) -> str | None:
    """Why a study file's ``value`` cannot be model option ``option`` (None when it can): booleans only
    from true/false, numbers never from booleans or quoted text (TOML has these types; a coerced string or bool hides
    a typo)."""
    if option.kind is bool and not isinstance(value, bool):
        return f"{option.name} = {value!r}: give true or false"
    if option.kind in (int, float) and isinstance(value, bool):
        return f"{option.name} = {value!r}: give a number, not a boolean"
    if option.kind in (int, float) and isinstance(value, str):
        return f"{option.name} = {value!r}: write the number without quotes"
    return None


def meant_key(row, key: str) -> str | None:
    """The key of the table ``row`` that looks like a misspelt ``key`` it lacks (None: none, or ``row`` is no table)."""
    return close_match(key, row) if isinstance(row, dict) and key not in row else None


def misspelt(key: str, row_keys, model) -> str:
    """The line of a key of a study row (a run, benchmark or check) that is neither the row's own (``row_keys``) nor an
    option of ``model``: "did you mean" the one it looks like, else the model's options."""
    names = [o.name for o in model.options]
    close = close_match(key, [*row_keys, *names])
    if close:
        return f"unknown key '{key}'; did you mean '{close}'?"
    return f"model {model.name} takes no option '{key}'; it takes: {', '.join(names)}"


def option_filter_errors(model, filters: dict, where: str, row_keys=()) -> list[str]:
    """Errors of the option filters of a benchmark or check (keys the model's options, values of their type;
    ``row_keys``: the row's own keys, which a misspelt key may stand for)."""
    errors = []
    names = {o.name: o for o in model.options}
    for k, v in filters.items():
        opt = names.get(k)
        if opt is None:
            errors.append(f"{where}.{k}: {misspelt(k, row_keys, model)}")
            continue
        why = strict_type(opt, v)
        if why is None:
            try:
                opt.coerce(model.name, v)
            except InputError as exc:
                why = exc.lines[0]
        if why:
            errors.append(f"{where}.{why}")
    return errors


def validate_checks(checks, scenes, models: set, path) -> list[str]:
    """One error line per problem of the study's ``[[checks]]`` tables (``scenes``: the study's scene files,
    ``models``: the models its runs use)."""

    if not isinstance(checks, list):
        return [f"{path}: checks = {checks!r}: write [[checks]] tables"]
    errors = []
    for j, c in enumerate(checks):
        where = f"{path}: checks[{j}]"
        if not isinstance(c, dict) or not isinstance(c.get("model"), str):
            typo = meant_key(c, "model")
            errors.append(
                f"{where}: unknown key '{typo}'; did you mean 'model'?"
                if typo
                else f"{where}: model: missing; every check names a model of the study's runs"
            )
            continue
        if not models:  # no run parsed: the runs' own lines say why
            continue
        if c["model"] not in models:
            errors.append(
                f"{where}.model = {c['model']!r}: no run of the study uses it; runs: {', '.join(sorted(models))}"
            )
            continue
        if "name" in c and not (isinstance(c["name"], str) and c["name"]):
            errors.append(f"{where}.name = {c['name']!r}: give a text")
        if "quantity" in c and c["quantity"] not in QUANTITIES:
            errors.append(f"{where}.quantity = {c['quantity']!r}: give one of {', '.join(QUANTITIES)}")
        bounds = c.get("observed_order")
        if bounds is None and any(close_match(k, ["observed_order"]) for k in c if k not in CHECK_KEYS):
            pass  # a misspelt observed_order: its own line says so (option_filter_errors)
        elif not isinstance(bounds, dict) or not bounds or set(bounds) - {"min", "max"}:
            typo = (
                [(k, close_match(k, ["min", "max"], 0.6)) for k in bounds if k not in ("min", "max")]
                if isinstance(bounds, dict)
                else []
            )
            typo = [t for t in typo if t[1]]
            errors.append(
                f"{where}.observed_order.{typo[0][0]}: unknown key '{typo[0][0]}'; did you mean '{typo[0][1]}'?"
                if typo
                else f"{where}.observed_order = {bounds!r}: give a table {{min = 1.9}}, {{max = 2.1}} or both"
            )
        elif not all(finite_number(v) for v in bounds.values()):
            errors.append(f"{where}.observed_order = {bounds!r}: min and max are finite numbers")
        elif bounds.get("min", -math.inf) > bounds.get("max", math.inf):
            errors.append(f"{where}.observed_order = {bounds!r}: min is above max")
        if c.get("expected", "pass") not in ("pass", "fail"):
            errors.append(
                f"{where}.expected = {c['expected']!r}: pass (default) or fail (a known defect the check documents)"
            )
        if "scene" in c and c["scene"] not in scenes:
            errors.append(f"{where}.scene = {c['scene']!r}: not one of the study's scenes")
        if "slenderness" in c and not (finite_number(c["slenderness"]) and c["slenderness"] > 0):
            errors.append(f"{where}.slenderness = {c['slenderness']!r}: give a positive number of the sweep")
        if "points" in c or "spacing" in c:
            errors.append(f"{where}: a check is over every grid of a series; drop points/spacing")
            continue
        filters = {k: v for k, v in c.items() if k not in CHECK_KEYS}
        errors += option_filter_errors(get_model(c["model"]), filters, where, CHECK_KEYS)
    return errors


def _label(check: dict) -> str:
    if check.get("name"):
        return check["name"]
    filters = ", ".join(f"{k} = {v}" for k, v in check.items() if k not in ("name", "observed_order", "expected"))
    bounds = " and ".join(
        f"{'>=' if k == 'min' else '<='} {v:g}"
        for k, v in sorted(check["observed_order"].items(), key=lambda kv: kv[0] != "min")
    )
    return f"{filters}: observed order {bounds}"


def _matches(check: dict, key: tuple, rows: list[dict]) -> bool:
    scene, model, options, slenderness = key  # tables.GROUP
    if model != check["model"]:
        return False
    if "scene" in check and rows[0].get("scene_file") != check["scene"]:
        return False
    if "slenderness" in check and (slenderness is None or float(slenderness) != float(check["slenderness"])):
        return False
    have = json.loads(options or "{}")
    return all(k in have and have[k] == v for k, v in check.items() if k not in CHECK_KEYS)


def _fmt(values, spec=".4g") -> str:
    return " ".join(format(v, spec) for v in values)


def _series_row(check: dict, key: tuple, rows: list[dict]) -> dict:
    """One check applied to one series (the rows of its cases), its order from the convergence table's."""
    conv = GROUPINGS["convergence"].compute(key, rows)
    main = rows[0].get("quantity") or "w"
    quantity = check.get("quantity", main)  # another quantity than the model's own: its own errors and order
    conv = [c for c in conv if c["quantity"] == quantity]
    column = "err_max" if quantity == main else f"err_max_{quantity}"
    bounds = check["observed_order"]
    ok = sorted(
        (r for r in rows if r.get("status") == "ok" and r.get("spacing") is not None), key=lambda r: float(r["spacing"])
    )
    h = np.array([float(r["spacing"]) for r in ok])
    err = np.array([float(r[column]) if r.get(column) is not None else math.nan for r in ok])
    pairwise = [log_slope(h[i : i + 2], err[i : i + 2])[0] for i in range(len(ok) - 1) if h[i + 1] != h[i]]
    n_grids = len(np.unique(h))
    order = conv[0]["observed_order"] if conv else math.nan
    failed = [r for r in rows if r.get("status") != "ok"]  # failed, or suspect (round-off): not in the order
    not_ok = Counter(r.get("status") for r in failed)
    messages = [f"{', '.join(f'{n} {s}' for s, n in not_ok.items())} of its {len(rows)} cases"] if failed else []
    if n_grids < MIN_GRIDS and failed and check.get("expected") == "fail":  # the documented defect: cases fail
        result = "expected-fail"
        messages.insert(
            0, f"{n_grids} grid(s) with a result (an order needs {MIN_GRIDS}): its cases fail as documented"
        )
    elif n_grids < MIN_GRIDS:
        result = "missing"
        messages.insert(0, f"{n_grids} grid(s) with a result; an order needs at least {MIN_GRIDS}")
    elif len(err) and np.all(np.abs(err) < ROUND_OFF_LEVEL):  # also all-zero errors (no order either)
        result = verdict(True, check.get("expected", "pass"))
        messages.insert(0, f"exact to round-off (every error < {ROUND_OFF_LEVEL:g}): no order to measure")
    elif not math.isfinite(order):
        result = verdict(False, check.get("expected", "pass"))
        messages.insert(0, "no observed order (errors zero or not finite)")
    else:
        good = bounds.get("min", -math.inf) <= order <= bounds.get("max", math.inf)
        result = verdict(good, check.get("expected", "pass"))
    scene, model, options, slenderness = key
    return {
        "name": _label(check),
        "scene": scene,
        "scene_file": rows[0].get("scene_file"),
        "model": model,
        "options": options,
        "slenderness": slenderness,
        "quantity": quantity,
        "n_grids": n_grids,
        "points": " ".join(str(r.get("points")) for r in ok),
        "spacings": _fmt(h),
        "errors": _fmt(err, ".3e"),
        "pairwise_orders": _fmt(pairwise, ".3f"),
        "observed_order": order,
        "r2": conv[0]["r2"] if conv else math.nan,
        "min": bounds.get("min"),
        "max": bounds.get("max"),
        "expected": check.get("expected", "pass"),
        "verdict": result,
        "message": "; ".join(messages),
        "case_ids": " ".join(r["case_id"] for r in ok + failed),
    }


def verdict(ok: bool, expected: str) -> str:
    """pass / fail, or for a row that documents a known defect (expected = fail): 'expected-fail' when it
    still fails and 'unexpected-pass' when it no longer does (then the row's text needs a look)."""
    if expected == "fail":
        return "unexpected-pass" if ok else "expected-fail"
    return "pass" if ok else "fail"


BENCH_VALUES = ("name", "scene", "model", "target", "tolerance", "quantity", "position", "expected")


def _case_keys(r) -> dict:
    """What a benchmark or check can filter a results row on: its options, points and slenderness."""
    sl = r.get("slenderness")
    return dict(json.loads(r.get("options") or "{}"), points=r.get("points"), slenderness=None if pd.isna(sl) else sl)


def _missing(b: dict, opts: dict, have: list[dict]) -> str:
    """Why no case matches benchmark ``b``: the first filter no case of its scene and model has."""
    if not have:
        return f"no case of the sweep runs {b['model']} on {b['scene']}"
    for k, v in opts.items():
        values = sorted({h.get(k) for h in have}, key=str)
        if not any(h.get(k) == v for h in have):
            return f"no case of the sweep has {k} = {v!r} (it has {', '.join(map(repr, values))})"
    return "no case of the sweep has every option the row names"


def match_benchmark(b: dict, df: pd.DataFrame):
    """(the results row a benchmark reads, None), or (None, its verdict row) when no case of the sweep
    matches (``missing``, with the filter nothing has) or its case failed (``fail`` / ``expected-fail``, with
    the failure). Filters: every key not a value of the row (options, points, slenderness)."""
    opts = {k: v for k, v in b.items() if k not in BENCH_VALUES}
    cand = df[(df["scene_file"] == b["scene"]) & (df["model"] == b["model"])]
    have = [_case_keys(r) for _, r in cand.iterrows()]
    hit = cand.iloc[[i for i, h in enumerate(have) if all(k in h and h[k] == v for k, v in opts.items())]]
    ok = hit[hit["status"] == "ok"]
    if len(ok):
        return ok.iloc[0], None
    head = {"name": b["name"], "scene": b["scene"], "scene_file": b["scene"], "model": b["model"]}
    if hit.empty:
        return None, {**head, "verdict": "missing", "message": _missing(b, opts, have)}
    r = hit.iloc[0]
    return None, {
        **head,
        "scene": r["scene"],
        "verdict": verdict(False, b.get("expected", "pass")),
        "case_id": r["case_id"],
        "message": f"its case is {r['status']}: {r['message']}",
    }


def skipped_note(skipped: list) -> str:
    """What a missing benchmark or check row adds when the study skipped combinations (it may name one of them)."""
    return f"; the study skipped {len(skipped)} combinations its models refuse (meta.json: skipped)" if skipped else ""


def check_rows(checks: list[dict], rows: list[dict], skipped: list = ()) -> list[dict]:
    """The rows of ``checks.csv``: every check against every series it matches (results ``rows`` as dicts,
    None for a missing value), in the checks' order; a check matching no series is one ``missing`` row (``skipped``:
    the study's skipped combinations, which it may have named)."""
    series = grouped("convergence", rows, compute=lambda key, group: group)  # the convergence table's series
    out = []
    for check in checks:
        hits = [_series_row(check, key, group) for key, group in series if _matches(check, key, group)]
        out += hits or [
            {
                "name": _label(check),
                "model": check["model"],
                "scene_file": check.get("scene"),
                "min": check["observed_order"].get("min"),
                "max": check["observed_order"].get("max"),
                "expected": check.get("expected", "pass"),
                "verdict": "missing",
                "message": "no series of the sweep matches the check's model and filters" + skipped_note(skipped),
            }
        ]
    return out


def write_checks(study, out: Path, rows: list[dict]) -> None:
    """``checks.csv`` in the output folder (only for a study with checks), written atomically."""
    if study.checks:
        table = pd.DataFrame(check_rows(study.checks, rows, study.skipped))
        write_atomic(Path(out) / "checks.csv", table.to_csv(index=False))


# ---- a finished study's verdict ---------------------------------------------------------------------------


def _read(path: Path) -> pd.DataFrame:
    return pd.read_csv(path) if path.is_file() and path.stat().st_size > 1 else pd.DataFrame()


def _covers(filters: dict, r: dict) -> bool:
    """A results row belongs to an expected-fail benchmark or check (its failure is the documented defect)."""
    if r.get("model") != filters["model"] or ("scene" in filters and r.get("scene_file") != filters["scene"]):
        return False
    have, skip = _case_keys(r), {*BENCH_VALUES, "observed_order"}
    return all(k in have and have[k] == v for k, v in filters.items() if k not in skip)


class Outcome:
    """The verdict of a finished study, from its results and the benchmarks and checks tables its run wrote
    in ``out``: :attr:`exit_code` 0 (every benchmark and check passes, every case ran) or 1, and :meth:`line`."""

    def __init__(self, study, out: Path, results: pd.DataFrame):
        out = Path(out)
        self.study = study
        self.results = results
        self.benchmarks = _read(out / "benchmarks.csv") if study.benchmarks else pd.DataFrame()
        self.checks = _read(out / "checks.csv") if study.checks else pd.DataFrame()
        documented = [b for b in study.benchmarks if b.get("expected") == "fail"]
        documented += [c for c in study.checks if c.get("expected") == "fail"]
        rows = results.to_dict("records")
        self.failed_cases = [r for r in rows if r.get("status") == "failed"]
        self.unexcused = [r for r in self.failed_cases if not any(_covers(d, r) for d in documented)]

    def _verdicts(self, table: pd.DataFrame) -> Counter:
        return Counter(table["verdict"]) if "verdict" in table else Counter()

    @property
    def exit_code(self) -> int:
        bad = sum(self._verdicts(t)[v] for t in (self.benchmarks, self.checks) for v in FAILING)
        return 1 if bad or self.unexcused else 0

    def failures(self) -> list[str]:
        """One line per failing benchmark and check."""
        lines = []
        for _, b in self.benchmarks.iterrows():
            if b["verdict"] in FAILING:
                lines.append(f"{b['verdict']}: benchmark {b['name']!r}: {benchmark_message(b)}")
        for _, c in self.checks.iterrows():
            if c["verdict"] in FAILING:
                lines.append(f"{c['verdict']}: check {c['name']!r}: {check_message(c)}")
        return lines

    def line(self) -> str:
        status = Counter(self.results["status"]) if "status" in self.results else Counter()
        b, c = self._verdicts(self.benchmarks), self._verdicts(self.checks)
        n_c = sum(c.values())
        extra = lambda n: f", {n} unexpected-pass" if n else ""  # noqa: E731
        return (
            f"summary: cases {status['ok']} ok, {status['failed']} failed, {status['suspect']} suspect; "
            f"benchmarks {b['pass']} pass, {b['fail']} fail, {b['expected-fail']} expected-fail, "
            f"{b['missing']} missing{extra(b['unexpected-pass'])}; orders checked {n_c} "
            f"({c['pass']} pass, {c['fail']} fail, {c['expected-fail']} expected-fail, {c['missing']} missing"
            f"{extra(c['unexpected-pass'])}); exit {self.exit_code}"
        )


def _g(v) -> str:
    return "-" if v is None or (isinstance(v, float) and v != v) else f"{v:.6g}" if isinstance(v, float) else str(v)


def benchmark_message(b) -> str:
    """A benchmark row's numbers in one line: target, computed value, ratio, relative error, tolerance, case."""
    if b.get("verdict") == "missing" or pd.isna(b.get("computed")):
        msg = b.get("message")
        return (msg if isinstance(msg, str) and msg else "no case of the sweep matches") + (
            f" (case {b['case_id']})" if isinstance(b.get("case_id"), str) else ""
        )
    return (
        f"target {_g(b.get('target'))}, computed {_g(b.get('computed'))}, ratio {_g(b.get('ratio'))}, "
        f"relative error {_g(b.get('rel_error'))} (tolerance {_g(b.get('tolerance'))}), case {b.get('case_id')}"
    )


def check_message(c) -> str:
    """A check row in one line: observed order against its bounds, pairwise orders, grids, cases."""
    bounds = " and ".join(f"{s} {_g(c.get(k))}" for k, s in (("min", ">="), ("max", "<=")) if not pd.isna(c.get(k)))
    parts = [f"observed order {_g(c.get('observed_order'))} (required {bounds})"]
    if isinstance(c.get("pairwise_orders"), str):
        parts.append(f"pairwise {c['pairwise_orders']}")
    if isinstance(c.get("points"), str):
        parts.append(f"points {c['points']}")
    if isinstance(c.get("scene"), str):
        parts.append(f"scene {c['scene']!r}")
    if isinstance(c.get("message"), str) and c["message"]:
        parts.append(c["message"])
    if isinstance(c.get("case_ids"), str):
        parts.append(f"cases {c['case_ids']}")
    return "; ".join(parts)
