"""Reading a scene: ``load_scene(path)`` and ``parse_scene(dict)`` validate everything before any model runs and
raise :class:`~pdverify.core.errors.InputError` with one line per problem (field, value, what is allowed)."""

from __future__ import annotations

import datetime
import difflib
import math
import tomllib
from pathlib import Path

import numpy as np
from pydantic import ValidationError

from .errors import InputError
from .geometry import axis_length, mechanism_message
from .loading import Displacement, Loading
from .scene import (
    SUPPORTS,
    Axis,
    Beam,
    Distributed,
    Dynamics,
    EndMotion,
    InnerSupport,
    Material,
    Motion,
    PointForce,
    PointMoment,
    PointTorque,
    Scene,
    Section,
    Segment,
    Spring,
    Supports,
    bends,
    straight_mechanism,
)


def _loc(loc) -> str:
    parts = []
    for i, p in enumerate(loc):
        if isinstance(p, int):
            parts.append(f"[{p}]")
        elif p in ("point_force", "point_moment", "distributed", "point_torque", "named", "spring") or (
            p == "displacement" and i == 2 and loc[0] == "loads"
        ):
            continue  # discriminator tag: not a field the user wrote
        else:
            parts.append(("." if parts else "") + str(p))
    return "".join(parts) or "scene"


def _allowed_keys(model_cls) -> str:
    return ", ".join(model_cls.model_fields)


_TABLES = {
    "beam": Beam,
    "section": Section,
    "material": Material,
    "supports": Supports,
    "axis": Axis,
    "dynamics": Dynamics,
    "loading": Loading,
}


def _message(err: dict, data: dict) -> str:
    loc = _loc(err["loc"])
    kind = err["type"]
    value = err.get("input")
    if kind == "extra_forbidden":
        parent = err["loc"][:-1]
        key = err["loc"][-1]
        cls = Scene
        if parent and parent[0] == "dynamics":
            cls = {1: Dynamics, 2: EndMotion}.get(len(parent), Motion)
        elif parent[:1] == ("supports",) and len(parent) >= 2:  # an end's spring table or an inner support
            cls = InnerSupport if parent[1] == "inner" else Spring
        elif parent[:1] == ("segments",):
            cls = Segment
        elif parent and parent[0] in _TABLES:
            cls = _TABLES[parent[0]]
        elif parent and parent[0] == "loads" and len(parent) >= 3:
            cls = {
                "point_force": PointForce,
                "point_moment": PointMoment,
                "distributed": Distributed,
                "point_torque": PointTorque,
                "displacement": Displacement,
            }.get(parent[2], Scene)
        import difflib

        close = difflib.get_close_matches(str(key), list(cls.model_fields), n=1, cutoff=0.75)
        hint = f"did you mean '{close[0]}'? " if close else ""
        return f"{loc}: unknown key '{key}'; {hint}allowed keys here: {_allowed_keys(cls)}"
    if kind == "missing":
        return f"{loc}: missing; this key is required"
    if kind == "union_tag_invalid" or kind == "union_tag_not_found":
        given = value.get("type") if isinstance(value, dict) else value
        kinds = "point_force, point_moment, distributed, point_torque, displacement"
        if given is None:
            return f"{loc}.type: missing; every load names its type: {kinds}"
        return f"{loc}.type = {given!r}: unknown load type; allowed: {kinds}"
    if kind == "literal_error" and loc.startswith("supports.inner"):
        return f"{loc} = {value!r}: unknown support inside the span; allowed: pinned, roller, clamped, spring"
    if kind == "literal_error" and loc.startswith("supports.") and loc.endswith(".type"):
        return (
            f'{loc} = {value!r}: a support given as a table is a spring: write type = "spring" with stiffness '
            "and/or rotational_stiffness, or give the support's name"
        )
    if kind == "literal_error" and loc.startswith("supports."):
        return f"{loc} = {value!r}: unknown support; allowed: {', '.join(SUPPORTS)}, or a spring table"
    if kind == "list_type" and loc in ("loads", "segments", "supports.inner") and isinstance(value, dict):
        return (
            f"{loc}: one table is given where a list of them is needed: write each as [[{loc}]] (double brackets), "
            f"not [{loc}]"
        )
    if kind == "float_type" and isinstance(value, bool):
        return f"{loc} = {str(value).lower()}: a number is needed here, not true/false"
    if kind == "float_type" and isinstance(value, str):
        return f"{loc} = {value!r}: a number is needed here (write it without quotes)"
    msg = _plain_words(kind, err.get("ctx") or {}, err["msg"])
    if isinstance(value, dict):  # a rule across the keys of a table: the table's name, then the rule
        return f"{loc}: {msg}"
    return f"{loc} = {_as_toml(value)}: {msg}"


