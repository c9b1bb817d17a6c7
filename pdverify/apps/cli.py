"""Command line: ``pdverify solve | models | ...``.

Every user error is printed as ``error: <one line>`` on stderr, never a traceback. Exit codes (docs/cli.md):
0 done, 1 a study's verdicts failed, 2 bad input (scene, study, option, file), 3 failed or refused
computation (singular, overflow, not enough memory), 4 output could not be written.

Each command is a thin typer function over the library (solve, study, report, verify, advise, bench, models,
modes); they share the option parsing and the error wrapping of :mod:`.cliargs` and the output paths of
:mod:`.output`; `bench` lives in :mod:`.bench_command`.
Imports are lazy: each command imports what it runs, so ``pdverify --help`` starts without importing the library.
"""

from __future__ import annotations

import os
import shlex
import sys
from pathlib import Path

import typer

from ..core.errors import InputError, OutputError
from ..core.version import __version__
from .bench_command import bench
from .cliargs import (
    _SCENE_FILES,
    HORIZON,
    HORIZON_LENGTH,
    POINTS,
    auto_options,
    given_file,
    given_path,
    grid_options,
    parse_options,
    positive,
    prepared,
    user_errors,
)
from .output import Format, check_apart, check_folder, check_writable, with_warnings, write_file
from .output import out_format as _out_format
from .output import result_table as _table

# One BLAS thread per process, unless the user sets otherwise: pdverify's matrices are banded or small and its
# parallelism is processes (--workers, a Dask cluster). A threaded BLAS spreading each small product over the cores
# competes with those processes and with the machine's other work, and on a loaded machine is slower than one
# thread. Set before numpy is first imported: the commands import it lazily.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

# what a study writes into its --out (pdverify/study/derived.py, the report): a --junit there would replace one
STUDY_FILES = tuple(
    f"{t}.{e}" for t in ("results", "convergence", "locking", "speed_error") for e in ("csv", "parquet")
) + ("speed_error_summary.csv", "trust.csv", "benchmarks.csv", "checks.csv", "nonlocal.csv", "meta.json", "scenes.json",
     "study.toml", ".pdverify.lock")  # fmt: skip

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
    help="pdverify: how far a peridynamic beam model is from the truth, in numbers.",
)


def _show_version(value: bool):
    if value:
        typer.echo(f"pdverify {__version__}")
        raise typer.Exit(0)


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", "-V", callback=_show_version, is_eager=True, help="print the version and exit"
    ),
):
    """pdverify: how far a peridynamic beam model is from the truth, in numbers."""


