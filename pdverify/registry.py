"""The model registry: every model of ``pdverify solve`` is a small object found here.

A model module (in ``pdverify.exact``, ``pdverify.models`` or ``reference_fem``) defines a list
``MODELS`` of :class:`Model` instances; the registry imports those packages' modules and collects
them, so adding a model never means editing a central file.

A model declares its options (name, type, default, allowed values), says which scenes it can solve
(:meth:`Model.check`) and solves one scene (:meth:`Model.solve`). :func:`run` validates the
options, times the whole call and returns a :class:`~pdverify.result.Result`.
"""

from __future__ import annotations

import importlib
import pkgutil
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import InputError
from .result import Result, check_finite
from .scene import Scene

MODEL_PACKAGES = ("pdverify.exact", "pdverify.models", "reference_fem")


@dataclass(frozen=True)
class Option:
    """One option a model takes. ``minimum`` is inclusive unless ``strict``."""

    name: str
    kind: type
    default: Any
    help: str = ""
    choices: tuple | None = None
    minimum: float | None = None
    strict: bool = False
    maximum: float | None = None

    def coerce(self, model: str, value):
        try:
            if self.kind is int:
                f = float(value)
                if f != int(f):
                    raise ValueError
                v = int(f)
            elif self.kind is float:
                v = float(value)
                if not np.isfinite(v):
                    raise ValueError
            elif self.kind is bool:
                v = value if isinstance(value, bool) else str(value).lower() in ("1", "true", "yes", "on")
            else:
                v = self.kind(value)
        except (TypeError, ValueError):
            raise InputError(
                f"{self.name} = {value!r}: model {model} needs {'an integer' if self.kind is int else 'a number' if self.kind is float else self.kind.__name__} here"
            ) from None
        if self.choices is not None and v not in self.choices:
            raise InputError(
                f"{self.name} = {value!r}: not an option of model {model}; allowed: {', '.join(map(str, self.choices))}"
            )
        if self.minimum is not None and (v < self.minimum or (self.strict and v == self.minimum)):
            raise InputError(
                f"{self.name} = {value!r}: model {model} needs {self.name} {'>' if self.strict else '>='} {self.minimum:g}"
                + (" (the horizon must cover at least one spacing)" if self.name == "horizon" else "")
            )
        if self.maximum is not None and v > self.maximum:
            raise InputError(f"{self.name} = {value!r}: model {model} needs {self.name} <= {self.maximum:g}")
        return v


POINTS = Option("points", int, 101, "material points / nodes along the axis, ends included", minimum=2)