def _plain_words(kind: str, ctx: dict, msg: str) -> str:
    """pydantic's message in the words of a scene file (a table, a number, a list), not of Python classes."""
    words = {
        "model_type": "a table is needed here (its keys on the lines below a [name] header)",
        "dict_type": "a table is needed here (its keys on the lines below a [name] header)",
        "float_type": "a number is needed here",
        "float_parsing": "a number is needed here",
        "int_type": "a whole number is needed here",
        "finite_number": "a finite number is needed here (not inf or nan)",
        "list_type": "a list is needed here, e.g. [0.0, 1.0]",
        "tuple_type": "a list is needed here, e.g. [0.0, 1.0]",
        "string_type": "a text in quotes is needed here",
        "greater_than": f"must be greater than {ctx.get('gt')}",
        "greater_than_equal": f"must be at least {ctx.get('ge')}",
        "less_than": f"must be less than {ctx.get('lt')}",
        "less_than_equal": f"must be at most {ctx.get('le')}",
        "too_short": f"needs {ctx.get('min_length')} values",
        "too_long": f"takes {ctx.get('max_length')} values",
    }
    if kind in words:
        return words[kind]
    return msg[len("Value error, ") :] if msg.startswith("Value error, ") else msg


def _as_toml(value) -> str:
    """A value as the scene file writes it (a date as its date, text in quotes), not as Python's repr."""
    if isinstance(value, (datetime.date, datetime.time)):
        return f"{value.isoformat()} (a date or time)"
    if isinstance(value, bool):
        return str(value).lower()
    return repr(value)


def _messages(errors: list[dict], data: dict) -> list[str]:
    """One line per problem; a misspelt key (``positon``) and the required key it stands for (``position``,
    then missing) are one problem: the unknown key's line says 'did you mean', the 'missing' line goes."""
    if not data:  # an empty file, or comments only: one line, not one per missing table
        return ["no scene given (an empty file or table); a scene gives name, beam, section, material, supports"]
    missing = {tuple(e["loc"]): e for e in errors if e["type"] == "missing"}
    dropped, hints = set(), {}
    for i, e in enumerate(errors):
        if e["type"] != "extra_forbidden":
            continue
        parent, key = tuple(e["loc"][:-1]), str(e["loc"][-1])
        names = [str(loc[-1]) for loc in missing if loc[:-1] == parent and loc not in dropped]
        close = difflib.get_close_matches(key, names, n=1, cutoff=0.75)
        if close:
            dropped.add(parent + (close[0],))
            hints[i] = close[0]
    out = []
    for i, e in enumerate(errors):
        if tuple(e["loc"]) in dropped and e["type"] == "missing":
            continue
        msg = _message(e, data)
        out.append(msg if i not in hints else msg.split("; ")[0] + f"; did you mean '{hints[i]}'?")
    return out


