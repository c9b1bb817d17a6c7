"""pd-rod and pd-torsion at a fixed horizon (docs/nonlocal.md, "A limit at fixed δ?"): no limit where a single point
inside carries a force, since the rod kernel's symbol grows only like ln(k delta); a limit under smooth loads."""

import numpy as np
import pytest

from pdverify.core.scene_file import load_scene
from pdverify.registry import get_model, run

DELTA = 0.05


def test_point_force_has_no_limit():
    """The continuum at the axial point force is the grid at continuum_m, flagged; the field at the load moves more
    with each doubling of m than with the one before (it grows like m / ln m)."""
    s = load_scene("studies/paper_moyer/rod_point_force.toml")
    r = run(s, "pd-rod", points=161, horizon_length=DELTA, continuum=True, continuum_m=16)
    assert "point force" in r.info["no_limit"] and r.info["continuum_levels"] == [8.0, 16.0]
    at_load = []
    for m in (4, 8, 16):
        u = np.asarray(run(s, "pd-rod", points=int(round(m / DELTA)) + 1, horizon_length=DELTA).fields["u"])
        at_load.append(float(u[len(u) // 2]))
    steps = np.abs(np.diff(at_load))
    assert steps[1] > steps[0] > 0


@pytest.mark.parametrize("model, member", [("pd-rod", "rod_cc_sine"), ("pd-torsion", "shaft_cf_uniform")])
def test_smooth_loads_keep_their_limit(model, member):
    s = load_scene(f"studies/nonlocal/{member}.toml")
    mdl = get_model(model)
    assert mdl.continuum_limit(s, mdl.resolve(s, {"points": 41, "horizon_length": DELTA})) is None
