"""What the report reads from a study folder (results and derived tables, meta.json, study.toml, scenes.json,
the case files), checked on the way in: a damaged or foreign input is one line naming the file and the fix."""

from __future__ import annotations

import csv
import json
import tomllib
from dataclasses import dataclass, field
from functools import cache, cached_property
from pathlib import Path

import pandas as pd

from ..core.errors import InputError, PdverifyError
from ..core.scene import UNITS, Scene
from ..study.outdir import SCENES
from ..study.spec import _scene
from ..study.store import case_file, read_curve
from .tables import LENGTH
from .text import folder, unit_of

# columns that hold text whatever they look like: a scene named "123", "NA" or "True" stays that name
TEXT_COLUMNS = frozenset(
    "study case_id code scene_file model reference version variant element form scene units options quantity "
    "status message warnings artefact_message check verdict name path held".split()
)
NUMBER_COLUMNS = frozenset(  # results.csv's columns the report computes with (and every err_* column)
    "slenderness points horizon horizon_length degree layers horizon_factor w_at_max w_ref_at_max assemble_s solve_s "
    "total_s dofs spacing m cond error_bound ref_error_bound continuum_error split_points".split()
)
DERIVED = ("convergence", "locking", "speed_error", "speed_error_summary", "benchmarks", "trust", "checks", "nonlocal")


def present(p: Path) -> bool:
    """Whether the study folder's file ``p`` is there; InputError when it is there but not a regular file (a device,
    a FIFO or a folder, or a symlink to one: reading /dev/zero would never end)."""
    if p.exists() and not p.is_file():
        raise InputError(f"{p}: not a regular file; run `pdverify study STUDY.toml --out {p.parent}` again")
    return p.exists()


def read_table(d: Path, name: str) -> pd.DataFrame:
    """``d/name.csv`` (empty when absent), text columns as text."""
    p = d / f"{name}.csv"
    if not present(p) or p.stat().st_size == 0:
        return pd.DataFrame()
    try:
        header = pd.read_csv(p, nrows=0).columns
        text = [c for c in header if c in TEXT_COLUMNS]
        numbers = {c: ["", "nan", "NaN", "NA", "None", "null"] for c in header if c not in TEXT_COLUMNS}
        df = pd.read_csv(p, dtype={c: "string" for c in text}, keep_default_na=False, na_values=numbers)
        for c in text:
            df[c] = df[c].fillna("").astype(str)
        return df
    except pd.errors.EmptyDataError:
        return pd.DataFrame()
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise InputError(
            f"{p}: not a readable CSV table ({str(exc).splitlines()[0][:120]}); run "
            f"`pdverify study STUDY.toml --out {d}` again"
        ) from None


def _short_rows(path: Path) -> tuple[int, int, int] | None:
    """(line, fields, header fields) of the first row whose field count differs from the header's, or None."""
    with open(path, newline="", encoding="utf-8") as fh:
        rows = csv.reader(fh)
        want = len(next(rows, []))
        for line, row in enumerate(rows, start=2):
            if row and len(row) != want:
                return line, len(row), want
    return None


@dataclass
class StudyFolder:
    """A study's outputs as the report uses them."""

    d: Path
    meta: dict
    res: pd.DataFrame
    tables: dict[str, pd.DataFrame] = field(default_factory=dict)
    titles: dict[str, str] = field(default_factory=dict)  # paper folder -> title (the study's [papers])
    description: str = ""
    study_text: str = ""

    @cached_property
    def ok(self) -> pd.DataFrame:
        return self.res[self.res["status"] == "ok"]

    def table(self, name: str) -> pd.DataFrame:
        return self.tables.get(name, pd.DataFrame())

    @cached_property
    def _units(self) -> dict[str, str]:
        """Unit system ('SI', 'inch-pound') of each scene file and scene name."""
        out = {}
        if "units" in self.res:
            for key in ("scene_file", "scene"):
                for k, u in zip(self.res[key], self.res["units"]):
                    if isinstance(u, str) and u in UNITS:
                        out.setdefault((key, k), u)
        return out

    def units(self, scene_file=None, scene=None) -> str:
        """The unit system of a scene (by file, else by name); SI when unknown."""
        return self._units.get(("scene_file", scene_file)) or self._units.get(("scene", scene)) or "SI"

    def length(self, scene_file=None, scene=None) -> str:
        return UNITS[self.units(scene_file, scene)]["length"]

    def unit_of_row(self, r, kind: str) -> str:
        """A table row's unit of a scene-dependent column: its scene's length, or its measured quantity's unit
        (the row's ``quantity``; w when it has none)."""
        system = self.units(r.get("scene_file"), r.get("scene"))
        if kind == LENGTH:
            return UNITS[system]["length"]
        q = r.get("quantity") if isinstance(r.get("quantity"), str) and r.get("quantity") else "w"
        return unit_of(q, system)

    @cached_property
    def scene_paper(self) -> dict[str, str]:
        """Paper folder of each scene name."""
        return {s: folder(f) for s, f in zip(self.res["scene"], self.res["scene_file"])}

    def curve(self, case_id) -> dict | None:
        """A case's curves (None when its file is gone), each file decoded once per build."""
        return self._curve(str(case_id))

    @cached_property
    def _curve(self):
        @cache
        def read(case_id: str):
            path = case_file(self.d / "cases", case_id)
            if path is None:
                return None
            try:
                return read_curve(path)
            except ValueError:
                raise InputError(
                    f"{path}: a damaged case file (not a whole, readable case record); run "
                    f"`pdverify study STUDY.toml --out {self.d}` again, which recomputes it, then the report"
                ) from None

        return read

    @cached_property
    def _scene_texts(self) -> dict:
        if not (self.d / SCENES).is_file():  # missing, or a FIFO or device under its name (reading it would block)
            return {}
        try:
            return json.loads((self.d / SCENES).read_text())
        except (OSError, ValueError, RecursionError):  # a study run before scenes.json was written (or it is damaged)
            return {}

    def scene(self, scene_file: str, slenderness=None) -> Scene | None:
        """The scene as run (the study's scenes.json), None when unknown or unreadable."""
        text = self._scene_texts.get(scene_file)
        if text is None:
            return None
        try:
            return _scene(text, scene_file, slenderness)
        except (PdverifyError, ValueError):
            return None


