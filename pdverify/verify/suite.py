"""The verification suite's scenes, written as a study (scene files + study.toml) that ``run_study`` runs.

The suite is fixed and versioned (:data:`SUITE_VERSION`): the same model gives the same card until the
version changes. Straight scenes: every support pair that holds the beam, with a point force, a point
moment, a uniform, a partial and a sine load (and a force at a free or guided end), at slenderness 20;
two uniform-load scenes from thick to very slender (locking); one scene on fine grids (round-off floor).
Curved scenes (arcs, one clockwise) when the model declares ``curved``. Loads sit on grid points of every
grid (quarter points), so the orders measure the model, not the load placement.

A rod (theory ``axial``) or a torsion bar (``torsion``) gets the same sets with its own loads (:data:`ROD_LOADS`:
axial forces or torques, point, uniform, partial, sine, and one at an end that does not hold the unknown) on the
support pairs that hold it (``scene.ROD_HELD``), against ``exact-rod`` or ``exact-torsion``; no locking scenes
(a rod's error does not depend on the slenderness).

A theory pdverify has no exact solution of (``higher-order``, ``continuum``) is judged by self-convergence:
the reference is the model itself, with the same options, on a grid :data:`SELF_REFINEMENT` times finer than
the set's finest (nested, so the grids' points are its points), and the distance of that solution from exact
Timoshenko theory is reported as the theory gap (run as one more set, not judged).
"""

# long module: the suite's fixed scenes and loads are data, versioned together

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from ..core.scene import ROD_HELD, SUPPORTS, is_mechanism
from ..core.scene_file import parse_scene
from ..registry import get_model
from ..registry.external import ExternalModel

# 1.1: natural frequencies of models that declare dynamics (verify.dynamics); 1.2: self-convergence for theories
# without an exact solution here, and superposition with the point-load positions shared by the three solves;
# 1.3: a clockwise arc among the curved scenes; 1.4: axial and torsion models (ROD_LOADS; the beams' cards unchanged),
# and a self-converged model's curved scenes against itself (was exact-curved: fem-plane-stress's card only);
# 1.5: higher-order models against exact-higher-order with their loads and pin (Model.reference_options; were
# self-converged); 1.6: the curved scenes' rotation, moment, shear and axial force (CURVED_QUANTITIES), each its own
# convergence check; 1.7: scenes as engineers draw them (engineering_scenes) for models that take supports inside
# the span, springs or segments; 1.8: locking on a curved axis (a clamped-free quarter circle under a uniform load,
# L/h = 5 ... 10^4, against exact-curved) for the curved beam models; 1.9: a 2D continuum's floor scene on
# CONTINUUM_FLOOR_GRIDS (its own reference on 10241 stations had a round-off bound above the errors it judged);
# 1.10: the engineers' scenes against the exact reference where it takes every one of them the model takes
# (exact-higher-order: the supports inside the span and the springs, not the segments pd-higher-order declines too)
SUITE_VERSION = "1.10"
GRIDS = (21, 41, 81, 161)
FULL_GRIDS = (11, 21, 41, 81, 161, 321, 641)
# the largest order a card can observe: an error of order p falls 2^p-fold from one grid to the next, and between the
# suite's coarsest and finest grids (three halvings) it stays within float64's range of relative errors, from 1 down to
# 2^-52, only when 3 p <= 52
MAX_ORDER = 52 / (len(GRIDS) - 1)
FLOOR_GRIDS = (161, 641, 2561)
FULL_FLOOR_GRIDS = (161, 641, 2561, 10241)
# a 2D continuum (theory "continuum", judged against itself): its floor reference, SELF_REFINEMENT times the finest
# floor grid, must stay within its own round-off reach; the strip's round-off bound passes its error from about 641
# stations on (docs/verify.md), a 1D model's only past 2561 points
CONTINUUM_FLOOR_GRIDS = (41, 161, 641)
FULL_CONTINUUM_FLOOR_GRIDS = (41, 161, 641, 2561)
SLENDERNESS = 20.0
LOCKING_SLENDERNESS = (5.0, 20.0, 100.0, 1000.0, 10000.0)
LENGTH, WIDTH = 1.0, 0.05
MATERIAL = {"youngs_modulus": 70e9, "poissons_ratio": 0.3}
SELF_REFINEMENT = 4  # self-convergence: the reference grid has this many times the spacings of the finest grid
GAP_REFERENCE = "exact-timoshenko"  # what a self-converged model's theory gap is measured against
PAIRS = [(left, right) for left in SUPPORTS for right in SUPPORTS if not is_mechanism(left, right)]
# what the curved scenes measure besides the displacement w (each its own convergence check on the card)
CURVED_QUANTITIES = ("rotation", "moment", "shear", "axial")