@app.command()
@user_errors
def solve(
    scene: Path = typer.Argument(..., help="scene TOML file"),
    model: str = typer.Option(..., "--model", "-m", help="model name (see `pdverify models`)"),
    points: str | None = POINTS,
    spacing: float | None = typer.Option(None, help="grid spacing in metres (instead of --points)"),
    horizon: float | None = HORIZON,
    horizon_length: float | None = HORIZON_LENGTH,
    degree: int | None = typer.Option(None, help="PD-function degree (models that have one)"),
    variant: str | None = typer.Option(None, help="model variant, e.g. paper | corrected"),
    element: str | None = typer.Option(None, help="element type of a FEM reference, e.g. q4 | q8 | q9"),
    layers: int | None = typer.Option(None, help="elements through the thickness (plane-stress reference)"),
    form: str | None = typer.Option(None, help="equation form of a model, e.g. primal | mixed"),
    option: list[str] | None = typer.Option(
        None,
        "--option",
        "-o",
        help="any other model option, key=value; static=true: the static part of a scene with \\[dynamics]",
    ),
    fmt: Format | None = typer.Option(
        None, "--format", help="output format (default: from the --out extension .csv/.json/.txt, else table)"
    ),
    out: Path | None = typer.Option(
        None, "--out", parser=given_file("result.csv"), help="write the output here instead of stdout"
    ),
    tolerance: float | None = typer.Option(None, "--tolerance", help="with --model auto: accepted relative error"),
    estimate: bool = typer.Option(
        False, "--estimate", help="also solve two nested grids and print a Richardson estimate of the error"
    ),
):
    """Solve one scene with one model and print the point results (--model auto: see `advise`)."""
    from ..core.scene_file import load_scene
    from ..registry import as_flag, get_model, run

    fmt = _out_format(out, fmt)
    if out is not None:
        check_writable(out, "--out")
    sc = load_scene(scene)  # before the models are imported: a bad scene fails fast
    _SCENE_FILES[:] = [sc]
    given = grid_options(
        parse_options(option),
        points=points,
        spacing=spacing,
        horizon=horizon,
        horizon_length=horizon_length,
        degree=degree,
        variant=variant,
        element=element,
        layers=layers,
        form=form,
    )
    model = "auto" if model.strip().lower() == "auto" else model
    auto_options(model, tolerance, given)  # --tolerance and --model auto, and what auto leaves out
    if model == "auto":
        from .advise import advise as _advise

        choice = _advise(sc, tolerance, static=as_flag(given.get("static", False))).choice
        of = get_model(choice.model).measures
        typer.echo(
            f"auto: {choice.model} --points {choice.points} (estimated error of {of} {choice.estimate:.2e})", err=True
        )
        model = choice.model
        given = dict(choice.options, points=choice.points, static=given.get("static", False))
    from ..measure.memory import check_memory
    from ..registry import model_argument, model_options

    m = get_model(model_argument(model))  # a manifest path registers its external model first
    has_continuum = "continuum_m" in given and m.option("continuum") is not None
    if has_continuum and not m.resolve(sc, model_options(given)).get("continuum"):
        raise InputError(  # a study's runs give it for the continuum that splits their errors; a solve has none
            f"continuum_m = {given['continuum_m']}: sets the levels of the continuum, which a solve computes with "
            "continuum = true only; add -o continuum=true or drop continuum_m"
        )
    check_memory(sc, m, given)
    if estimate:
        from ..measure.richardson import with_estimate

        result = with_estimate(sc, m, given, run)
    else:
        result = run(sc, m, **given)
    for w in result.warning_lines():  # on stderr too, whatever the format or file
        typer.echo(w, err=True)
    if out is not None and out.suffix in result.writers:
        write_file(out, with_warnings(result, out.suffix), "--out")
        typer.echo(f"wrote {shlex.quote(str(out))}", err=True)  # a name ending in a space shows it
        return
    text = {Format.json: result.to_json, Format.csv: result.to_csv, Format.table: lambda: _table(result)}[fmt]()
    if out is not None:
        text = text if text.endswith("\n") else text + "\n"
        write_file(out, lambda path: Path(path).write_text(text, encoding="utf-8"), "--out")
        typer.echo(f"wrote {shlex.quote(str(out))}", err=True)  # a name ending in a space shows it
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


@app.command()
@user_errors
def modes(
    scene: Path = typer.Argument(..., help="scene TOML file (its supports, section and material; density needed)"),
    model: str = typer.Option(..., "--model", "-m", help="a model with a mass operator: pd-rod, pd-timoshenko, ..."),
    points: str | None = POINTS,
    horizon: float | None = HORIZON,
    horizon_length: float | None = HORIZON_LENGTH,
    option: list[str] | None = typer.Option(None, "--option", "-o", help="model option, key=value (repeatable)"),
    count: int = typer.Option(5, "--count", help="how many modes, lowest first"),
    fmt: Format = typer.Option(Format.table, "--format", help="table | json | csv"),
):
    """The first natural frequencies of a model's discrete operator against the analytic ones, with the
    relative error per mode (rod and torsion bar: closed form; Timoshenko and Euler-Bernoulli beams: their
    characteristic determinants)."""
    from ..core.scene_file import load_scene
    from ..measure.modes import modes as _modes

    sc = load_scene(scene)
    _SCENE_FILES[:] = [sc]
    given = grid_options(parse_options(option), points=points, horizon=horizon, horizon_length=horizon_length)
    from ..measure.memory import check_memory
    from ..registry import get_model, model_argument

    check_memory(sc, get_model(model_argument(model)), given)
    table = _modes(sc, model, given, count)
    for w in table.warnings:
        typer.echo(f"warning: {w}", err=True)
    text = {Format.json: table.to_json, Format.csv: table.to_csv, Format.table: table.to_table}[fmt]()
    sys.stdout.write(text if text.endswith("\n") else text + "\n")


@app.command("models")
@user_errors
def list_models():
    """List the available models, their options and source papers."""
    from ..registry import models

    for name, m in models().items():
        opts = ", ".join(f"{o.name}={o.default}" for o in m.options)
        typer.echo(f"{name:22s} {m.title}  [{opts}]")
        if m.source:
            typer.echo(f"{'':22s} source: {m.source}")
        c = m.capabilities()
        typer.echo(
            f"{'':22s} solves: {'/'.join(c['analyses'])}, {'/'.join(c['axes'])} axes; supports "
            f"{', '.join(c['supports'])}; loads {', '.join(c['load_types'])}; sections {', '.join(c['shapes'])}"
            + (f"; materials {', '.join(c['materials'])}" if c["materials"] else "")
            + ("; load paths" if c["load_path"] else "")
        )


