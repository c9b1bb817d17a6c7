"""Scenes as engineers draw them: continuous beams over supports inside the span, overhangs, elastic (spring)
supports, stepped and bi-material beams. The exact solutions (exact-eb, exact-timoshenko: piecewise closed forms
with the inner reactions as unknowns) against the nodally exact elements (fem-eb, fem-timoshenko, both forms),
textbook values, statics and mirror images."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.errors import InputError
from pdverify.core.reactions import load_resultants
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, models, run

LOADS = [  # a force, a couple, a partial and a sine load: loads in every span of the scenes below
    {"type": "point_force", "position": 0.7, "value": -300.0},
    {"type": "point_moment", "position": 1.3, "value": 150.0},
    {"type": "distributed", "value": -500.0, "start": 0.2, "end": 1.1},
    {"type": "distributed", "value": 400.0, "shape": "sine"},
    {"type": "point_force", "position": 1.85, "value": 120.0},
]
STEPPED = [
    {"start": 0.0, "end": 0.9, "section": {"width": 0.05, "height": 0.14}},
    {"start": 0.9, "end": 2.0},
]
BIMATERIAL = [
    {"start": 0.0, "end": 1.1, "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3}},
    {"start": 1.1, "end": 2.0, "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33}},
]
SCENES = {
    "two spans": {"left": "pinned", "right": "pinned", "inner": [{"position": 1.0, "type": "pinned"}]},
    "three spans": {
        "left": "pinned",
        "right": "roller",
        "inner": [{"position": 0.6, "type": "pinned"}, {"position": 1.4, "type": "roller"}],
    },
    "overhangs": {
        "left": "free",
        "right": "free",
        "inner": [{"position": 0.4, "type": "pinned"}, {"position": 1.6, "type": "pinned"}],
    },
    "on springs": {
        "left": {"type": "spring", "stiffness": 2e5, "rotational_stiffness": 1e4},
        "right": {"type": "spring", "stiffness": 5e5},
    },
    "inner clamp and spring": {
        "left": "free",
        "right": "pinned",
        "inner": [
            {"position": 0.5, "type": "clamped"},
            {"position": 1.5, "type": "spring", "stiffness": 1e6, "rotational_stiffness": 3e3},
        ],
    },
    "propped cantilever over a support": {
        "left": "clamped",
        "right": "free",
        "inner": [{"position": 1.2, "type": "pinned"}],
    },
}
CASES = [(name, sup, []) for name, sup in SCENES.items()] + [
    ("stepped", {"left": "clamped", "right": "pinned"}, STEPPED),
    ("bi-material", {"left": "pinned", "right": "pinned", "inner": [{"position": 0.8, "type": "pinned"}]}, BIMATERIAL),
    ("stepped on springs", SCENES["on springs"], STEPPED),
]
PAIRS = [("exact-eb", "fem-eb"), ("exact-timoshenko", "fem-timoshenko")]


def scene(supports, segments=(), loads=LOADS):
    d = scene_dict("pinned", "pinned", loads)
    d["supports"] = supports
    if segments:
        d["segments"] = list(segments)
    return parse_scene(d)


def mirrored(supports, segments, L=2.0):
    """The mirror image x -> L - x of a scene's supports, segments and loads (a couple changes sign)."""
    inner = [dict(s, position=L - s["position"]) for s in supports.get("inner", [])]
    sup = {"left": supports["right"], "right": supports["left"], "inner": inner[::-1]}
    segs = [dict(g, start=L - g["end"], end=L - g["start"]) for g in segments][::-1]
    loads = []
    for ld in LOADS:
        d = dict(ld)
        if "position" in d:
            d["position"] = L - d["position"]
        if d["type"] == "point_moment":
            d["value"] = -d["value"]
        if "start" in d:
            d["start"], d["end"] = L - d["end"], L - d["start"]
        loads.append(d)
    return scene(sup, segs, loads)


