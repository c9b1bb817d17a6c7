"""The model contract (pdverify/registry.py): System, declared capabilities checked before solving,
variant rules, the static part of a [dynamics] scene."""

import doctest
import subprocess
import sys

import numpy as np
import pytest
from helpers import ROOT, scene_dict

from pdverify import registry
from pdverify.core.contract import Model, System
from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.numerics.band import Band
from pdverify.numerics.linalg import solve_linear
from pdverify.registry import get_model, models, problems, run

EXAMPLE2 = ROOT / "studies/paper_moyer/beam_example2.toml"
ONE_LOAD = [{"type": "point_force", "position": 1.3, "value": -200.0}]


def test_doctest():
    assert doctest.testmod(registry).failed == 0


def test_capabilities_are_declared_data():
    for m in models().values():
        assert m.analyses and m.analyses <= {"static", "dynamic"}, m.name
        assert m.supports <= registry.SUPPORTS | {"roller"}, m.name
        assert m.load_types <= registry.LOAD_TYPES | {"point_torque", "displacement"}, m.name
        assert m.straight or m.curved, m.name
        assert all(isinstance(r, registry.Rule) for r in m.variant_rules), m.name
        assert not hasattr(m, "limit_system") and not hasattr(m, "kind"), m.name  # one contract: assemble()
    assert {n for n, m in models().items() if "dynamic" in m.analyses} == {
        "exact-modal-rod",
        "exact-modal-timoshenko",
        "fem-timoshenko",
        "pd-bond-pair",
        "pd-eb",
        "pd-higher-order",
        "pd-rod",
        "pd-timoshenko",
        "pd-torsion",
    }


@pytest.mark.parametrize("name", [n for n, m in models().items() if m.assembles])
def test_assemble_returns_the_system_solve_factorises(name):
    """Every model declaring ``assembles`` returns a System whose free unknowns are the result's dofs
    (one load: one solve, also for pd-curved); solving it gives the model's own deflection."""
    m = get_model(name)
    sc = (
        load_scene(ROOT / "studies/paper_curved/quintic_manufactured.toml")
        if name == "pd-curved-mms"
        else parse_scene(
            scene_dict(
                "clamped",
                "pinned",
                ONE_LOAD
                if m.bending
                else [{"type": "point_force", "position": 1.3, "value": 0.0, "axial": 200.0}]
                if m.axial
                else [{"type": "point_torque", "position": 1.3, "value": 50.0}],
            )
        )
    )
    params = m.resolve(sc, {"points": 41})
    s = m.assemble(sc, params)
    assert isinstance(s, System) and isinstance(s.info, dict)
    assert s.matrix.shape == (len(s.rhs), len(s.rhs)) and np.all((s.free >= 0) & (s.free < len(s.rhs)))
    r = run(sc, m, points=41)
    assert s.unknowns == r.dofs
    z, _ = solve_linear(s.matrix, s.rhs)
    z = z * s.info.get("cscale_i", 1.0)  # pd-curved solves for its unknowns over its column scales (their units)
    field = r.w if m.bending else (r.fields.get("u") if m.axial else r.fields["twist"])
    scale = np.abs(field).max()
    assert scale > 0
    # the result's values are among the System's unknowns (each model numbers them its own way: ghosts,
    # interleaved fields); all of them but pd-higher-order's pinned end, whose w is restored from its tie
    # after the solve (pin = face: 40 of 41 points found, measured)
    found = np.abs(z[None, :] - field[:, None]).min(axis=1) <= 1e-9 * scale
    assert found.sum() >= len(field) - (name == "pd-higher-order"), (name, found.mean())


def test_system_reduced_eliminated_and_held():
    B = Band.from_sparse(
        __import__("scipy.sparse", fromlist=["diags"]).diags([[-1.0] * 4, [2.0] * 5, [-1.0] * 4], [-1, 0, 1]).tocsr()
    )
    rhs = np.arange(5.0)
    B.fix([0, 4], rhs)
    s = System(B, rhs, np.array([1, 2, 3]))
    K, b = s.reduced()
    assert not s.eliminated and s.unknowns == 3
    assert K.toarray().tolist() == [[2, -1, 0], [-1, 2, -1], [0, -1, 2]] and b.tolist() == [1, 2, 3]


