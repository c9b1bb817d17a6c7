"""The model registry: every model of ``pdverify solve`` is found here, and :func:`run` solves a scene with one.

A paper's package under ``pdverify.papers`` and each module of ``pdverify.exact`` list their models in
``MODELS``; the registry imports them and collects them, so adding a model never means editing a central
file. Models of other packages (the finite-element references of ``reference_fem`` too) arrive through the
entry-point group ``pdverify.models`` (:mod:`pdverify.registry.plugins`). The contract a model follows
(:class:`Model`, :class:`Option`, :class:`Rule`, :class:`System`) is :mod:`pdverify.core.contract`; it is
re-exported here, the import path plug-ins use.

>>> sorted(get_model("pd-eb").supports), "dynamic" in get_model("pd-timoshenko").analyses
(['clamped', 'free', 'guided', 'pinned', 'roller'], True)
"""

from __future__ import annotations

import copy
import importlib
import json
import pkgutil
import time

import numpy as np

from .. import exact, papers
from ..core.contract import (
    LOAD_TYPES,
    MOTION_COMPONENT,
    POINTS,
    SUPPORTS,
    Model,
    Option,
    Rule,
    System,
    points_from_spacing,
    variant_problems,
)
from ..core.errors import InputError, SolveError
from ..core.reactions import equilibrium_reactions
from ..core.result import Result, check_finite, quantity_of
from ..core.scene import Scene
from ..core.scene_file import parse_scene
from ..core.text import close_match
from ..numerics.features import stiffness_step_warnings, unresolved_features_warnings
from ..numerics.kept import Kept
from ..numerics.loads import POINT_SPAN, narrow_spans_as_points
from ..theory.continuum import continuum_solution, model_error_warning, no_limit_warning
from .close_supports import close_supports_warning
from .end_loads import end_load_warnings
from .external import ExternalModel, load_manifest
from .grid_check import grid_check
from .history_check import history_check
from .jump_rotation import jump_rotation_warning
from .plugins import discover, remember_manifest

__all__ = [
    "LOAD_TYPES",
    "MOTION_COMPONENT",
    "POINTS",
    "SUPPORTS",
    "Model",
    "Option",
    "Rule",
    "System",
    "as_flag",
    "get_model",
    "horizon_info",
    "model_argument",
    "models",
    "points_from_spacing",
    "problems",
    "run",
    "static_part",
    "use_manifest",
    "variant_problems",
]

_REGISTRY: dict[str, Model] | None = None


def builtin_modules() -> list[str]:
    """The modules that list built-in models in ``MODELS``: each paper's package (``pdverify.papers.<paper>``)
    and each module of ``pdverify.exact``."""
    found = []
    for pkg, packages in ((papers, True), (exact, False)):
        for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda i: i.name):
            if not info.name.startswith("_") and info.ispkg == packages:
                found.append(f"{pkg.__name__}.{info.name}")
    return found


def models() -> dict[str, Model]:
    """All registered models by name (imported once). The built-in models are registered before the plug-ins
    are imported, so a plug-in that asks for the models while it is imported sees those."""
    global _REGISTRY
    if _REGISTRY is None:
        reg: dict[str, Model] = {}
        for name in builtin_modules():
            mod = importlib.import_module(name)
            for m in getattr(mod, "MODELS", ()):
                if m.name in reg:
                    raise RuntimeError(f"model name {m.name!r} registered twice ({mod.__name__})")
                reg[m.name] = m
        _REGISTRY = reg
        _REGISTRY = dict(sorted({**reg, **discover(reg)}.items()))
    return _REGISTRY


def use_manifest(path) -> str:
    """Register the external model of the manifest at ``path`` (unless registered from the same file) and
    return its name. The path is appended to ``PDVERIFY_MODELS_PATH``, so worker processes started later
    (a process pool, a local Dask cluster, ``bench``'s subprocess) find it too. Raises InputError."""
    from pathlib import Path

    path = Path(path).resolve()
    reg = models()
    m = load_manifest(path)
    old = reg.get(m.name)
    if old is not None and not (isinstance(old, ExternalModel) and old.path == m.path):
        raise InputError(f"{path}: name = {m.name!r}: a model of that name exists already; rename the external model")
    reg[m.name] = m
    remember_manifest(path)
    return m.name


