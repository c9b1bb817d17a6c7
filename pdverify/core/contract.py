"""The model contract: what a model declares and provides (docs/contract.md has the version for model authors).

* **Options** -- a model declares its options (:class:`Option`: name, type, default, allowed values);
  :meth:`Model.resolve` validates what the user gave and fills in the defaults.
* **Capabilities, as data** -- each model declares what it can solve: ``analyses`` (``"static"`` and/or
  ``"dynamic"``), ``straight`` / ``curved`` axes, ``supports``, ``load_types``, the load components it
  carries (``bending``, ``axial``, ``torsion``), ``end_motions`` (prescribed end motions of a
  ``[dynamics]`` table) and ``variant_rules`` (:class:`Rule`: the option values a variant's equations
  define). :meth:`Model.check` turns them into one line per problem; :meth:`Model.resolve` applies
  :func:`variant_problems`, so a study file is checked when it is loaded.
* **Solve** -- :meth:`Model.solve` returns a :class:`~pdverify.core.result.Result`.
* **Assembled system** -- a linear static model whose solve factorises one linear system sets
  ``assembles = True`` and implements :meth:`Model.assemble`, which returns that :class:`System`
  (the matrix as a :class:`~pdverify.numerics.band.Band` or scipy sparse, the right-hand side, the free
  unknowns, info). ``pdverify bench`` times the banded solve of exactly that system. Models whose static
  path is nonlinear for some options declare them in ``nonlinear_when``; models with a time integrator list
  ``"dynamic"`` in ``analyses`` and implement :meth:`Model.bench_dynamics`.

>>> import numpy as np, scipy.sparse as sp
>>> K = sp.diags([[-1.0] * 3, [2.0] * 4, [-1.0] * 3], [-1, 0, 1]).tocsr()
>>> s = System(K, np.ones(4), free=np.arange(4), info={})
>>> s.unknowns, s.eliminated
(4, True)
>>> Kf, bf = System(K, np.ones(4), free=np.array([1, 2]), info={}).reduced()
>>> Kf.toarray().tolist(), bf.tolist()
([[2.0, -1.0], [-1.0, 2.0]], [1.0, 1.0])

One file on purpose: Option, Rule, System and Model with its capability checks are read together by a model
author.
"""

# long module: the Model class every model implements, its options and capabilities in one place

from __future__ import annotations

from dataclasses import dataclass, field
from decimal import Decimal
from typing import Any

import numpy as np
import scipy.sparse as sp

from .errors import InputError
from .horizon import Horizon
from .result import Result
from .scene import Scene, straight_mechanism
from .text import close_match


def whole_number(value) -> int:
    """``value`` as a whole number: an integer (or its digits) exactly, whatever its size (2**53 + 1 through a float
    would be 2**53); a number with a fractional part is a ValueError."""
    if isinstance(value, (int, np.integer)):
        return int(value)
    try:
        return int(str(value).strip())
    except ValueError:
        f = float(value)
        if f != int(f):
            raise ValueError from None
        return int(f)


