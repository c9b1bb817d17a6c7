"""A scaled scene gives the same relative result: every static model on a straight beam (and every axial and torsion
model on a straight rod or shaft), the scene scaled in length
(every length: the beam, its section, load positions and spans; 1e-6 to 1e6), in modulus (1e-3 to 1e15) and in
load (1e-6 to 1e6), gives the same deflection relative to its largest value and the same warnings as the unscaled
scene. A model whose numbers depend on the units (an absolute tolerance, a rank test on unscaled rows, a round-off
bound in absolute terms) fails here.

Tolerance: the two runs' own round-off bounds (``info["error_bound"]``, each relative to max |w|, which covers the
rounding of the scaled inputs as data error; an estimate "usually within a factor of 3", Higham 2002 §15.3, hence
BOUND_FACTOR) plus a few eps for the normalisation; closed forms, which solve at most a small dense system of
condition ``info["cond"]``, get SCALE_EPS cond eps.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from helpers import PAIRS, scene_dict
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.registry import models, run

SCALE_EPS = 64  # a closed form's rounding: a few dozen operations on each value, each within eps
BOUND_FACTOR = 3.0  # Hager's estimate of a norm is usually within a factor of 3 of it (Higham 2002, §15.3)

# every static straight-beam model, with the options that set its grid; a curved model on a straight axis too
SKIP = {
    "exact-curved-cantilever": "clamped-free only; exact-curved covers it",
    "exact-curved-manufactured": "ignores the scene's loads by design",
    "pd-curved-mms": "manufactured loads",
    "exact-elastica": "a nonlinear reference for one end load",
    "fem-plane-stress": "the 2D continuum: its own scale test below, slow",
    "exact-eringen": "refuses the couple inside the span; its nonlocal length scales too: tests/exact/test_eringen.py",
}
MODELS = sorted(n for n, m in models().items() if "static" in m.analyses and m.straight and m.bending and n not in SKIP)

LOADS = [
    {"type": "point_force", "position": 0.7, "value": -300.0},
    {"type": "point_moment", "position": 1.3, "value": 150.0},
    {"type": "distributed", "value": -500.0, "start": 0.2, "end": 1.1},
    {"type": "distributed", "value": 400.0, "shape": "sine"},
]


def scaled(left: str, right: str, length: float, modulus: float, load: float) -> dict:
    """The test beam (L = 2, 0.05 x 0.1 section, E = 70 GPa) with every length times ``length``, the modulus times
    ``modulus`` and every load times ``load`` (forces and moments by the same factor, line loads per unit length)."""
    loads = []
    for ld in LOADS:
        d = dict(ld)
        for key in ("position", "start", "end"):
            if key in d:
                d[key] *= length
        d["value"] *= (
            load * (length if d["type"] == "point_moment" else 1.0) / (length if d["type"] == "distributed" else 1.0)
        )
        loads.append(d)
    return scene_dict(
        left,
        right,
        loads,
        beam={"length": 2.0 * length},
        section={"width": 0.05 * length, "height": 0.1 * length},
        material={"youngs_modulus": 70e9 * modulus, "poissons_ratio": 0.33},
    )


def words(warnings: list[str]) -> list[str]:
    """A warning without its numbers (a position or a load scales with the scene; its text must not change)."""
    return sorted(re.sub(r"[-+]?\d[\d.]*(e[-+]?\d+)?", "#", w) for w in warnings)


def relative(result) -> np.ndarray:
    w = np.asarray(result.w, float)
    return w / np.abs(w).max()


def tolerance(a, b) -> float:
    eps = np.finfo(float).eps
    bounds = [r.info.get("error_bound") for r in (a, b)]
    if any(v is None for v in bounds):
        return SCALE_EPS * eps * max(r.info.get("cond", 1.0) for r in (a, b))
    return BOUND_FACTOR * sum(bounds) + 8 * eps


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    pair=st.sampled_from(PAIRS),
    length=st.sampled_from([1e-6, 1e-3, 1e3, 1e6]),
    modulus=st.sampled_from([1e-3, 1e-9, 1e6, 1e5 / 70]),
    load=st.sampled_from([1e-6, 1e6]),
)
@pytest.mark.parametrize("name", MODELS)
def test_a_scaled_scene_gives_the_same_relative_result(name, pair, length, modulus, load):
    options = {"points": 41} if models()[name].option("points") is not None else {}
    base = run(parse_scene(scaled(*pair, 1.0, 1.0, 1.0)), name, **options)
    other = run(parse_scene(scaled(*pair, length, modulus, load)), name, **options)
    assert np.allclose(np.asarray(other.x) / length, base.x, rtol=1e-15, atol=1e-15 * 2.0)
    diff = np.abs(relative(other) - relative(base)).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))
    assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


@pytest.mark.parametrize("options", [{}, {"form": "primal"}, {"unknowns": "displacements"}, {"degree": 6}])
@pytest.mark.parametrize("factors", [(1e6, 1e-3, 1e6), (1e-6, 1e15, 1e-3), (1e3, 1.0, 1.0)])
def test_pd_curved_solves_the_same_system_in_any_units(options, factors):
    """pd-curved's unknowns mix lengths, rotations, forces and moments; its equilibration (rows, then columns, by
    their largest entries) is not the same for a matrix in other units, so an I-section at L x 1e6, E x 1e-3 had a
    condition estimate of 2.5e25 where the unscaled scene's is 2.2e11, and w 2.2 % off under a round-off warning. In
    the beam's own units the matrix, hence its condition estimate (6 digits), is the same whatever the scene's."""
    d = scaled("clamped", "pinned", 1.0, 1.0, 1.0)
    section = {"shape": "I", "height": 0.3, "flange_width": 0.15, "flange_thickness": 0.0107, "web_thickness": 0.0071}
    d["section"] = section
    k, e, f = factors
    o = scaled("clamped", "pinned", k, e, f)
    o["section"] = {key: v * k if key != "shape" else v for key, v in section.items()}
    opts = {"points": 21, **options}
    base = run(parse_scene(d), "pd-curved", **opts)
    other = run(parse_scene(o), "pd-curved", **opts)
    assert other.info["cond"] == pytest.approx(base.info["cond"], rel=1e-5)
    diff = np.abs(relative(other) - relative(base)).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))
    assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


@pytest.mark.parametrize("modulus", [1e300 / 70e9, 1e-300 / 70e9])
def test_pd_curved_solves_moduli_near_the_float_range_s_ends(modulus):
    """E = 1e300 or 1e-300: sqrt(EA EI) overflowed (the system held inf: refused), and the load vector of the
    beam's units came within a few powers of ten of overflow (the round-off bound inf). Both solve as E = 70 GPa."""
    base = run(parse_scene(scaled("clamped", "free", 1.0, 1.0, 1.0)), "pd-curved", points=21)
    other = run(parse_scene(scaled("clamped", "free", 1.0, modulus, 1.0)), "pd-curved", points=21)
    assert other.info["error_bound"] <= 10 * base.info["error_bound"]
    diff = np.abs(relative(other) - relative(base)).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))
    assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