def model_argument(name: str) -> str:
    """A ``--model`` value: a model name as it is, a path to a manifest (``*.toml``) registered first."""
    import os

    if name.endswith(".toml") or os.sep in name:
        return use_manifest(name)
    return name


def get_model(name: str) -> Model:
    reg = models()
    if name not in reg:
        close = close_match(name, reg)
        hint = f"did you mean '{close}'? " if close else ""
        raise InputError(f"model = {name!r}: unknown model; {hint}available: {', '.join(reg)}")
    return reg[name]


def static_part(scene: Scene, m: Model, given: dict) -> tuple[Scene, dict]:
    """The scene and options of the static response to a scene's loads (``static = true``): a dynamic
    model with an ``analysis`` option runs its static analysis; any other model gets the scene without its
    ``[dynamics]`` table, which it may drop only when the table prescribes no end motion."""
    d = scene.dynamics
    moved = [
        (side, k)
        for side in ("left", "right")
        if d is not None and getattr(d, side) is not None
        for k in MOTION_COMPONENT
        if getattr(getattr(d, side), k) is not None
    ]
    if "dynamic" in m.analyses and m.option("analysis") is not None and (m.end_motions or not moved):
        if given.get("analysis", "static") not in ("static", "auto"):  # else its static part would drop the motion
            raise InputError(f"static = true and analysis = {given['analysis']!r}: give one of them")
        return scene, dict(given, analysis="static")
    if d is None:
        return scene, given
    if moved and not m.end_motions:
        side, k = moved[0]
        can = [n for n, x in models().items() if x.end_motions and getattr(x, MOTION_COMPONENT[k])]
        raise InputError(
            f"dynamics.{side}.{k}: model {m.name} cannot prescribe end motions, so its static part "
            f"would leave out this one; use a model that can ({', '.join(can) or 'none installed'})"
        )
    return scene.model_copy(update={"dynamics": None}), given


def problems(scene: Scene, m: Model, static: bool = False) -> list[str]:
    """Every reason ``m`` cannot solve ``scene`` (its declared capabilities and its own check), one line
    each; ``static``: only the static response to the loads is asked for (:func:`static_part`)."""
    if static:
        try:
            scene, _ = static_part(scene, m, {})
        except InputError as exc:
            return exc.lines
    return m.check(scene)


CHECK_FLAGS = ("history_check", "grid_check")  # run's own estimates of a result's error, on by default
RUN_FLAGS = ("static", *CHECK_FLAGS)  # options of :func:`run` itself, not of a model


def model_options(options: dict) -> dict:
    """``options`` without :data:`RUN_FLAGS`: what the model's own ``resolve`` takes."""
    return {k: v for k, v in options.items() if k not in RUN_FLAGS}


def resolved(m: Model, scene: Scene, given: dict) -> dict:
    """The options ``m`` resolves from ``given`` on ``scene``, with :data:`CHECK_FLAGS` where given (a study's row
    records them beside the model's options)."""
    return {**m.resolve(scene, model_options(given)), **{k: given[k] for k in CHECK_FLAGS if k in given}}


def as_flag(value, name: str = "static") -> bool:
    """A yes/no run option ``name`` given as a bool or a string (``-o static=true``)."""
    if isinstance(value, bool):
        return value
    v = str(value).strip().lower()
    if v in ("1", "true", "yes", "on"):
        return True
    if v in ("0", "false", "no", "off"):
        return False
    raise InputError(f"{name} = {value!r}: give true or false")


def horizon_info(m: Model, scene: Scene, params: dict, info: dict) -> None:
    """Record a PD model's horizon delta (length), spacing dx and m = delta / dx in a result's ``info`` (``horizon``,
    ``spacing``, ``m``), each from the model's own info where it gave it."""
    dx = info.get("spacing") or m.spacing(scene, params)
    delta = info.get("horizon") or m.delta(scene, params)
    info.update(horizon=float(delta), spacing=float(dx), m=round(float(delta) / float(dx), 9))


def exact_on(points: int):
    """scene -> exact Euler-Bernoulli theory's result on ``points`` points (what the end-load estimate weighs each
    load's response with)."""
    return lambda scene: run(scene, "exact-eb", points=points)