def _short(v: int) -> str:
    """A whole number past 1e15 in three digits (1e+20), past the float range too (1.00e+400)."""
    try:
        return format(float(v), ".3g")
    except OverflowError:
        return format(Decimal(v), ".3g")


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
            if isinstance(value, bool) and self.kind in (int, float):
                raise ValueError  # numbers never from true/false
            if isinstance(value, str) and ("_" in value or not value.isascii()) and self.kind in (int, float):
                raise ValueError  # Python reads "3_0" as 30 and Arabic-Indic "٤١" as 41: not a number as written
            if self.kind is int:
                v = whole_number(value)
            elif self.kind is float:
                v = float(value)
                if not np.isfinite(v):
                    raise ValueError
            elif self.kind is bool:  # true/false only: "maybe" or 2 is an error, not False
                if isinstance(value, bool):
                    v = value
                elif str(value).strip().lower() in ("true", "false"):
                    v = str(value).strip().lower() == "true"
                else:
                    raise ValueError
            else:
                v = self.kind(value)
        except (TypeError, ValueError, OverflowError):
            raise InputError(
                f"{self.name} = {value!r}: model {model} needs "
                + {int: "an integer", float: "a finite number", bool: "true or false"}.get(
                    self.kind, self.kind.__name__
                )
                + " here"
            ) from None
        if self.choices is not None and v not in self.choices:
            close = close_match(v, self.choices) if isinstance(v, str) else None
            hint = f"did you mean '{close}'? " if close else ""
            raise InputError(
                f"{self.name} = {value!r}: not an option of model {model}; {hint}allowed: "
                + ", ".join(map(str, self.choices))
            )
        if self.minimum is not None and (v < self.minimum or (self.strict and v == self.minimum)):
            raise InputError(
                f"{self.name} = {value!r}: model {model} needs {self.name} "
                f"{'>' if self.strict else '>='} {self.minimum:g}"
                + (" (the horizon must cover at least one spacing)" if self.name == "horizon" else "")
            )
        if self.maximum is not None and v > self.maximum:
            shown = (_short(v) if v > 10**18 else str(v)) if isinstance(v, int) else repr(value)  # not 400 digits
            most = (
                f"{int(self.maximum)}" if self.kind is int and float(self.maximum).is_integer() else f"{self.maximum:g}"
            )
            raise InputError(f"{self.name} = {shown}: model {model} needs {self.name} <= {most}")
        return v


@dataclass
class System:
    """The linear system a linear static model's solve factorises: ``matrix @ z = rhs``.

    ``matrix``: a :class:`~pdverify.numerics.band.Band` or a scipy sparse matrix. ``free``: the indices, in the
    model's own numbering of its unknowns, of those the supports leave free. Either the held unknowns
    were eliminated (``matrix`` is ``len(free)`` square and z = u[free]: :attr:`eliminated`), or they
    keep their place with a unit row and a cleared column (z is the whole u, zero where held).
    ``info``: what the assembly chose (ghost layers, form, ...), merged into the result's info."""

    matrix: Any  # a pdverify.numerics.band.Band or a scipy sparse matrix
    rhs: np.ndarray
    free: np.ndarray
    info: dict = field(default_factory=dict)

    @property
    def unknowns(self) -> int:
        """Free unknowns (the result's ``dofs`` for a single-solve model)."""
        return len(self.free)

    @property
    def eliminated(self) -> bool:
        return self.matrix.shape[0] == len(self.free)

    def reduced(self) -> tuple[sp.csr_matrix, np.ndarray]:
        """(CSR, rhs) of the free unknowns only: the rows and columns of ``free`` (the held ones dropped)."""
        K = sp.csr_matrix(self.matrix.tocsr())  # a Band or any scipy sparse matrix
        if self.eliminated:
            return K, np.asarray(self.rhs)
        f = np.asarray(self.free, np.int64)
        return K[f][:, f].tocsr(), np.asarray(self.rhs)[f]


@dataclass(frozen=True)
class Rule:
    """An option value a variant's equations define (checked by :func:`run` before solving).

    When every option in ``when`` has the given value, option ``option`` must be one of ``allowed`` (if
    given) and a whole number (if ``whole``); ``why`` names the equation that defines only those."""

    when: tuple[tuple[str, Any], ...]
    option: str
    why: str
    allowed: tuple | None = None
    whole: bool = False
    unless: str | None = None  # an option that, when given, lifts the rule (a horizon given as a length)

    def applies(self, params: dict) -> bool:
        return all(params.get(k) == v for k, v in self.when) and not (
            self.unless and params.get(self.unless) is not None
        )

    def problem(self, model: str, params: dict) -> str | None:
        if not self.applies(params) or self.option not in params:
            return None
        v = params[self.option]
        bad_value = self.allowed is not None and v not in self.allowed
        bad_whole = self.whole and float(v) != int(float(v))
        if not (bad_value or bad_whole):
            return None
        cond = ", ".join(f"{k} = {val}" for k, val in self.when)
        need = "a whole number" if bad_whole else "one of " + ", ".join(map(str, self.allowed))
        return f"{self.option} = {v!r}: not defined by {cond} of model {model}, which takes {need} ({self.why})"