@pytest.mark.parametrize("length", [2.0, 1e3, 1e-3])
@pytest.mark.parametrize("pair", [("clamped", "free"), ("free", "clamped")])
def test_a_free_end_s_fitted_ghosts_scale_too(pair, length):
    """pd-timoshenko corrected fits its free end's ghosts of w and the rotation by least squares under the end's
    conditions: the fit weighed metres against radians, so a scene scaled by 1e3 moved its tip by 7.2e-6 relative
    (bound 1.4e-8). It now fits w and L times the rotation, both lengths."""
    opts = {"points": 81, "variant": "corrected", "horizon": 8}
    base = run(parse_scene(scaled(*pair, 1.0, 1.0, 1.0)), "pd-timoshenko", **opts)
    other = run(parse_scene(scaled(*pair, length, 1.0, 1.0)), "pd-timoshenko", **opts)
    diff = np.abs(relative(other) - relative(base)).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))


SPRING = {"type": "spring", "stiffness": 1e6, "rotational_stiffness": 2e5}  # N/m and N m/rad at the test beam's size


def spring(length: float, modulus: float) -> dict:
    """SPRING for the scene scaled by ``length`` and ``modulus``: a force per length scales as E L, a moment per
    radian as E L^3."""
    return {**SPRING, "stiffness": 1e6 * modulus * length, "rotational_stiffness": 2e5 * modulus * length**3}


@pytest.mark.parametrize("factors", [(1e-6, 1.0, 1.0), (1e6, 1e-3, 1e6), (1e-3, 1e15, 1e-3)])
@pytest.mark.parametrize(
    "name, variant", [(n, {}) for n in MODELS] + [("pd-timoshenko", {"variant": v}) for v in ("corrected", "paper")]
)
def test_a_spring_end_scales_too(name, variant, factors):
    """Springs at an end or both, scaled with the scene. pd-timoshenko's load column of a spring at an end kept the
    rows above 1e-14 of its largest entry, w's rows and the rotation's together: at L x 1e-6 the w rows were 1e6 times
    larger and a rotation row of the closure fell below it (w 4e-9 off, 130 times the round-off bound)."""
    if not models()[name].springs:
        pytest.skip(f"{name} takes no springs")
    options = {"points": 41, **variant} if models()[name].option("points") is not None else {}
    for left, right in ((SPRING, "clamped"), ("clamped", SPRING), (SPRING, SPRING)):
        sides = [spring(*factors[:2]) if s is SPRING else s for s in (left, right)]
        try:
            base = run(parse_scene(scaled(left, right, 1.0, 1.0, 1.0)), name, **options)
        except InputError as refused:  # pd-curved: two springs leave the axial translation free; so do they scaled
            with pytest.raises(InputError, match=re.escape(str(refused)[:40])):
                run(parse_scene(scaled(*sides, *factors)), name, **options)
            continue
        other = run(parse_scene(scaled(*sides, *factors)), name, **options)
        diff = np.abs(relative(other) - relative(base)).max()
        assert diff <= tolerance(base, other), (left, right, diff, tolerance(base, other))
        assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