def test_declared_supports_and_load_types_are_checked_before_solving(monkeypatch):
    """The check reads the declarations: a model that declares no guided end or no point moment rejects
    them with one line each, before its solve runs."""
    base = get_model("pd-eb")

    class Narrow(type(base)):
        name = "narrow-test"
        supports = frozenset({"clamped", "pinned", "free"})
        load_types = frozenset({"point_force", "distributed"})

        def solve(self, scene, params):  # pragma: no cover - must not be reached
            raise AssertionError("solved a scene it declared it cannot")

    sc = parse_scene(
        scene_dict("guided", "pinned", ONE_LOAD + [{"type": "point_moment", "position": 1.0, "value": 5.0}])
    )
    with pytest.raises(InputError) as exc:
        run(sc, Narrow())
    assert exc.value.lines == [
        "supports.left = 'guided': model narrow-test does not represent it; it takes clamped, free, pinned",
        "loads[1].type = 'point_moment': model narrow-test takes distributed, point_force",
    ]


def test_static_model_rejects_a_dynamics_scene_unless_the_static_part_is_asked():
    """It returned all zeros for beam_example2 (an end-driven transient) before; a dynamic model that cannot move
    its ends (pd-eb) names the motion, static part or not."""
    sc = load_scene(EXAMPLE2)
    with pytest.raises(InputError, match=r"^dynamics: model fem-eb solves statics only .*-o static=true"):
        run(sc, "fem-eb")
    with pytest.raises(InputError, match=r"^dynamics.right.displacement: model pd-eb cannot prescribe end motions"):
        run(sc, "pd-eb")
    # its static part is the settled end offset, which pd-eb cannot prescribe: named, not dropped
    with pytest.raises(
        InputError,
        match=r"^dynamics.right.displacement: model pd-eb cannot prescribe end motions"
        r".*\(pd-timoshenko\)",
    ):
        run(sc, "pd-eb", static="true")
    # a dynamics table that moves nothing: the static part is the scene without it
    loaded = scene_dict(
        "clamped", "free", ONE_LOAD, material={"youngs_modulus": 70e9, "poissons_ratio": 0.33, "density": 2700.0}
    )
    dyn = parse_scene(dict(loaded, dynamics={"end_time": 0.1}))
    for name in ("fem-eb", "pd-eb", "fem-timoshenko"):  # fem-timoshenko: dynamic, with no analysis option
        a = run(dyn, name, points=41, static=True)
        b = run(parse_scene(loaded), name, points=41)
        assert np.array_equal(a.w, b.w) and np.abs(a.w).max() > 0
    assert problems(dyn, get_model("fem-eb")) and not problems(dyn, get_model("fem-eb"), static=True)


def test_dynamic_model_static_part_is_its_static_analysis():
    sc = load_scene(EXAMPLE2)
    a = run(sc, "pd-timoshenko", points=21, static=True)
    b = run(sc, "pd-timoshenko", points=21, analysis="static")
    assert a.info["analysis"] == "static" and np.array_equal(a.w, b.w)
    # clamped-clamped with the right end offset by 0.1 in: 0.05 in at the centre (the scene's description)
    assert abs(np.interp(50.0, a.x, a.w) - 0.05) < 1e-9
    with pytest.raises(InputError, match="static = true and analysis = 'dynamic'"):
        run(sc, "pd-timoshenko", points=21, static=True, analysis="dynamic")
    with pytest.raises(InputError, match="static = 'maybe': give true or false"):
        run(sc, "pd-timoshenko", static="maybe")


def test_end_motion_of_an_unknown_the_model_lacks_is_named():
    with pytest.raises(InputError, match="^dynamics.right.displacement: model pd-rod has no such unknown"):
        run(load_scene(EXAMPLE2), "pd-rod")