SUPPORTS = frozenset({"clamped", "pinned", "roller", "guided", "free"})  # docs/supports.md: one meaning each


def missing_torsion_constant(scene: Scene, model: str) -> str | None:
    """The line naming a section without a torsion constant J (a profile or area-and-inertia section has none of its
    own; a rectangle and a thin-walled I have), which a torsion model needs; None when every piece of the beam has
    one."""
    if all(sec.J is not None for _, _, sec, _ in scene.pieces()):
        return None
    return (
        f"section.torsion_constant: {model} needs the torsion constant J of every section (a profile or "
        "area-and-inertia section has none of its own); add torsion_constant (or give width and height)"
    )


LOAD_TYPES = frozenset({"point_force", "point_moment", "distributed"})  # + "point_torque" for torsion models

# an end motion of [dynamics.left/right] and the load component (Model attribute) whose unknown it moves
MOTION_COMPONENT = {"displacement": "bending", "rotation": "bending", "axial": "axial", "twist": "torsion"}

MAX_POINTS = 2**53  # a grid's points: a whole number float64 holds exactly (and a results table's int64)
POINTS = Option(
    "points", int, 101, "material points / nodes along the axis, ends included", minimum=2, maximum=MAX_POINTS
)
HORIZON_LENGTH = Option(
    "horizon_length",
    float,
    None,
    "the horizon delta in the scene's length unit (instead of horizon, a multiple of the spacing): m = delta / dx",
    minimum=0.0,
    strict=True,
)
CONTINUUM = Option(
    "continuum",
    bool,
    False,
    "the model's nonlocal continuum solution at this horizon (its sums replaced by integrals): a closed form where "
    "one exists, else extrapolated in m at fixed delta, with its own error estimate (docs/nonlocal.md)",
)
CONTINUUM_M = Option(
    "continuum_m",
    int,
    None,
    "the finest m of the continuum's extrapolation, two levels at least (default: the model's; fewer is cheaper and "
    "less accurate)",
    minimum=8,
    maximum=256,  # past m = 128 the extrapolation's levels gain round-off, not accuracy (docs/nonlocal.md)
)
NONLOCAL = (HORIZON_LENGTH, CONTINUUM, CONTINUUM_M)  # the options of every PD model (one with a ``horizon`` option)


