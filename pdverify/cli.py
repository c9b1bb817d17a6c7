"""Command line: ``pdverify solve | models | ...``.

Every user error is printed as ``error: <one line>`` on stderr with exit code 2 (3 for a failed
computation), never a traceback.
"""

from __future__ import annotations

import functools
from collections import Counter
import sys
from enum import Enum
from pathlib import Path
from typing import Optional

import typer

from . import __version__
from .errors import InputError, PdverifyError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="pdverify: how far a peridynamic beam model is from the truth, in numbers.",
)


def _fail(exc: PdverifyError) -> None:
    for line in exc.lines:
        typer.echo(f"error: {line}", err=True)
    raise typer.Exit(exc.exit_code)


def user_errors(fn):
    """Turn PdverifyError into one line per problem and a non-zero exit code."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except PdverifyError as exc:
            _fail(exc)

    return wrapper


class Format(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


def parse_options(pairs: list[str] | None) -> dict:
    """``key=value`` strings from ``--option`` into a dict (values stay strings; models coerce)."""
    out = {}
    for item in pairs or []:
        if "=" not in item:
            raise InputError(f"--option {item!r}: write key=value")
        k, v = item.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def _table(result) -> str:
    cols = result.columns()
    names = list(cols)
    lines = [f"# scene: {result.scene}   model: {result.model}   dofs: {result.dofs}   version: {result.version}"]
    lines.append("# parameters: " + ", ".join(f"{k}={v}" for k, v in result.parameters.items()))
    lines.append("# timings: " + ", ".join(f"{k}={v:.4g}" for k, v in result.timings.items()))
    for k, v in result.info.items():
        if not isinstance(v, (list, dict)):
            lines.append(f"# {k}: {v}")
    lines += [f"# {w}" for w in result.warning_lines()]
    lines.append("".join(f"{n:>16}" for n in names))
    n = len(cols["x"])
    for i in range(n):
        lines.append("".join(f"{float(cols[c][i]):16.8g}" for c in names))
    return "\n".join(lines) + "\n"


@app.command()
@user_errors
def solve(
    scene: Path = typer.Argument(..., help="scene TOML file"),
    model: str = typer.Option(..., "--model", "-m", help="model name (see `pdverify models`)"),
    points: Optional[int] = typer.Option(None, help="material points / nodes along the axis, ends included"),
    spacing: Optional[float] = typer.Option(None, help="grid spacing in metres (instead of --points)"),
    horizon: Optional[float] = typer.Option(None, help="horizon as a multiple of the spacing (3 = the papers' 3.015)"),
    degree: Optional[int] = typer.Option(None, help="PD-function degree (models that have one)"),
    variant: Optional[str] = typer.Option(None, help="model variant, e.g. paper | corrected"),
    element: Optional[str] = typer.Option(None, help="element type of a FEM reference, e.g. q4 | q8 | q9"),
    layers: Optional[int] = typer.Option(None, help="elements through the thickness (plane-stress reference)"),
    form: Optional[str] = typer.Option(None, help="equation form of a model, e.g. primal | mixed"),
    option: Optional[list[str]] = typer.Option(None, "--option", "-o", help="any other model option, key=value"),
    fmt: Format = typer.Option(Format.table, "--format", help="output format"),
    out: Optional[Path] = typer.Option(None, "--out", help="write the output here instead of stdout"),
    tolerance: Optional[float] = typer.Option(None, "--tolerance", help="with --model auto: accepted relative error"),
):
    """Solve one scene with one model and print the point results (--model auto: see `advise`)."""
    from .registry import get_model, run
    from .scene import load_scene

    sc = load_scene(scene)  # before the models are imported: a bad scene fails fast
    given = dict(points=points, spacing=spacing, horizon=horizon, degree=degree, variant=variant,
                 element=element, layers=layers, form=form)
    given.update(parse_options(option))
    if model == "auto":
        from .advise import advise as _advise

        if tolerance is None:
            raise InputError("--model auto needs --tolerance (relative error you can accept, e.g. 1e-3)")
        choice = _advise(sc, tolerance).choice
        typer.echo(f"auto: {choice.model} --points {choice.points} (estimated error {choice.estimate:.2e})", err=True)
        model = choice.model
        given = dict(choice.options, points=choice.points)
    m = get_model(model)
    result = run(sc, m, **given)
    if out is not None and out.suffix in result.writers:
        result.writers[out.suffix](str(out))
        typer.echo(f"wrote {out}", err=True)
        return
    for w in result.warning_lines():  # on stderr too, whatever the format
        typer.echo(w, err=True)
    text = {Format.json: result.to_json, Format.csv: result.to_csv, Format.table: lambda: _table(result)}[fmt]()
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text if text.endswith("\n") else text + "\n")
        typer.echo(f"wrote {out}", err=True)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


@app.command("models")
@user_errors
def list_models():
    """List the available models, their options and source papers."""
    from .registry import models

    for name, m in models().items():
        opts = ", ".join(f"{o.name}={o.default}" for o in m.options)
        typer.echo(f"{name:22s} {m.title}  [{opts}]")
        if m.source:
            typer.echo(f"{'':22s} source: {m.source}")


def _slug(name: str) -> str:
    import re

    return re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_") or "study"


@app.command()
@user_errors
def study(
    study_file: Path = typer.Argument(..., help="study TOML file"),
    out: Optional[Path] = typer.Option(None, "--out", help="output directory (default reports/<study file stem>)"),
    workers: Optional[int] = typer.Option(None, "--workers", help="local worker processes (default: all cores)"),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Dask scheduler address tcp://HOST:PORT"),
    report: bool = typer.Option(False, "--report", help="also write the HTML report into the output directory"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
):
    """Run a study: every case of the sweep, errors against the reference, derived tables."""
    from .study import load_study, run_study

    spec = load_study(study_file)
    out = out or Path("reports") / _slug(study_file.stem)
    df = run_study(spec, out, workers=workers, scheduler=scheduler, progress=not quiet)
    counts = dict(Counter(df["status"]).most_common())  # (pandas' value_counts: ~15 ms on its first call)
    typer.echo(f"{spec.name}: {len(df)} cases ({counts}); results in {out}/results.csv", err=True)
    for _, r in df[df["status"] != "ok"].iterrows():
        typer.echo(f"failed: {r['model']} on {r['scene_file']}: {r['message']}", err=True)
    if report:
        from .report import build_report

        index = build_report(out)
        typer.echo(f"report: {index}")


@app.command()
@user_errors
def advise(
    scene: Path = typer.Argument(..., help="scene TOML file"),
    tolerance: float = typer.Option(1e-3, "--tolerance", help="relative error you can accept"),
    budget: float = typer.Option(30.0, "--budget", help="seconds per candidate model for the grid search"),
):
    """Pick the cheapest model and grid that reach the tolerance on this scene (with the estimate)."""
    from .advise import advise as _advise
    from .advise import format_advice
    from .scene import load_scene

    typer.echo(format_advice(_advise(load_scene(scene), tolerance, budget)))


@app.command()
@user_errors
def report(
    study_dir: Path = typer.Argument(..., help="a study output directory (holds results.csv)"),
    out: Optional[Path] = typer.Option(None, "--out", help="write the report here (default: the study directory)"),
):
    """Turn a study's results into a self-contained HTML report (index.html)."""
    from .report import build_report

    typer.echo(f"report: {build_report(study_dir, out)}")