@pytest.mark.parametrize(
    "model,given,match",
    [
        ("pd-eb", {"variant": "paper", "horizon": 2.5}, r"horizon = 2\.5: not defined by variant = paper .*Eq\. 32"),
        ("pd-eb", {"variant": "paper", "form": "mixed"}, r"form = 'mixed': not defined by variant = paper"),
        (
            "pd-bond-pair",
            {"variant": "continuous-alpha"},
            r"ends = 'auto': not defined by variant = continuous-alpha .*use ends = mirror",
        ),
        ("pd-bond-pair", {"variant": "continuous-alpha", "ends": "mirror", "horizon": 2.5}, r"horizon = 2\.5: .*whole"),
        ("pd-higher-order", {"variant": "paper", "ends": "truncated"}, r"ends = 'truncated': .*Appendix B"),
        ("pd-higher-order", {"variant": "paper", "pin": "face"}, r"pin = 'face': .*Eq\. B41"),
        ("pd-higher-order", {"variant": "paper", "shear": "centred"}, r"shear = 'centred': .*Eq\. 14d-f"),
        ("pd-higher-order", {"variant": "paper", "loads": "faces"}, r"loads = 'faces': .*Eq\. 16b"),
        ("pd-higher-order", {"variant": "paper", "horizon": 2.5}, r"horizon = 2\.5: .*Eq\. 14"),
        (
            "pd-timoshenko",
            {"variant": "corrected", "grid": "cells"},
            r"grid = 'cells': not defined by variant = corrected",
        ),
    ],
)
def test_variant_rules_reject_values_the_equations_do_not_define(model, given, match):
    sc = parse_scene(scene_dict("clamped", "pinned", ONE_LOAD))
    with pytest.raises(InputError, match=match):
        run(sc, model, points=41, **given)


@pytest.mark.parametrize(
    "model,given",
    [
        ("pd-eb", {"variant": "paper", "horizon": 2}),
        ("pd-bond-pair", {"variant": "continuous-alpha", "ends": "mirror"}),
        ("pd-bond-pair", {"variant": "paper", "horizon": 2.5}),
        ("pd-higher-order", {"variant": "paper", "ends": "mirror", "pin": "mid"}),
        ("pd-timoshenko", {"variant": "paper", "grid": "cells"}),
        ("pd-eb", {"variant": "corrected", "horizon": 2.5}),
    ],
)
def test_variant_rules_accept_what_the_equations_define(model, given):
    sc = parse_scene(scene_dict("clamped", "pinned", ONE_LOAD))
    assert np.isfinite(run(sc, model, points=41, **given).w).all()


def test_rule_applies_only_to_its_variant():
    rule = get_model("pd-eb").variant_rules[0]
    assert rule.problem("pd-eb", {"variant": "corrected", "horizon": 2.5}) is None
    assert rule.problem("pd-eb", {"variant": "paper", "horizon": 3.0}) is None
    assert "Eq. 32" in rule.problem("pd-eb", {"variant": "paper", "horizon": 2.5})


@pytest.mark.slow
def test_cli_exit_2_one_line():
    for args in (
        ["studies/paper_moyer/beam_example2.toml", "--model", "pd-eb"],
        ["studies/examples/cantilever_tip_load.toml", "--model", "pd-eb", "--variant", "paper", "--horizon", "2.5"],
    ):
        r = subprocess.run(
            [sys.executable, "-m", "pdverify.apps.cli", "solve", *args], capture_output=True, text=True, cwd=ROOT
        )
        assert r.returncode == 2 and r.stderr.startswith("error: ") and r.stderr.count("\n") == 1, r.stderr
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "pdverify.apps.cli",
            "solve",
            "studies/paper_moyer/beam_example2.toml",
            "--model",
            "pd-timoshenko",
            "--points",
            "21",
            "-o",
            "static=true",
            "--format",
            "csv",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr


def test_bench_probes_no_attributes():
    """bench and advise read the declarations (assembles, analyses, bench_scene), never hasattr/getattr."""
    for f in ("bench.py", "advise.py"):
        src = (ROOT / "pdverify" / "apps" / f).read_text()
        assert "hasattr(" not in src and "getattr(m" not in src and "getattr(model" not in src, f


def test_dynamic_only_model_needs_a_dynamics_table(monkeypatch):
    class Transient(type(get_model("pd-timoshenko"))):
        name = "transient-test"
        analyses = frozenset({"dynamic"})

    sc = parse_scene(scene_dict("clamped", "free", ONE_LOAD))
    assert problems(sc, Transient()) == [
        "dynamics: model transient-test solves transient runs only; add a [dynamics] table (end_time, ...)"
    ]


def test_new_model_defaults_are_the_plain_static_beam():
    m = Model()
    assert m.analyses == {"static"} and not m.assembles and m.straight and not m.curved
    with pytest.raises(NotImplementedError):
        m.assemble(None, {})