def straight(left: str, right: str, loads: list[dict], slenderness: float = SLENDERNESS, name: str = "") -> dict:
    """A straight scene of the suite (length 1 m, width 50 mm, height = length / slenderness)."""
    return {
        "name": name or f"{left}-{right}",
        "beam": {"length": LENGTH},
        "section": {"width": WIDTH, "height": LENGTH / slenderness},
        "material": dict(MATERIAL),
        "supports": {"left": left, "right": right},
        "loads": loads,
    }


LOADS = {
    "point force": [{"type": "point_force", "position": 0.5, "value": -1000.0}],
    "point moment": [{"type": "point_moment", "position": 0.25, "value": 200.0}],
    "uniform": [{"type": "distributed", "value": -1000.0}],
    "partial": [{"type": "distributed", "value": -1000.0, "start": 0.25, "end": 0.75}],
    "sine": [{"type": "distributed", "value": -1000.0, "shape": "sine"}],
}


def _axial(position=None, **load) -> dict:
    """An axial load of 1 kN (per metre) along +x (the rod suite's loads)."""
    return {"value": 0.0, "axial": 1000.0, **load, **({} if position is None else {"position": position})}


def _torque(**load) -> dict:
    """A distributed torque of 100 N m/m (the torsion suite's loads)."""
    return {"type": "distributed", "value": 0.0, "torque": 100.0, **load}


ROD_LOADS = {  # suite 1.4
    "axial": {
        "point force": [_axial(0.5, type="point_force")],
        "uniform": [_axial(type="distributed")],
        "partial": [_axial(type="distributed", start=0.25, end=0.75)],
        "sine": [_axial(type="distributed", shape="sine")],
    },
    "torsion": {
        "point torque": [{"type": "point_torque", "position": 0.5, "value": 100.0}],
        "uniform": [_torque()],
        "partial": [_torque(start=0.25, end=0.75)],
        "sine": [_torque(shape="sine")],
    },
}


def rod_kind(model) -> str | None:
    """ "axial" or "torsion" for a model of a rod or torsion bar (its theory), None for a beam."""
    return model.theory if model.theory in ROD_HELD else None


def loads_for(kind: str | None) -> dict:
    """The suite's loads of a beam (kind None), a rod or a torsion bar."""
    return LOADS if kind is None else ROD_LOADS[kind]


def pairs_for(kind: str | None) -> list[tuple[str, str]]:
    """The support pairs that hold a beam (kind None), or of those, the ones that hold the rod's unknown."""
    return PAIRS if kind is None else [p for p in PAIRS if set(p) & set(ROD_HELD[kind])]


def end_force(left: str, right: str, kind: str | None = None) -> list[dict] | None:
    """A force at an end of the pair that does not hold the unknown (free or guided for a beam's deflection; for a
    rod, an axial force or a torque at an end outside ``ROD_HELD``); None when both ends hold it."""
    for support, position in ((right, LENGTH), (left, 0.0)):
        if kind is None and support in ("free", "guided"):
            return [{"type": "point_force", "position": position, "value": -1000.0}]
        if kind is not None and support not in ROD_HELD[kind]:
            if kind == "axial":
                return [_axial(position, type="point_force")]
            return [{"type": "point_torque", "position": position, "value": 100.0}]
    return None