class Model(Horizon):
    """Base class. Subclasses set ``name``, ``title``, ``source``, ``options`` and ``solve``.

    ``points`` (if among the options) may also be given as ``spacing``; the registry converts.
    """

    name: str = ""
    title: str = ""
    source: str = ""
    options: tuple[Option, ...] = (POINTS,)
    # -- capabilities: what the model can solve, as data (checked by `run` before solving) --------
    analyses: frozenset[str] = frozenset({"static"})  # "static" and/or "dynamic" (a time integrator)
    straight: bool = True  # solves straight axes
    curved: bool = False  # solves curved axes
    supports: frozenset[str] = SUPPORTS  # end conditions it represents (scene.supports.left/right)
    springs: bool = False  # elastic supports (a [supports] end or inner support given as a spring table)
    inner_supports: bool = False  # supports inside the span (supports.inner)
    segments: bool = False  # sections and materials that change along the axis ([[segments]])
    shapes: frozenset[str] = frozenset({"rectangle", "given", "I", "profile"})  # section kinds (Section.kind) it takes
    load_types: frozenset[str] = LOAD_TYPES  # loads[i].type it applies
    materials: frozenset[str] = frozenset()  # material laws past elasticity it takes: yield_stress, failure_strain
    load_path: bool = False  # follows a [loading] path (load factors, steps, unloading)
    end_motions: bool = False  # prescribed end motions ([dynamics.left/right]) in its solution
    variant_rules: tuple[Rule, ...] = ()  # option values each variant's equations define (Rule)
    # -- the assembled system -------------------------------------------------------------------
    assembles: bool = False  # a linear static solve of one System: implements assemble()
    nonlinear_when: tuple[tuple[str, Any], ...] = ()  # options that switch solve() to a nonlinear path
    bench_scene: str | None = None  # the scene `pdverify bench` times (a path under studies/), if its own
    axial: bool = False  # carries axial loads (loads[i].axial)
    bending: bool = True  # carries transverse loads (loads[i].value)
    torsion: bool = False  # carries torques (point_torque, loads[i].torque)
    theory: str = "euler-bernoulli"  # euler-bernoulli | timoshenko | higher-order | continuum | axial | torsion
    measures: str = "w"  # the output a study measures against its reference: w, or a point field (u, twist)
    reference: bool = False  # closed-form or reference model (not a candidate of `pdverify advise` by default)
    breaks: bool = False  # places its particles at the scene's features (pd-curved's segments), whatever the grid
    order: float = 2.0  # the order of convergence its equations promise (what `pdverify verify` expects)
    jump_rotation: tuple[float, float] = (0.0, 0.0)  # c of its rotation's error c |J| h² / EI next to a jump J of the
    # shear inside the span and at an end (measured on its default variant: registry/jump_rotation.py)
    end_load_error: dict = {}  # C of its deflection's error C (h / d)² under a load d from a clamped or pinned end
    # ({"clamped": C, "pinned": C}; measured on its default variant: registry/end_loads.py)
    modes: bool = False  # gives the mass and stiffness of its transient: implements eigenproblem()
    histories: bool = False  # a reference giving time histories at any probes and times: implements history_at()
    grid_checked: bool = False  # its error on coarse grids outruns its warnings: every static solve on a grid carries
    # the same solve on about half the points (checks_own_grid)

    def promised_order(self, params: dict) -> float:
        """The order of convergence the equations promise with these options (``params`` over the defaults): the
        model's :attr:`order`, unless a variant's degree sets it (pd-curved). What ``solve --estimate`` and ``advise``
        hold an observed order against."""
        return float(self.order)

    def checks_own_grid(self, scene: Scene, params: dict) -> bool:
        """Whether a static solve of ``scene`` with these options (resolved) carries its own estimate from the same
        solve on about half the points (:func:`~pdverify.registry.grid_check.grid_check`): where the model's error on
        coarse grids is known to outrun its warnings (pd-curved on a curved axis; :attr:`grid_checked`: pd-eb,
        pd-bond-pair, pd-rod, pd-torsion). The model's :attr:`grid_checked` by default."""
        return self.grid_checked

    def estimate_constants(self, scene: Scene, params: dict) -> tuple[dict, tuple[float, float]]:
        """(:attr:`end_load_error`, :attr:`jump_rotation`) for these options (``params``, or the defaults where they
        name none): the attributes, measured on the default variant, for that variant, nothing for another. A model
        whose other variants or options change the constants and were measured on them gives theirs here."""
        opt = self.option("variant")
        if opt is None or params.get("variant", opt.default) == opt.default:
            return self.end_load_error, self.jump_rotation
        return {}, (0.0, 0.0)

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """Reasons this model cannot solve ``scene`` with these options (``params``, resolved), before any work: a
        variant or form that does not define what the scene holds (pd-bond-pair's Taylor ends and a support inside
        the span). Empty by default; the solve raises the same line. A study lists such combinations as skipped."""
        return []

    def declines(self, scene: Scene, options: dict) -> list[str]:
        """Why the model does not take ``scene`` with ``options``: its capabilities (:meth:`check`), else what the
        variant does not define there (:meth:`refusals`); empty when it takes it, or when the options themselves are
        bad (the solve says so)."""
        try:
            return self.check(scene) or self.refusals(scene, self.resolve(scene, dict(options)))
        except InputError:
            return []

    def check(self, scene: Scene) -> list[str]:
        """Reasons this model cannot solve ``scene`` (empty when it can): its declared capabilities first
        (subclasses add their own reasons to ``super().check(scene)``)."""
        out = []
        if not scene.is_straight and not self.curved:
            out.append(f"model {self.name} solves straight beams only; axis.type = {scene.axis.type!r}")
        if scene.is_straight and not self.straight:
            out.append(f"model {self.name} solves curved beams only; axis.type = 'straight'")
        for side in ("left", "right"):
            sup = scene.supports.kind(side)
            if sup == "spring" and not self.springs:
                out.append(
                    f"supports.{side} = spring: model {self.name} has no elastic supports; use a model that has "
                    "(`pdverify models` lists each model's supports: exact-eb, fem-eb, ...)"
                )
            elif sup != "spring" and sup not in self.supports:
                out.append(
                    f"supports.{side} = {sup!r}: model {self.name} does not represent it; it takes "
                    f"{', '.join(sorted(self.supports))}"
                )
        if scene.supports.inner and not self.inner_supports:
            out.append(
                f"supports.inner: model {self.name} holds the beam at its ends only; use a model with supports "
                "inside the span (`pdverify models`: exact-eb, fem-eb, ...)"
            )
        elif self.inner_supports and not self.springs and any(s.type == "spring" for s in scene.supports.inner):
            out.append(f"supports.inner: model {self.name} has no elastic supports; give rigid ones")
        if scene.segments and not self.segments:
            out.append(
                f"segments: model {self.name} takes one section and one material; use a model that takes segments "
                "(`pdverify models`: exact-eb, fem-eb, ...)"
            )
        sections = [("section", scene.section)] + [
            (f"segments[{i}].section", g.section) for i, g in enumerate(scene.segments)
        ]
        for where, sec in sections:
            if sec is not None and sec.kind not in self.shapes:
                out.append(
                    f"{where}.shape = {sec.kind!r}: model {self.name} takes a rectangle (its equations use the "
                    "section's depth and width); give width and height"
                )
        out += self._path_problems(scene)
        if self.bending and (why := straight_mechanism(scene)) is not None:  # (a scene that bends it is refused)
            out.append(why)
        if scene.dynamics is None and "static" not in self.analyses:
            out.append(
                f"dynamics: model {self.name} solves transient runs only; add a [dynamics] table (end_time, ...)"
            )
        if scene.dynamics is not None and "dynamic" not in self.analyses:
            out.append(
                f"dynamics: model {self.name} solves statics only and the scene asks for a transient run; "
                "use a dynamic model (`pdverify models` lists each model's analyses) or ask for the static part "
                "(-o static=true)"
            )
        if scene.dynamics is not None and not (self.end_motions or self.reference) and "dynamic" in self.analyses:
            moved = [
                f"dynamics.{side}.{k}"
                for side in ("left", "right")
                for k in MOTION_COMPONENT
                if getattr(scene.dynamics, side) is not None and getattr(getattr(scene.dynamics, side), k) is not None
            ]
            if moved:
                out.append(
                    f"{moved[0]}: model {self.name} cannot prescribe end motions; use a model that can "
                    "(`pdverify models`: end_motions) or drop the motion"
                )
        if scene.dynamics is not None and self.end_motions:
            for side in ("left", "right"):
                em = getattr(scene.dynamics, side)
                for k, component in MOTION_COMPONENT.items():
                    if em is not None and getattr(em, k) is not None and not getattr(self, component):
                        out.append(
                            f"dynamics.{side}.{k}: model {self.name} has no such unknown to move; "
                            "use a model that carries it or drop the motion"
                        )
        if self.theory == "torsion" and (lacks := missing_torsion_constant(scene, self.name)):
            out.append(lacks)
        for i, load in enumerate(scene.loads):
            if load.type not in self.load_types and load.type != "point_torque":  # torques: the twist check below
                out.append(
                    f"loads[{i}].type = {load.type!r}: model {self.name} takes {', '.join(sorted(self.load_types))}"
                )
                continue
            if getattr(load, "axial", 0.0) != 0.0 and not self.axial:
                out.append(
                    f"loads[{i}].axial = {load.axial!r}: model {self.name} has no axial displacement; "
                    "use a model with an axial DOF or drop the axial component"
                )
            torque = load.type == "point_torque" or getattr(load, "torque", 0.0) != 0.0
            if torque and not (self.torsion and (load.type != "point_torque" or load.type in self.load_types)):
                out.append(
                    f"loads[{i}]: a torque: model {self.name} has no twist; use a torsion model (pd-torsion) "
                    "or drop the torque"
                )
            if load.value != 0.0 and not self.bending and load.type != "point_torque":
                what = "moments" if load.type == "point_moment" else "transverse loads"
                only, field = (
                    ("twist only", "torque (or a point_torque load)") if self.torsion else ("axial only", "axial")
                )
                out.append(
                    f"loads[{i}].value = {load.value!r}: model {self.name} carries no {what} ({only}); "
                    f"give the load as loads[i].{field} or use a bending model"
                )
        return out

    def _path_problems(self, scene: Scene) -> list[str]:
        """Material laws past elasticity and load paths this model does not take (``materials``, ``load_path``)."""
        out = []
        mats = [("material", scene.material)] + [
            (f"segments[{i}].material", g.material) for i, g in enumerate(scene.segments) if g.material is not None
        ]
        for where, mat in mats:
            for law in ("yield_stress", "failure_strain"):
                if getattr(mat, law) is not None and law not in self.materials:
                    takes = f"takes {', '.join(sorted(self.materials))} only" if self.materials else "is elastic only"
                    out.append(
                        f"{where}.{law}: model {self.name} {takes}; drop {law} or use a model that takes it "
                        "(`pdverify models`: pd-bond-pair, ...)"
                    )
        if scene.loading is not None and not self.load_path:
            out.append(
                f"loading: model {self.name} solves one load, not a load path; drop [loading] or use a model that "
                "follows one (`pdverify models`: pd-bond-pair, ...)"
            )
        return out

    def solve(self, scene: Scene, params: dict) -> Result:  # pragma: no cover - interface
        raise NotImplementedError

    def new_result(self, scene: Scene, params: dict, x, w, **parts) -> Result:
        """The :class:`~pdverify.core.result.Result` of this model's solve of ``scene`` with ``params``: the scene's
        and model's names and a copy of the options filled in; ``parts``: rotation, fields, dofs, timings, info."""
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=x, w=w, **parts)

    def assemble(self, scene: Scene, params: dict) -> System:
        """The :class:`System` that :meth:`solve` factorises (models with ``assembles = True``)."""
        raise NotImplementedError(f"model {self.name} assembles no linear system (assembles = False)")

    def eigenproblem(self, scene: Scene, params: dict) -> tuple:
        """(K on the free DOFs, mass): K phi = omega^2 M phi of its transient (models with ``modes``); the mass a
        vector (lumped) or a sparse symmetric positive definite matrix (consistent)."""
        raise NotImplementedError(f"model {self.name} gives no eigenproblem (modes = False)")

    def history_at(self, scene: Scene, params: dict, probes, t):
        """Translations at ``probes`` (columns) and times ``t`` (rows), for references with ``histories``."""
        raise NotImplementedError(f"model {self.name} gives no time histories (histories = False)")

    def bench_dynamics(self, scene: Scene, params: dict, steps: int = 200) -> float:
        """Point-updates per second of the time integrator (models with ``"dynamic"`` in ``analyses``)."""
        raise NotImplementedError(f"model {self.name} has no time integrator")

    def reference_options(self, params: dict) -> dict | None:
        """The options of its theory's exact solution that give this model's continuum with ``params`` (the user's
        options over the defaults): {} by default; None when its equations converge to something the exact
        solution does not represent (then it is judged against itself on a finer grid)."""
        return {}

    def linear(self, params: dict) -> bool:
        """False when ``params`` select a nonlinear path (``nonlinear_when``)."""
        return not any(params.get(k) == v for k, v in self.nonlinear_when)

    def capabilities(self) -> dict:
        """The declared capabilities as plain data (``pdverify models``, docs/contract.md)."""
        return {
            "analyses": sorted(self.analyses),
            "axes": [a for a, ok in (("straight", self.straight), ("curved", self.curved)) if ok],
            "supports": sorted(self.supports) + ["spring"] * self.springs + ["inner"] * self.inner_supports,
            "segments": self.segments,
            "shapes": sorted(self.shapes),
            "materials": sorted(self.materials),
            "load_path": self.load_path,
            "load_types": sorted(self.load_types),
            "components": [c for c in ("bending", "axial", "torsion") if getattr(self, c)],
            "measures": self.measures,
            "end_motions": self.end_motions,
            "assembles": self.assembles,
            "variant_rules": [f"{dict(r.when)}: {r.option} ({r.why})" for r in self.variant_rules],
        }

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray] | None:
        """Fields at arbitrary positions ``x`` (exact models); None when only point values exist."""
        return None

    def evaluator(self, scene: Scene, params: dict):
        """A function x -> fields (as :meth:`evaluate`) for repeated evaluation on one scene, or None when
        the model has no ``evaluate``. Models whose ``evaluate`` solves first override this to solve once, and give
        the function the solve's round-off bound as an ``error_bound`` attribute (a study's reference rows read it)."""
        if type(self).evaluate is Model.evaluate:
            return None
        return lambda x: self.evaluate(scene, params, x)

    # -- option handling -----------------------------------------------------------------
    def option(self, name: str) -> Option | None:
        return next((o for o in self.options if o.name == name), None)

    def with_defaults(self, params: dict) -> dict:
        """``params`` over the options' defaults, each of this model's options read as its type (``-o degree=4.0``
        is 4; a value that is not: InputError) but not checked against the scene or the variant rules
        (:meth:`resolve` does that): for a method asked with the user's options only (a card's check, the suite's
        reference)."""
        given = {
            k: (o.coerce(self.name, v) if v is not None and (o := self.option(k)) is not None else v)
            for k, v in params.items()
        }
        return {o.name: o.default for o in self.options} | given

    def resolve(self, scene: Scene, given: dict, rules: bool = True) -> dict:
        """Validate ``given`` options against this model and fill in the defaults; ``rules``: also against
        its ``variant_rules`` (:func:`variant_problems`; off only to build a variant's operator with
        another's option, as a test of the assembly)."""
        given = {k: v for k, v in given.items() if v is not None and k != "static"}  # static: a run option (run)
        if "spacing" in given:
            if self.option("points") is None:
                raise InputError(f"spacing: model {self.name} takes no grid; drop --spacing")
            if "points" in given:
                raise InputError("points and spacing both given; give one of them")
            given["points"] = points_from_spacing(scene.length, given.pop("spacing"))
        names = [o.name for o in self.options]
        for key in given:
            if key not in names:
                close = close_match(key, names)
                hint = f"did you mean '{close}'? " if close else ""
                raise InputError(
                    f"{key}: model {self.name} takes no option '{key}'; {hint}it takes: {', '.join(names) or 'none'}"
                )
        params, short = {}, None
        for opt in self.options:
            try:
                params[opt.name] = opt.coerce(self.name, given[opt.name]) if opt.name in given else opt.default
            except InputError:
                if opt.name != "points" or (short := _below(opt, given["points"])) is None:
                    raise
                params["points"] = short  # below the model's least: refused below, with the least at its horizon
        if params.get("horizon_length") is not None:
            if "horizon" in given:
                raise InputError(
                    "horizon and horizon_length both given; give one of them (horizon: a multiple of the spacing, "
                    "horizon_length: a length)"
                )
            params["horizon"] = self.horizon_from_length(scene, params)
        found = variant_problems(self, params) if rules else []
        if found:
            raise InputError(found)
        if short is not None:  # what no number of points changes first (the variant and the scene), then the least
            raise InputError(self.refusals(scene, params) or self._too_few_points(scene, params))
        if rules and (found := self.grid_problems(scene, params)):
            raise InputError(found)
        return params

    def _too_few_points(self, scene: Scene, params: dict) -> list[str]:
        """The refusal of ``points`` below the option's least: the least number of points the grid takes with the
        other options given (:meth:`grid_problems`; a wider horizon needs more: doubled until one fits, then bisected),
        not the bare least; where none up to :data:`LEAST_SEARCH` fits, the grid's own reason there."""
        least = int(self.option("points").minimum)
        problems = lambda n: self.grid_problems(scene, {**params, "points": n})  # noqa: E731
        lo, hi = least - 1, least  # problems(lo) or lo below the least; the least that fits is in (lo, hi]
        while found := problems(hi):
            if hi >= LEAST_SEARCH:
                return found
            lo, hi = hi, min(2 * hi, LEAST_SEARCH)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if not problems(mid) else (mid, hi)
        at = f" with horizon = {params['horizon']:g}" if params.get("horizon") and hi > least else ""
        return [f"points = {params['points']}: model {self.name}{at} needs points >= {hi}"]


