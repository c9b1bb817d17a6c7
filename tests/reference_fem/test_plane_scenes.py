"""fem-plane-stress with supports inside the span, springs and segments (reference_fem/plane_scenes.py): statics to
round-off, mirror images, a spring's rigid limit, a segment of the scene's own material, and the 2D strip against
exact-timoshenko (the beam theory's gap at L/h = 20, not a convergence: the strip converges to its own 2D solution)."""

import sys
from pathlib import Path

import numpy as np
import pytest

from pdverify.core.errors import InputError
from pdverify.core.reactions import load_resultants
from pdverify.registry import get_model, run

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "exact"))
from test_continuous_beams import BIMATERIAL, CASES, LOADS, mirrored, scene  # noqa: E402

TAKEN = [c for c in CASES if c[0] in ("two spans", "three spans", "overhangs", "inner clamp and spring", "bi-material")]


@pytest.mark.parametrize("name,supports,segments", TAKEN, ids=[c[0] for c in TAKEN])
def test_reactions_balance_the_loads_to_round_off(name, supports, segments):
    sc = scene(supports, segments)
    r = run(sc, "fem-plane-stress", points=41, layers=4).info["reactions"]
    at = {"left": 0.0, "right": sc.length} | {f"inner_{i}": s.position for i, s in enumerate(sc.supports.inner)}
    force = sum(v for k, v in r.items() if k.startswith("force"))
    moment = sum(v * at[k[len("force_") :]] for k, v in r.items() if k.startswith("force"))
    moment += sum(v for k, v in r.items() if k.startswith("moment"))
    load, load_moment = load_resultants(sc)
    size = sum(abs(ld["value"]) for ld in LOADS) * sc.length
    assert abs(force + load) <= 1e-9 * size and abs(moment + load_moment) <= 1e-9 * size * sc.length
    assert abs(sum(v for k, v in r.items() if k.startswith("axial"))) <= 1e-9 * size


@pytest.mark.parametrize("name,supports,segments", TAKEN[:3], ids=[c[0] for c in TAKEN[:3]])
def test_the_strip_is_within_the_beam_theory_gap_of_exact_timoshenko(name, supports, segments):
    """L/h = 20: w within 4e-3 and the reactions within 2e-3 of the Timoshenko beam's (measured 2.1e-3 and 4.3e-4 on
    two spans, 3.5e-3 and 1.6e-3 on three; the overhangs' determinate reactions to 2e-11)."""
    sc = scene(supports, segments)
    r = run(sc, "fem-plane-stress", points=41)
    ex = get_model("exact-timoshenko").evaluate(sc, {}, r.x)
    assert np.abs(r.w - ex["w"]).max() <= 4e-3 * np.abs(ex["w"]).max()
    re = run(sc, "exact-timoshenko", points=3).info["reactions"]
    gap = max(abs(r.info["reactions"][k] - v) for k, v in re.items()) / max(abs(v) for v in re.values())
    assert gap <= (1e-9 if name == "overhangs" else 2e-3)


def test_a_mirror_scene_gives_the_mirror_result():
    supports, segments = TAKEN[1][1], TAKEN[1][2]
    a = run(scene(supports, segments), "fem-plane-stress", points=41, layers=4)
    b = run(mirrored(supports, segments), "fem-plane-stress", points=41, layers=4)
    back = np.interp(a.x, (2.0 - b.x)[::-1], b.w[::-1])
    assert np.abs(back - a.w).max() <= 1e-9 * np.abs(a.w).max()


def test_a_stiff_inner_spring_is_the_pinned_support():
    """k -> large: the spring's parabola-weighted mean deflection is the pinned (face) support's condition."""
    pinned = {"left": "pinned", "right": "pinned", "inner": [{"position": 1.0, "type": "roller"}]}
    spring = {"left": "pinned", "right": "pinned", "inner": [{"position": 1.0, "type": "spring", "stiffness": 1e14}]}
    a = run(scene(pinned), "fem-plane-stress", points=41, layers=4)
    b = run(scene(spring), "fem-plane-stress", points=41, layers=4)
    assert np.abs(a.w - b.w).max() <= 1e-5 * np.abs(a.w).max()
    assert b.info["reactions"]["force_inner_0"] == pytest.approx(a.info["reactions"]["force_inner_0"], rel=1e-5)


def test_segments_of_the_scene_s_own_material_give_the_uniform_strip():
    same = [{"start": 0.0, "end": 0.8}, {"start": 0.8, "end": 2.0}]
    supports = TAKEN[0][1]
    a = run(scene(supports), "fem-plane-stress", points=41, layers=4)
    b = run(scene(supports, same), "fem-plane-stress", points=41, layers=4)
    assert np.abs(a.w - b.w).max() <= 1e-10 * np.abs(a.w).max()
    stiffer = run(scene(supports, BIMATERIAL), "fem-plane-stress", points=41, layers=4)
    assert np.abs(stiffer.w).max() < 0.9 * np.abs(a.w).max()  # 200 GPa over [0, 1.1], the scene's 70 GPa beyond


@pytest.mark.parametrize("name", ["stepped", "on springs"])
def test_what_the_strip_cannot_hold_is_refused_in_one_line(name):
    supports, segments = next((s, g) for n, s, g in CASES if n == name)
    with pytest.raises(InputError) as err:
        run(scene(supports, segments), "fem-plane-stress", points=21)
    assert len(err.value.lines) == 1
