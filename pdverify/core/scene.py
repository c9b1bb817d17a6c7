"""Scenes: the TOML description of one beam problem that every model shares.

The straight-beam keys (``name``, ``[beam]``, ``[section]``, ``[material]``, ``[supports]``,
``[[loads]]``) are a contract read by other tools: extend, never rename. SI units unless the scene says
``units = "inch-pound"`` (any consistent set works; the key labels reports), z up, x from the left end (0)
to the right end (``beam.length``).

The scene is one pydantic model tree whose validators (supports, loads, axes, units, dynamics, strict types)
read the neighbouring fields. Reading a scene file, the error wording and the checks across tables are
:mod:`pdverify.core.scene_file` (``load_scene``, ``parse_scene``).
"""

# long module: the scene file's tables and their validation, one pydantic model per table

from __future__ import annotations

import math
from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Discriminator, Field, Strict, Tag, model_validator

from .errors import InputError
from .loading import Displacement, Loading
from .section import Section  # noqa: F401  (a scene's [section] table; re-exported with the other tables)

SUPPORTS = ("clamped", "pinned", "free", "guided", "roller")
Support = Literal["clamped", "pinned", "free", "guided", "roller"]
# What each support holds, per end, in the axis frame (tangential displacement, normal displacement, rotation):
# one meaning on every axis and in every model (docs/supports.md). Straight models without an axial unknown
# see only (normal, rotation), so there roller = pinned.
HELD = {
    "clamped": (True, True, True),
    "pinned": (True, True, False),
    "roller": (False, True, False),
    "guided": (False, False, True),
    "free": (False, False, False),
}
# What holds the single unknown of a rod (axial displacement) or of a torsion bar (twist): a roller slides
# axially, but holds the twist as a pinned (fork) support does (docs/supports.md)
ROD_HELD = {"axial": ("clamped", "pinned"), "torsion": ("clamped", "pinned", "roller")}


Real = Annotated[float, Strict()]  # a float that an int may give, never a boolean or a string ("true" is not 1.0)
Finite = Annotated[Real, Field(allow_inf_nan=False)]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Beam(_Strict):
    length: Real = Field(gt=0, allow_inf_nan=False)


class Material(_Strict):
    youngs_modulus: Real = Field(gt=0, allow_inf_nan=False)
    poissons_ratio: Real = Field(gt=-1.0, lt=0.5, allow_inf_nan=False)
    density: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    shear_modulus: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    yield_stress: Real | None = Field(default=None, gt=0, allow_inf_nan=False)  # elastic-perfectly plastic (Pa)
    failure_strain: Real | None = Field(default=None, gt=0, allow_inf_nan=False)  # brittle: the fibre strain at failure

    @property
    def E(self) -> float:
        return self.youngs_modulus

    @property
    def G(self) -> float:
        if self.shear_modulus is not None:
            return self.shear_modulus
        return self.youngs_modulus / (2.0 * (1.0 + self.poissons_ratio))


class Spring(_Strict):
    """An elastic support: ``stiffness`` against the deflection (force per length, N/m) and
    ``rotational_stiffness`` against the rotation (moment per radian, N m/rad); either may be zero."""

    type: Literal["spring"] = "spring"
    stiffness: Real = Field(default=0.0, ge=0, allow_inf_nan=False)
    rotational_stiffness: Real = Field(default=0.0, ge=0, allow_inf_nan=False)

    @model_validator(mode="after")
    def _some(self):
        if self.stiffness == 0.0 and self.rotational_stiffness == 0.0:
            raise ValueError("a spring needs stiffness or rotational_stiffness above 0 (with both 0 the end is free)")
        return self


