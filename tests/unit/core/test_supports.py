"""One meaning per support (docs/supports.md): roller in every model, the axial condition of each support
where a model has an axial unknown, and mechanisms found from the geometry before solving."""

import subprocess
import sys

import numpy as np
import pytest
from helpers import MIXED_LOADS, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.geometry import constraint_rows, mechanism_message, rigid_body_modes
from pdverify.core.scene import HELD, SUPPORTS, Scene, is_mechanism
from pdverify.core.scene_file import parse_scene
from pdverify.registry import models, run

TRANSVERSE = (
    "exact-eb",
    "exact-timoshenko",
    "fem-eb",
    "fem-timoshenko",
    "pd-eb",
    "pd-higher-order",
    "pd-timoshenko",
    "pd-bond-pair",
)
AXIAL_MODELS = ("exact-curved", "pd-curved", "fem-plane-stress")
EA_LOAD = 4000.0  # N, an axial point force at mid-span


def ring(left, right, degrees=360.0):
    L = 2 * np.pi * degrees / 360.0
    return scene_dict(
        left,
        right,
        [{"type": "point_force", "position": 0.3 * L, "value": -100.0}],
        beam={"length": L},
        axis={"type": "arc", "radius": 1.0, "opening_angle_deg": degrees},
    )


# -- the vocabulary -------------------------------------------------------------------------------


def test_every_support_has_one_meaning():
    assert set(HELD) == set(SUPPORTS)
    assert HELD["roller"] == (False, True, False) and HELD["pinned"] == (True, True, False)
    assert HELD["guided"] == (False, False, True) and HELD["clamped"] == (True, True, True)


@pytest.mark.parametrize("name", TRANSVERSE)
@pytest.mark.parametrize("other", ["clamped", "pinned", "roller", "guided"])
def test_roller_is_pinned_without_an_axial_unknown(name, other):
    """A straight model with w (and rotation) only: a roller holds w and frees the rotation, as pinned does;
    the axial slide it adds has no unknown to act on, so the results are identical."""
    roller = run(parse_scene(scene_dict("roller", other, MIXED_LOADS)), name)
    pinned = run(parse_scene(scene_dict("pinned", "pinned" if other == "roller" else other, MIXED_LOADS)), name)
    assert np.array_equal(roller.w, pinned.w)


@pytest.mark.parametrize(
    "opts",
    [
        {"variant": "paper", "reading": "energy"},
        {"variant": "paper", "reading": "literal"},
        {"variant": "paper", "reading": "layer"},
        {"form": "direct"},
    ],
)
def test_roller_is_pinned_in_every_pd_eb_reading(opts):
    """The same for pd-eb's other paths; before, reading = layer put the 2.015 dx layer at pinned ends only
    (a roller-pinned simply supported beam 4.0 % off the pinned-pinned one at 101 points)."""
    roller = run(parse_scene(scene_dict("roller", "roller", MIXED_LOADS)), "pd-eb", **opts)
    pinned = run(parse_scene(scene_dict("pinned", "pinned", MIXED_LOADS)), "pd-eb", **opts)
    assert np.array_equal(roller.w, pinned.w)


def test_torsion_roller_holds_the_twist():
    loads = [{"type": "point_torque", "position": 0.7, "value": 30.0}]
    a = run(parse_scene(scene_dict("roller", "guided", loads)), "pd-torsion")
    b = run(parse_scene(scene_dict("pinned", "guided", loads)), "pd-torsion")
    assert np.array_equal(a.fields["twist"], b.fields["twist"]) and a.fields["twist"][0] == 0.0


