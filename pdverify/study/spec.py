"""Study files: parse, validate everything before running anything, expand the sweep into cases.

```toml
name = "pd-eb convergence"
scenes = ["paper_diyaroglu/clamped_free.toml"]   # relative to the study file
reference = "exact-eb"                            # or {model = "fem-eb", points = 401}
[[runs]]                                          # a run may set its own reference, scenes (a subset) and
                                                  # slenderness list (instead of [sweep]'s)
model = "pd-eb"
variant = ["paper", "corrected"]                  # every list is a sweep axis
points = [51, 101, 201]
[sweep]
slenderness = [10, 100]                           # optional: section height = length / slenderness
[papers]                                          # optional: one report page per scene folder
paper_diyaroglu = "Diyaroglu, Oterkus & Oterkus"
[[benchmarks]]                                    # optional verification-manual rows
name = "tip deflection"
scene = "paper_diyaroglu/clamped_free.toml"
model = "pd-eb"
variant = "corrected"
points = 101
target = -0.1                                     # omitted: the reference's value
tolerance = 0.005                                 # relative; default 0.01
[[checks]]                                        # optional order checks (pdverify/study/checks.py)
model = "pd-eb"
variant = "corrected"
observed_order = { min = 1.9 }
```
Optional verification cards (``pdverify verify``, docs/verify.md), run after the study's cases into
``OUT/verify/<model>[_options]/`` and listed in the report; their failures change the exit status only with
``verify_required = true``:
```toml
verify = ["pd-eb", "pd-eb variant=paper"]         # model and options (key=value), or {model = ..., ...}
verify_required = false                           # default
```
Values are typed as TOML types them: a boolean option takes only true/false, a number never a boolean.
"""

# long module: the study file's schema and its validation, one error line per problem

from __future__ import annotations

import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from ..core.errors import InputError
from ..core.result import FIELD_NAMES, QUANTITIES, canonical
from ..core.scene import Scene
from ..core.scene_file import load_scene, parse_scene, read_toml
from ..core.text import close_match
from ..core.version import __version__
from ..registry import Model, get_model, model_options, models, use_manifest
from ..registry.plugins import GROUP
from .checks import BENCH_VALUES, finite_number, meant_key, option_filter_errors, strict_type, validate_checks
from .entries import model_errors, verify_entries
from .runs import Run, as_list, parse_quantities, parse_run, reference_table, twice

STUDY_KEYS = {
    "name",
    "description",
    "scenes",
    "reference",
    "runs",
    "sweep",
    "benchmarks",
    "papers",
    "checks",
    "external",
    "verify",
    "verify_required",
    "quantities",
}  # the study file's top-level keys
STORE_SCHEMA = 4  # bump when a case record's content or format changes: older case files are then recomputed
BENCH_KEYS = set(BENCH_VALUES)  # the values of a benchmark row; its other keys filter the cases


def code_packages() -> list[str]:
    """The packages whose code can change a number: pdverify and the top-level package of every
    ``pdverify.models`` entry point (reference_fem's finite elements and any installed plug-in)."""
    from importlib.metadata import entry_points

    tops = sorted({ep.value.split(":")[0].split(".")[0] for ep in entry_points(group=GROUP)})
    return ["pdverify", *(t for t in tops if t != "pdverify")]