@pytest.mark.parametrize("name,supports,segments", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("exact,fem", PAIRS, ids=["euler-bernoulli", "timoshenko"])
@pytest.mark.parametrize("form", ["mixed", "direct"])
def test_exact_and_fem_agree(name, supports, segments, exact, fem, form):
    """Both nodally exact: the deflection at the nodes and the reactions agree to 1e-9 of their largest values."""
    sc = scene(supports, segments)
    f = run(sc, fem, points=41, form=form)
    ex = get_model(exact).evaluate(sc, {}, f.x)
    assert np.abs(f.w - ex["w"]).max() <= 1e-9 * np.abs(ex["w"]).max()
    assert np.abs(f.rotation - ex["rotation"]).max() <= 1e-9 * np.abs(ex["rotation"]).max()
    re, rf = run(sc, exact, points=11).info["reactions"], f.info["reactions"]
    scale = max(abs(v) for v in re.values())
    assert re.keys() == {k for k in rf if k != "method"}
    assert all(abs(rf[k] - v) <= 1e-9 * scale for k, v in re.items()), (re, rf)


@pytest.mark.parametrize("name,supports,segments", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko", "fem-eb", "fem-timoshenko"])
def test_reactions_balance_the_loads(name, supports, segments, model):
    sc = scene(supports, segments)
    r = run(sc, model, points=41).info["reactions"]
    at = {"left": 0.0, "right": sc.length} | {f"inner_{i}": s.position for i, s in enumerate(sc.supports.inner)}
    force = sum(v for k, v in r.items() if k.startswith("force"))
    moment = sum(v * at[k[len("force_") :]] for k, v in r.items() if k.startswith("force"))
    moment += sum(v for k, v in r.items() if k.startswith("moment"))
    load, load_moment = load_resultants(sc)
    size = sum(abs(ld["value"]) for ld in LOADS) * sc.length
    assert abs(force + load) <= 1e-12 * size and abs(moment + load_moment) <= 1e-12 * size * sc.length


@pytest.mark.parametrize("name,supports,segments", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko", "fem-eb", "fem-timoshenko"])
def test_a_mirror_scene_gives_the_mirror_result(name, supports, segments, model):
    a = run(scene(supports, segments), model, points=41)
    b = run(mirrored(supports, segments), model, points=41)
    back = np.interp(a.x, (2.0 - b.x)[::-1], b.w[::-1])
    assert np.abs(back - a.w).max() <= 1e-9 * np.abs(a.w).max()


def test_two_equal_spans_under_a_uniform_load():
    """Textbook: end reactions 3 q l / 8, the middle one 10 q l / 8 (l = one span); no deflection at the support."""
    q, l = -1000.0, 1.0
    sc = scene(SCENES["two spans"], loads=[{"type": "distributed", "value": q}])
    r = run(sc, "exact-eb", points=11).info["reactions"]
    assert r["force_left"] == pytest.approx(-3 * q * l / 8, rel=1e-13)
    assert r["force_right"] == pytest.approx(-3 * q * l / 8, rel=1e-13)
    assert r["force_inner_0"] == pytest.approx(-10 * q * l / 8, rel=1e-13)


def test_a_stepped_cantilever_tip_deflection_is_the_unit_load_integral():
    """delta = P ∫ (L - x)^2 / EI(x) dx (+ P ∫ 1 / kGA(x) dx for Timoshenko), piece by piece."""
    L, a, P = 2.0, 0.9, -100.0
    segments = [
        {"start": 0.0, "end": a, "section": {"width": 0.05, "height": 0.15}},
        {"start": a, "end": L, "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3}},
    ]
    sc = scene({"left": "clamped", "right": "free"}, segments, [{"type": "point_force", "position": L, "value": P}])
    (a0, b0, s0, m0), (a1, b1, s1, m1) = sc.pieces()
    EI0, EI1 = m0.E * s0.I, m1.E * s1.I
    bending = P * ((L**3 - (L - a) ** 3) / (3 * EI0) + (L - a) ** 3 / (3 * EI1))
    shear = P * (a / (s0.k * m0.G * s0.A) + (L - a) / (s1.k * m1.G * s1.A))
    assert run(sc, "exact-eb", points=2).w[-1] == pytest.approx(bending, rel=1e-13)
    assert run(sc, "exact-timoshenko", points=2).w[-1] == pytest.approx(bending + shear, rel=1e-13)


@pytest.mark.parametrize("stiffness,limit", [(1e16, "pinned"), (1e-4, "free")])
def test_a_spring_tends_to_its_limits(stiffness, limit):
    load = [{"type": "distributed", "value": -1000.0}]
    spring = run(
        scene({"left": "clamped", "right": {"type": "spring", "stiffness": stiffness}}, loads=load), "exact-eb"
    )
    rigid = run(scene({"left": "clamped", "right": limit}, loads=load), "exact-eb")
    assert np.abs(spring.w - rigid.w).max() <= 1e-8 * np.abs(rigid.w).max()


def test_models_that_hold_the_beam_at_its_ends_only_refuse_in_one_line():
    """Every model declares what it represents (springs, inner supports, segments); one that does not refuses such
    a scene before solving, one line per problem, naming the table."""
    sc = scene(SCENES["three spans"], STEPPED)
    for name, m in models().items():
        if m.inner_supports and m.segments:
            continue
        problems = m.check(sc)
        assert any(p.startswith("supports.inner") for p in problems) or m.inner_supports, name
        assert any(p.startswith("segments") for p in problems) or m.segments, name
        with pytest.raises(InputError):
            run(sc, name)


@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko"])
@pytest.mark.parametrize(
    "spring,rigid",
    [
        ({"right": {"type": "spring", "stiffness": 0.0, "rotational_stiffness": 1e300}}, {"right": "guided"}),
        ({"right": {"type": "spring", "stiffness": 1e300}}, {"right": "pinned"}),
        (
            {"inner": [{"position": 0.61, "type": "spring", "stiffness": 1e300}], "right": "free"},
            {"inner": [{"position": 0.61, "type": "pinned"}], "right": "free"},
        ),
    ],
    ids=["end rotational", "end translational", "inner"],
)
def test_a_spring_too_stiff_to_write_is_the_rigid_support(model, spring, rigid):
    """A spring of 1e300 on a soft beam (E = 1e-3, 20 mm square: k L^3 / EI about 1e313, past float64): the boundary
    condition k w + V = 0 is written as w + V / k = 0, so the closed form is the rigid support's (it raised
    LinAlgError from the rank test's SVD on the overflowed rows, exit 70: sweep 40 F1); fem-eb and fem-timoshenko
    agree with it to 1e-14 where they solve."""

    def scene(supports):
        d = {
            "name": "soft",
            "beam": {"length": 1.0},
            "section": {"width": 0.02, "height": 0.02},
            "material": {"youngs_modulus": 1e-3, "poissons_ratio": 0.3},
            "supports": {"left": "clamped", **supports},
            "loads": [{"type": "point_force", "position": 0.5, "value": -1.0}],
        }
        return parse_scene(d)

    a, b = run(scene(spring), model, points=21), run(scene(rigid), model, points=21)
    assert np.abs(a.w - b.w).max() <= 1e-12 * np.abs(b.w).max()
    assert np.abs(a.rotation - b.rotation).max() <= 1e-12 * np.abs(b.rotation).max()
