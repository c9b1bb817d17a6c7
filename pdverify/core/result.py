"""The result of one solve: point positions, deflection, rotation, other fields, cost."""

from __future__ import annotations

import io
import json
import time
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from .errors import MissingQuantity, SolveError
from .version import __version__

# What a study can measure, and where a result holds it: its canonical name, then the names the models' fields use
# (M, V, N: the bending moment, sagging positive; the shear force V = dM/dx; the axial force, tension positive).
# A curved model's Q (the shear of its own frame, Q = -dM/ds) counts as -shear.
QUANTITIES = {
    "w": "deflection",
    "rotation": "rotation of the section (counter-clockwise)",
    "moment": "bending moment (sagging positive)",
    "shear": "shear force (dM/dx)",
    "axial": "axial force (tension positive)",
    "u": "axial displacement",
    "twist": "angle of twist",
}
FIELD_NAMES = {"moment": ("moment", "M"), "shear": ("shear", "V"), "axial": ("axial", "N")}


def canonical(name: str) -> str:
    """The :data:`QUANTITIES` name of an output (``M`` -> moment, ``V`` -> shear, ``N`` -> axial), else the name."""
    return next((q for q, names in FIELD_NAMES.items() if name in names), name)


def quantity_of(w, rotation, fields: dict, quantity: str):
    """The values of ``quantity`` (:data:`QUANTITIES`) among a solution's w, rotation and fields; None when it
    has none."""
    if quantity == "w":
        return w
    if quantity == "rotation":
        return rotation if rotation is not None else fields.get("rotation")
    for name in FIELD_NAMES.get(quantity, (quantity,)):
        if name in fields:
            return fields[name]
    if quantity == "shear" and "Q" in fields:
        return -np.asarray(fields["Q"], float)
    return None


@dataclass
class Result:
    """What every model returns.

    ``x``: positions of the real points (m), no fictitious ones; ``w``: deflection there (m, +z);
    ``rotation``: rotation (rad, counter-clockwise) where the model has one; ``fields``: other
    point outputs (axial displacement ``u``, resultants ``N``, ``Q``, ``M`` ...); ``info``:
    scalars such as the condition-number estimate, mesh, element, warnings; ``path``: the steps of a load path.
    ``writers`` maps a file suffix (".vtu") to a function writing a model-specific artefact.
    """

    scene: str
    model: str
    parameters: dict
    x: np.ndarray
    w: np.ndarray
    rotation: np.ndarray | None = None
    fields: dict[str, np.ndarray] = field(default_factory=dict)
    dofs: int = 0
    timings: dict[str, float] = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    path: list[dict] | None = None  # one entry per step of a load path (factor, w, reactions, ...), in order
    version: str = __version__
    writers: dict[str, Callable[[str], None]] = field(default_factory=dict, repr=False)

    def measured(self, quantity: str = "w") -> np.ndarray:
        """The output ``quantity`` (:data:`QUANTITIES`: w, rotation, moment, shear, axial, or a point field such
        as a rod's u or a torsion bar's twist); MissingQuantity (an InputError and a KeyError) when it has none."""
        got = quantity_of(self.w, self.rotation, self.fields, quantity) if isinstance(quantity, str) else None
        if got is None:
            have = ", ".join(q for q in QUANTITIES if quantity_of(self.w, self.rotation, self.fields, q) is not None)
            raise MissingQuantity(f"quantity = {quantity!r}: model {self.model} gives no such output; it gives {have}")
        return np.asarray(got, float)

    def to_dict(self) -> dict:
        out = {
            "scene": self.scene,
            "model": self.model,
            "parameters": plain_json(self.parameters),
            "x": plain_json(self.x),
            "w": plain_json(self.w),
        }
        if self.rotation is not None:
            out["rotation"] = plain_json(self.rotation)
        if self.fields:
            out["fields"] = {k: plain_json(v) for k, v in self.fields.items()}
        out["dofs"] = int(self.dofs)
        out["timings"] = {k: float(v) for k, v in self.timings.items()}
        if self.info:
            out["info"] = plain_json(self.info)
        if self.path is not None:
            out["path"] = plain_json(self.path)
        out["version"] = self.version
        return out

    def to_json(self) -> str:
        return json.dumps(self.to_dict())

    def columns(self) -> dict[str, np.ndarray]:
        cols = {"x": self.x, "w": self.w}
        if self.rotation is not None:
            cols["rotation"] = self.rotation
        for k, v in self.fields.items():
            if np.shape(v) == np.shape(self.x):
                cols[k] = v
        return cols

    def to_csv(self) -> str:
        """A header line and one row per point; a result that carries warnings starts with one comment
        line per warning, ``# warning: ...``, and, when through-section stresses were asked for (option
        ``stations``) or the run made an estimate of its own error, the lines of :meth:`output_lines` (read it back
        with ``pandas.read_csv(..., comment="#")``; without either it is a plain table)."""
        shown = any(self.info.get(k) for k in ("sections", "estimate", "grid_estimate", "history_estimate"))
        head = self.warning_lines() + (self.output_lines() if shown else [])
        return "".join(f"# {one_line(line)}\n" for line in head) + columns_csv(self.columns())

    def output_lines(self) -> list[str]:
        """``reactions: force_left=...`` and, per station of ``info["sections"]``, ``section x = ...: z,
        sigma_xx, sigma_zz, tau_xz`` followed by one line of those four numbers per z (the CSV's comment lines
        and the table's header; JSON carries them in ``info``)."""
        out = []
        if self.info.get("estimate"):
            out.append(self.info["estimate"]["line"])
        for key, part in (("grid_estimate", "field"), ("history_estimate", "series")):  # run's own estimates
            if est := self.info.get(key):
                coarse, fine = est["grids"]
                said = f"difference {est['difference']:.3g} in {est[part]}" if "difference" in est else est.get("note")
                out.append(
                    f"{key}: the same {'solve' if part == 'field' else 'run'} on {coarse} points against {fine}: {said}"
                )
        r = self.info.get("reactions")
        if r:
            out.append("reactions: " + ", ".join(f"{k}={v:.8g}" for k, v in r.items() if not isinstance(v, str)))
        for sec in self.info.get("sections", []):
            out.append(f"section x = {sec['x']:.8g}: z, sigma_xx, sigma_zz, tau_xz")
            rows = zip(sec["z"], sec["sigma_xx"], sec["sigma_zz"], sec["tau_xz"])
            out += [", ".join(f"{v:.8g}" for v in row) for row in rows]
        return out

    def warning_lines(self) -> list[str]:
        """``warning: ...`` once per entry of ``info["warnings"]`` (what the table and CSV formats print)."""
        return [f"warning: {w}" for w in self.info.get("warnings", [])]