LEAST_SEARCH = 1 << 20  # points up to which the least a grid takes is searched (Model._too_few_points)


def _below(opt: Option, value) -> int | None:
    """``value`` as a whole number when it is one below ``opt``'s least (a refusal that names the least at the model's
    horizon instead, :meth:`Model._too_few_points`), else None (another refusal)."""
    if isinstance(value, bool):
        return None
    try:
        v = whole_number(value)
    except (TypeError, ValueError, OverflowError):
        return None
    return v if opt.minimum is not None and v < opt.minimum and (opt.maximum is None or v <= opt.maximum) else None


# a spacing is taken when length / spacing is a whole number to this relative tolerance: a decimal spacing's
# round-off (1e-16), not a spacing typed to a few digits (0.0571428 for 2/35 is 1.2e-6 off and refused)
SPACING_DIGITS = 1e-9


def points_from_spacing(length: float, spacing) -> int:
    """The number of points of a uniform grid of ``spacing`` on ``length``; InputError where the spacing does not
    divide the length into whole intervals (to :data:`SPACING_DIGITS`)."""
    try:
        dx = float(spacing)
    except (TypeError, ValueError):
        raise InputError(f"spacing = {spacing!r}: needs a number (metres)") from None
    if not dx > 0:
        raise InputError(f"spacing = {spacing!r}: must be positive")
    n = length / dx
    if n < 1 - 1e-9:
        raise InputError(f"spacing = {dx:g}: larger than the beam length {length:g}")
    if not n < 2.0**53:
        raise InputError(
            f"spacing = {dx:g}: {n:.3g} intervals of the length {length:g}, more than a grid can count exactly "
            "(2^53); give a larger spacing"
        )
    if abs(n - round(n)) > SPACING_DIGITS * max(1.0, n):
        k = max(1, round(n))
        raise InputError(
            f"spacing = {dx!r}: does not divide the length {length!r} into whole intervals ({n!r}); "
            f"give length / spacing an integer to {SPACING_DIGITS:g} (the nearest: spacing = {length / k!r}), "
            f"or --points {k + 1}"
        )
    return int(round(n)) + 1


def variant_problems(m: Model, params: dict) -> list[str]:
    """The options in ``params`` that the chosen variant's equations do not define (``variant_rules``)."""
    return [p for p in (r.problem(m.name, params) for r in m.variant_rules) if p]
