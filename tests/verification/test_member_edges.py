"""A distributed axial load or torque that ends inside a rod or a torsion bar (sweep 34 S34-9, sweep 31 U6): its jump
bends u's (the twist's) slope there, which the horizon's bonds smooth, and pd-rod's u was 6.0e-3 of its largest off
at 41 points (horizon 2) with no warning; a patch [0.2, 0.35] L on a clamped-pinned rod 2.8e-3 at 51 points. The line
(pdverify/papers/moyer/load_edges.py) estimates c Σ |p| h² / S from above (benchmarks/member_edges.py)."""

import re

import numpy as np
import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.registry import run

MEMBERS = {"pd-rod": ("exact-rod", "axial", "u"), "pd-torsion": ("exact-torsion", "torque", "twist")}


def member(component, start, end, left="clamped", right="pinned"):
    load = {"type": "distributed", "value": 0.0, component: 1e3}
    load.update({} if start is None else {"start": start, "end": end})
    return parse_scene(
        {
            "name": "a patch on a member",
            "beam": {"length": 1.0},
            "section": {"width": 0.02, "height": 0.05},
            "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
            "supports": {"left": left, "right": right},
            "loads": [load],
        }
    )


def estimate(r):
    said = [w for w in r.info.get("warnings", []) if "ends inside the member" in w]
    assert len(said) <= 1, said
    return float(re.search(r"here ([\d.e+-]+) of its largest", said[0]).group(1)) if said else None


@pytest.mark.parametrize("model", sorted(MEMBERS))
def test_a_load_ending_inside_a_member_is_estimated_from_above(model):
    ref, component, field = MEMBERS[model]
    sc = member(component, 0.2, 0.35)
    r, e = run(sc, model, points=51, horizon=2), run(sc, ref, points=51)
    got, want = np.asarray(r.fields[field]), np.asarray(e.fields[field])
    error = float(np.abs(got - want).max() / np.abs(want).max())
    assert error > 1e-3  # the case the line must tell
    assert error <= estimate(r) <= 100 * error
    mirror = member(component, 0.65, 0.8, "pinned", "clamped")
    assert estimate(run(mirror, model, points=51, horizon=2)) == estimate(r)
    fine = run(sc, model, points=401, horizon=2)  # second order: (400 / 50)² = 64 times smaller
    assert estimate(fine) is None or estimate(fine) <= estimate(r) / 40


@pytest.mark.parametrize("model", sorted(MEMBERS))
def test_no_member_edge_line_for_a_load_over_the_whole_member(model):
    assert estimate(run(member(MEMBERS[model][1], None, None), model, points=51, horizon=2)) is None