class InnerSupport(_Strict):
    """A support inside the span at ``position``: ``pinned`` or ``roller`` hold the deflection (a straight beam has
    no axial unknown there: the two are one), ``clamped`` the deflection and the rotation, ``spring`` resists them
    elastically (``stiffness``, ``rotational_stiffness``)."""

    position: Real = Field(allow_inf_nan=False)
    type: Literal["pinned", "roller", "clamped", "spring"]
    stiffness: Real | None = Field(default=None, ge=0, allow_inf_nan=False)
    rotational_stiffness: Real | None = Field(default=None, ge=0, allow_inf_nan=False)

    @model_validator(mode="after")
    def _springs_only(self):
        given = [k for k in ("stiffness", "rotational_stiffness") if getattr(self, k) is not None]
        if self.type != "spring" and given:
            raise ValueError(f'{", ".join(given)}: a {self.type} support holds rigidly; give type = "spring"')
        if self.type == "spring" and not (self.stiffness or self.rotational_stiffness):
            raise ValueError("a spring needs stiffness or rotational_stiffness above 0")
        return self

    @property
    def holds_deflection(self) -> bool:
        return self.type != "spring" or bool(self.stiffness)

    @property
    def holds_rotation(self) -> bool:
        return self.type == "clamped" or (self.type == "spring" and bool(self.rotational_stiffness))


def _end_kind(value) -> str:
    return "named" if isinstance(value, str) else "spring"


# an end's support: a name, or a spring given as a table (pydantic reads it by the value's type, so a bad name or a
# bad spring gives one error, tagged "named" or "spring", which the scene file's messages drop)
EndSupport = Annotated[Annotated[Support, Tag("named")] | Annotated[Spring, Tag("spring")], Discriminator(_end_kind)]


class Supports(_Strict):
    """One support per end, each a name (one meaning on every axis and in every model: :data:`HELD`,
    docs/supports.md) or a :class:`Spring`; and any number of supports inside the span (``inner``)."""

    left: EndSupport
    right: EndSupport
    inner: list[InnerSupport] = Field(default_factory=list)

    def kind(self, side: str) -> str:
        """The support's name at ``side`` ("left" or "right"): one of :data:`SUPPORTS` or ``"spring"``."""
        sup = getattr(self, side)
        return sup if isinstance(sup, str) else "spring"

    def holds_deflection_at(self, side: str) -> bool:
        """True when the end ``side`` holds the deflection rigidly (a named support, not a spring: :data:`HELD`)."""
        end = getattr(self, side)
        return isinstance(end, str) and HELD[end][1]

    @property
    def simple(self) -> bool:
        """True for a named support at each end and none inside (what every model represents)."""
        return isinstance(self.left, str) and isinstance(self.right, str) and not self.inner


class Segment(_Strict):
    """A stretch [``start``, ``end``] of the axis with its own ``section`` and/or ``material`` (the scene's own
    tables where one is not given): stepped shafts, haunched girders, joints of two materials."""

    start: Real = Field(allow_inf_nan=False)
    end: Real = Field(allow_inf_nan=False)
    section: Section | None = None
    material: Material | None = None


Frame = Literal["local", "global"]


class PointForce(_Strict):
    """``value`` acts along the normal (+z for a straight beam), ``axial`` along the tangent (+x).

    ``frame = "local"`` (default): normal/tangent of the axis at the load; ``"global"``: ``axial`` is the
    global x component and ``value`` the global y (= z, up) component. Identical for straight beams."""

    type: Literal["point_force"]
    position: Real = Field(allow_inf_nan=False)
    value: Real = Field(allow_inf_nan=False)
    axial: Real = Field(default=0.0, allow_inf_nan=False)
    frame: Frame = "local"


class PointMoment(_Strict):
    type: Literal["point_moment"]
    position: Real = Field(allow_inf_nan=False)
    value: Real = Field(allow_inf_nan=False)


class Distributed(_Strict):
    type: Literal["distributed"]
    value: Real = Field(allow_inf_nan=False)
    start: Real | None = Field(default=None, allow_inf_nan=False)
    end: Real | None = Field(default=None, allow_inf_nan=False)
    shape: Literal["uniform", "sine"] = "uniform"
    axial: Real = Field(default=0.0, allow_inf_nan=False)
    torque: Real = Field(default=0.0, allow_inf_nan=False)
    frame: Frame = "local"


class PointTorque(_Strict):
    """A twisting moment about the beam axis (right-hand rule about +x); carried by torsion models only."""

    type: Literal["point_torque"]
    position: Real = Field(allow_inf_nan=False)
    value: Real = Field(allow_inf_nan=False)


Load = Annotated[PointForce | PointMoment | Distributed | PointTorque | Displacement, Field(discriminator="type")]