def mirror(scene: dict) -> dict:
    """The mirror-image scene (x -> L - x): supports swapped, positions mirrored, moments and axial forces
    reversed (the mirror's u is -u(L - x); w and the twist are w(L - x) and twist(L - x))."""
    L = scene["beam"]["length"]
    loads = []
    for ld in scene["loads"]:
        ld = dict(ld)
        if "position" in ld:
            ld["position"] = L - ld["position"]
        if ld["type"] == "point_moment":
            ld["value"] = -ld["value"]
        if ld.get("axial"):  # an axial force reverses; a torque (about the axis) does not
            ld["axial"] = -ld["axial"]
        if ld["type"] == "distributed" and ("start" in ld or "end" in ld):
            ld["start"], ld["end"] = L - ld.get("end", L), L - ld.get("start", 0.0)
        loads.append(ld)
    sup = scene["supports"]
    out = {
        **scene,
        "name": scene["name"] + " (mirror)",
        "loads": loads,
        "supports": {"left": sup["right"], "right": sup["left"]},
    }
    if sup.get("inner"):  # supports inside the span and segments mirrored too
        out["supports"]["inner"] = [dict(s, position=L - s["position"]) for s in sup["inner"]][::-1]
    if scene.get("segments"):
        out["segments"] = [dict(g, start=L - g["end"], end=L - g["start"]) for g in scene["segments"]][::-1]
    return out


def curved_scenes() -> list[dict]:
    """Arcs, one of them clockwise: cantilevers and statically indeterminate ones (reference exact-curved)."""
    sec, half_pi = {"width": 0.05, "height": 0.05}, 1.5707963267948966
    arc = {"type": "arc", "radius": 1.0, "opening_angle_deg": 90.0}
    base = {"beam": {"length": half_pi}, "section": sec, "material": dict(MATERIAL), "axis": arc}
    return [
        {
            **base,
            "name": "quarter circle, clamped-free, tip force",
            "supports": {"left": "clamped", "right": "free"},
            "loads": [{"type": "point_force", "position": half_pi, "value": -1000.0}],
        },
        {
            **base,
            "name": "quarter circle, clamped-pinned, uniform",
            "supports": {"left": "clamped", "right": "pinned"},
            "loads": [{"type": "distributed", "value": -1000.0}],
        },
        {
            **base,
            "name": "quarter circle clockwise, clamped-pinned, uniform",
            "axis": {**arc, "direction": "clockwise"},
            "supports": {"left": "clamped", "right": "pinned"},
            "loads": [{"type": "distributed", "value": -1000.0}],
        },
        {
            **base,
            "name": "semicircle, pinned-pinned, force at the crown",
            "beam": {"length": 2 * half_pi},
            "axis": {**arc, "opening_angle_deg": 180.0},
            "supports": {"left": "pinned", "right": "pinned"},
            "loads": [{"type": "point_force", "position": half_pi, "value": -1000.0}],
        },
    ]


def _span_loads(force_at: float, moment_at: float) -> list[dict]:
    """A uniform load with a point force and a point moment in two of the spans (on grid points of every grid)."""
    return [
        {"type": "distributed", "value": -1000.0},
        {"type": "point_force", "position": force_at, "value": -1000.0},
        {"type": "point_moment", "position": moment_at, "value": 200.0},
    ]


def _as_rod_load(load: dict, kind: str) -> dict:
    """A beam load of the engineers' scenes as the rod's (axial) or the bar's (torsion) at the same place: the
    distributed load 1 kN/m (100 N m/m), a point force or moment an axial force of its value (5 x a moment's) or a
    torque of a tenth of it (half a moment's)."""
    at = {"position": load["position"]} if "position" in load else {}
    if load["type"] == "distributed":
        return _axial(type="distributed") if kind == "axial" else _torque()
    size = load["value"] * (1.0 if load["type"] == "point_force" else 5.0)
    if kind == "axial":
        return {"type": "point_force", **at, "value": 0.0, "axial": size}
    return {"type": "point_torque", **at, "value": size / 10.0}