def _json_object(text) -> bool:
    """Whether a results row's options cell is empty or a JSON object."""
    if text is None or (isinstance(text, str) and not text.strip()) or (isinstance(text, float) and text != text):
        return True
    try:
        return isinstance(json.loads(text), dict)
    except (TypeError, ValueError, RecursionError):
        return False


def load(d: Path) -> StudyFolder:
    """The study folder ``d``, checked: results.csv present, whole and a pdverify table; meta.json an object."""
    if not d.is_dir():
        what = "not a folder" if d.exists() else "no such folder"
        raise InputError(f"{d}: {what}; give a study's output folder (`pdverify study STUDY.toml --out {d}` makes one)")
    if not present(d / "results.csv"):
        raise InputError(f"{d}: no results.csv; run `pdverify study STUDY.toml --out {d}` first")
    again = f"run `pdverify study STUDY.toml --out {d}` again"
    try:
        meta = json.loads((d / "meta.json").read_text()) if present(d / "meta.json") else {"study": d.name}
    except (ValueError, UnicodeDecodeError, RecursionError):  # nested past Python's recursion limit: damaged too
        raise InputError(f"{d / 'meta.json'}: not valid JSON; {again}") from None
    res = read_table(d, "results")
    if res.empty:
        raise InputError(f"{d / 'results.csv'}: no cases (an empty table); {again}")
    for col in ("case_id", "scene_file", "scene", "status", "model", "slenderness", "points", "err_max"):
        if col not in res:
            raise InputError(f"{d / 'results.csv'}: no '{col}' column; not a pdverify results table ({again})")
    short = _short_rows(d / "results.csv")
    if short:
        line, got, want = short
        raise InputError(f"{d / 'results.csv'}: line {line} has {got} fields, the header {want}; {again}")
    for col in res.columns:
        if (col in NUMBER_COLUMNS or col.startswith("err_")) and not pd.api.types.is_numeric_dtype(res[col]):
            bad = pd.to_numeric(res[col], errors="coerce").isna() & res[col].notna()
            i = int(bad.to_numpy().argmax())
            raise InputError(
                f"{d / 'results.csv'}: line {i + 2}, column '{col}' = {str(res[col].iloc[i])[:40]!r}: not a number; "
                f"{again}"
            )
    if "options" in res:  # every figure and table reads a row's options as a JSON object
        for i, text in enumerate(res["options"]):
            if not _json_object(text):
                raise InputError(
                    f"{d / 'results.csv'}: line {i + 2}, column 'options' = {str(text)[:40]!r}: not a JSON object; "
                    f"{again}"
                )
    if not isinstance(meta, dict):
        raise InputError(f"{d / 'meta.json'}: not a JSON object; {again}")
    if not (d / "cases").is_dir():  # every figure's curves: each would be drawn empty
        raise InputError(f"{d}: no cases folder (the cases' curves); {again}, which recomputes them")
    study = d / "study.toml"
    titles, description, text = {}, "", ""
    if present(study):
        text = study.read_text(encoding="utf-8", errors="replace")
        try:
            spec = tomllib.loads(text)
            titles = {str(k): str(v) for k, v in dict(spec.get("papers", {})).items()}
            description = str(spec.get("description", ""))
        except (tomllib.TOMLDecodeError, AttributeError, TypeError, ValueError):
            titles = {}
    return StudyFolder(
        d=d,
        meta=meta,
        res=res,
        tables={n: read_table(d, n) for n in DERIVED},
        titles=titles,
        description=description,
        study_text=text,
    )