class Axis(_Strict):
    """Shape of the beam axis. ``straight`` is the default; curved axes are read by ``pd-curved``
    and the curved plane-stress reference (see their docs for the extra keys). An arc turns
    ``counterclockwise`` (curvature +1/R, the default) or ``clockwise`` (curvature -1/R) from its start angle."""

    type: Literal["straight", "arc", "polynomial"] = "straight"
    radius: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    opening_angle_deg: Real | None = Field(default=None, gt=0, le=360, allow_inf_nan=False)
    start_angle_deg: Real = Field(default=0.0, allow_inf_nan=False)
    direction: Literal["counterclockwise", "clockwise"] | None = None  # arcs only; None = counterclockwise
    coefficients: list[Annotated[Real, Field(allow_inf_nan=False)]] | None = None
    x_range: tuple[Annotated[Real, Field(allow_inf_nan=False)], Annotated[Real, Field(allow_inf_nan=False)]] | None = (
        None
    )

    @model_validator(mode="after")
    def _complete(self):
        if self.type == "arc" and (self.radius is None or self.opening_angle_deg is None):
            raise ValueError("an arc axis needs radius and opening_angle_deg")
        if self.type != "arc" and self.direction is not None:
            raise ValueError(f"direction applies to arc axes only (a {self.type} axis bends as its coefficients say)")
        keys = {"arc": ("radius", "opening_angle_deg"), "polynomial": ("coefficients", "x_range")}
        for kind, names in keys.items():
            given = [k for k in names if getattr(self, k) is not None]
            if self.type != kind and given:
                verb, it = ("applies", "it") if len(given) == 1 else ("apply", "them")
                raise ValueError(
                    f"{' and '.join(given)} {verb} to {kind} axes only and this axis is {self.type}: set "
                    f'type = "{kind}" or drop {it}'
                )
        if self.type == "polynomial":
            if not self.coefficients or self.x_range is None:
                raise ValueError("a polynomial axis needs coefficients (of y(x), constant first) and x_range")
            if not self.x_range[0] < self.x_range[1]:
                raise ValueError(f"x_range = {list(self.x_range)}: the first value must be below the second")
        return self


class Motion(_Strict):
    """A prescribed end motion of time: ``sine_ramp`` = amplitude sin(2 pi frequency t) until
    ``hold_after``, then the value reached there; ``sine`` = amplitude sin(2 pi frequency t); ``step`` = amplitude."""

    type: Literal["sine_ramp", "sine", "step"]
    amplitude: Real = Field(allow_inf_nan=False)
    frequency: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    hold_after: Real | None = Field(default=None, ge=0, allow_inf_nan=False)

    @model_validator(mode="after")
    def _complete(self):
        if self.type in ("sine_ramp", "sine") and self.frequency is None:
            raise ValueError(f"a {self.type} motion needs frequency (Hz)")
        if self.type == "sine_ramp" and self.hold_after is None:
            raise ValueError("a sine_ramp motion needs hold_after (the time from which the value is held)")
        return self


class EndMotion(_Strict):
    """Prescribed motion of one end: transverse ``displacement``, ``axial`` displacement, ``rotation``, ``twist``."""

    displacement: Motion | None = None
    axial: Motion | None = None
    rotation: Motion | None = None
    twist: Motion | None = None


class Dynamics(_Strict):
    """Optional ``[dynamics]`` table: a transient run from rest (loads applied as steps at t = 0).

    ``damping_ratio``: fraction of critical damping of the first mode (mass-proportional); or ``damping`` =
    c_d / rho in 1/s. ``damping_on``: ``all`` (default; the damping force is c_d/rho times each DOF's inertia, the
    rotations' too: every mode of an undamped beam decays at the same rate c_d/(2 rho), so a damped run settles) or
    ``translations`` (Moyer & Miraglia's Eq. 36-37: the rotations undamped; a beam's shear-rotation modes are then
    damped only through their coupling to w and ring for long). ``time_step``: default = safety x stable limit.
    ``probes``: positions whose time histories are recorded; ``output_interval``: seconds between records."""

    end_time: Real = Field(gt=0, allow_inf_nan=False)
    time_step: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    damping_ratio: Real | None = Field(default=None, ge=0, allow_inf_nan=False)
    damping: Real | None = Field(default=None, ge=0, allow_inf_nan=False)
    damping_on: Literal["all", "translations"] = "all"
    output_interval: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    probes: list[Real] = Field(default_factory=list)
    left: EndMotion | None = None
    right: EndMotion | None = None

    @model_validator(mode="after")
    def _complete(self):
        if self.damping_ratio is not None and self.damping is not None:
            raise ValueError("give damping_ratio or damping, not both")
        for key in ("time_step", "output_interval"):
            value = getattr(self, key)
            if value is not None and value > self.end_time:
                raise ValueError(
                    f"{key} = {value:g} s is longer than end_time = {self.end_time:g} s (the run would take one "
                    f"step or record none); give a {key} below end_time"
                )
        return self