def _check_loads(scene: Scene) -> list[str]:
    lines = []
    L = scene.length
    for i, load in enumerate(scene.loads):
        if isinstance(load, (PointForce, PointMoment, PointTorque, Displacement)):
            if not 0.0 <= load.position <= L:
                lines.append(
                    f"loads[{i}].position = {load.position!r}: outside the beam [0, {L}]; "
                    "give a position between 0 and beam.length"
                )
        else:
            a, b = scene.span(load)
            for key, v in (("start", a), ("end", b)):
                if not 0.0 <= v <= L:
                    lines.append(
                        f"loads[{i}].{key} = {v!r}: outside the beam [0, {L}]; give a value between 0 and beam.length"
                    )
            if a >= b:
                lines.append(f"loads[{i}].start = {a!r}, end = {b!r}: start must be below end")
    return lines


_FIXES = {
    "displacement": ("clamped", "pinned", "roller"),
    "axial": ("clamped", "pinned"),
    "rotation": ("clamped", "guided"),
    "twist": ("clamped", "pinned", "roller"),
}


def _check_dynamics(scene: Scene) -> list[str]:
    d = scene.dynamics
    if d is None:
        return []
    lines = []
    for i, p in enumerate(d.probes):
        if not 0.0 <= p <= scene.length:
            lines.append(
                f"dynamics.probes[{i}] = {p!r}: outside the beam [0, {scene.length}]; give positions on the beam"
            )
    for side in ("left", "right"):
        em = getattr(d, side)
        if em is None:
            continue
        sup = scene.supports.kind(side)
        for key, allowed in _FIXES.items():
            if getattr(em, key) is not None and sup not in allowed:
                lines.append(
                    f"dynamics.{side}.{key}: a {sup} end leaves this motion free, so it cannot be prescribed; "
                    f"set supports.{side} to {' or '.join(allowed)}"
                )
    return lines


def _check_supports(scene: Scene) -> list[str]:
    """Supports inside the span: on the beam, one per position (and none at an end, which has its own support),
    on straight axes (a curved axis's supports are its ends')."""
    sup, L = scene.supports, scene.length
    lines = []
    ends = ((0.0, "left"), (L, "right"))
    held = {at: f"supports.{side} = {sup.kind(side)!r}" for at, side in ends if sup.holds_deflection_at(side)}
    held |= {s.position: f"supports.inner[{i}]" for i, s in enumerate(sup.inner) if s.type != "spring"}
    for i, ld in enumerate(scene.loads):
        if ld.type == "displacement" and ld.position in held:
            lines.append(
                f"loads[{i}].position = {ld.position!r}: {held[ld.position]} already holds the deflection there; "
                "move the prescribed deflection or drop that support"
            )
    if not sup.inner and sup.simple:
        return lines
    if not scene.is_straight:
        lines.append(
            f"supports: springs and supports inside the span are for straight beams; axis.type = {scene.axis.type!r}"
        )
    seen: dict[float, int] = {}
    apart = SUPPORTS_APART * L
    for i, s in enumerate(sup.inner):
        where = f"supports.inner[{i}].position = {s.position!r}"
        near = [(f"supports.{side} (the {side} end)", at) for at, side in ends]
        near += [(f"supports.inner[{j}]", sup.inner[j].position) for j in seen.values()]
        close = [(name, at) for name, at in near if abs(s.position - at) <= apart]
        if not 0.0 < s.position < L:
            lines.append(f"{where}: not inside the beam (0, {L}); an end's support is supports.left or supports.right")
        elif s.position in seen:
            lines.append(f"{where}: supports.inner[{seen[s.position]}] is at the same position; give one support there")
        elif close:
            lines.append(
                f"{where}: within {apart:.3g} ({SUPPORTS_APART:g} of the length) of {close[0][0]} at {close[0][1]!r}, "
                "where the models take the two as one point (their split of the reaction is not defined); give one "
                f"support there, or place them at least {apart:.3g} apart"
            )
        seen.setdefault(s.position, i)
    return lines


