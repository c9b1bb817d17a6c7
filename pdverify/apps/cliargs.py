"""What every command of the command line shares: one line per user error and its exit code
(:func:`user_errors`), the grid's options (``--points``, ``--horizon``, ``--horizon-length``) and ``-o key=value``
model options."""

from __future__ import annotations

import functools
import os
from pathlib import Path

import numpy as np
import typer

from ..core.errors import InputError, PdverifyError, SolveError
from ..core.text import PAST_RANGE


def _fail(exc: PdverifyError) -> None:
    for line in exc.lines:
        typer.echo(f"error: {line}", err=True)
    raise typer.Exit(exc.exit_code)


def user_errors(fn):
    """Turn PdverifyError into one line per problem and a non-zero exit code; a computation that runs out
    of memory or out of the floating-point range becomes one line and exit code 3."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        try:
            # numpy's own RuntimeWarnings are not the command's: a result that holds NaN or inf is refused as a
            # whole (check_finite), and far-out numbers are named in the error line below
            with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
                return fn(*args, **kwargs)
        except SolveError as exc:  # a failed computation on far-out numbers: name them (E = 1e-300 reads singular)
            extreme = _extreme_values()
            _fail(SolveError([exc.lines[0] + extreme, *exc.lines[1:]]) if extreme else exc)
        except PdverifyError as exc:
            _fail(exc)
        except MemoryError:
            _fail(SolveError("out of memory during the computation; use fewer points (a larger spacing)"))
        except (OverflowError, FloatingPointError, ZeroDivisionError) as exc:
            if isinstance(exc, ZeroDivisionError) and not _extreme_values():  # an underflow to 0 of far-out numbers,
                _internal(exc)  # else a defect
            _fail(
                SolveError(
                    f"the computation left the floating-point range ({exc.__class__.__name__}: "
                    f"{exc.args[-1] if exc.args else exc}){_extreme_values()}; give the scene in units "
                    "that keep its numbers within about 1e-100..1e100"
                )
            )
        except (typer.Exit, typer.Abort, KeyboardInterrupt, BrokenPipeError):  # the CLI's own (cli.main)
            raise
        except Exception as exc:  # a defect of pdverify, not of the input: one line, its own exit code
            if os.environ.get("PDVERIFY_DEBUG"):
                raise
            _internal(exc)

    return wrapper


INTERNAL_EXIT = 70  # a defect of pdverify itself (EX_SOFTWARE of sysexits.h): not 1, which CI reads as a failed check


def _internal(exc: Exception) -> None:
    """One line for an exception no input should cause, with where it was raised, and exit :data:`INTERNAL_EXIT`."""
    import traceback

    frames = traceback.extract_tb(exc.__traceback__)
    where = f" at {Path(frames[-1].filename).name}:{frames[-1].lineno}" if frames else ""
    text = str(exc).splitlines()[0] if str(exc) else ""
    typer.echo(
        f"error: internal error of pdverify ({exc.__class__.__name__}{': ' + text if text else ''}{where}); "
        "please report it with the command and its input files; PDVERIFY_DEBUG=1 shows the traceback",
        err=True,
    )
    raise typer.Exit(INTERNAL_EXIT)


_SCENE_FILES: list = []  # scene files a command read, to name their extreme values when a computation overflows


def _extreme_values() -> str:
    """'; extreme values: beam.length = 1e+300' for the numbers of the scenes read that are far out of range."""
    import math

    found = []

    def walk(v, where):
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, f"{where}.{k}" if where else k)
        elif isinstance(v, list):
            for i, x in enumerate(v):
                walk(x, f"{where}[{i}]")
        elif (
            isinstance(v, (int, float))
            and not isinstance(v, bool)
            and v != 0
            and math.isfinite(v)
            and not 1e-100 <= abs(v) <= 1e100
        ):
            found.append(f"{where} = {v:g}")

    for sc in _SCENE_FILES:
        walk(sc.model_dump(mode="json", exclude_none=True), "")
    return f"; extreme values: {', '.join(found)}" if found else ""


# the grid's options, the same on every command that takes a grid (solve, modes; verify: the horizon only, the suite
# sets the grids); each is the model option of its name (-o points=... works as well), refused by a model without it
# read by the model like ``-o points=N`` (so ``--points 1e3`` is 1000 both ways, ``--points 1e3.5`` refused both ways)
POINTS = typer.Option(
    None, "--points", metavar="N", help="material points / nodes along the axis, ends included (a whole number)"
)
HORIZON = typer.Option(None, "--horizon", help="horizon as a multiple of the spacing (3 = the papers' 3.015)")
HORIZON_LENGTH = typer.Option(
    None, "--horizon-length", help="horizon in metres (option horizon_length; models that take one)"
)


def grid_options(options: dict, **named) -> dict:
    """The model options of a command: its named options (``--points``, ``--horizon``, ...; None where not given)
    with its ``-o key=value`` ones. A key given both ways is an error, not a silent choice of one of them."""
    given = {k: v for k, v in named.items() if v is not None}
    for key in given.keys() & options.keys():
        raise InputError(
            f"--{key.replace('_', '-')} {given[key]} and -o {key}={options[key]}: the same option twice; give one"
        )
    return {**given, **options}


def positive(option: str, value: float) -> float:
    """A positive, finite number for ``option`` (a tolerance, a budget in seconds), or one line (exit 2)."""
    import math

    if not (math.isfinite(value) and value > 0):
        said = PAST_RANGE if math.isinf(value) else ""
        raise InputError(f"{option} {value}{said}: give a positive, finite number")
    return value


def parse_options(pairs: list[str] | None) -> dict:
    """``key=value`` strings from ``--option`` into a dict (values stay strings; models coerce)."""
    out = {}
    for item in pairs or []:
        if "=" not in item:
            raise InputError(f"--option {item!r}: write key=value")
        k, v = (part.strip() for part in item.split("=", 1))
        if not k:
            raise InputError(f"--option {item!r}: no option name before '='; write key=value")
        if k in out:
            raise InputError(f"-o {k}={out[k]} and -o {k}={v}: the same option twice; give one")
        out[k] = v
    return out


def given_path(text: str) -> Path:
    """An ``--out`` / ``--junit`` path as given; an empty one (an unset shell variable: ``--out "$OUT"``) is a usage
    error, not the current folder that ``Path("")`` would be."""
    if not str(text).strip():
        raise typer.BadParameter("an empty path; give a file or folder name ('.' for the current folder)")
    if str(text).strip() == "-":  # not standard output: a file named "-" would be written
        raise typer.BadParameter("'-': output goes to standard output without --out; give a file or folder name")
    return Path(text)


def given_file(example: str):
    """The parser of a file option's path (``solve --out``, ``--junit``): :func:`given_path`, and not one whose last
    component names a folder (``--out results/``, ``results/.``: ``Path`` would drop it and write a file named
    results); ``example``: the file name its message suggests."""

    def parse(text: str) -> Path:
        path = given_path(text)
        last = str(text).replace(os.altsep or os.sep, os.sep).rsplit(os.sep, 1)[-1]
        if last in ("", ".", ".."):  # "x/", "x/." and "x/..": a folder, where Path drops what says so
            raise typer.BadParameter(f"{text!r} names a folder; give a file, e.g. {Path(text) / example}")
        return path

    return parse


def spread_repeats(argv: list[str], option: str = "--points") -> list[str]:
    """``--points 1000 10000`` (as the README writes it) -> ``--points 1000 --points 10000``: the values that follow
    the option up to the next option. Only for ``bench``, whose --points takes several sizes and which takes no
    other argument."""
    command = next((a for a in argv if not a.startswith("-")), None)  # the global options take no values
    if command != "bench":
        return argv
    out, after = [], 0  # after: how many values the last --points has taken
    for arg in argv:
        if arg == option:
            after = 0
        elif arg.startswith("-"):
            after = -1
        elif after >= 0:
            after += 1
            if after > 1:
                out.append(option)
        out.append(arg)
    return out


def single_repeats(command, argv: list[str]) -> str | None:
    """The line refusing a single-valued option of the command given twice (``--points 41 --points 81`` took the
    last), or None. ``command``: the click group of the app."""
    name = next((a for a in argv if not a.startswith("-")), None)
    sub = getattr(command, "commands", {}).get(name)
    if sub is None:
        return None
    flags = {
        o: p.name
        for p in sub.params
        if getattr(p, "param_type_name", "") == "option" and not p.multiple and not p.is_flag and p.nargs == 1
        for o in p.opts + p.secondary_opts
    }
    seen: dict[str, tuple[str, str]] = {}
    for i, arg in enumerate(argv):
        flag, eq, value = arg.partition("=") if arg.startswith("--") else (arg, "", "")
        if flag not in flags:
            continue
        value = value if eq else (argv[i + 1] if i + 1 < len(argv) else "")
        if flags[flag] in seen:
            first, before = seen[flags[flag]]
            return f"{first} {before} and {flag} {value}: the same option twice; give one"
        seen[flags[flag]] = (flag, value)
    return None


def prepared(command, argv: list[str]) -> list[str]:
    """The command line as the app reads it (:func:`spread_repeats`), or a usage error naming an option given twice."""
    try:  # typer >= 0.2x carries its own copy of click (as main)
        from typer._click import exceptions as click
    except ImportError:  # pragma: no cover - older typer: click itself
        from click import exceptions as click

    if line := single_repeats(command, argv):
        raise click.UsageError(line)
    return spread_repeats(argv)


def auto_options(model: str, tolerance: float | None, given: dict) -> None:
    """InputError for ``solve``'s --model auto and --tolerance that do not go together: --tolerance beside a named
    model (a misspelt one named first, and 'auto' where it looks like it), --model auto without --tolerance or with
    options it would drop (one that no model takes named as such)."""
    from ..core.text import close_match  # deferred: `pdverify --help` starts without the library
    from ..registry import get_model, model_argument, models  # deferred: the models load when a command asks

    if tolerance is not None and model != "auto":
        if close_match(model.strip().lower(), ["auto"]) and model not in models():
            raise InputError(
                f"--model {model}: unknown model; did you mean 'auto'? (--tolerance asks for --model auto)"
            )
        get_model(model_argument(model))  # a misspelt model is named first: the line that mends it
        raise InputError(
            f"--tolerance {tolerance:g}: applies to --model auto only (the model given: {model!r}); drop it or use "
            "--model auto"
        )
    if model != "auto":
        return
    if tolerance is None:
        raise InputError("--model auto needs --tolerance (relative error you can accept, e.g. 1e-3)")
    positive("--tolerance", tolerance)
    chosen = sorted(k for k in given if k != "static")
    unknown = [k for k in chosen if all(m.option(k) is None for m in models().values())]
    if unknown:
        raise InputError(f"-o {unknown[0]}: no model takes this option; drop it (`pdverify models` lists each one's)")
    if chosen:
        them = "them" if len(chosen) > 1 else "it"
        raise InputError(
            f"--model auto chooses the model and its grid, so {', '.join(chosen)} would be dropped: name a model "
            f"(-m MODEL) to give {them}, or drop {them}"
        )