UNITS = {
    "SI": {"length": "m", "force": "N", "stress": "Pa"},
    "inch-pound": {"length": "in", "force": "lbf", "stress": "psi"},
}
"""The unit systems a scene may declare (``units = "inch-pound"``; default SI). Every model works in whatever
consistent units the scene uses; the key only labels lengths and forces in reports."""


class Scene(_Strict):
    name: str = Field(min_length=1)
    description: str = ""
    units: Literal["SI", "inch-pound"] = "SI"
    beam: Beam
    section: Section
    material: Material
    supports: Supports
    loads: list[Load] = Field(default_factory=list)
    axis: Axis = Field(default_factory=Axis)
    dynamics: Dynamics | None = None
    segments: list[Segment] = Field(default_factory=list)
    loading: Loading | None = None  # a load path (pdverify.core.loading)

    # -- derived quantities ------------------------------------------------------------------
    @property
    def length_unit(self) -> str:
        """'m' or 'in': the unit of lengths and deflections (``units``)."""
        return UNITS[self.units]["length"]

    @property
    def length(self) -> float:
        return self.beam.length

    @property
    def EI(self) -> float:
        return self.material.E * self.section.I

    @property
    def EA(self) -> float:
        return self.material.E * self.section.A

    @property
    def kGA(self) -> float:
        return self.section.k * self.material.G * self.section.A

    @property
    def uniform(self) -> bool:
        """True when one section and one material hold along the whole beam (no ``segments``)."""
        return not self.segments

    def pieces(self) -> list[tuple[float, float, Section, Material]]:
        """(start, end, section, material) of each stretch of the beam in order: the segments with the scene's
        own section and material filled in where a segment gives none, or the whole beam."""
        if not self.segments:
            return [(0.0, self.length, self.section, self.material)]
        return [(g.start, g.end, g.section or self.section, g.material or self.material) for g in self.segments]

    def stiffness_at(self, x) -> dict[str, np.ndarray]:
        """EI, EA and kGA at the positions ``x`` (at an interface, those of the segment to its right)."""
        x = np.asarray(x, float)
        out = {k: np.empty_like(x) for k in ("EI", "EA", "kGA")}
        for a, _, sec, mat in self.pieces():
            on = x >= a
            out["EI"][on] = mat.E * sec.I
            out["EA"][on] = mat.E * sec.A
            out["kGA"][on] = sec.k * mat.G * sec.A
        return out

    @property
    def slenderness(self) -> float:
        return self.length / self.section.depth

    @property
    def is_straight(self) -> bool:
        return self.axis.type == "straight"

    @property
    def has_axial_loads(self) -> bool:
        return any(getattr(load, "axial", 0.0) != 0.0 for load in self.loads)

    def span(self, load: Distributed) -> tuple[float, float]:
        """(start, end) of a distributed load, defaults filled in."""
        a = 0.0 if load.start is None else load.start
        b = self.length if load.end is None else load.end
        return a, b

    def load_shape(self, load: Distributed, x) -> np.ndarray:
        """The shape of a distributed load at x (1, or sin(πx/L) for ``shape = "sine"``); its span not applied."""
        x = np.asarray(x, dtype=float)
        return np.ones_like(x) if load.shape == "uniform" else np.sin(np.pi * x / self.length)

    def with_slenderness(self, slenderness: float) -> Scene:
        """The same scene with the section height set to length / slenderness.

        A rectangle keeps its width; a section given by area and inertia is scaled as the
        equivalent rectangle (area ~ h, inertia ~ h^3)."""
        if isinstance(slenderness, bool) or not (isinstance(slenderness, (int, float)) and 0 < slenderness < math.inf):
            raise InputError(f"slenderness = {slenderness!r}: give a positive, finite length / depth ratio")
        h_new = self.length / slenderness
        s = self.section
        if s.shape in ("I", "profile"):  # every height scaled: area ~ h, inertia ~ h^3
            r = h_new / s.depth
            keys = {"height": s.height * r, "flange_thickness": s.flange_thickness * r} if s.shape == "I" else {}
            sec = s.model_copy(update=keys if s.shape == "I" else {"y": [v * r for v in s.y]})
        elif s.height is not None:
            sec = s.model_copy(update={"height": h_new})
        else:
            r = h_new / s.depth
            sec = s.model_copy(update={"area": s.A * r, "inertia": s.I * r**3})
        return self.model_copy(update={"section": sec})

    def to_dict(self) -> dict:
        return self.model_dump(mode="json", exclude_none=True)