def test_rod_roller_slides_axially():
    """pd-rod: a roller end is free axially, so clamped-roller is the clamped-free rod: u(x >= 0.7) =
    F 0.7 / EA (exact for the piecewise linear u, which the corrected variant reproduces to round-off)."""
    loads = [{"type": "point_force", "position": 0.7, "value": 0.0, "axial": EA_LOAD}]
    sc = parse_scene(scene_dict("clamped", "roller", loads))
    r = run(sc, "pd-rod", points=41)
    assert r.fields["u"][-1] == pytest.approx(EA_LOAD * 0.7 / sc.EA, rel=1e-9)
    with pytest.raises(InputError, match="roller-roller"):
        run(parse_scene(scene_dict("roller", "roller", loads)), "pd-rod")


@pytest.mark.parametrize("name", AXIAL_MODELS)
def test_axial_condition_of_pinned_and_roller(name):
    """A straight beam, axial force F at mid-span: pinned-roller carries F in the left half only, so
    u(L) = u(L/2) = F (L/2) / EA; pinned-pinned shares it between the halves: u(L/2) = F L / (4 EA),
    u(L) = 0. fem-plane-stress (q8) holds the face means and puts F on the mid-height node: its u(L) is the
    face mean, exact for a uniform bar to the discretisation (measured 1e-12), and its mid-span value carries
    the 2D point-force term (log-singular at the node: the test reads u(L/2) from the beam models only)."""
    loads = [{"type": "point_force", "position": 1.0, "value": 0.0, "axial": EA_LOAD}]
    opts = {"element": "q8", "layers": 4} if name == "fem-plane-stress" else {}
    sc = parse_scene(scene_dict("pinned", "roller", loads))
    r = run(sc, name, points=41, **opts)
    ref = EA_LOAD * 1.0 / sc.EA
    assert r.fields["u"][-1] == pytest.approx(ref, rel=1e-6)
    assert abs(r.fields["u"][0]) <= 1e-12 * ref
    p = run(parse_scene(scene_dict("pinned", "pinned", loads)), name, points=41, **opts)
    assert abs(p.fields["u"][-1]) <= 1e-12 * ref
    if name != "fem-plane-stress":
        assert p.fields["u"][20] == pytest.approx(ref / 2, rel=1e-6)


def test_guided_slides_axially_in_every_axial_model():
    """guided holds the rotation only: pinned-guided under an axial end force at the guided end stretches
    like a bar, u(L) = F L / EA, in every model with an axial unknown (fem-plane-stress: the guided face
    slides as a whole; a clamped face instead of the pin would add its 2D Poisson restraint, -8.6e-4 here)."""
    loads = [{"type": "point_force", "position": 2.0, "value": 0.0, "axial": EA_LOAD}]
    sc = parse_scene(scene_dict("pinned", "guided", loads))
    for name in AXIAL_MODELS + ("pd-rod",):
        opts = {"element": "q8", "layers": 4} if name == "fem-plane-stress" else {}
        r = run(sc, name, points=41, **opts)
        assert r.fields["u"][-1] == pytest.approx(EA_LOAD * 2.0 / sc.EA, rel=1e-6), name


# -- every model: roller accepted with its meaning, or rejected with one line -----------------------


@pytest.mark.parametrize("name", sorted(models()))
def test_every_model_takes_or_rejects_roller(name):
    """Each registered model either solves a roller scene it can represent (finite numbers) or rejects it
    with an InputError (exit 2): never another exception."""
    model = models()[name]
    for d in (
        scene_dict("roller", "clamped", MIXED_LOADS),
        scene_dict("pinned", "roller", MIXED_LOADS),
        ring("roller", "clamped", 120.0),
    ):
        sc = parse_scene(d)
        if model.check(sc):
            continue
        try:
            r = run(sc, name)
        except InputError:
            continue
        assert np.all(np.isfinite(r.w))


# -- mechanisms ------------------------------------------------------------------------------------


def test_straight_roller_pairs_hold_w():
    assert not is_mechanism("roller", "roller") and not is_mechanism("roller", "guided")
    assert is_mechanism("roller", "free") and not is_mechanism("roller", "clamped")