def engineering_scenes(kind: str | None = None) -> list[dict]:
    """Scenes as engineers draw them (suite 1.7), loads in every span (a rod's or a bar's, ``kind``, at the same
    places: :func:`_as_rod_load`): continuous over two and three spans, an
    overhang on both sides, a beam on springs, a stepped and a bi-material beam. Supports, segment ends and loads sit
    on grid points of every grid (and where the mirror image puts them back exactly); the springs are about the
    beam's own stiffness (48 EI / L³ = 1.7e6 N/m)."""
    steel = {"youngs_modulus": 200e9, "poissons_ratio": 0.3}
    out = [
        (
            "two spans",
            {"left": "pinned", "right": "pinned", "inner": [{"position": 0.5, "type": "pinned"}]},
            [],
            _span_loads(0.25, 0.75),
        ),
        (
            "three spans",
            {
                "left": "pinned",
                "right": "roller",
                "inner": [{"position": 0.35, "type": "pinned"}, {"position": 0.7, "type": "roller"}],
            },
            [],
            _span_loads(0.5, 0.85) + [{"type": "point_force", "position": 0.25, "value": 500.0}],
        ),
        (
            "overhangs",
            {
                "left": "free",
                "right": "free",
                "inner": [{"position": 0.25, "type": "pinned"}, {"position": 0.75, "type": "roller"}],
            },
            [],
            _span_loads(0.5, 0.9) + [{"type": "point_force", "position": 0.0, "value": -500.0}],
        ),
        (
            "on springs",
            {
                "left": "pinned",
                "right": {"type": "spring", "stiffness": 1e6, "rotational_stiffness": 1e4},
                "inner": [{"position": 0.5, "type": "spring", "stiffness": 2e6}],
            },
            [],
            _span_loads(0.25, 0.75),
        ),
        (
            "stepped",
            {"left": "clamped", "right": "pinned"},
            [{"start": 0.0, "end": 0.4, "section": {"width": WIDTH, "height": 0.07}}, {"start": 0.4, "end": LENGTH}],
            _span_loads(0.25, 0.7),
        ),
        (
            "bi-material",
            {"left": "clamped", "right": "pinned", "inner": [{"position": 0.55, "type": "pinned"}]},
            [{"start": 0.0, "end": 0.55, "material": steel}, {"start": 0.55, "end": LENGTH}],
            _span_loads(0.25, 0.8),
        ),
    ]
    scenes = []
    for name, supports, segments, loads in out:
        loads = loads if kind is None else [_as_rod_load(ld, kind) for ld in loads]
        sc = straight("pinned", "pinned", loads, name=name)
        sc["supports"] = supports
        if segments:
            sc["segments"] = segments
        scenes.append(sc)
    return scenes


def curved_locking_scene(slenderness: float) -> dict:
    """A clamped-free quarter circle (R = 1) under a uniform load, its section height L / ``slenderness``."""
    half_pi = 1.5707963267948966
    return {
        "name": f"quarter circle, clamped-free, uniform, L/h = {slenderness:g}",
        "beam": {"length": half_pi},
        "section": {"width": 0.05, "height": half_pi / slenderness},
        "material": dict(MATERIAL),
        "axis": {"type": "arc", "radius": 1.0, "opening_angle_deg": 90.0},
        "supports": {"left": "clamped", "right": "free"},
        "loads": [{"type": "distributed", "value": -1000.0}],
    }


@dataclass
class Plan:
    """The scenes of one verification: ``meta`` maps a scene file to what it tests."""

    scenes: dict[str, dict]
    meta: dict[str, dict]
    grids: tuple
    floor_grids: tuple
    reference: str | dict | None  # a model name or {model, options}; None: self-convergence (:func:`finer`)
    curved_reference: str | None
    engineering_reference: str | dict | None = None  # the engineers' scenes': ``reference`` where it takes them all


def engineering_reference(reference, taken: list[dict]):
    """What the engineers' scenes ``taken`` (those the model, with its options, takes) are judged against: the suite's
    ``reference`` where it takes every one of them, else None (the model against itself)."""
    return reference if taken and takes_all(reference, taken) else None


def takes_all(reference, scenes: list[dict]) -> bool:
    """True when the reference (a name or {model, options}) solves every one of ``scenes`` (its check)."""
    if reference is None:
        return False
    m = get_model(reference["model"] if isinstance(reference, dict) else reference)
    return all(not m.check(parse_scene(sc)) for sc in scenes)


