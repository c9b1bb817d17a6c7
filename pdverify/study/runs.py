"""One ``[[runs]]`` table of a study file, checked before anything runs: its model, its reference (the
study's unless the run sets its own; it must give the quantity the model is measured on), the scenes and
slenderness list it runs, and its sweep axes (every other key: a list of values, each of the type the model's
option takes)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..core.errors import InputError
from ..core.result import QUANTITIES
from ..core.text import close_match
from ..registry import CHECK_FLAGS, Model, get_model, models
from .checks import finite_number, meant_key, misspelt, strict_type

RUN_KEYS = {"model", "reference", "scenes", "slenderness", "quantities"}


def measures_mismatch(where: str, model, ref_model) -> str:
    """One line: the run's reference gives another quantity than its model is measured on (e.g. pd-rod's u
    against exact-eb's w), naming the references that give it."""
    same = [n for n, m in models().items() if m.reference and m.measures == model.measures]
    return (
        f"{where}: reference {ref_model.name} gives {ref_model.measures}, but model {model.name} is measured on "
        f"{model.measures}; give a reference that gives {model.measures} ({', '.join(same) or 'none installed'}) "
        'or reference = "none"'
    )


def reference_table(value, where: str) -> dict:
    """A ``reference`` as a table ``{model, options...}``: a model name or a table naming one."""
    if isinstance(value, str):
        return {"model": value}
    if isinstance(value, dict) and isinstance(value.get("model"), str):
        return dict(value)
    typo = meant_key(value, "model")
    if typo:
        raise InputError(f"{where}reference.{typo}: unknown key '{typo}'; did you mean 'model'?")
    raise InputError(f"{where}reference = {value!r}: give a model name or a table {{model = ..., options...}}")


def as_list(v):
    """A value of a sweep: a list as it is, a single value as a list of one."""
    return v if isinstance(v, list) else [v]


@dataclass
class Run:
    """One ``[[runs]]`` table, its form checked: the model as written and as registered, the reference, the
    scene files and slenderness list it runs, and its sweep axes (every other key, a list of values each)."""

    where: str
    written: str
    model: Model
    reference: dict
    scenes: list[str]
    slenderness: list
    axes: dict[str, list]
    quantities: tuple = ()


def parse_quantities(value, where: str) -> tuple[tuple, list[str]]:
    """A ``quantities`` list (the study's or a run's) and its error lines."""
    if value is None:
        return (), []
    if not isinstance(value, list) or not all(isinstance(q, str) and q in QUANTITIES for q in value):
        bad = [q for q in value if q not in QUANTITIES] if isinstance(value, list) else []
        close = close_match(bad[0], QUANTITIES) if bad and isinstance(bad[0], str) else None
        hint = f"'{bad[0]}': did you mean '{close}'? " if close else ""
        return (), [f"{where}quantities = {value!r}: {hint}give a list of {', '.join(QUANTITIES)}"]
    return tuple(dict.fromkeys(value)), []


def parse_run(
    path: Path, i: int, run, reference: dict, slenderness: list, scene_objs: dict, quantities: tuple = ()
) -> tuple[Run | None, list[str]]:
    """The run's model, reference, scenes, slenderness list (the study's unless the run sets its own) and sweep
    axes, and their error lines; None when one of them is wrong, or its reference gives another quantity than
    the model is measured on."""
    where = f"{path}: runs[{i}]"
    if not isinstance(run, dict) or not isinstance(run.get("model"), str):
        typo = meant_key(run, "model")
        if typo:
            return None, [f"{where}: unknown key '{typo}'; did you mean 'model'?"]
        if isinstance(run, dict) and "model" in run:
            return None, [
                f'{where}: model = {run["model"]!r}: not a model name; give one in quotes, e.g. model = "pd-eb"'
            ]
        return None, [f"{where}: model: missing; every run names a model"]
    try:
        model = get_model(run["model"])
    except InputError as exc:
        return None, [f"{where}: {exc.lines[0]}"]
    run_ref = reference
    if "reference" in run:
        try:
            run_ref = reference_table(run["reference"], f"runs[{i}].")
        except InputError as exc:
            return None, [f"{path}: {exc.lines[0]}"]
    if run_ref["model"] != "none" and run_ref["model"] in models():  # (an unknown one is reported with the cases)
        if (ref_model := get_model(run_ref["model"])).measures != model.measures:
            return None, [measures_mismatch(where, model, ref_model)]
    run_scenes = run.get("scenes", list(scene_objs))
    if not isinstance(run_scenes, list) or any(s not in scene_objs for s in run_scenes):
        return None, [f"{where}.scenes = {run_scenes!r}: must list scenes of the study's scenes"]
    if not run_scenes and "scenes" not in run:  # the study's scenes did not load: their lines say why
        return None, []
    if not run_scenes:
        return None, [f"{where}.scenes = []: the run would have no case; list scenes of the study's, or drop the key"]
    if dup := twice(f"{where}.scenes", run_scenes):
        return None, [dup]
    run_slen = slenderness
    if "slenderness" in run:  # this run's own slenderness sweep, in place of [sweep]'s
        run_slen = as_list(run["slenderness"])
        if not run_slen or any(not (finite_number(v) and v > 0) for v in run_slen):
            return None, [
                f"{where}.slenderness = {run['slenderness']!r}: give positive finite numbers (length / height)"
            ]
        if dup := twice(f"{where}.slenderness", run_slen):
            return None, [dup]
    axes, errors = _run_axes(where, run, model)
    if axes is None:
        return None, errors
    if "quantities" in run:
        quantities, bad = parse_quantities(run["quantities"], f"{where}.")
        if bad:
            return None, bad
    return Run(where, run["model"], model, run_ref, run_scenes, run_slen, axes, quantities), errors


def _run_axes(where: str, run: dict, model: Model) -> tuple[dict | None, list[str]]:
    """The run's sweep axes and their error lines: values of the wrong type (then None: the coerced values
    would only add confusing errors) or an empty list."""
    axes = {k: as_list(v) for k, v in run.items() if k not in RUN_KEYS}
    unknown = [k for k in axes if model.option(k) is None and k not in ("spacing", *CHECK_FLAGS)]
    if unknown:  # before the types: a misspelt key's values would only add confusing lines
        return None, [f"{where}.{k}: {misspelt(k, RUN_KEYS | {'spacing', *CHECK_FLAGS}, model)}" for k in unknown]
    typed = [
        f"{where}.{why}"
        for k, v in axes.items()
        if model.option(k) is not None
        for why in dict.fromkeys(strict_type(model.option(k), x) for x in v)
        if why
    ]
    typed += [
        f"{where}.{k} = {x!r}: give true or false"
        for k in CHECK_FLAGS
        for x in dict.fromkeys(axes.get(k, []))
        if not isinstance(x, bool)
    ]
    if typed:
        return None, typed
    return axes, [
        f"{where}.{k} = []: an empty sweep runs nothing; give values or drop the key" for k, v in axes.items() if not v
    ] + [twice(f"{where}.{k}", v) for k, v in axes.items() if twice("", v)]


def twice(where: str, values: list) -> str:
    """The error line of a list that gives a value twice (a case runs once, so the second would vanish silently),
    or ""."""
    seen = []
    for v in values:
        if v in seen:
            return f"{where} = {values!r}: {v!r} is listed twice (a case runs once); give each value once"
        seen.append(v)
    return ""