@app.command()
@user_errors
def bench(
    model: Optional[list[str]] = typer.Option(None, "--model", "-m", help="model(s) to time; default: all with an assembled system"),
    points: Optional[list[int]] = typer.Option(None, "--points", help="sizes; default 1e3 1e4 1e5 1e6 (1e5 max for 4-DOF/PDDO models)"),
    fmt: Format = typer.Option(Format.table, "--format", help="table, or json (one object per line)"),
    scene: Optional[Path] = typer.Option(None, help="scene to time (default: the example cantilever)"),
    out: Optional[Path] = typer.Option(None, "--out", help="also write DIR/bench.jsonl and the performance page DIR/index.html"),
):
    """Time assembly and solve against the banded-solve limit of the same matrix, per model and size."""
    import json as _json

    from .bench import DEFAULT_POINTS, SMALL_MODELS, accurate, bench_subprocess, cost_slope, default_models
    from .registry import get_model

    names = model or default_models()
    for n in names:
        get_model(n)
    rows = []
    for n in names:
        sizes = points or [p for p in DEFAULT_POINTS if p <= SMALL_MODELS.get(n, 10**9)]
        for p in sizes:
            row = bench_subprocess(n, p, str(scene) if scene else None)
            rows.append(row)
            if fmt == Format.json:
                typer.echo(_json.dumps(row))
            elif row.get("status") != "ok":
                typer.echo(f"{n:18s} {p:>9d}  failed: {row.get('message')}")
            else:
                f = lambda v, spec: "-" if v is None else format(v, spec)  # noqa: E731
                typer.echo(
                    f"{n:18s} {p:>9d} dofs={row['dofs']:>9d} error={f(row.get('max_error'), '.1e')} "
                    f"assemble={f(row['assemble_s'], '.3g')}s "
                    f"solve={f(row['solve_s'], '.3g')}s total={row['total_s']:.3g}s limit={f(row['limit_s'], '.3g')}s "
                    f"ratio={f(row['ratio'], '.2f')} mem={row['peak_mem_mb']:.0f}MB "
                    f"updates/s={f(row['updates_per_s'], '.3g')}"
                    + ("" if accurate(row) else "  (error above 1e-6 or unknown: counts toward no target)")
                )
    slopes = cost_slope(rows)
    for n, s in slopes.items():
        line = {"model": n, "cost_slope": s}
        typer.echo(_json.dumps(line) if fmt == Format.json else f"{n:18s} cost ~ N^{s:.2f}")
    if out:
        from .report.perf import build_performance

        page = build_performance(rows, out, slopes)
        if fmt != Format.json:
            typer.echo(f"performance page: {page}")


@app.command()
def version():
    """Print the package version."""
    typer.echo(__version__)


def main():  # console-script entry point
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