EXACT = {  # the exact solution of each theory that has one here
    "euler-bernoulli": "exact-eb",
    "timoshenko": "exact-timoshenko",
    "axial": "exact-rod",
    "torsion": "exact-torsion",
    "higher-order": "exact-higher-order",
}


def reference_for(theory: str) -> str | None:
    """The exact solution of the model's declared theory; None for a theory pdverify has none of (continuum): the
    model is judged against itself on a finer grid."""
    return EXACT.get(theory)


def exact_reference(model, options: dict) -> str | dict | None:
    """The reference a study gives for ``model`` with ``options``: its theory's exact solution with the options
    that match the model's (:meth:`~pdverify.registry.Model.reference_options`), a name or an inline table; None
    when there is none or the model's equations converge to something else (self-convergence)."""
    name, extra = reference_for(model.theory), model.reference_options(options)
    if name is None or extra is None:
        return None
    return {"model": name, **extra} if extra else name


def reference_name(reference: str | dict | None) -> str | None:
    """How a card names a reference: ``exact-higher-order (loads = faces, pin = face)``."""
    if not isinstance(reference, dict):
        return reference
    opts = ", ".join(f"{k} = {v}" for k, v in reference.items() if k != "model")
    return f"{reference['model']} ({opts})"


def finer(grids) -> int:
    """The self-convergence reference grid of a set of grids: :data:`SELF_REFINEMENT` times the finest one's
    spacings (nested: every grid point of the finest grid is one of its points)."""
    return SELF_REFINEMENT * (max(grids) - 1) + 1


def self_reference(model, options: dict, grids) -> dict:
    """The model itself, with the card's options, on the grid :func:`finer` than ``grids``."""
    return {"model": model.name, **options, "points": finer(grids)}


def plan(model, full: bool = False, options: dict | None = None) -> Plan:
    scenes, meta = {}, {}

    def add(kind: str, scene: dict, **info):
        f = f"scenes/{len(scenes):03d}.toml"
        scenes[f] = scene
        meta[f] = {"set": kind, "name": scene["name"], **info}

    kind = rod_kind(model)
    loads = loads_for(kind)
    for left, right in pairs_for(kind):
        cases = dict(loads)
        if end_force(left, right, kind):
            cases["end force" if kind != "torsion" else "end torque"] = end_force(left, right, kind)
        for load, lds in cases.items():
            add(
                "convergence",
                straight(left, right, lds, name=f"{left}-{right}, {load}"),
                pair=f"{left}-{right}",
                load=load,
                slenderness=SLENDERNESS,
            )
    for left, right in (("clamped", "free"), ("clamped", "clamped")) if kind is None else ():
        for s in LOCKING_SLENDERNESS:
            add(
                "locking",
                straight(left, right, LOADS["uniform"], s, f"{left}-{right}, uniform, L/h = {s:g}"),
                pair=f"{left}-{right}",
                load="uniform",
                slenderness=s,
            )
    add(
        "floor",
        straight("clamped", "free", loads["uniform"], name="clamped-free, uniform (fine grids)"),
        pair="clamped-free",
        load="uniform",
        slenderness=SLENDERNESS,
    )
    if model.inner_supports or model.springs or model.segments:
        for sc in engineering_scenes(kind):  # (a scene the model cannot hold is declined: listed on the card)
            sup = sc["supports"]
            add(
                "engineering",
                sc,
                pair=f"{sup['left'] if isinstance(sup['left'], str) else 'spring'}-"
                f"{sup['right'] if isinstance(sup['right'], str) else 'spring'}",
                load="span loads",
                slenderness=SLENDERNESS,
            )
    if model.curved:
        for sc in curved_scenes():
            add(
                "curved",
                sc,
                pair=f"{sc['supports']['left']}-{sc['supports']['right']}",
                load=sc["loads"][0]["type"],
                slenderness=sc["beam"]["length"] / sc["section"]["height"],
            )
    reference = exact_reference(model, options or {})
    # the engineers' scenes the model takes (it declines the others on its card, whatever the reference)
    engineering = [
        sc for f, sc in scenes.items() if meta[f]["set"] == "engineering" and not model.check(parse_scene(sc))
    ]
    # membrane and shear locking show on a curved axis (a straight one does not couple them): the beam models judged
    # against exact-curved; a continuum strip at L/h = 10^4 needs far more elements than the suite's grids
    for s in LOCKING_SLENDERNESS if model.curved and reference_for(model.theory) else ():
        add(
            "curved_locking",
            curved_locking_scene(s),
            pair="quarter circle clamped-free",
            load="uniform",
            slenderness=s,
        )
    if model.theory == "continuum":
        floor_grids = FULL_CONTINUUM_FLOOR_GRIDS if full else CONTINUUM_FLOOR_GRIDS
    else:
        floor_grids = FULL_FLOOR_GRIDS if full else FLOOR_GRIDS
    return Plan(
        scenes,
        meta,
        FULL_GRIDS if full else GRIDS,
        floor_grids,
        reference,
        # a theory judged against itself is so on curved axes too (exact-curved is a beam theory: the 2D strip
        # converges to its own solution, 1.7e-2 away on the clamped-pinned quarter circle)
        "exact-curved" if model.curved and reference_for(model.theory) else None,
        # where the exact solution cannot hold one of them: the model against itself (:func:`verify.verify` asks
        # again of the scenes the model's options refuse too)
        engineering_reference(reference, engineering),
    )


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):  # an inline table (a run's reference)
        return "{" + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"no TOML for {v!r}")