@pytest.mark.slow
@pytest.mark.parametrize("length", [1e-6, 1e6])
def test_the_plane_stress_reference_scales_too(length):
    options = {"points": 21, "layers": 2, "element": "q8"}
    base = run(parse_scene(scaled("clamped", "pinned", 1.0, 1.0, 1.0)), "fem-plane-stress", **options)
    other = run(parse_scene(scaled("clamped", "pinned", length, 1e3, 1e-3)), "fem-plane-stress", **options)
    diff = np.abs(relative(other) - relative(base)).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))
    assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


ROD_MODELS = sorted(n for n, m in models().items() if "static" in m.analyses and m.straight and not m.bending)


def rod_loads(torsion: bool, length: float, load: float) -> list[dict]:
    """A point load at 0.35 L and a line load over [0.1 L, 0.55 L]: torques for a shaft, axial forces for a rod."""
    if torsion:
        return [
            {"type": "point_torque", "position": 0.7 * length, "value": 300.0 * load * length},
            {"type": "distributed", "value": 0.0, "torque": 200.0 * load, "start": 0.2 * length, "end": 1.1 * length},
        ]
    return [
        {"type": "point_force", "position": 0.7 * length, "value": 0.0, "axial": -300.0 * load},
        {
            "type": "distributed",
            "value": 0.0,
            "axial": 400.0 * load / length,
            "start": 0.2 * length,
            "end": 1.1 * length,
        },
    ]


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    pair=st.sampled_from([("clamped", "free"), ("free", "clamped"), ("clamped", "clamped")]),
    length=st.sampled_from([1e-6, 1e-3, 1e3, 1e6]),
    modulus=st.sampled_from([1e-3, 1e-9, 1e6]),
    load=st.sampled_from([1e-6, 1e6]),
)
@pytest.mark.parametrize("name", ROD_MODELS)
def test_a_scaled_rod_or_shaft_gives_the_same_relative_result(name, pair, length, modulus, load):
    """The axial and torsion models: the same relative displacement or twist and the same warnings."""
    model = models()[name]
    options = {"points": 41} if model.option("points") is not None else {}

    def solve(f_length, f_modulus, f_load):
        d = scaled(*pair, f_length, f_modulus, f_load)
        d["loads"] = rod_loads(model.torsion, f_length, f_load)
        return run(parse_scene(d), name, **options)

    base, other = solve(1.0, 1.0, 1.0), solve(length, modulus, load)
    a, b = (np.asarray(r.measured(model.measures), float) for r in (base, other))
    diff = np.abs(b / np.abs(b).max() - a / np.abs(a).max()).max()
    assert diff <= tolerance(base, other), (diff, tolerance(base, other))
    assert words(other.info.get("warnings", [])) == words(base.info.get("warnings", []))


def test_a_horizon_length_of_whole_and_half_spacings_scales_too():
    """Sweep 34 S34-2: at horizon_length = 2.5 spacings the scaled copy's 0.0175 / 0.007 = 2.5000000000000004 kept a
    member of weight 4e-16 (pd-eb: J 3 against 2, the load taken by its cell averages, w 2.1e-2 against 9.5e-3 off),
    and pd-higher-order's statics stretch of two depths, 10.000000000000002 spacings, took 11 (V 9.5e-3 against
    5.2e-4). A share of a spacing within 1e-9 of a whole number now counts as whole."""

    def scene(length, width, height, start, end):  # the scaled copy's numbers as a user types them
        load = {"type": "distributed", "value": -1e3, "start": start, "end": end}
        return parse_scene(
            {
                "name": "a patch beside a clamp",
                "beam": {"length": length},
                "section": {"width": width, "height": height},
                "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
                "supports": {"left": "clamped", "right": "pinned"},
                "loads": [load],
            }
        )

    one, scaled = scene(1.0, 0.02, 0.05, 0.045, 0.075), scene(0.7, 0.014, 0.035, 0.0315, 0.0525)
    for model in ("pd-eb", "pd-higher-order"):
        a, c = run(one, model, points=101, horizon_length=0.025), run(scaled, model, points=101, horizon_length=0.0175)
        for q in ("V", "M"):
            qa, qc = np.asarray(a.fields[q]), np.asarray(c.fields[q])
            assert np.abs(qa / np.abs(qa).max() - qc / np.abs(qc).max()).max() < 1e-9, (model, q)
        assert len(a.info.get("warnings", [])) == len(c.info.get("warnings", []))