SUPPORTS_APART = 1e-9  # of the length: supports closer than this are one point to the grids (numerics/features.py)


def _check_segments(scene: Scene) -> list[str]:
    """Segments cover [0, length] in order, without gaps or overlaps (ends meet to 1e-12 of the length)."""
    segs, L = scene.segments, scene.length
    if not segs:
        return []
    lines, tol = [], 1e-12 * L
    if not scene.is_straight:
        lines.append(f"segments: for straight beams; axis.type = {scene.axis.type!r}")
    at = 0.0
    for i, g in enumerate(segs):
        if not g.start < g.end:
            lines.append(f"segments[{i}]: start = {g.start!r}, end = {g.end!r}: start must be below end")
        if abs(g.start - at) > tol:
            what = "a gap" if g.start > at else "an overlap"
            lines.append(
                f"segments[{i}].start = {g.start!r}: {what} after {at!r}; segments cover [0, beam.length] in order, "
                "each starting where the one before ends"
            )
        at = g.end
    if abs(at - L) > tol:
        lines.append(f"segments[{len(segs) - 1}].end = {at!r}: the last segment must end at beam.length = {L!r}")
    return lines


def _check_magnitudes(scene: Scene) -> list[str]:
    """The derived stiffnesses of the section and of each segment must be ordinary floating-point numbers: a width
    of 5e-324 (the smallest subnormal) gives an area of 0, a modulus of 1e300 times a large section overflows."""
    tiny = float(np.finfo(float).tiny)
    tables = [("section", scene.section, scene.material)] + [
        (f"segments[{i}]", g.section or scene.section, g.material or scene.material)
        for i, g in enumerate(scene.segments)
    ]
    for where, sec, mat in tables:
        given = ", ".join(
            f"{k} = {getattr(sec, k)!r}" for k in ("width", "height", "area", "inertia") if getattr(sec, k) is not None
        )
        try:
            derived = {
                "area": sec.A,
                "second moment of area": sec.I,
                "EI": mat.E * sec.I,
                "EA": mat.E * sec.A,
                "kGA": sec.k * mat.G * sec.A,
            }
        except OverflowError:  # a power of a float past the range (height³ of 1e200) raises rather than gives inf
            derived = {"the section's properties": math.inf}
        ratio = mat.G / mat.E  # the shear and bending stiffnesses' ratio, which the beam models divide by
        if not 1e-100 <= ratio <= 1e100:
            return [
                f"{'material' if where == 'section' else where}: shear_modulus = {mat.G!r} and youngs_modulus = "
                f"{mat.E!r} give G / E = {ratio!r}, outside "
                "1e-100..1e100 (the models divide by it); give the two moduli of one material in one unit"
            ]
        for name, value in derived.items():
            if not (math.isfinite(value) and value >= tiny):
                return [
                    f"{where}: {given} and youngs_modulus = {mat.E!r} give {name} = {value!r}, not an ordinary float "
                    "(it under- or overflows); give the scene in units that keep its numbers within about "
                    "1e-100..1e100"
                ]
    return []


LOAD_FLOOR = float(np.finfo(float).tiny / np.finfo(float).eps)  # 1.0e-292: loads all nearer 0 than this leave
# their fields (and the models' products on the way) below float64's normal range, where they lose their digits


def _check_loads_range(scene: Scene) -> list[str]:
    """The largest load component, unless 0, at least :data:`LOAD_FLOOR` in size: loads of 1e-317 N (subnormal
    floats) gave exact-eb's M 21 % off and pd-eb's M and V 0, unwarned. A small component beside larger ones is
    kept (it only adds nothing)."""
    sizes = [(abs(getattr(ld, k, 0.0)), i, k) for i, ld in enumerate(scene.loads) for k in ("value", "axial", "torque")]
    size, i, k = max(sizes, default=(0.0, 0, "value"))
    if 0.0 < size < LOAD_FLOOR:
        return [
            f"loads[{i}].{k} = {getattr(scene.loads[i], k)!r}: the largest load is below {LOAD_FLOOR:.4g} in size, so "
            "its fields fall below float64's normal range (2.2e-308) and lose their digits; give the scene in units "
            "that keep its numbers within about 1e-100..1e100"
        ]
    return []