def _slug(name: str) -> str:
    import re

    return re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_") or "study"


@app.command()
@user_errors
def study(
    study_file: Path = typer.Argument(..., help="study TOML file"),
    out: Path | None = typer.Option(
        None, "--out", parser=given_path, help="output directory (default reports/<study file stem>)"
    ),
    workers: int | None = typer.Option(
        None, "--workers", help="local worker processes, 1 or more (default: all cores; 1: in this process)"
    ),
    scheduler: str | None = typer.Option(
        None,
        "--scheduler",
        help="Dask scheduler address tcp://HOST:PORT (connect timeout 5 s; exit 2 when none is reached)",
    ),
    report: bool = typer.Option(False, "--report", help="also write the HTML report into the output directory"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
    junit: Path | None = typer.Option(
        None, "--junit", parser=given_file("junit.xml"), help="also write the verdicts as JUnit XML to FILE"
    ),
):
    """Run a study: every case of the sweep, errors against the reference, derived tables, verdicts. The output
    folder is locked while the run uses it and holds one study (exit 4 otherwise: see docs/studies.md).

    Exit status (docs/ci.md), the last line on stderr is the summary:
    0 every benchmark and order check passes (an expected-fail row that fails counts) and every case ran;
    1 a benchmark or check fails or is missing, or a case failed outside an expected-fail row;
    2 bad input; 3 a failed computation; 4 output could not be written, or the folder is in use.
    """
    from .pipeline import load_study, run

    if workers is not None and workers < 1:  # an option is checked before the files it applies to
        raise InputError(f"--workers {workers}: give a whole number of processes, 1 or more")
    spec = load_study(study_file)
    out = out or Path("reports") / _slug(study_file.stem)
    check_folder(out, "--out")
    if junit is not None:
        check_writable(junit, "--junit")
        check_apart(junit, out, STUDY_FILES, ("cases", "histories", "verify", "vtu"))
    done = run(
        spec,
        out,
        workers=workers,
        scheduler=scheduler,
        progress=not quiet,
        report=report,
        junit=junit,
        echo=lambda line: typer.echo(line, err=True),
    )
    if done.report is not None:
        typer.echo(f"report: {done.report}")
    typer.echo(done.summary, err=True)
    raise typer.Exit(done.exit_code)


@app.command()
@user_errors
def advise(
    scene: Path | None = typer.Argument(None, help="scene TOML file"),
    tolerance: float = typer.Option(1e-3, "--tolerance", help="relative error you can accept"),
    budget: float = typer.Option(30.0, "--budget", help="seconds per candidate model for the grid search"),
    static: bool = typer.Option(False, "--static", help="a scene with \\[dynamics]: advise on its static part"),
    rebuild_priors: bool = typer.Option(
        False, "--rebuild-priors", help="regenerate pdverify/data/advisor_priors.json (a small study)"
    ),
):
    """Pick the cheapest model and grid that reach the tolerance on this scene (with the estimate)."""
    from ..core.scene_file import load_scene
    from .advise import advise as _advise
    from .advise import format_advice
    from .priors import PRIORS
    from .priors import rebuild_priors as _rebuild

    if rebuild_priors:
        data = _rebuild()
        typer.echo(f"wrote {PRIORS}: {len(data['series'])} series, code digest {data['code_digest']}")
        return
    positive("--tolerance", tolerance)
    positive("--budget", budget)
    if scene is None:
        raise InputError("scene: give a scene file (or --rebuild-priors)")
    sc = load_scene(scene)
    _SCENE_FILES[:] = [sc]
    typer.echo(format_advice(_advise(sc, tolerance, budget, static=static)))


@app.command()
@user_errors
def report(
    study_dir: Path = typer.Argument(..., help="a study output directory (holds results.csv)"),
    out: Path | None = typer.Option(
        None, "--out", parser=given_path, help="write the report here (default: the study directory)"
    ),
):
    """Turn a study's results into a self-contained HTML report (index.html)."""
    from ..report import build_report

    if out is not None:
        check_folder(out, "--out")
        check_writable(out / "index.html", "--out")
    typer.echo(f"report: {build_report(study_dir, out)}")


@app.command("verify")
@user_errors
def verify_cmd(
    model: str = typer.Argument(..., help="model name, or path to an external model's manifest (.toml)"),
    horizon: float | None = HORIZON,
    horizon_length: float | None = HORIZON_LENGTH,
    option: list[str] | None = typer.Option(None, "--option", "-o", help="model option, key=value (repeatable)"),
    out: Path | None = typer.Option(
        None, "--out", parser=given_path, help="output directory (default reports/verify/<model>)"
    ),
    full: bool = typer.Option(False, "--full", help="more and finer grids (slower)"),
    order: float | None = typer.Option(None, "--order", help="expected order (default: the model's, else 2)"),
    workers: int | None = typer.Option(None, "--workers", help="local worker processes (default: all cores)"),
    scheduler: str | None = typer.Option(None, "--scheduler", help="Dask scheduler address tcp://HOST:PORT"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
    junit: Path | None = typer.Option(
        None, "--junit", parser=given_file("junit.xml"), help="also write the checks as JUnit XML to FILE"
    ),
):
    """Run the verification suite on a model and write its report card (card.html, card.json, junit.xml).
    Exit code 1 when a check fails."""
    from ..registry import model_argument
    from ..verify import verify
    from ..verify.card import junit as card_junit

    name = model_argument(model)
    options = grid_options(parse_options(option), horizon=horizon, horizon_length=horizon_length)
    out = out or Path("reports") / "verify" / _slug(name + "".join(f"_{k}_{v}" for k, v in options.items()))
    check_folder(out, "--out")
    if junit is not None:
        check_writable(junit, "--junit")
        check_apart(junit, out, ("card.json", "card.html"), ("study", "suite"))
    card = verify(name, out, options, full=full, order=order, workers=workers, scheduler=scheduler, progress=not quiet)
    for c in card["checks"]:
        typer.echo(f"{c['verdict']:>5}  {c['check']}: {c['summary']}")
    if junit is not None:
        try:
            write_file(junit, lambda path: Path(path).write_text(card_junit(card), encoding="utf-8"), "--junit")
        except OutputError as exc:
            raise OutputError(f"{exc.lines[0]}; the card is in {out}") from None
        typer.echo(f"junit: {junit}", err=True)
    typer.echo(f"{card['model']}: {card['verdict']} (suite {card['suite_version']}); card: {out}/card.html")
    if card["verdict"] == "fail":
        raise typer.Exit(1)


app.command("bench")(user_errors(bench))


@app.command()
def version():
    """Print the package version."""
    typer.echo(__version__)


def main(argv: list[str] | None = None):  # console-script entry point
    """Run the CLI; a usage error (unknown option, bad value of an option) is one ``error:`` line, exit code 2."""
    try:  # typer >= 0.2x carries its own copy of click
        from typer._click import exceptions as click
    except ImportError:  # pragma: no cover - older typer: click itself
        from click import exceptions as click

    no_args = getattr(click, "NoArgsIsHelpError", ())  # click < 8.2 prints the help itself
    argv = list(sys.argv[1:] if argv is None else argv)
    command = typer.main.get_command(app)
    try:
        rv = command.main(args=prepared(command, argv), prog_name="pdverify", standalone_mode=False)
    except no_args as exc:
        text = exc.ctx.get_help() if exc.ctx is not None else ""  # typer's rich help prints itself, returns ""
        if text:
            typer.echo(text)
        sys.exit(2)
    except click.UsageError as exc:
        hint = f"; see `{exc.ctx.command_path} -h`" if exc.ctx is not None else ""
        typer.echo(f"error: {exc.format_message().replace('Value error, ', '').rstrip('.')}{hint}", err=True)
        sys.exit(2)
    except typer.Abort:
        typer.echo("error: aborted", err=True)
        sys.exit(130)
    except BrokenPipeError:  # stdout closed early (`pdverify solve ... | head`): stop quietly, as other tools do
        _closed_stdout()
    try:  # what is still buffered meets a reader that left (`pdverify models | head -1`)
        sys.stdout.flush()
    except BrokenPipeError:
        _closed_stdout()
    sys.exit(rv if isinstance(rv, int) else 0)


def _closed_stdout():
    """Exit 1 without a word when stdout's reader has gone (no flush of what is left at exit)."""
    import os

    os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    sys.exit(1)


if __name__ == "__main__":  # pragma: no cover
    main()