def is_mechanism(left: str, right: str) -> bool:
    """True when the supports leave a rigid-body mode of the transverse deflection w = a + b x (the axial
    displacement, where a model has one, is checked by :func:`pdverify.core.geometry.rigid_body_modes`)."""
    held = ("clamped", "pinned", "roller")
    translation_fixed = left in held or right in held
    rotation_fixed = "clamped" in (left, right) or "guided" in (left, right) or (left in held[1:] and right in held[1:])
    return not (translation_fixed and rotation_fixed)


def rigid_rows(scene) -> np.ndarray:
    """The conditions the supports put on a rigid motion w = a + b x of a straight beam, rows (at, bt) with
    at a + bt b = 0: a deflection held (or a spring's) at x gives (1, x), a rotation held (or a rotational
    spring's) gives (0, 1); positions in units of the length."""
    rows = []
    sup = scene.supports
    for side, x in (("left", 0.0), ("right", 1.0)):
        end = getattr(sup, side)
        if isinstance(end, Spring):
            deflection, rotation = end.stiffness > 0, end.rotational_stiffness > 0
        else:
            deflection, rotation = HELD[end][1], HELD[end][2]
        rows += [(1.0, x)] * deflection + [(0.0, 1.0)] * rotation
    for inner in sup.inner:
        x = inner.position / scene.length
        rows += [(1.0, x)] * inner.holds_deflection + [(0.0, 1.0)] * inner.holds_rotation
    rows += [(1.0, ld.position / scene.length) for ld in scene.loads if ld.type == "displacement"]
    return np.array(rows, float).reshape(-1, 2)


def straight_mechanism(scene) -> str | None:
    """The one-line reason a straight beam on these supports is a mechanism across its axis (None when it is not):
    a model that bends refuses such a scene (``Model.check``), and so does the scene itself when it bends it."""
    if not scene.is_straight:
        return None
    sup = scene.supports
    if sup.simple and not any(ld.type == "displacement" for ld in scene.loads):
        if not is_mechanism(sup.left, sup.right):
            return None
        return (
            f"supports = {sup.left}-{sup.right}: a mechanism (the beam can move as a rigid body: no static solution, "
            "and rigid-body modes, which the models do not compute); fix the deflection at one end and the rotation "
            "somewhere (clamped, or pinned/roller at both ends, or pinned with guided)"
        )
    if np.linalg.matrix_rank(rigid_rows(scene)) == 2:
        return None
    inner = ", ".join(f"{s.type} at {s.position:g}" for s in sup.inner) or "none inside"
    return (
        f"supports = {sup.kind('left')}-{sup.kind('right')} ({inner}): a mechanism (the beam can move as a rigid "
        "body); hold the deflection at two places, or the deflection and the rotation at one (springs count when "
        "their stiffness is above 0)"
    )


def bends(scene) -> bool:
    """True when the scene loads or moves the beam across its axis (a transverse force, a moment, a prescribed
    deflection or rotation). A rod's or a torsion bar's scene does not, so its supports need only hold its own
    unknown: a rod pinned at one end and free at the other is valid (pd-rod, exact-rod)."""
    if any(ld.type == "point_moment" or (ld.type != "point_torque" and ld.value != 0.0) for ld in scene.loads):
        return True
    d = scene.dynamics
    ends = () if d is None else (d.left, d.right)
    return any(em is not None and (em.displacement is not None or em.rotation is not None) for em in ends)