def test_rank_test_finds_the_rigid_motions():
    """3-column rank test: plane rigid motions (a, b, ω L) against the ends' held directions."""
    ring_pp = Scene.model_validate(ring("pinned", "pinned"))
    modes = rigid_body_modes(ring_pp)
    assert len(modes) == 1 and abs(modes[0][2]) > 0.9  # a rotation (about the common pin)
    assert "rigid rotation about (1, 0)" in mechanism_message(ring_pp)  # the ring starts at (R, 0)
    arc_rr = Scene.model_validate(ring("roller", "roller", 120.0))
    assert "rigid rotation about (0, 0)" in mechanism_message(arc_rr)  # the normals meet at the centre
    straight_rr = Scene.model_validate(scene_dict("roller", "roller"))
    assert "rigid translation along (1, 0)" in mechanism_message(straight_rr)
    for left, right in (("pinned", "pinned"), ("roller", "pinned"), ("clamped", "free"), ("pinned", "guided")):
        assert mechanism_message(Scene.model_validate(ring(left, right, 120.0))) is None, (left, right)
    assert constraint_rows(Scene.model_validate(scene_dict("free", "clamped"))).shape == (3, 3)


def _toml(d: dict) -> str:
    """A scene dict as TOML (tables of scalars and one array of load tables: all a scene needs)."""

    def value(v):
        return f'"{v}"' if isinstance(v, str) else repr(float(v)) if isinstance(v, float) else repr(v)

    lines = [f"name = {value(d['name'])}"]
    for key, table in d.items():
        if isinstance(table, dict):
            lines += [f"[{key}]"] + [f"{k} = {value(v)}" for k, v in table.items()]
    for load in d["loads"]:
        lines += ["[[loads]]"] + [f"{k} = {value(v)}" for k, v in load.items()]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(
    "left,right,needle",
    [
        ("pinned", "pinned", "rigid rotation about (1, 0)"),  # pd-curved gave |u| = 144 m, exact-curved 6e29 m
        ("roller", "pinned", "rigid rotation about (1, 0)"),
        ("guided", "guided", "2 independent rigid-body motions"),
    ],
)
@pytest.mark.slow
def test_ring_mechanisms_exit_2_naming_the_supports(tmp_path, left, right, needle):
    path = tmp_path / "ring.toml"
    path.write_text(_toml(ring(left, right)))
    for model in ("pd-curved", "exact-curved"):
        r = subprocess.run(
            [sys.executable, "-m", "pdverify.apps.cli", "solve", str(path), "--model", model],
            capture_output=True,
            text=True,
        )
        assert r.returncode == 2, r.stderr
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: ") and f"supports = {left}-{right}" in lines[0]
        assert needle in lines[0] and "Traceback" not in r.stderr


@pytest.mark.parametrize("name", AXIAL_MODELS)
def test_two_rollers_on_a_straight_axis_slide_in_axial_models(name):
    """Straight roller-roller holds w (transverse models solve it) but not the axial translation: every model
    with an axial unknown rejects it before solving."""
    sc = parse_scene(scene_dict("roller", "roller", MIXED_LOADS))
    assert run(sc, "exact-eb").w is not None
    with pytest.raises(InputError, match="roller-roller: a mechanism on this straight axis"):
        run(sc, name)


def test_bond_pair_mirror_ends_roller_is_pinned_in_w():
    loads = [{"type": "point_force", "position": 0.7, "value": -300.0}]
    roller = run(parse_scene(scene_dict("roller", "clamped", loads)), "pd-bond-pair", points=61, ends="mirror")
    pinned = run(parse_scene(scene_dict("pinned", "clamped", loads)), "pd-bond-pair", points=61, ends="mirror")
    assert abs(roller.w[0]) <= 1e-12 * np.abs(pinned.w).max()
    assert np.allclose(roller.w, pinned.w, rtol=0, atol=1e-9 * np.abs(pinned.w).max())