def test_study_crossing_a_paper_variant_with_foreign_options_fails_when_loaded(tmp_path):
    """resolve applies the variant rules, so a study is refused before any case runs (one line per
    problem, repeated scenes once)."""
    from pdverify.study import load_study

    p = tmp_path / "s.toml"
    p.write_text(
        f'name = "x"\nscenes = ["{ROOT}/studies/paper_diyaroglu/clamped_free.toml", '
        f'"{ROOT}/studies/paper_diyaroglu/clamped_clamped.toml"]\nreference = "exact-eb"\n'
        '[[runs]]\nmodel = "pd-bond-pair"\nvariant = ["continuous-alpha", "corrected"]\nends = ["mirror", "taylor"]\n'
        "points = [51, 101]\n"
    )
    with pytest.raises(InputError) as exc:
        load_study(p)
    assert (
        len([ln for ln in exc.value.lines if "ends = 'taylor': not defined by variant = continuous-alpha" in ln]) == 1
    )


ROD = [{"type": "distributed", "value": 0.0, "axial": 100.0}]
TORQUE = [{"type": "distributed", "value": 0.0, "torque": 10.0}]


@pytest.mark.parametrize(
    "model, loads, options",
    [
        ("pd-eb", None, {}),
        ("pd-bond-pair", None, {}),
        ("pd-timoshenko", None, {}),
        ("pd-timoshenko", None, {"variant": "corrected", "horizon": 5}),
        ("pd-higher-order", None, {}),
        ("pd-curved", None, {}),
        ("pd-rod", ROD, {}),
        ("pd-torsion", TORQUE, {}),
    ],
)
def test_too_few_points_names_the_least_the_model_takes(model, loads, options):
    """points below a model's least: the refusal names the least its grid takes at the options given (pd-torsion said
    "needs points >= 6", then at 6 "with horizon = 3 needs at least 8 points"), and that many run."""
    d = scene_dict("clamped", "pinned", [{"type": "distributed", "value": -100.0}] if loads is None else loads)
    sc = parse_scene(d)
    with pytest.raises(InputError) as got:
        registry.run(sc, model, points=2, **options)
    (line,) = got.value.lines
    least = int(line.rsplit(">= ", 1)[1])
    assert line.startswith(f"points = 2: model {model}")
    r = registry.run(sc, model, points=least, **options)
    assert len(r.x) >= least and np.isfinite(r.w).all()


def test_the_least_points_search_finds_a_wide_family_s_and_names_a_grid_that_never_fits():
    """The least is searched by doubling and bisection (it stopped 4,096 points above the bare least and named that:
    pd-eb at horizon 3000 was told 4,101, which is refused; 6,001 is its least), and where no grid up to 2^20 points
    fits, the grid's own reason is given (pd-curved, degree 8 on families of 7: it named 4,101 points)."""
    sc = parse_scene(scene_dict("clamped", "pinned", [{"type": "distributed", "value": -100.0}]))
    with pytest.raises(InputError) as got:
        registry.run(sc, "pd-eb", points=2, horizon=3000)
    assert got.value.lines == ["points = 2: model pd-eb with horizon = 3000 needs points >= 6001"]
    m = registry.get_model("pd-eb")
    assert not m.grid_problems(sc, m.with_defaults({"points": 6001, "horizon": 3000}))
    assert m.grid_problems(sc, m.with_defaults({"points": 6000, "horizon": 3000}))
    with pytest.raises(InputError) as got:
        registry.run(sc, "pd-curved", points=2, degree=8, horizon=3)
    assert got.value.lines[0].startswith("horizon = 3: a family of 7 particles cannot carry degree 8")


@pytest.mark.parametrize(
    "model, right, options, refusal",
    [
        ("pd-eb", "pinned", {"reading": "layer"}, "reading = 'layer': a reading of the paper's boundary treatment"),
        ("pd-rod", "free", {"variant": "paper"}, "supports.right = free: variant paper sets no traction condition at"),
        (
            "pd-torsion",
            "guided",
            {"variant": "paper"},
            "supports.right = guided: variant paper sets no traction condition",
        ),
    ],
)
def test_too_few_points_comes_after_what_no_number_of_points_changes(model, right, options, refusal):
    """A variant's refusal of the options or supports comes before the least points (sweep 11: 23 combinations were
    sent to a least that was then refused for another reason)."""
    loads = {"pd-rod": ROD, "pd-torsion": TORQUE}.get(model, [{"type": "distributed", "value": -100.0}])
    sc = parse_scene(scene_dict("clamped", right, loads))
    for points in (2, 101):
        with pytest.raises(InputError) as got:
            registry.run(sc, model, points=points, **options)
        assert got.value.lines[0].startswith(refusal), got.value.lines


