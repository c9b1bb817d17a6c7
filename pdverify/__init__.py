"""pdverify: how far is a peridynamic beam model from the truth, in numbers.

The public Python API (what a notebook uses; the CLI is built on the same three calls)::

    >>> import pdverify
    >>> scene = pdverify.load_scene("studies/examples/cantilever_tip_load.toml")
    >>> result = pdverify.run(scene, "exact-eb", points=5)
    >>> round(float(result.w[-1]), 12)  # P L^3 / (3 EI) = -50 / (3 * 200e9 * 1e-8 / 12)
    -0.1

- :func:`load_scene` reads and validates a scene file (raises :class:`InputError` naming the field);
- :func:`run` solves a scene with a model and its options and returns a :class:`Result`;
- :func:`run_study` runs a study file (or a loaded study) and returns its results as a DataFrame.

Imports are lazy so that ``pdverify --help`` stays fast.
"""

from __future__ import annotations

from .core.version import __version__

__all__ = ["load_scene", "run", "run_study", "Result", "Scene", "InputError", "__version__"]


def load_scene(path):
    """Read and validate a scene TOML file; a :class:`pdverify.core.scene.Scene`."""
    from .core.scene_file import load_scene as _load

    return _load(path)


def run(scene, model, estimate=False, **options):
    """Solve ``scene`` (a Scene or a path to a scene file) with ``model`` (a registered name or a Model). A grid
    too large for the machine's memory is refused before it is allocated (SolveError naming the largest that fits).
    ``estimate``: also solve two nested grids; ``result.info["estimate"]`` is then a Richardson estimate of the
    discretisation error (:mod:`pdverify.measure.richardson`), with a warning where the grids are not in the
    asymptotic range."""
    from .core.contract import Model
    from .measure.memory import check_memory
    from .registry import get_model
    from .registry import run as _run

    if not hasattr(scene, "length"):
        scene = load_scene(scene)
    if isinstance(model, str):
        model = get_model(model)
    if isinstance(model, Model):  # anything else is refused by the registry's run, in one line
        check_memory(scene, model, options)
        if estimate:
            from .measure.richardson import with_estimate

            return with_estimate(scene, model, options, _run)
    return _run(scene, model, **options)


def run_study(study, out=None, workers=None, scheduler=None, progress=False, report=False, junit=None):
    """Run a study (a path to a study TOML file or a loaded Study) as ``pdverify study`` does: its cases, the
    verification cards it asks for, ``junit`` XML and, with ``report``, the HTML report, into ``out`` (default
    ``reports/<study file stem>``). Returns a :class:`~pdverify.apps.pipeline.StudyRun`: ``results`` (the
    table, a DataFrame, which the run also stands in for), ``cards``, ``exit_code``, ``summary``."""
    from pathlib import Path

    from .apps.pipeline import load_study, run

    if isinstance(study, (str, Path)):
        path = Path(study)
        study = load_study(path)
        out = out if out is not None else Path("reports") / path.stem
    if out is None:
        raise TypeError("run_study: give out= (an output folder) with a loaded study")
    from .apps.output import check_folder

    check_folder(Path(out), "out =")  # a file, or an unwritable place: OutputError before any case (as the CLI)
    return run(study, Path(out), workers=workers, scheduler=scheduler, progress=progress, report=report, junit=junit)


def __getattr__(name):
    if name == "Result":
        from .core.result import Result

        return Result
    if name == "Scene":
        from .core.scene import Scene

        return Scene
    if name == "InputError":
        from .core.errors import InputError

        return InputError
    raise AttributeError(f"module 'pdverify' has no attribute {name!r}")