@lru_cache(maxsize=1)
def code_digest() -> str:
    """A digest of every source file of :func:`code_packages`: part of each case's key, so editing a model
    recomputes its cases instead of resuming stale ones (conservative: any code change recomputes every
    case). A plug-in that cannot be found is left out (the registry warns about it)."""
    import importlib.util

    h = hashlib.sha256()
    for pkg in code_packages():
        try:
            spec = importlib.util.find_spec(pkg)
        except (ImportError, ValueError):
            spec = None
        if spec is None or spec.origin is None:
            continue
        root = Path(spec.origin).parent
        if Path(spec.origin).name != "__init__.py":  # a single-module plug-in
            h.update(Path(spec.origin).read_bytes())
            continue
        for f in sorted(root.rglob("*.py")):
            h.update(str(f.relative_to(root)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


GRID_OPTIONS = ("points", "horizon", "horizon_length")  # options that set the grid, not the operator group


@dataclass
class Case:
    scene_file: str
    scene_text: str
    slenderness: float | None
    model: str
    given: dict
    reference: dict
    quantities: tuple = ()  # more quantities to measure than the model's own (rotation, moment, shear, axial)

    @property
    def case_id(self) -> str:
        key = json.dumps(
            [
                _text_digest(self.scene_text),
                self.model,
                sorted(self.given.items()),
                self.slenderness,
                sorted(self.reference.items()),
                __version__,
                STORE_SCHEMA,
                code_digest(),
            ]
            + ([list(self.quantities)] if self.quantities else []),
            sort_keys=True,
            default=str,
        )
        return hashlib.sha256(key.encode()).hexdigest()[:16]

    def scene(self) -> Scene:
        return _scene(self.scene_text, self.scene_file, self.slenderness)

    @property
    def size(self) -> int:
        """How large a case is, to run the largest batches first: its points and those of a reference it solves (a
        reference of its own kind solved once per batch counts in each case; the order is what matters); a transient
        times the states it records (end_time / output_interval: a time step each at least), so that the few long
        time-stepping runs start first instead of ending the study on one worker."""
        points = _points(self.given.get("points")) + _points(self.reference.get("points"))
        return points * _recorded_states(self.scene_text)

    @property
    def batch_order(self) -> tuple:
        """Where a case runs in its batch (:attr:`operator_group`): scene by scene, each scene's finest grid first.
        A model judged against itself solves its reference grid as a case (the theory gap) and as the reference of
        the coarser grids: run one right after the other, the second takes the solve the first kept
        (:mod:`.solves`), where a batch run grid by grid would have pushed it out of the few results a process
        keeps."""
        return (self.scene_file, str(self.slenderness), -_points(self.given.get("points")))

    @property
    def operator_group(self) -> str:
        """The key of the cases that run in one process (:func:`pdverify.study.execute.pool`): the model, its options
        but the grid, the slenderness and the scene without its loads, whatever their references. Cases with one key
        solve the same operators (another load on the same grid) and the same references' operators, so one process
        factorises each once (:mod:`pdverify.numerics.factorcache`), and a model's solve on its own reference grid is
        made once for the case on that grid and the reference of the coarser ones (:mod:`.solves`)."""
        given = {k: v for k, v in self.given.items() if k not in GRID_OPTIONS}
        key = [self.model, given, self.slenderness, _skeleton(self.scene_text)]
        return json.dumps(key, sort_keys=True, default=str)


def _points(value) -> int:
    """A grid's points as a number (0 when not given or not a number: the spacing sets the grid)."""
    return value if isinstance(value, int) and not isinstance(value, bool) else 0


_NOT_OPERATOR = ("loads", "name", "description")  # what a scene may change without changing its operators


@lru_cache(maxsize=256)
def _parsed(text: str) -> dict | None:
    """A scene file's TOML, read once per scene (None when it is no TOML: such a case fails with its own record).
    Shared by its callers: read it, never change it."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return None


@lru_cache(maxsize=256)
def _skeleton(text: str) -> str:
    """A scene file without its loads and its names, as sorted JSON, once per scene (the text itself when it is no
    TOML)."""
    data = _parsed(text)
    if data is None:
        return text
    return json.dumps({k: v for k, v in data.items() if k not in _NOT_OPERATOR}, sort_keys=True, default=str)


@lru_cache(maxsize=256)
def _recorded_states(text: str) -> int:
    """The states a scene's transient records (end_time / output_interval, or / time_step when it gives no interval),
    1 for a static scene, one that gives neither, or one not read."""
    try:
        dyn = (_parsed(text) or {}).get("dynamics")
        return max(1, round(float(dyn["end_time"]) / float(dyn.get("output_interval") or dyn["time_step"])))
    except (AttributeError, KeyError, TypeError, ValueError, ZeroDivisionError, OverflowError):
        return 1


@lru_cache(maxsize=256)
def _text_digest(text: str) -> str:
    """A scene file's digest, once per scene (a study's cases share a few scenes)."""
    return hashlib.sha256(text.encode()).hexdigest()


def _shared_names(path: Path, scene_objs: dict) -> list[str]:
    """Scene files of different content that share a name: the tables group a series by the scene's name, so their
    errors would merge into one convergence series (the 17 support pairs of one transient would give one 'order')."""
    seen: dict[str, tuple[str, str]] = {}
    out = []
    for f, (text, sc) in scene_objs.items():
        if sc.name in seen and seen[sc.name][1] != text:
            out.append(
                f"{path}: scenes {seen[sc.name][0]} and {f} are both named {sc.name!r}; the tables group the cases by "
                "name, so give each scene its own name"
            )
        seen.setdefault(sc.name, (f, text))
    return out


@lru_cache(maxsize=256)
def _scene(scene_text: str, scene_file: str, slenderness) -> Scene:
    """Parsed (and rescaled) scene, once per process: scenes are frozen, so sharing is safe."""

    s = parse_scene(tomllib.loads(scene_text), source=scene_file)
    return s.with_slenderness(slenderness) if slenderness else s


@dataclass
class Study:
    name: str
    path: Path
    text: str
    scenes: list[str]
    reference: dict
    runs: list[dict]
    slenderness: list
    benchmarks: list[dict] = field(default_factory=list)
    checks: list[dict] = field(default_factory=list)
    verify: list[dict] = field(default_factory=list)  # {"model", "options", "folder"}: the verification cards
    verify_required: bool = False
    cases: list[Case] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    quantities: tuple = ()  # what every run measures besides its model's own quantity (a run may set its own)


def _benchmark_errors(bench: dict, where: str, study: Study) -> list[str]:
    """Target, tolerance and option filters of one benchmark row: a number that can pass or fail."""
    errors = []
    try:
        model = get_model(bench["model"])
    except InputError as exc:
        return [f"{where}: {exc.lines[0]}"]
    if "target" in bench and not (finite_number(bench["target"]) and bench["target"] != 0):
        errors.append(
            f"{where}.target = {bench['target']!r}: give a non-zero finite number (the tolerance is relative to it)"
        )
    tol = bench.get("tolerance", 0.01)
    if not (finite_number(tol) and tol > 0):
        errors.append(f"{where}.tolerance = {tol!r}: give a positive relative tolerance, e.g. 0.01")
    if "target" not in bench:
        refs = {c.reference["model"] for c in study.cases if c.scene_file == bench["scene"] and c.model == model.name}
        if refs == {"none"}:
            errors.append(f'{where}.target: missing, and its run has no reference (reference = "none"); give a target')
    filters = {k: v for k, v in bench.items() if k not in BENCH_KEYS | {"points", "slenderness"}}
    errors += option_filter_errors(model, filters, where, BENCH_KEYS | {"points", "slenderness"})
    if "points" in bench and not (
        isinstance(bench["points"], int) and not isinstance(bench["points"], bool) and bench["points"] >= 2
    ):
        errors.append(f"{where}.points = {bench['points']!r}: give a whole number of points of the sweep")
    if "slenderness" in bench and not (finite_number(bench["slenderness"]) and bench["slenderness"] > 0):
        errors.append(f"{where}.slenderness = {bench['slenderness']!r}: give a positive number of the sweep")
    return errors


def _external(path: Path, manifests) -> list[str]:
    """Register the external models of the study's ``external = ["manifest.toml", ...]`` (relative to the
    study file; see pdverify.registry.external); the problems as error lines."""

    if not isinstance(manifests, list) or not all(isinstance(m, str) for m in manifests):
        return [f"{path}: external = {manifests!r}: give a list of manifest files"]
    errors = []
    for m in manifests:
        try:
            use_manifest(path.parent / m)
        except InputError as exc:
            errors.extend(exc.lines)
    return errors


def _head(path: Path, data: dict) -> tuple[tuple[str, list, list], list[str]]:
    """The study's name, scene files and runs (as listed; an unusable list is empty), and the error lines of
    those, of unknown top-level keys and of ``[papers]``."""
    meant = {key: close_match(key, STUDY_KEYS - set(data)) for key in data if key not in STUDY_KEYS}
    errors = [
        f"{path}: unknown key '{key}'; "
        + (f"did you mean '{close}'?" if close else f"allowed: {', '.join(sorted(STUDY_KEYS))}")
        for key, close in meant.items()
    ]
    misspelt = set(meant.values())  # a key misspelt is one problem: its "missing" line goes
    name = data.get("name")
    if (not isinstance(name, str) or not name) and "name" not in misspelt:
        given = "missing" if name is None else "empty" if name == "" else f"= {name!r}: not a text"
        errors.append(f'{path}: name {given}; give the study a name in quotes, e.g. name = "my study"')
    if not isinstance(data.get("description", ""), str):
        errors.append(f'{path}: description = {data["description"]!r}: give a text in quotes, e.g. description = "..."')
    scenes = data.get("scenes")
    if not isinstance(scenes, list) or not scenes or not all(isinstance(s, str) for s in scenes):
        given = "missing" if scenes is None else f"= {scenes!r}"
        if "scenes" not in misspelt:
            errors.append(f"{path}: scenes {given}: give a non-empty list of scene files (a run's scenes pick from it)")
        scenes = []
    elif dup := twice(f"{path}: scenes", scenes):
        errors.append(dup)
    runs = data.get("runs")
    if not isinstance(runs, list) or not runs:
        if "runs" not in misspelt:
            errors.append(f"{path}: runs: missing or empty; add at least one [[runs]] table with a model")
        runs = []
    papers = data.get("papers", {})
    if not isinstance(papers, dict) or not all(isinstance(v, str) for v in papers.values()):
        errors.append(f'{path}: papers = {papers!r}: give a table {{scene folder = "page title"}}')
    for key, table in (("benchmarks", "[[benchmarks]]"), ("checks", "[[checks]]")):
        value = data.get(key, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            errors.append(f"{path}: {key} = {value!r}: give {table} tables (an array of tables), or leave it out")
    return (name, scenes, runs), errors


def scene_folder(scene_file) -> str:
    """The name of a scene file's folder: a report's page (a paper's scenes) and a ``[papers]`` key."""
    return Path(str(scene_file)).parent.name or "scenes"


def _papers_errors(path: Path, papers, scenes: list) -> list[str]:
    """A ``[papers]`` key that names no folder of the study's scenes (its page would keep the folder's own name)."""
    if not isinstance(papers, dict):
        return []  # said by _head
    folders = {scene_folder(s) for s in scenes}
    out = []
    for key in papers:
        if key not in folders:
            close = close_match(key, folders)
            hint = f"did you mean '{close}'?" if close else f"the scenes' folders: {', '.join(sorted(folders))}"
            out.append(f"{path}: papers.{key}: no scene of the study is in a folder '{key}'; {hint}")
    return out


def _sweep(path: Path, data: dict) -> tuple[list, list[str]]:
    """``[sweep]``'s slenderness list (``[None]``: the scenes' own sections) and its error lines."""
    errors = []
    sweep = data.get("sweep", {})
    if not isinstance(sweep, dict) or set(sweep) - {"slenderness"}:
        typo = (
            [k for k in sweep if k != "slenderness" and close_match(k, ["slenderness"])]
            if isinstance(sweep, dict)
            else []
        )
        errors.append(
            f"{path}: sweep.{typo[0]}: unknown key '{typo[0]}'; did you mean 'slenderness'?"
            if typo
            else f"{path}: sweep = {sweep!r}: only 'slenderness' (a list) can be swept here"
        )
        sweep = {}
    slen = as_list(sweep.get("slenderness", [None]))
    if not slen:
        errors.append(f"{path}: sweep.slenderness = []: an empty sweep runs nothing; give values or drop it")
    for s in slen:
        if s is not None and not (finite_number(s) and s > 0):
            errors.append(f"{path}: sweep.slenderness value {s!r}: must be a positive finite number (length / height)")
    if dup := twice(f"{path}: sweep.slenderness", slen):
        errors.append(dup)
    return slen, errors


def _study_reference(path: Path, data: dict) -> tuple[dict, list[str]]:
    """The study's reference (default exact-eb) as a table ``{model, options...}`` and its error lines."""
    try:
        return reference_table(data.get("reference", "exact-eb"), ""), []
    except InputError as exc:
        return {"model": "exact-eb"}, [f"{path}: {l}" for l in exc.lines]


def _read_scenes(path: Path, scenes: list[str]) -> tuple[dict[str, tuple[str, Scene]], list[str]]:
    """Each scene file's text and scene (paths relative to the study file), and the error lines of the files
    that do not load and of different scenes that share a name."""
    scene_objs: dict[str, tuple[str, Scene]] = {}
    errors = []
    for s in scenes:
        p = (path.parent / s) if not Path(s).is_absolute() else Path(s)
        try:
            sc = load_scene(p)
            scene_objs[s] = (p.read_text(encoding="utf-8-sig"), sc)  # the text load_scene read: no byte-order mark
        except InputError as exc:
            errors.extend(exc.lines)
    return scene_objs, errors + _shared_names(path, scene_objs)


def _reference_case_errors(path: Path, ref_model: Model, reference: dict, sfile: str, scene: Scene) -> list[str]:
    """Whether the reference takes its options (typed as TOML types them) on this scene and can solve it."""
    ref_given = {k: v for k, v in reference.items() if k != "model"}
    errors = [
        f"{path}: reference.{why}"
        for k, v in ref_given.items()
        if ref_model.option(k) is not None and (why := strict_type(ref_model.option(k), v))
    ]
    if not errors:  # (a coerced value would only add a confusing error)
        try:
            ref_model.resolve(scene, ref_given)
        except InputError as exc:
            errors.append(f"{path}: reference: {exc.lines[0]}")
    if reasons := ref_model.check(scene):
        errors.append(f"{path}: reference {ref_model.name} cannot solve {sfile}: {reasons[0]}")
    return errors


def _run_cases(run: Run, study: Study, scene_objs: dict, reasons_of: dict, refs_checked: set) -> list[str]:
    """Append the run's cases to ``study.cases``, every combination of its axes on every scene and slenderness,
    and those its model cannot solve to ``study.skipped``; the error lines of options the model does not take
    and of its reference. ``reasons_of``: (model, scene, slenderness) -> why the model cannot solve it;
    ``refs_checked``: what was validated, each once per study: (scene, slenderness, reference) and, for a swept
    slenderness, (scene, slenderness), the scaled scene itself."""
    combos = [dict(zip(run.axes, combo)) for combo in itertools.product(*run.axes.values())]
    ref_model = None
    if run.reference["model"] != "none":  # "none": no reference (e.g. large rotations), no errors
        try:
            ref_model = get_model(run.reference["model"])
        except InputError as exc:  # the study's own reference is reported once, as the study's
            own = run.reference["model"] != study.reference["model"]
            return [f"{run.where}: reference: {exc.lines[0]}"] if own and combos and run.scenes else []
    errors = []
    for given in combos:
        for sfile in run.scenes:
            stext, sc = scene_objs[sfile]
            for sl in run.slenderness:
                scx = sc.with_slenderness(sl) if sl else sc
                try:
                    if sl and (sfile, sl) not in refs_checked:  # the scaled scene is a scene too (its numbers' range)
                        refs_checked.add((sfile, sl))
                        parse_scene(scx.to_dict(), source=f"{sfile} at slenderness = {sl!r}")
                    params = run.model.resolve(scx, model_options(given))
                except InputError as exc:
                    errors.append(f"{run.where}: {exc.lines[0]}")
                    continue
                if (run.model.name, sfile, sl) not in reasons_of:  # the same for every option set
                    reasons_of[(run.model.name, sfile, sl)] = run.model.check(scx)
                if reasons := reasons_of[(run.model.name, sfile, sl)] or run.model.refusals(scx, params):
                    study.skipped.append(f"{run.written} on {sfile}: {reasons[0]}")
                    continue
                ref_key = (sfile, sl, repr(sorted(run.reference.items())))
                if ref_model is not None and ref_key not in refs_checked:  # once per scene and reference
                    refs_checked.add(ref_key)
                    errors += _reference_case_errors(study.path, ref_model, run.reference, sfile, scx)
                study.cases.append(
                    Case(sfile, stext, sl, run.model.name, dict(given), dict(run.reference), run.quantities)
                )
    return errors


MAX_CASES = 20_000  # cases of one study (the main job has about 450, a verification card about 450); more is refused


def _expand_runs(study: Study, scene_objs: dict) -> list[str]:
    """Expand every run of the study into its cases (:func:`_run_cases`); the error lines."""
    errors: list[str] = []
    reasons_of: dict = {}
    refs_checked: set = set()
    parsed_runs = []
    for i, run in enumerate(study.runs):
        parsed, found = parse_run(study.path, i, run, study.reference, study.slenderness, scene_objs, study.quantities)
        errors += found
        if parsed is not None:
            parsed_runs.append(parsed)
    sizes = [(math.prod(map(len, r.axes.values())) * len(r.scenes) * len(r.slenderness), r) for r in parsed_runs]
    if sum(n for n, _ in sizes) > MAX_CASES:  # before any case is checked (each check may solve a little)
        n, big = max(sizes, key=lambda t: t[0])
        axes = " x ".join(f"{len(v)} {k}" for k, v in big.axes.items() if len(v) > 1) or "its options"
        return errors + [
            f"{study.path}: {sum(n for n, _ in sizes):,} cases, more than a study may have ({MAX_CASES:,}); the "
            f"largest is {big.where} ({n:,}: {len(big.scenes)} scenes x {len(big.slenderness)} slenderness x "
            f"{axes}): sweep fewer values or split the study"
        ]
    for parsed in parsed_runs:
        errors += _run_cases(parsed, study, scene_objs, reasons_of, refs_checked)
    return errors


def _benchmark_rows_errors(study: Study, scene_objs: dict) -> list[str]:
    """The error lines of the study's ``[[benchmarks]]`` rows: keys, scene, position, expected and quantity,
    and :func:`_benchmark_errors`."""
    errors = []
    for j, bench in enumerate(study.benchmarks):
        where = f"{study.path}: benchmarks[{j}]"
        if not isinstance(bench, dict) or not {"name", "scene", "model"} <= set(bench):
            typo = [(meant_key(bench, k), k) for k in ("name", "scene", "model")]
            typo = [(t, k) for t, k in typo if t and t not in ("name", "scene", "model")]
            errors.append(
                f"{where}: unknown key '{typo[0][0]}'; did you mean '{typo[0][1]}'?"
                if typo
                else f"{where}: needs name, scene and model"
            )
            continue
        if bench["scene"] not in scene_objs:
            errors.append(f"{where}.scene = {bench['scene']!r}: not one of the study's scenes")
            continue
        errors += _benchmark_errors(bench, where, study)
        errors += _benchmark_output_errors(bench, where, scene_objs[bench["scene"]][1].length, _measured(study, bench))
    return errors


def _measured(study: Study, bench: dict) -> set:
    """The quantities the study measures besides the models' own on the runs of the benchmark's model (the study's
    ``quantities`` and its runs'): their references are kept in the cases, so a benchmark of one needs no target."""
    runs = [r for r in study.runs if isinstance(r, dict) and r.get("model") == bench["model"]]
    out = set(study.quantities)
    for r in runs:
        if isinstance(r.get("quantities"), list):
            out |= {q for q in r["quantities"] if isinstance(q, str)}
    return out


def _benchmark_output_errors(bench: dict, where: str, length: float, measured: set = frozenset()) -> list[str]:
    """The error lines of a benchmark row's position (on a beam of ``length``), expected and quantity (``measured``:
    the other quantities whose reference the study keeps, :func:`_measured`)."""
    errors = []
    if "position" in bench:
        pos = bench["position"]
        if not isinstance(pos, (int, float)) or isinstance(pos, bool) or not 0 <= pos <= length:
            errors.append(f"{where}.position = {pos!r}: give a number between 0 and the beam length {length:g}")
    if bench.get("expected", "pass") not in ("pass", "fail"):
        errors.append(
            f"{where}.expected = {bench['expected']!r}: pass (default) or fail (a known defect the row documents)"
        )
    measures = models()[bench["model"]].measures if bench["model"] in models() else "w"
    q = bench.get("quantity", measures)
    names = [*QUANTITIES, *(n for ns in FIELD_NAMES.values() for n in ns)]
    if not isinstance(q, str):
        errors.append(f"{where}.quantity = {q!r}: give an output name (w, rotation, u, theta, M ...)")
    elif q not in names and (close := close_match(q, names)):  # a misspelt name, before what else the row lacks
        errors.append(f"{where}.quantity = {q!r}: no such output; did you mean '{close}'?")
    elif q != measures and "position" not in bench:
        errors.append(
            f"{where}.quantity = {q!r}: a quantity other than {measures} (rotation or a field of the model's result, "
            "e.g. u, theta, M) is read at a point: give its position"
        )
    elif q != measures and "target" not in bench and canonical(q) not in measured:
        add = f'add "{canonical(q)}" to the study\'s quantities, or ' if canonical(q) in QUANTITIES else ""
        errors.append(
            f"{where}.quantity = {q!r}: the study keeps the reference of {measures} and of the quantities it measures "
            f"({', '.join(sorted(measured)) or 'none other'}) only; {add}give a target"
        )
    return errors


def load_study(path: str | Path, card_errors=None) -> Study:
    """Read a study file and validate every scene, model, option and reference. Raises InputError.
    ``card_errors(model, options)``: the problems of each ``verify`` entry (the pipeline passes
    :func:`pdverify.verify.entry_errors`: whether the suite applies to the model and its options)."""
    path = Path(path)
    text, data = read_toml(path, "study")
    (name, scenes, runs), errors = _head(path, data)
    slen, sweep_errors = _sweep(path, data)
    reference, reference_errors = _study_reference(path, data)
    errors += sweep_errors + reference_errors + _external(path, data.get("external", []))
    if errors:
        raise InputError(errors)

    scene_objs, errors = _read_scenes(path, scenes)
    if reference["model"] != "none":
        errors += [f"{path}: reference: {line}" for line in model_errors(reference["model"])]
    checks = data.get("checks", [])
    study = Study(
        name,
        path,
        text,
        scenes,
        reference,
        runs,
        slen,
        list(data.get("benchmarks", [])),
        list(checks) if isinstance(checks, list) else [],
    )
    study.quantities, found = parse_quantities(data.get("quantities"), f"{path}: ")
    errors += found
    errors += _expand_runs(study, scene_objs)
    errors += _benchmark_rows_errors(study, scene_objs)
    run_models = {r["model"] for r in runs if isinstance(r, dict) and isinstance(r.get("model"), str)}
    errors += validate_checks(checks, scene_objs, run_models & set(models()), path)
    errors += _papers_errors(path, data.get("papers"), scenes)
    study.verify, study.verify_required, found = verify_entries(data, path, card_errors)
    errors += found
    if errors:
        # one line per problem, duplicates (same bad option on many scenes) once
        raise InputError(list(dict.fromkeys(errors)))
    if not study.cases:
        raise InputError(
            f"{path}: the study expands to no case a model can solve; skipped: {'; '.join(study.skipped[:3])}"
        )
    return study