class Model:
    """Base class. Subclasses set ``name``, ``title``, ``source``, ``options`` and ``solve``.

    ``points`` (if among the options) may also be given as ``spacing``; the registry converts.
    """

    name: str = ""
    title: str = ""
    source: str = ""
    options: tuple[Option, ...] = (POINTS,)
    kind: str = "static"  # static | dynamic
    curved: bool = False  # solves curved axes
    axial: bool = False  # carries axial loads (loads[i].axial)
    bending: bool = True  # carries transverse loads (loads[i].value)
    torsion: bool = False  # carries torques (point_torque, loads[i].torque)
    theory: str = "euler-bernoulli"  # euler-bernoulli | timoshenko | higher-order | continuum (what it can represent)
    reference: bool = False  # closed-form or reference model (not a candidate of `pdverify advise` by default)

    def check(self, scene: Scene) -> list[str]:
        """Reasons this model cannot solve ``scene`` (empty when it can)."""
        out = []
        if not scene.is_straight and not self.curved:
            out.append(f"model {self.name} solves straight beams only; axis.type = {scene.axis.type!r}")
        for i, load in enumerate(scene.loads):
            if getattr(load, "axial", 0.0) != 0.0 and not self.axial:
                out.append(f"loads[{i}].axial = {load.axial!r}: model {self.name} has no axial displacement; "
                           "use a model with an axial DOF or drop the axial component")
            torque = load.type == "point_torque" or getattr(load, "torque", 0.0) != 0.0
            if torque and not self.torsion:
                out.append(f"loads[{i}]: a torque: model {self.name} has no twist; use a torsion model (pd-torsion) "
                           "or drop the torque")
            if load.value != 0.0 and not self.bending and load.type != "point_torque":
                what = "moments" if load.type == "point_moment" else "transverse loads"
                out.append(f"loads[{i}].value = {load.value!r}: model {self.name} carries no {what} (axial only); "
                           "give the load as loads[i].axial or use a bending model")
        return out

    def solve(self, scene: Scene, params: dict) -> Result:  # pragma: no cover - interface
        raise NotImplementedError

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray] | None:
        """Fields at arbitrary positions ``x`` (exact models); None when only point values exist."""
        return None

    def evaluator(self, scene: Scene, params: dict):
        """A function x -> fields (as :meth:`evaluate`) for repeated evaluation on one scene, or None when
        the model has no ``evaluate``. Models whose ``evaluate`` solves first override this to solve once."""
        if type(self).evaluate is Model.evaluate:
            return None
        return lambda x: self.evaluate(scene, params, x)

    # -- option handling -----------------------------------------------------------------
    def option(self, name: str) -> Option | None:
        return next((o for o in self.options if o.name == name), None)

    def resolve(self, scene: Scene, given: dict) -> dict:
        """Validate ``given`` options against this model and fill in the defaults."""
        given = {k: v for k, v in given.items() if v is not None}
        if "spacing" in given:
            if self.option("points") is None:
                raise InputError(f"spacing: model {self.name} takes no grid; drop --spacing")
            if "points" in given:
                raise InputError("points and spacing both given; give one of them")
            given["points"] = points_from_spacing(scene.length, given.pop("spacing"))
        names = [o.name for o in self.options]
        for key in given:
            if key not in names:
                raise InputError(
                    f"{key}: model {self.name} takes no option '{key}'; it takes: {', '.join(names) or 'none'}"
                )
        params = {}
        for opt in self.options:
            params[opt.name] = opt.coerce(self.name, given[opt.name]) if opt.name in given else opt.default
        return params


def points_from_spacing(length: float, spacing) -> int:
    try:
        dx = float(spacing)
    except (TypeError, ValueError):
        raise InputError(f"spacing = {spacing!r}: needs a number (metres)") from None
    if not dx > 0:
        raise InputError(f"spacing = {spacing!r}: must be positive")
    n = length / dx
    if n < 1 - 1e-9:
        raise InputError(f"spacing = {dx:g}: larger than the beam length {length:g}")
    if abs(n - round(n)) > 1e-6 * max(1.0, n):
        raise InputError(
            f"spacing = {dx:g}: does not divide the length {length:g} into whole intervals ({n:.6g}); "
            "choose length / spacing an integer, or give --points"
        )
    return int(round(n)) + 1


_REGISTRY: dict[str, Model] | None = None


def models() -> dict[str, Model]:
    """All registered models by name (imported once)."""
    global _REGISTRY
    if _REGISTRY is None:
        reg: dict[str, Model] = {}
        for pkg_name in MODEL_PACKAGES:
            pkg = importlib.import_module(pkg_name)
            for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda i: i.name):
                if info.name.startswith("_"):
                    continue
                mod = importlib.import_module(f"{pkg_name}.{info.name}")
                for m in getattr(mod, "MODELS", ()):
                    if m.name in reg:
                        raise RuntimeError(f"model name {m.name!r} registered twice ({mod.__name__})")
                    reg[m.name] = m
        _REGISTRY = dict(sorted(reg.items()))
    return _REGISTRY


def get_model(name: str) -> Model:
    reg = models()
    if name not in reg:
        raise InputError(f"model = {name!r}: unknown model; available: {', '.join(reg)}")
    return reg[name]


def run(scene: Scene, model: str | Model, **given) -> Result:
    """Solve ``scene`` with ``model`` and the given options; the whole call is timed (``total_s``)."""
    t0 = time.perf_counter()
    m = get_model(model) if isinstance(model, str) else model
    problems = m.check(scene)
    if problems:
        raise InputError(problems)
    params = m.resolve(scene, given)
    result = check_finite(m.solve(scene, params))
    result.timings["total_s"] = time.perf_counter() - t0
    result.timings.setdefault("assemble_s", 0.0)
    result.timings.setdefault("solve_s", 0.0)
    return result