# the last static solves without their grid check, by scene, model and options: a card's cases run by operator (one
# grid, the loads and scenes on it) and each scene's grids finest first, so a grid's check comes back after others
_unchecked_kept = Kept(64, budget=1_000_000, size=lambda r: len(r.x))  # at most a million points together


def _unchecked(scene: Scene, m: Model, given: dict) -> Result:
    """``run(scene, m, **given, grid_check=False)``, or a copy of the same call made before in this process: on a
    series of grids solved finest first (a verification card's), the grid check of one grid is the next coarser
    grid's solve. A solve is deterministic (the same bits); a kept one's timings are those of the solve that made it.
    A model object the registry does not hold (made by the caller) is solved afresh."""
    if models().get(m.name) is not m:
        return run(scene, m, **given, grid_check=False)
    key = json.dumps([scene.to_dict(), m.name, given], sort_keys=True, default=repr)
    return copy.deepcopy(_unchecked_kept.get(key, lambda: run(scene, m, **given, grid_check=False)))


def _check_own_grid(scene: Scene, m: Model, params: dict, given: dict, result: Result) -> None:
    """:func:`~pdverify.registry.grid_check.grid_check` of ``result``, its coarser solve through :func:`_unchecked`
    with the same options but the grid (and the solver: the same system, and a Krylov one may refuse the smaller
    grid)."""
    coarse = {k: v for k, v in given.items() if k not in ("spacing", "solver", "points")}

    def grown(n: int) -> dict:
        """At a fixed horizon length the coarser solve's horizon grows with its spacing: the same factor (as a
        length, which a variant that needs a whole factor takes), so the difference carries the model error too,
        which two grids at one length share unseen."""
        if params.get("horizon_length") is None:
            return {}
        ratio = m.spacing(scene, dict(params, points=n)) / m.spacing(scene, params)
        return {"horizon_length": params["horizon_length"] * ratio}

    grid_check(m, scene, params, result, lambda n: _unchecked(scene, m, {**coarse, **grown(n), "points": n}))


UNLOADED = (
    "the scene has no loads (or only zero ones): every displacement, force and reaction is zero; give its "
    "[[loads]] (docs/scenes.md)"
)


def loaded(scene: Scene) -> bool:
    """True when a load of the scene has a value that is not zero (a force, moment, torque, an axial or torque
    share of a distributed load, a prescribed deflection): a static solve without one is zero everywhere."""
    return any(getattr(ld, k, 0.0) != 0.0 for ld in scene.loads for k in ("value", "axial", "torque"))