def toml_text(data: dict) -> str:
    """A scene or study table as TOML (scalars, tables of scalars, arrays of tables of scalars)."""
    lines = [
        f"{k} = {toml_value(v)}"
        for k, v in data.items()
        if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict))
    ]
    for k, v in data.items():
        if isinstance(v, dict):
            lines += ["", f"[{k}]"] + [f"{kk} = {toml_value(vv)}" for kk, vv in v.items()]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                lines += ["", f"[[{k}]]"] + [f"{kk} = {toml_value(vv)}" for kk, vv in item.items()]
    return "\n".join(lines) + "\n"


def write_study(p: Plan, model, options: dict, folder: Path) -> Path:
    """The plan as scene files and a study file in ``folder``; returns the study file's path."""

    for f, scene in p.scenes.items():
        (folder / f).parent.mkdir(parents=True, exist_ok=True)
        (folder / f).write_text(toml_text(scene))
    files = lambda *sets: [f for f, m in p.meta.items() if m["set"] in sets and f in p.scenes]  # noqa: E731
    run = {"model": model.name, **options}
    ref = lambda grids: p.reference or self_reference(model, options, grids)  # noqa: E731
    runs = [
        {
            **run,
            "points": list(p.grids),
            "scenes": files("convergence", "locking"),
            "reference": ref(p.grids),
        },
        {**run, "points": list(p.floor_grids), "scenes": files("floor"), "reference": ref(p.floor_grids)},
    ]
    if p.reference is None:  # the theory gap: the self-convergence reference against exact Timoshenko theory
        runs.append({**run, "points": [finer(p.grids)], "scenes": files("convergence"), "reference": GAP_REFERENCE})
    if files("engineering"):
        eng = p.engineering_reference or self_reference(model, options, p.grids)
        runs.append({**run, "points": list(p.grids), "scenes": files("engineering"), "reference": eng})
    if files("curved"):
        curved = p.curved_reference or self_reference(model, options, p.grids)
        runs.append(
            {
                **run,
                "points": list(p.grids),
                "scenes": files("curved", "curved_locking"),
                "reference": curved,
                "quantities": list(CURVED_QUANTITIES),
            }
        )
    study = {
        "name": f"pdverify verify {model.name} (suite {SUITE_VERSION})",
        "scenes": list(p.scenes),
        "reference": p.reference or GAP_REFERENCE,
        "runs": runs,
    }
    if isinstance(model, ExternalModel):
        study["external"] = [str(model.path)]
    path = folder / "study.toml"
    path.write_text(toml_text(study))
    return path