def merge_info(info: dict, *parts: dict, **more) -> dict:
    """``info.update(part, ..., **more)`` with the ``warnings`` lists joined in order: a solve's info merged into what
    a model gathered before it keeps both's warnings (an update would keep only the last list)."""
    said = list(info.get("warnings", []))
    for part in (*parts, more):
        said += [w for w in part.get("warnings", []) if w not in said]
        info.update(part)
    if said:
        info["warnings"] = said
    return info


def check_finite(result: Result) -> Result:
    """A result holding NaN or inf (in a field or a reaction) is a failed computation, never an output: raises
    SolveError (exit 3) with one line naming the model and the first field that is not finite."""

    arrays = {
        "x": result.x,
        "w": result.w,
        "rotation": result.rotation,
        **{f"fields.{k}": v for k, v in result.fields.items()},
        **{
            f"reaction {k}": v
            for k, v in (result.info.get("reactions") or {}).items()
            if isinstance(v, (float, int)) and not isinstance(v, bool)
        },
    }
    for name, v in arrays.items():
        if v is None:
            continue
        a = np.asarray(v)
        if a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
            bad = int(np.size(a) - np.count_nonzero(np.isfinite(a)))
            raise SolveError(
                f"{result.model}: the computed {name} is not finite (NaN/inf at {bad} of {np.size(a)} "
                "values): the scene's numbers overflow or underflow this model's arithmetic (e.g. a "
                "modulus near 1e-300 or 1e300); give them in units that keep them near 1"
            )
    return result


def columns_csv(cols: dict, fmt: str = "%.17g") -> str:
    """Named equal-length columns as CSV text: a header line, then one row per entry."""
    buf = io.StringIO()
    buf.write(",".join(cols) + "\n")
    np.savetxt(buf, np.column_stack([np.asarray(v, float) for v in cols.values()]), delimiter=",", fmt=fmt)
    return buf.getvalue()


def plain_json(v):
    """numpy -> JSON-able Python (NaN/inf become None so the JSON stays valid)."""
    if isinstance(v, dict):
        return {str(k): plain_json(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [plain_json(x) for x in v]
    if isinstance(v, np.ndarray):
        return plain_json(v.tolist())
    if isinstance(v, (np.floating, float)):
        f = float(v)
        return f if np.isfinite(f) else None
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return v


_CONTROL = {c: f"\\x{c:02x}" for c in (*range(32), 127)} | {9: " ", 10: "\\n", 13: "\\r"}


def one_line(text) -> str:
    """``text`` on one line: its control characters (a newline in a scene's name, a NUL) written as escapes, so a
    ``#`` comment line of a table or CSV stays one line."""
    return str(text).translate(_CONTROL)


class Timer:
    """Collects named wall-clock intervals: ``with timer("assemble"): ...`` -> ``assemble_s``."""

    def __init__(self):
        self.timings: dict[str, float] = {}

    @contextmanager
    def __call__(self, name: str):
        t0 = time.perf_counter()
        try:
            yield
        finally:
            key = f"{name}_s"
            self.timings[key] = self.timings.get(key, 0.0) + time.perf_counter() - t0