def run(scene: Scene, model: str | Model, **given) -> Result:
    """Solve ``scene`` with ``model`` and the given options; the whole call is timed (``total_s``).

    ``static = true`` (CLI ``-o static=true``; not a model option): the static response to the loads of a scene that
    has a ``[dynamics]`` table (:func:`static_part`); without it a static-only model rejects such a scene. A
    transient of a model that is not a reference carries the estimate of its error from the same history on about
    half the points (:func:`~pdverify.registry.history_check.history_check`; ``history_check = false``, not a model
    option: none); a static solve of a model that asks for it (``Model.checks_own_grid``: pd-curved on a curved
    axis, pd-eb, pd-bond-pair, pd-rod, pd-torsion) the estimate from the same solve on about half the points
    (:func:`~pdverify.registry.grid_check.grid_check`; ``grid_check = false``: none), both solves kept
    (:func:`_unchecked`: ``total_s`` the solve's as it was made, plus the check's). Before solving, the scene is
    checked against the model's declared capabilities and the options against its ``variant_rules``: every problem
    one line of the :class:`InputError` (exit 2). Floating-point overflow and invalid operations inside the solve
    raise no numpy warning: a result that holds NaN or inf is refused as a whole by
    :func:`~pdverify.core.result.check_finite` (one error, exit 3)."""
    t0 = time.perf_counter()
    if not isinstance(model, (str, Model)):
        raise InputError(f"model = {model!r}: give a model's name (see `pdverify models`) or a pdverify Model")
    if not isinstance(scene, Scene):
        raise InputError(f"scene = {type(scene).__name__}: give a Scene (pdverify.load_scene or parse_scene)")
    scene = parse_scene(scene.to_dict(), source=f"scene {scene.name!r}")  # a copy changed by model_copy is checked too
    m = get_model(model) if isinstance(model, str) else model
    check_history = as_flag(given.pop("history_check", True), "history_check")
    check_grid = as_flag(given.pop("grid_check", True), "grid_check")
    if as_flag(given.pop("static", False)):
        scene, given = static_part(scene, m, given)
    found = m.check(scene)
    if found:
        raise InputError(found)
    params = m.resolve(scene, given)  # the options, their variant's rules included
    if found := m.refusals(scene, params):  # what the variant does not define on this scene: before any work
        raise InputError(found)
    scene = narrow_spans_as_points(scene, POINT_SPAN)  # a span whose two ends would round to one point
    own_grid = "points" in params and not params.get("continuum") and m.checks_own_grid(scene, params)
    if check_grid and scene.dynamics is None and own_grid:  # (a continuum has no grid to estimate)
        result = _unchecked(scene, m, given if check_history else {**given, "history_check": False})
        t1 = time.perf_counter()
        _check_own_grid(scene, m, params, given, result)
        result.timings["total_s"] = result.timings.get("total_s", 0.0) + time.perf_counter() - t1
        return result
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            solved = continuum_solution(m, scene, params) if params.get("continuum") else m.solve(scene, params)
    except MemoryError as exc:  # an allocation numpy or scipy refused: the grid is too large for this machine
        size = f"points = {params['points']}: " if "points" in params else ""
        raise SolveError(
            f"{size}model {m.name} ran out of memory ({str(exc) or 'an allocation failed'}); use fewer points "
            "(pdverify.solve and the command line estimate the limit before solving)"
        ) from None
    result = check_finite(solved)
    if scene.dynamics is None and not loaded(scene):
        result.info.setdefault("warnings", []).append(UNLOADED)
    if m.option("horizon") is not None:
        horizon_info(m, scene, params, result.info)
        grid_flags = [] if m.breaks else unresolved_features_warnings(scene, float(result.info["spacing"]))
        if not m.breaks and m.theory in ("euler-bernoulli", "timoshenko"):
            grid_flags += stiffness_step_warnings(scene)
        for flag in (
            no_limit_warning(m, scene, params),
            model_error_warning(m, scene, result.info, params),
            *grid_flags,
        ):
            if flag:
                result.info.setdefault("warnings", []).append(flag)
    if (
        "reactions" not in result.info
        and scene.is_straight
        and scene.dynamics is None
        and scene.supports.simple
        and m.bending
        and m.theory in ("euler-bernoulli", "timoshenko")
        and len(result.x) >= 4
    ):
        moment = quantity_of(result.w, result.rotation, result.fields, "moment")  # M or moment, as it names it
        result.info["reactions"] = equilibrium_reactions(scene, result.x, result.w, result.rotation, moment)
        check_finite(result)
    if "reactions" in result.info and m.bending and (close := close_supports_warning(scene)):
        result.info.setdefault("warnings", []).append(close)
    # a transient integrates the static solve's operator and loads, so the loads' estimate is its too, but the
    # rotation's takes the static reactions
    end_load, jump_constants = ({}, (0.0, 0.0)) if params.get("continuum") else m.estimate_constants(scene, params)
    if end_load and (flags := end_load_warnings(end_load, scene, result.info, exact_on(len(result.x)))):
        result.info.setdefault("warnings", []).extend(flags)
    if any(jump_constants) and "reactions" in result.info and scene.dynamics is None:
        if jump := jump_rotation_warning(jump_constants, scene, result.rotation, result.info):
            result.info.setdefault("warnings", []).append(jump)
    if check_history and "history" in result.info and "points" in params and not (m.histories or m.reference):
        coarse = {k: v for k, v in given.items() if k != "spacing"}  # the grid given as a spacing: as points
        history_check(scene, m, params, result, lambda n: run(scene, m, **dict(coarse, points=n, history_check=False)))
    result.timings["total_s"] = time.perf_counter() - t0
    result.timings.setdefault("assemble_s", 0.0)
    result.timings.setdefault("solve_s", 0.0)
    return result
