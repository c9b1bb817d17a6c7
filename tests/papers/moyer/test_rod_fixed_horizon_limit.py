"""pd-rod and pd-torsion at a fixed horizon (docs/nonlocal.md, "A limit at fixed δ?"): no limit where a single point
inside carries a force, since the rod kernel's symbol grows only like ln(k delta); a limit under smooth loads."""

import numpy as np
import pytest

from pdverify.core.scene_file import load_scene, parse_scene
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


def test_timoshenko_point_force_has_no_limit():
    """pd-timoshenko corrected under a point force at mid-span (a deep section, shear in the deflection): the
    deflection at the load moves by nearly the same amount at each doubling of m (measured 2.87e-8, 2.72e-8,
    2.63e-8 m for m = 8 -> 64 at delta = 0.2 L: growth like ln m), and its continuum says there is no limit."""
    d = load_scene("studies/nonlocal/pp_sine.toml").model_dump(exclude_none=True)
    d["loads"] = [{"type": "point_force", "position": 0.5, "value": -1000.0}]
    d["section"].update(height=0.2, width=0.1)
    s = parse_scene(d)
    mids = []
    for m in (8, 16, 32):
        w = np.asarray(
            run(s, "pd-timoshenko", points=int(round(m / 0.2)) + 1, horizon_length=0.2, variant="corrected").w
        )
        mids.append(float(w[len(w) // 2]))
    steps = np.diff(mids)
    assert steps[1] / steps[0] > 0.9  # a converging model would halve (first order) or quarter its steps
    r = run(s, "pd-timoshenko", points=41, horizon_length=0.2, variant="corrected", continuum=True, continuum_m=16)
    assert "point force inside the beam" in r.info["no_limit"]


def test_timoshenko_support_inside_has_no_limit():
    """A support inside is a point force on the beam (its reaction): pd-timoshenko corrected on a pinned-pinned beam
    held at 0.4 L under a uniform load, delta = 0.05 L, moves away from the beam as m grows (sweep 28 R1: 1.69e-2 at
    m = 4, 3.58e-2 at m = 128 off exact-timoshenko, growth like ln m); its continuum and its discrete solves at that
    horizon say there is no limit."""
    d = load_scene("studies/nonlocal/pp_uniform.toml").model_dump(exclude_none=True)
    d["supports"]["inner"] = [{"type": "pinned", "position": 0.4}]
    d["section"].update(height=0.05, width=0.05)
    s = parse_scene(d)
    exact = get_model("exact-timoshenko").evaluator(s, {})
    errors = []
    for m in (4, 16, 64):
        r = run(s, "pd-timoshenko", points=int(round(m / DELTA)) + 1, horizon_length=DELTA, variant="corrected")
        e = exact(r.x)["w"]
        errors.append(float(np.abs(r.w - e).max() / np.abs(e).max()))
    assert errors[0] < errors[1] < errors[2]  # refining at a fixed horizon moves away
    assert any("support inside the beam" in w and "no limit" in w for w in r.info["warnings"])
    c = run(s, "pd-timoshenko", points=41, horizon_length=DELTA, variant="corrected", continuum=True, continuum_m=16)
    assert "support inside the beam" in c.info["no_limit"]
