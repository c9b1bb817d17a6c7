"""Properties every linear static straight-beam model must have, checked on random valid scenes.

Runs over every registered model (models land in the registry as they are written), so a new model is
checked without touching this file: linearity in the load (superposition) and mirror symmetry.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdverify.registry import models, run
from pdverify.scene import is_mechanism, parse_scene

from conftest import scene_dict

SUPPORTS = ("clamped", "pinned", "free", "guided")
PAIRS = [(l, r) for l in SUPPORTS for r in SUPPORTS if not is_mechanism(l, r)]


def static_models():
    return [m for m in models().values() if "static" in m.analyses and m.bending]


def _opts(m):
    """Small grids so the property tests stay fast; the model's defaults otherwise."""
    given_ = {}
    if m.option("points") is not None:
        given_["points"] = 41
    return given_


loads_st = st.lists(
    st.one_of(
        st.builds(lambda a, v: {"type": "point_force", "position": a, "value": v},
                  st.sampled_from([0.0, 0.25, 0.5, 1.0, 1.5, 2.0]), st.floats(-500, 500).filter(lambda v: abs(v) > 1)),
        st.builds(lambda a, v: {"type": "point_moment", "position": a, "value": v},
                  st.sampled_from([0.5, 1.0, 2.0]), st.floats(-200, 200).filter(lambda v: abs(v) > 1)),
        st.builds(lambda ab, v, sh: {"type": "distributed", "value": v, "start": ab[0], "end": ab[1], "shape": sh},
                  st.sampled_from([(0.0, 2.0), (0.5, 1.5), (0.0, 1.0)]), st.floats(-900, 900).filter(lambda v: abs(v) > 1),
                  st.sampled_from(["uniform", "sine"])),
    ),
    min_size=1, max_size=3,
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


@pytest.mark.parametrize("model", [m.name for m in static_models()])
@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(pair=st.sampled_from(PAIRS), la=loads_st, lb=loads_st, c=st.floats(-3, 3).filter(lambda c: abs(c) > 0.1))
def test_superposition_and_mirror(model, pair, la, lb, c):
    from pdverify.registry import get_model

    m = get_model(model)
    left, right = pair
    sa = parse_scene(scene_dict(left, right, la))
    if m.check(sa):
        return
    sb = parse_scene(scene_dict(left, right, lb))
    scaled_b = [dict(l, value=c * l["value"]) for l in lb]
    sab = parse_scene(scene_dict(left, right, la + scaled_b))
    ra, rb, rab = (run(s, m, **_opts(m)) for s in (sa, sb, sab))
    L, EI = sa.length, sa.EI
    # a deflection scale of the loads (loads at a clamped end give w = 0 up to round-off)
    floor = sum(abs(l["value"]) * L ** {"point_force": 3, "point_moment": 2, "distributed": 4}[l["type"]]
                        for l in la + scaled_b) / EI
    assert np.allclose(ra.x, rab.x) or len(ra.x) != len(rab.x)
    if len(ra.x) == len(rab.x) == len(rb.x) and np.allclose(ra.x, rb.x):
        scale = max(np.abs(ra.w).max(), np.abs(c * rb.w).max(), floor)
        assert np.abs(rab.w - (ra.w + c * rb.w)).max() <= 1e-9 * scale
    # mirror: swap the supports and reflect the loads -> reflected deflection
    L = sa.length
    sm = parse_scene(scene_dict(right, left, [_mirror(l, L) for l in la]))
    if m.check(sm):
        return
    rm = run(sm, m, **_opts(m))
    if len(rm.x) == len(ra.x) and np.allclose(L - rm.x[::-1], ra.x, atol=1e-12 * L):
        scale = max(np.abs(ra.w).max(), floor)
        assert np.abs(rm.w[::-1] - ra.w).max() <= 1e-8 * scale
