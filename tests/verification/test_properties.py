"""Properties every linear static straight-beam model must have, checked on random valid scenes.

Runs over every registered model (models land in the registry as they are written), so a new model is
checked without touching this file: linearity in the load (superposition) and mirror symmetry.
"""

import numpy as np
import pytest
from helpers import scene_dict
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from pdverify.core.scene import is_mechanism
from pdverify.core.scene_file import parse_scene
from pdverify.registry import models, run

SUPPORTS = ("clamped", "pinned", "roller", "free", "guided")
PAIRS = [(l, r) for l in SUPPORTS for r in SUPPORTS if not is_mechanism(l, r)]
# models left out, each with its reason (every other static bending model is checked: a new one is too)
NOT_LINEAR_IN_THE_LOAD = {"exact-elastica": "large rotations: the elastica is not linear in the load"}
NO_SCENE_LOADS = {"pd-curved-mms", "exact-curved-manufactured"}  # their loads are the manufactured solution's


def _probe(left, right):
    return parse_scene(scene_dict(left, right, [{"type": "point_force", "position": 2.0, "value": -100.0}]))


def static_models():
    return [
        m
        for m in models().values()
        if "static" in m.analyses
        and m.bending
        and m.name not in NOT_LINEAR_IN_THE_LOAD
        and m.name not in NO_SCENE_LOADS
    ]


def pairs_of(m):
    """The support pairs the model accepts (exact-curved-cantilever: cantilevers only)."""
    return [p for p in PAIRS if not m.check(_probe(*p))]


def test_every_checked_model_takes_some_support_pair():
    for m in static_models():
        assert pairs_of(m), m.name


def _opts(m):
    """Small grids so the property tests stay fast; the model's defaults otherwise."""
    given_ = {}
    if m.option("points") is not None:
        given_["points"] = 41
    return given_


loads_st = st.lists(
    st.one_of(
        st.builds(
            lambda a, v: {"type": "point_force", "position": a, "value": v},
            st.sampled_from([0.0, 0.25, 0.5, 1.0, 1.5, 2.0]),
            st.floats(-500, 500).filter(lambda v: abs(v) > 1),
        ),
        st.builds(
            lambda a, v: {"type": "point_moment", "position": a, "value": v},
            st.sampled_from([0.5, 1.0, 2.0]),
            st.floats(-200, 200).filter(lambda v: abs(v) > 1),
        ),
        st.builds(
            lambda ab, v, sh: {"type": "distributed", "value": v, "start": ab[0], "end": ab[1], "shape": sh},
            st.sampled_from([(0.0, 2.0), (0.5, 1.5), (0.0, 1.0)]),
            st.floats(-900, 900).filter(lambda v: abs(v) > 1),
            st.sampled_from(["uniform", "sine"]),
        ),
    ),
    min_size=1,
    max_size=3,
)


def _mirror(load, L):
    d = dict(load)
    if d["type"] == "distributed":
        a, b = d["start"], d["end"]
        d["start"], d["end"] = L - b, L - a
        if d.get("shape") == "sine":  # sin(pi x / L) is symmetric about the centre
            pass
    else:
        d["position"] = L - d["position"]
        if d["type"] == "point_moment":
            d["value"] = -d["value"]
    return d


def _common(ra, rb, rab):
    """Indices into each result of the positions the three share (FEM references add nodes at load positions,
    so their grids differ with the loads; superposition holds at the nodes they share)."""
    L = max(ra.x.max(), 1.0)
    key = lambda x: np.round(np.asarray(x) / L, 9)  # noqa: E731
    shared = np.intersect1d(np.intersect1d(key(ra.x), key(rb.x)), key(rab.x))
    return [np.flatnonzero(np.isin(key(r.x), shared)) for r in (ra, rb, rab)]


@pytest.mark.parametrize("model", [m.name for m in static_models()])
@settings(
    max_examples=6,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much],
)
@given(data=st.data(), la=loads_st, lb=loads_st, c=st.floats(-3, 3).filter(lambda c: abs(c) > 0.1))
@pytest.mark.slow
def test_superposition_and_mirror(model, data, la, lb, c):
    from pdverify.registry import get_model

    m = get_model(model)
    left, right = data.draw(st.sampled_from(pairs_of(m)), label="supports")
    sa = parse_scene(scene_dict(left, right, la))
    sb = parse_scene(scene_dict(left, right, lb))
    scaled_b = [dict(l, value=c * l["value"]) for l in lb]
    sab = parse_scene(scene_dict(left, right, la + scaled_b))
    assume(not (m.check(sa) or m.check(sb) or m.check(sab)))  # loads it declines (a cantilever reference's ends)
    # pd-higher-order's default cuts the bonds at interior point loads, so its operator depends on where the
    # loads are (like an FE mesh with nodes at the loads): three load sets, three operators, superposition only
    # to the discretisation error (measured 3.7e-8 of the deflection, clamped-clamped, 41 points). Linearity
    # is a property of one operator: checked with the cuts off; the mirror below runs the defaults.
    same_operator = {"cuts": "none"} if m.option("cuts") is not None else {}
    ra, rb, rab = (run(s, m, **_opts(m), **same_operator) for s in (sa, sb, sab))
    L, EI = sa.length, sa.EI
    # a deflection scale of the loads (loads at a clamped end give w = 0 up to round-off)
    floor = (
        sum(
            abs(l["value"]) * L ** {"point_force": 3, "point_moment": 2, "distributed": 4}[l["type"]]
            for l in la + scaled_b
        )
        / EI
    )
    ia, ib, iab = _common(ra, rb, rab)
    assert len(iab) >= min(len(ra.x), 11), (len(ra.x), len(rb.x), len(rab.x))  # the shared nodes: a real check
    scale = max(np.abs(ra.w).max(), np.abs(c * rb.w).max(), floor)
    assert np.abs(rab.w[iab] - (ra.w[ia] + c * rb.w[ib])).max() <= 1e-9 * scale
    # mirror: swap the supports and reflect the loads -> reflected deflection
    sm = parse_scene(scene_dict(right, left, [_mirror(l, L) for l in la]))
    assert not m.check(sm), m.check(sm)  # a model that takes a scene takes its mirror image
    rm = run(sm, m, **_opts(m))
    if same_operator:  # the mirror runs the defaults (ra above ran with the cuts off)
        ra = run(sa, m, **_opts(m))
    assert len(rm.x) == len(ra.x) and np.allclose(L - rm.x[::-1], ra.x, atol=1e-12 * L)
    scale = max(np.abs(ra.w).max(), floor)
    assert np.abs(rm.w[::-1] - ra.w).max() <= 1e-8 * scale