@pytest.mark.parametrize("gap, warned", [(1e-4, True), (1e-2, True), (0.3, False)])
@pytest.mark.parametrize("model", ["fem-eb", "fem-timoshenko", "exact-eb"])
def test_supports_closer_than_a_depth_say_their_split_is_the_theorys(model, gap, warned):
    """Sweep 13: two pinned supports 1e-4 m apart on a beam 0.1 m deep split a uniform load's 1250 N as 875 / 375 N in
    Euler-Bernoulli theory and 626 / 622 N in Timoshenko's, each model unwarned. Every result now says so, with both
    exact splits, where they differ by more than 5 % of the sum (pdverify.registry.close_supports)."""
    from pdverify.core.scene_file import parse_scene
    from pdverify.exact.straight import solve_straight

    inner = [{"position": 1.0, "type": "pinned"}, {"position": 1.0 + gap, "type": "pinned"}]
    d = {
        "name": "close supports",
        "beam": {"length": 2.0},
        "section": {"width": 0.05, "height": 0.1},
        "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
        "supports": {"left": "pinned", "right": "pinned", "inner": inner},
        "loads": [{"type": "distributed", "value": -1000.0}],
    }
    sc = parse_scene(d)
    flags = [w for w in run(sc, model, points=201).info.get("warnings") or [] if "depths: how the load" in w]
    assert len(flags) == int(warned)
    if warned:
        eb, ti = (solve_straight(sc, s).reactions() for s in (False, True))
        assert f"exact-eb: {eb['force_inner_0']:.4g} and {eb['force_inner_1']:.4g}" in flags[0]
        assert abs(eb["force_inner_0"] - ti["force_inner_0"]) > 0.05 * 1250.0  # what the warning is for


@pytest.mark.parametrize("stiffness, warned", [(1e12, True), (1e6, False)])
def test_a_stiff_spring_beside_a_support_says_its_split_is_the_theorys(stiffness, warned):
    """Sweep 16: a spring of 1e12 N/m 0.4 depths from a clamp split the load -8013 / 9644 N in Euler-Bernoulli theory
    and -905 / 2531 N in Timoshenko's, unwarned (the warning took rigid supports only). A spring inside now counts;
    the two theories' splits decide, so a soft one (1e6 N/m: theirs agree) is not warned."""
    from pdverify.core.scene_file import parse_scene

    d = {
        "name": "stiff spring near a clamp",
        "beam": {"length": 1.0},
        "section": {"width": 0.02, "height": 0.05},
        "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
        "supports": {
            "left": "clamped",
            "right": "pinned",
            "inner": [{"position": 0.02, "type": "spring", "stiffness": stiffness}],
        },
        "loads": [
            {"type": "point_force", "position": 0.01, "value": -1000.0},
            {"type": "distributed", "value": -1000.0},
        ],
    }
    for model in ("exact-eb", "exact-timoshenko"):
        flags = run(parse_scene(d), model, points=201).info.get("warnings") or []
        assert any("depths: how the load" in w for w in flags) == warned, flags


@pytest.mark.parametrize("model", ["pd-eb", "fem-eb", "exact-timoshenko", "pd-rod"])
@pytest.mark.parametrize(
    "loads, warned",
    [
        ([], True),
        ([{"type": "point_force", "position": 0.5, "value": 0.0}], True),
        ([{"type": "distributed", "value": 0.0, "axial": -5.0}], False),
        ([{"type": "point_moment", "position": 0.5, "value": 2.0}], False),
    ],
)
def test_a_scene_without_loads_says_its_zeros_are_no_answer(model, loads, warned):
    """Sweep 40 F6: a scene with no loads solved to zeros everywhere without a line. Every static result of one says
    so; an axial share or a moment is a load."""
    if model == "pd-rod" and loads and loads[0]["type"] == "point_moment":  # a rod's load: an axial force
        loads = [{"type": "point_force", "position": 0.5, "value": 0.0, "axial": 3.0}]
    elif model != "pd-rod" and loads and loads[0].get("axial"):  # a beam's: a distributed load across its axis
        loads = [{"type": "distributed", "value": -5.0, "start": 0.2, "end": 0.4}]
    result = run(parse_scene(scene_dict("clamped", "pinned", loads)), model, points=21)
    assert (registry.UNLOADED in (result.info.get("warnings") or [])) == warned
    if warned:
        assert not np.any(result.w)