def parse_scene(data: dict, source: str = "scene") -> Scene:
    """Validate a scene given as a dict (parsed TOML) and return it, or raise InputError."""
    if not isinstance(data, dict):
        raise InputError(f"{source}: a scene must be a TOML table, got {type(data).__name__}")
    try:
        scene = Scene.model_validate(data)
    except ValidationError as exc:
        raise InputError([f"{source}: {m}" for m in _messages(exc.errors(), data)]) from None
    lines = (
        _check_magnitudes(scene)
        + _check_loads_range(scene)
        + _check_loads(scene)
        + _check_dynamics(scene)
        + _check_supports(scene)
        + _check_segments(scene)
    )
    if not scene.is_straight:
        with np.errstate(all="ignore"):
            arc = axis_length(scene.axis)
        if not np.isfinite(arc):  # its positions overflow: no geometry (nor rigid-body modes) to check
            lines.append(
                f"axis: the {scene.axis.type} axis's arc length overflows a float64 ({arc}); give smaller "
                + ("coefficients or a shorter x_range" if scene.axis.type == "polynomial" else "a smaller radius")
            )
        elif abs(arc - scene.length) > 1e-6 * arc:
            lines.append(
                f"beam.length = {scene.length!r}: the {scene.axis.type} axis is {arc:.12g} m long (arc length); "
                "set beam.length to it"
            )
    if (why := straight_mechanism(scene)) is not None and bends(scene):
        lines.append(why)
    elif not scene.is_straight and not lines:
        if (why := mechanism_message(scene)) is not None:
            lines.append(why)
    if lines:
        raise InputError([f"{source}: {line}" for line in lines])
    return scene


MAX_TOML_BYTES = 64 * 2**20  # a scene or study file larger than this (64 MiB) is refused before it is read


def read_toml(path: str | Path, what: str) -> tuple[str, dict]:
    """(text, parsed table) of a TOML file, or InputError naming the file and what is wrong."""
    path = Path(path)
    # a device or a FIFO is never read (/dev/zero is endless)
    if path.exists() and not path.is_dir() and not path.is_file():
        raise InputError(f"{path}: not a regular file; give a {what} TOML file")
    if path.is_file() and path.stat().st_size > MAX_TOML_BYTES:
        raise InputError(
            f"{path}: {path.stat().st_size:,} bytes, more than any {what} file (the limit is {MAX_TOML_BYTES:,}); "
            f"give a {what} TOML file"
        )
    try:
        text = path.read_text(encoding="utf-8-sig")  # a byte-order mark (some Windows editors write one) is dropped
    except FileNotFoundError:
        raise InputError(f"{path}: no such {what} file; check the path") from None
    except IsADirectoryError:
        raise InputError(f"{path}: is a folder; give a {what} TOML file in it") from None
    except UnicodeDecodeError as exc:
        raise InputError(
            f"{path}: not a text file (byte 0x{exc.object[exc.start]:02x} at offset {exc.start} is not "
            f"UTF-8); give a {what} TOML file"
        ) from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read the {what} file ({exc.strerror or exc})") from None
    if "\x00" in text:
        raise InputError(f"{path}: not a text file (it contains NUL bytes); give a {what} TOML file")
    try:
        return text, tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: TOML syntax error: {exc}") from None
    except RecursionError:  # the parser recurses per level of nested arrays and tables
        raise InputError(
            f"{path}: TOML nested too deeply (arrays or tables within each other); give a {what} file"
        ) from None


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene TOML file."""
    _, data = read_toml(path, "scene")
    return parse_scene(data, source=str(path))
