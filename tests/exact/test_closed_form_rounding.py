"""The round-off bound of the closed forms exact-eb and exact-timoshenko (pdverify/exact/straight.py: rounding): a
field is a sum of terms that cancel where a load sits close to an end relative to the length; the bound covers the
error there and warns past 1e-6, and is at round-off on ordinary scenes."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run


def cantilever(length: float, at: float):
    d = scene_dict("clamped", "free", [{"type": "point_force", "position": at, "value": -50.0}])
    d.update(beam={"length": length}, section={"width": 0.01, "height": 0.01})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    return parse_scene(d)


@pytest.mark.parametrize("ratio", [1e-2, 1e-3, 1e-4, 1e-5, 1e-6])
@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko"])
def test_the_bound_covers_a_force_beside_the_clamp(model, ratio):
    """Tip deflection under a force at a = ratio L: P a^2 (3 L - a) / (6 EI) (Euler-Bernoulli; Timoshenko adds
    P a / kGA), terms of P L^3 / EI cancelled to P a^2 L / EI: a relative error of about eps / ratio^2."""
    L = 1.0
    sc = cantilever(L, ratio * L)
    r = run(sc, model, points=11)
    P, a, EI = -50.0, ratio * L, sc.EI
    tip = P * a**2 * (3 * L - a) / (6 * EI) + (
        P * a / (sc.section.k * sc.material.G * sc.section.A) if model == "exact-timoshenko" else 0.0
    )
    error = abs(r.w[-1] - tip) / abs(tip)
    bound = r.info["error_bound"]
    assert error <= bound, (error, bound)
    warned = any("round-off bound" in w for w in r.info.get("warnings", []))
    assert warned == (bound > 1e-6)
    if ratio <= 1e-6:
        assert warned  # an error of ~1e-4 (measured 1.6e-4 at L = 1e6 with a = 1) is not silent


def test_an_ordinary_scene_is_at_round_off():
    r = run(cantilever(2.0, 1.3), "exact-eb", points=41)
    assert r.info["error_bound"] < 1e-13 and not r.info.get("warnings")


@pytest.mark.parametrize("model", ["fem-eb", "fem-timoshenko"])
def test_a_load_merged_into_a_node_is_warned(model):
    """The beam references put a load within 1e-12 L of a node on it (reference_fem/beam_elements.py): a force 1 m
    from the clamp of a 1e12 m cantilever lands on the clamp and the beam does not move; the result says so."""
    merged = run(cantilever(1e12, 1.0), model, points=11)
    assert np.all(merged.w == 0.0)
    assert any("within 1e-12 of the length" in w for w in merged.info.get("warnings", []))
    apart = run(cantilever(1e12, 3e11), model, points=11)
    assert not any("within 1e-12 of the length" in w for w in apart.info.get("warnings", []))


@pytest.mark.parametrize("model", ["exact-eb", "exact-timoshenko"])
@pytest.mark.parametrize(
    "left, right, load",
    [
        ("clamped", "free", {"type": "point_force", "position": 0.0, "value": -50.0}),
        ("clamped", "free", {"type": "point_moment", "position": 0.0, "value": 20.0}),
        ("pinned", "pinned", {"type": "point_force", "position": 2.0, "value": 30.0}),
    ],
)
def test_a_scene_whose_loads_all_go_into_the_supports_has_no_round_off_warning(left, right, load, model):
    """w = 0 exactly: its terms cancel to their rounding, which is all there is, so the bound is that rounding
    relative to the terms (cond eps), not to max |w| (before: "round-off bound 9.6 exceeds 1e-06")."""
    r = run(parse_scene(scene_dict(left, right, [load])), model, points=5)
    assert r.info["error_bound"] <= 1e-12 and not r.info.get("warnings")


@pytest.mark.parametrize("model, fem", [("exact-eb", "fem-eb"), ("exact-timoshenko", "fem-timoshenko")])
def test_a_short_soft_segment_s_cancellation_is_in_the_bound(model, fem):
    """A 1e-6 m segment with E = 1e3 inside a steel beam: the closed form integrates M / EI over it as the difference
    of the antiderivatives from 0 at its ends, which cancel, and the soft segment's stiffness magnifies the rounding
    left: w 1.5e-8 off (fem-eb, nodally exact, agrees with a 40-digit integral to 7e-13) where the bound said 5.7e-12.
    The bound now sums the magnitudes of those differences' terms."""
    d = {"name": "s", "beam": {"length": 2.0}, "section": {"width": 0.05, "height": 0.1},
         "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3},
         "supports": {"left": "clamped", "right": "pinned"},
         "loads": [{"type": "point_force", "position": 0.7, "value": -1000.0}],
         "segments": [{"start": 0.0, "end": 1.0},
                      {"start": 1.0, "end": 1.000001, "material": {"youngs_modulus": 1e3, "poissons_ratio": 0.3}},
                      {"start": 1.000001, "end": 2.0}]}  # fmt: skip
    sc = parse_scene(d)
    exact, ref = run(sc, model, points=41), run(sc, fem, points=41)
    keep = np.isin(np.asarray(ref.x), np.asarray(exact.x))
    error = np.abs(np.asarray(ref.w)[keep] - exact.w).max() / np.abs(exact.w).max()
    assert 1e-9 < error <= exact.info["error_bound"], (error, exact.info["error_bound"])


@pytest.mark.parametrize("ratio", [1e-2, 1e-4, 1e-6, 1e-8])
@pytest.mark.parametrize("segments", [False, True])
def test_the_rod_s_bound_covers_a_force_beside_a_clamp(ratio, segments):
    """exact-rod (it had no bound): a clamped-clamped rod, an axial force F at a = ratio L; beyond it u = F a (L - x)
    / (L EA), at most F a / EA, from terms of F L / EA (R0 x and the force's own integral, which cancel): a relative
    error of about eps / ratio, which the bound covers (on two segments of one section, too: the same rod)."""
    L, F = 2.0, 1000.0
    d = scene_dict("clamped", "clamped", [{"type": "point_force", "position": ratio * L, "value": 0.0, "axial": F}])
    d["beam"] = {"length": L}
    if segments:
        d["segments"] = [{"start": 0.0, "end": 0.5 * L}, {"start": 0.5 * L, "end": L}]
    sc = parse_scene(d)
    r = run(sc, "exact-rod", points=11)
    a = ratio * L
    x = np.linspace(a, L, 1001)
    exact = F * a * (L - x) / (L * sc.EA)
    error = np.abs(get_model("exact-rod").evaluate(sc, {}, x)["u"] - exact).max() / exact[0]
    assert 0.0 < r.info["error_bound"] and error <= r.info["error_bound"], (error, r.info["error_bound"])
    assert (r.info["error_bound"] > 1e-6) == any("round-off bound" in w for w in r.info.get("warnings", []))
