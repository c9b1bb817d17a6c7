"""The exact solutions are the ground truth: check them against textbook closed forms and statics."""

import numpy as np
import pytest
from helpers import ROOT, scene_dict

from pdverify.core.errors import SolveError
from pdverify.core.scene import is_mechanism
from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.registry import run

L, P, C, q = 2.0, -350.0, 120.0, -900.0


def F(x, scene, shear):
    return solve_straight(scene, shear).fields(x)


def rel(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


def pf(a, v=P):
    return {"type": "point_force", "position": a, "value": v}


def pm(a, v=C):
    return {"type": "point_moment", "position": a, "value": v}


def udl(v=q, start=None, end=None, shape="uniform"):
    d = {"type": "distributed", "value": v, "shape": shape}
    if start is not None:
        d["start"] = start
    if end is not None:
        d["end"] = end
    return d


x = np.linspace(0, L, 41)
xl = x[x <= L / 2]

# (supports, loads, x, textbook EB deflection w(x; EI), textbook shear part w_s(x; kGA) or None)
CASES = {
    "cantilever tip force": (
        ("clamped", "free"),
        [pf(L)],
        x,
        lambda x, EI: P * x**2 * (3 * L - x) / (6 * EI),
        lambda x, kGA: P * x / kGA,
    ),
    "cantilever tip moment": (("clamped", "free"), [pm(L)], x, lambda x, EI: C * x**2 / (2 * EI), lambda x, kGA: 0 * x),
    "cantilever uniform load": (
        ("clamped", "free"),
        [udl()],
        x,
        lambda x, EI: q * x**2 * (6 * L**2 - 4 * L * x + x**2) / (24 * EI),
        lambda x, kGA: q * (L * x - x**2 / 2) / kGA,
    ),
    "simply supported centre force": (
        ("pinned", "pinned"),
        [pf(L / 2)],
        xl,
        lambda x, EI: P * x * (3 * L**2 - 4 * x**2) / (48 * EI),
        lambda x, kGA: P * x / (2 * kGA),
    ),
    "simply supported uniform load": (
        ("pinned", "pinned"),
        [udl()],
        x,
        lambda x, EI: q * x * (L**3 - 2 * L * x**2 + x**3) / (24 * EI),
        lambda x, kGA: q * x * (L - x) / (2 * kGA),
    ),
    "clamped-clamped centre force": (
        ("clamped", "clamped"),
        [pf(L / 2)],
        xl,
        lambda x, EI: P * x**2 * (3 * L - 4 * x) / (48 * EI),
        lambda x, kGA: P * x / (2 * kGA),
    ),
    "clamped-clamped uniform load": (
        ("clamped", "clamped"),
        [udl()],
        x,
        lambda x, EI: q * x**2 * (L - x) ** 2 / (24 * EI),
        lambda x, kGA: q * x * (L - x) / (2 * kGA),
    ),
    "simply supported off-centre force": (
        ("pinned", "pinned"),
        [pf(0.5)],
        x[x <= 0.5],
        lambda x, EI: P * (L - 0.5) * x * (L**2 - (L - 0.5) ** 2 - x**2) / (6 * L * EI),
        None,
    ),
    "simply supported end moment": (
        ("pinned", "pinned"),
        [pm(0.0)],
        x,
        lambda x, EI: C * x * (2 * L**2 - 3 * L * x + x**2) / (6 * L * EI),
        lambda x, kGA: 0 * x,
    ),
    "propped cantilever uniform load": (
        ("clamped", "pinned"),
        [udl()],
        x,
        lambda x, EI: q * x**2 * (3 * L**2 - 5 * L * x + 2 * x**2) / (48 * EI),
        None,
    ),
    "clamped-guided end force": (
        ("clamped", "guided"),
        [pf(L)],
        x,
        lambda x, EI: P * x**2 * (3 * L - 2 * x) / (12 * EI),
        lambda x, kGA: P * x / kGA,
    ),
    "pinned-guided uniform load": (
        ("pinned", "guided"),
        [udl()],
        x,
        lambda x, EI: q * x * ((2 * L) ** 3 - 2 * (2 * L) * x**2 + x**3) / (24 * EI),
        None,
    ),
    "simply supported sine load": (
        ("pinned", "pinned"),
        [udl(shape="sine")],
        x,
        lambda x, EI: q * L**4 / (np.pi**4 * EI) * np.sin(np.pi * x / L),
        lambda x, kGA: q * L**2 / (np.pi**2 * kGA) * np.sin(np.pi * x / L),
    ),
}


TEXTBOOK = [(n, False) for n in CASES] + [(n, True) for n, c in CASES.items() if c[4] is not None]


@pytest.mark.parametrize("name,shear", TEXTBOOK)
def test_textbook(name, shear, make_scene):
    (left, right), loads, xs, w_eb, w_s = CASES[name]
    scene = make_scene(left, right, loads)
    want = w_eb(xs, scene.EI) + (w_s(xs, scene.kGA) if shear else 0)
    got = F(xs, scene, shear)["w"]
    assert rel(got, want) < 1e-12, name


def test_partial_span_cantilever_tip(make_scene):
    """Cantilever, uniform load over [0, a] from the clamp: tip w = q a^3 (4L - a) / (24 EI)."""
    a = 0.7
    scene = make_scene("clamped", "free", [udl(start=0.0, end=a)])
    got = F(np.array([L]), scene, False)["w"][0]
    assert abs(got - q * a**3 * (4 * L - a) / (24 * scene.EI)) < 1e-12 * abs(got)


def test_partial_span_sine_superposition(make_scene):
    """Sine load split into two partial spans adds up to the whole-span sine load."""
    whole = make_scene("clamped", "pinned", [udl(shape="sine")])
    parts = make_scene("clamped", "pinned", [udl(shape="sine", end=0.6), udl(shape="sine", start=0.6)])
    for shear in (False, True):
        assert rel(F(x, parts, shear)["w"], F(x, whole, shear)["w"]) < 1e-12


def test_rotation_is_slope_for_euler_bernoulli(make_scene):
    scene = make_scene("clamped", "pinned", [pf(0.3), pm(1.1), udl(start=0.2, end=1.5, shape="sine")])
    xs = np.linspace(0.01, L - 0.01, 200)
    h = 1e-6
    f = F(xs, scene, False)
    slope = (F(xs + h, scene, False)["w"] - F(xs - h, scene, False)["w"]) / (2 * h)
    assert np.max(np.abs(slope - f["rotation"])) < 1e-7 * np.max(np.abs(f["rotation"]))


ALL = ("clamped", "pinned", "free", "guided")
SUPPORT_PAIRS = [(l, r) for l in ALL for r in ALL if not is_mechanism(l, r)]


@pytest.mark.parametrize("left,right", SUPPORT_PAIRS)
@pytest.mark.parametrize("shear", [False, True])
def test_equilibrium_and_boundary_conditions(left, right, shear, make_scene):
    loads = [
        pf(0.0, 40.0),
        pf(0.37),
        pm(0.8),
        pm(L, -55.0),
        udl(start=0.4, end=1.3),
        udl(-300.0, shape="sine", start=0.9),
        pf(L, 75.0),
    ]
    scene = make_scene(left, right, loads)
    sol = solve_straight(scene, shear)
    r = sol.reactions()
    total_f = 40.0 + P + 75.0 + q * 0.9 + (-300.0) * L / np.pi * (np.cos(np.pi * 0.9 / L) - np.cos(np.pi))
    assert abs(r["force_left"] + r["force_right"] + total_f) < 1e-10 * 1000
    # moment balance about x = 0 (counter-clockwise positive: force f at a gives f a)
    from scipy.integrate import quad

    m_loads = P * 0.37 + C - 55.0 + 75.0 * L + q * (1.3**2 - 0.4**2) / 2
    m_loads += quad(lambda s: -300.0 * np.sin(np.pi * s / L) * s, 0.9, L, epsabs=1e-13)[0]
    assert abs(r["moment_left"] + r["moment_right"] + r["force_right"] * L + m_loads) < 1e-9 * 1000
    ends = sol.fields(np.array([0.0, L]))
    for i, s in ((0, left), (1, right)):
        scale = {"w": np.abs(sol.fields(x)["w"]).max(), "rotation": np.abs(sol.fields(x)["rotation"]).max()}
        if s in ("clamped", "pinned"):
            assert abs(ends["w"][i]) < 1e-12 * scale["w"]
        if s in ("clamped", "guided"):
            assert abs(ends["rotation"][i]) < 1e-12 * scale["rotation"]
    # reactions vanish where nothing holds the beam
    if left == "free":
        assert abs(r["force_left"]) < 1e-9 and abs(r["moment_left"]) < 1e-9
    if right in ("pinned", "free"):
        assert abs(r["moment_right"]) < 1e-9


def test_timoshenko_tends_to_euler_bernoulli(make_scene):
    """As the section gets stiff in shear the two exact solutions coincide."""
    scene = make_scene("clamped", "pinned", [pf(0.7), udl()])
    stiff = scene.model_copy(update={"material": scene.material.model_copy(update={"shear_modulus": 1e30})})
    assert rel(F(x, stiff, True)["w"], F(x, scene, False)["w"]) < 1e-12


@pytest.mark.slow
def test_models_registered_and_solve_cli_json(tmp_path):
    import json
    import subprocess
    import sys

    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "pdverify.apps.cli",
            "solve",
            "studies/examples/cantilever_tip_load.toml",
            "--model",
            "exact-eb",
            "--points",
            "11",
            "--format",
            "json",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert set(d) >= {"scene", "model", "parameters", "x", "w", "rotation", "dofs", "timings", "version"}
    assert len(d["x"]) == 11 and d["x"][-1] == 1.0
    # P L^3 / 3EI with P = -50 N, L = 1 m, EI = 200e9 * 1e-8 / 12
    assert d["w"][-1] == pytest.approx(-50 / (3 * 200e9 * 1e-8 / 12), rel=1e-12)
    assert set(d["timings"]) >= {"assemble_s", "solve_s", "total_s"}


@pytest.mark.parametrize("length", [1e-6, 3e-4, 1.0, 3e3, 1e5])
@pytest.mark.parametrize("left,right", [("clamped", "free"), ("clamped", "guided"), ("pinned", "pinned")])
def test_any_size_of_beam_is_solved_not_called_a_mechanism(length, left, right, make_scene):
    """A MEMS cantilever (300 µm, silicon) and a kilometre girder alike: the boundary conditions' 4x4 system is
    scaled row by row, so its rank test never mistakes a small or huge length for a mechanism. The closed form
    agrees with the nodally exact fem references to their round-off (a few eps of the largest value)."""
    h = length / 20
    loads = [{"type": "point_force", "position": length, "value": -1e-3}, {"type": "distributed", "value": -1.0}]
    sc = make_scene(
        left,
        right,
        loads,
        beam={"length": length},
        section={"width": h, "height": h},
        material={"youngs_modulus": 169e9, "poissons_ratio": 0.28},
    )
    for exact, fem in (("exact-eb", "fem-eb"), ("exact-timoshenko", "fem-timoshenko")):
        e, f = run(sc, exact, points=11), run(sc, fem, points=11)
        top = np.abs(f.w).max()
        assert np.abs(e.w - f.w).max() <= 100 * np.finfo(float).eps * top + f.info["error_bound"] * top


def test_a_mechanism_is_still_refused_by_the_closed_form(make_scene):
    """The scene refuses a free-free beam before any model runs; the closed form refuses it too if asked."""
    sc = make_scene("clamped", "free").model_copy(
        update={"supports": make_scene("clamped", "free").supports.model_copy(update={"left": "free"})}
    )
    with pytest.raises(SolveError, match="mechanism"):
        solve_straight(sc, shear=False)


@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko"])
def test_a_point_on_a_load_carries_the_mean_of_its_sides_at_any_scale(model):
    """A cantilever's force at 0.7 L on the 14th of 41 points: V there is the mean of its sides (150 of 0 and 300) at
    every length scale and in the mirror image; before, the rounding of the scaled positions chose a side (0 at
    L = 2, 300 at L = 2000)."""

    for k in (1.0, 1e3, 1e-3):
        d = scene_dict("clamped", "free", [{"type": "point_force", "position": 0.7 * k, "value": -300.0}])
        d.update(beam={"length": 2.0 * k}, section={"width": 0.05 * k, "height": 0.1 * k})
        assert run(parse_scene(d), model, points=41).fields["V"][14] == pytest.approx(150.0, rel=1e-9)
    m = scene_dict("free", "clamped", [{"type": "point_force", "position": 1.3, "value": -300.0}])
    assert run(parse_scene(m), model, points=41).fields["V"][26] == pytest.approx(-150.0, rel=1e-9)


def test_exact_higher_order_on_a_load_carries_the_mean_of_its_sides_at_any_scale():
    """As exact-eb's (above): V at the force's point is 150 of 0 and 300 at L = 2 and 2000 (it was 0 and 300)."""
    for k in (1.0, 1e3):
        d = scene_dict("clamped", "free", [{"type": "point_force", "position": 0.7 * k, "value": -300.0}])
        d.update(beam={"length": 2.0 * k}, section={"width": 0.05 * k, "height": 0.1 * k})
        assert run(parse_scene(d), "exact-higher-order", points=41).fields["V"][14] == pytest.approx(150.0, rel=1e-9)
