"""pd-eb's shear and rotation at and between point loads closer than its differences' stencil (sweeps 16, 17)."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.registry import run


def field_error(left: str, right: str, loads: list, field: str = "V", points: int = 201) -> float:
    """max |f - f_exact-eb| / max |f_exact-eb| of pd-eb's ``field`` (V or rotation) on a 1 m steel beam, 20 x 50 mm."""
    d = scene_dict(left, right, loads)
    d.update(beam={"length": 1.0}, section={"width": 0.02, "height": 0.05})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    sc = parse_scene(d)
    r, e = run(sc, "pd-eb", points=points), run(sc, "exact-eb", points=points)
    get = (lambda res: res.rotation) if field == "rotation" else (lambda res: res.fields[field])
    return float(np.abs(get(r) - get(e)).max() / np.abs(get(e)).max())


def shear_error(left: str, right: str, loads: list) -> float:
    """:func:`field_error` of V at 201 points."""
    return field_error(left, right, loads)


@pytest.mark.parametrize("gap", [1, 2, 3])
@pytest.mark.parametrize("first", ["point_force", "point_moment"])
def test_shear_between_two_close_point_loads_follows_statics(first, gap):
    """Two point loads 1 or 2 spacings apart left M's differences no stretch of three points between them: V 35-58 % of
    max |V| off at and between them at 201 points (a clamped-clamped beam), unwarned, where M was within 8e-5. Those
    points now take statics between the points beside the pair (outputs.close_loads_by_statics): V within the M
    error's order of exact-eb (measured at most 1.5e-6)."""
    dx = 1.0 / 200
    value = -700.0 if first == "point_force" else 300.0
    loads = [
        {"type": first, "position": 0.5, "value": value},
        {"type": "point_force", "position": 0.5 + gap * dx, "value": -490.0},
    ]
    err = shear_error("clamped", "clamped", loads)
    assert err < 1e-5, err


def test_shear_between_two_couples_three_spacings_apart_follows_statics():
    """Sweep 17: two couples exactly 3 spacings apart on a cantilever (201 points) left V 3.75e-3 of max |V| off between
    them, unwarned: the statics took loads less than 3 spacings apart only. At most 3 apart now: V within 1e-5."""
    loads = [
        {"type": "point_moment", "position": 0.5, "value": 300.0},
        {"type": "point_moment", "position": 0.515, "value": 210.0},
        {"type": "distributed", "value": -100.0},
    ]
    err = shear_error("clamped", "free", loads)
    assert err < 1e-5, err


@pytest.mark.parametrize("kinds", [("point_moment", "point_moment"), ("point_moment", "point_force")])
def test_rotation_between_two_close_point_loads_is_second_order(kinds):
    """Sweep 17 N2: two couples (or a couple and a force) 1 spacing apart off the grid left the rotation, differences of
    w across the curvature's jumps, 1.9e-2 of max |rotation| off at 201 points and 9.6e-3 at 401, unwarned. Those points
    now integrate M / EI from the rotation beside the pair (numerics.statics.rotation_over): the observed order
    between 201 and 401 points is the differences' 2 elsewhere (measured 2.01 and 2.01)."""
    errs = []
    for points in (201, 401):
        dx = 1.0 / (points - 1)
        value = {"point_moment": 300.0, "point_force": -700.0}
        loads = [
            {"type": kinds[0], "position": 0.5 + 0.37 * dx, "value": value[kinds[0]]},
            {"type": kinds[1], "position": 0.5 + 1.37 * dx, "value": 0.7 * value[kinds[1]]},
            {"type": "distributed", "value": -100.0},
        ]
        errs.append(field_error("clamped", "clamped", loads, "rotation", points))
    rate = np.log2(errs[0] / errs[1])
    assert abs(rate - 2) < 0.1, (errs, rate)


@pytest.mark.parametrize("ends", [("pinned", "pinned"), ("clamped", "clamped"), ("clamped", "free")])
def test_shear_at_a_short_patch_follows_statics(ends):
    """Sweep 18 H3: a distributed load on one spacing ([0.5, 0.51] at 101 points) left V at its ends 0.49 of max |V|
    off (0.25 on two spacings), unwarned: the differences of M cut at its kinks had no stretch of three points
    between them. Its ends now join the clusters taken by statics: V within the M error's order of exact-eb."""
    loads = [{"type": "distributed", "value": -5000.0, "start": 0.5, "end": 0.51}]
    err = field_error(*ends, loads, "V", 101)
    assert err < 1e-5, err
