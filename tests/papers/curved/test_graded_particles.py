"""pd-curved on particles graded by ends (``grading`` > 1, ``graded_by = "ends"``): the mixed form's families and the
warning of those that jump (docs/models/curved.md, graded particles)."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.papers.curved.particles import ENDS_GRADING, default_horizon
from pdverify.registry import run

SINE = [{"type": "distributed", "value": -1000.0, "shape": "sine"}]
STEEL = {"youngs_modulus": 200e9, "poissons_ratio": 0.3}


def _sine_beam():
    return parse_scene(
        scene_dict(
            "pinned", "pinned", SINE, beam={"length": 2.0}, section={"width": 0.05, "height": 0.1}, material=STEEL
        )
    )


def _error(scene, points, **options):
    r = run(scene, "pd-curved", points=points, **options)
    ref = run(scene, "exact-timoshenko", points=points)
    return np.abs(r.w - ref.w).max() / np.abs(ref.w).max(), r.info.get("warnings", [])


def test_particles_graded_by_ends_converge_at_the_order_of_the_degree():
    """Gathered a hundredfold at the pins, P = 4: the default families were 7 particles (P + 3), and the error jumped
    from grid to grid (6.7e-2, 4.6e-3, 1.1e-2 at 161, 321, 641 particles, against 6.4e-8 ... 2.5e-10 on uniform
    ones); the interpolating central stencil (P + 1) converges at order 4 (3.87, 3.96 from 321 to 1281)."""
    assert default_horizon(4, "mixed", graded_ends=True) == 2 and default_horizon(4, "mixed") == 3
    errors = [_error(_sine_beam(), n, grading=100.0, graded_by="ends")[0] for n in (641, 1281)]
    assert abs(np.log2(errors[0] / errors[1]) - 4) < 0.1, errors


@pytest.mark.parametrize(
    "degree, horizon, warned",
    [(4, 0, False), (4, 3, True), (5, 0, True), (2, 0, False), (6, 0, False)],
)
def test_families_larger_than_the_interpolating_stencil_on_particles_graded_by_ends_warn(degree, horizon, warned):
    """More than P + 1 members (an odd degree, a horizon given above P/2) on particles graded past ENDS_GRADING by
    ends: the result says the error jumps; at ENDS_GRADING itself, or graded by curvature, it does not."""
    scene = _sine_beam()
    opts = dict(degree=degree, horizon=horizon, graded_by="ends")
    flag = "lopsided where the particles gather"
    assert any(flag in w for w in _error(scene, 81, grading=100.0, **opts)[1]) is warned
    assert not any(flag in w for w in _error(scene, 81, grading=ENDS_GRADING, **opts)[1])
    assert not any(flag in w for w in _error(scene, 81, grading=100.0, degree=degree, horizon=horizon)[1])


def test_particles_graded_by_ends_gather_at_the_supports_inside_and_the_joints():
    """A pin inside and two segment joints are breaks with one-sided families: particles graded by ends gather there
    too. P = 2, grading 1000: order 2 (1.0e-3, 2.5e-4, 6.3e-5 at 161, 321, 641 particles here; with a partial load
    beside, gathered at the ends and point loads only, the error stalled at 0.13, 7.3e-2, 7.9e-2)."""
    d = scene_dict("clamped", "pinned", [{"type": "point_force", "position": 0.4, "value": -1000.0}])
    d.update(beam={"length": 2.0}, section={"width": 0.05, "height": 0.1}, material=STEEL)
    d["supports"]["inner"] = [{"position": 1.1, "type": "pinned"}]
    d["segments"] = [
        {"start": 0.0, "end": 0.7},
        {"start": 0.7, "end": 1.5, "section": {"width": 0.05, "height": 0.07}},
        {"start": 1.5, "end": 2.0, "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33}},
    ]
    scene = parse_scene(d)
    errors = [_error(scene, n, degree=2, grading=1000.0, graded_by="ends")[0] for n in (321, 641)]
    assert abs(np.log2(errors[0] / errors[1]) - 2) < 0.1, errors


def test_the_primal_form_on_particles_graded_by_ends_warns():
    """The primal form's families are lopsided where the particles gather too: past ENDS_GRADING it warns (a quarter
    circle pinned at both ends, P = 3, grading 20: 0.26, 0.35, 0.047 off at 81, 161, 321 particles with its locking
    warning only)."""
    scene = _sine_beam()
    flag = "grading = 100 by ends in the primal form"
    assert any(flag in w for w in _error(scene, 81, form="primal", grading=100.0, graded_by="ends")[1])
    assert not any(
        "by ends in the primal form" in w
        for w in _error(scene, 81, form="primal", grading=ENDS_GRADING, graded_by="ends")[1]
    )
