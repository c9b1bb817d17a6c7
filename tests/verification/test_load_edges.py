"""A distributed load's edge within two horizons of an end (sweep 31 U5, sweep 30 T5): pd-eb's (corrected) shear beside
it is off by about c |q| h, where the end's ghosts carry one smooth w across the load's jump (in the interior the
corrected variant spreads a load by its jumps and the edge costs nothing). A patch 6.3 spacings from a clamped end left
V 2.65e-3 of max |V| off at 401 points, horizon 5, with no warning. The line (pdverify/numerics/load_warnings.py:
edge_shear_warnings) estimates it from above; benchmarks/load_edges.py sweeps the constants."""

import numpy as np
import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.registry import run


def beam(left, right, load, length=1.0):
    return parse_scene(
        {
            "name": "a load's edge near an end",
            "beam": {"length": length},
            "section": {"width": 0.02 * length, "height": 0.05 * length},
            "material": {"youngs_modulus": 2e11, "poissons_ratio": 0.3},
            "supports": {"left": left, "right": right},
            "loads": [load],
        }
    )


def edge_line(lines):
    said = [w for w in lines if "that its ghosts reach: the shear" in w]
    assert len(said) <= 1, said
    return float(said[0].split("here ")[1].split(" ")[0]) if said else None


def shear_error(sc, r):
    """The shear's largest error relative to the model's max |V| (the line's measure)."""
    ex = run(sc, "exact-eb", points=len(r.x))
    V = np.asarray(r.fields["V"])
    return float(np.abs(V - ex.fields["V"]).max() / np.abs(V).max())


def patch(start, end, value=-1e3):
    return {"type": "distributed", "value": value, "start": start, "end": end}


# (ends, the patch in spacings of the 401-point grid, horizon): short patches (their jump large beside max |V|) with an
# edge 6.3 or 2.2 spacings from a clamped or pinned end, 9.3 from a guided end past the 6 spacings its fitted line names
CASES = [
    (("clamped", "pinned"), (6.3, 15.3), 5),
    (("clamped", "pinned"), (2.2, 12), 3),
    (("pinned", "pinned"), (6.3, 16), 4),
    (("guided", "clamped"), (9.3, 40), 5),
]


@pytest.mark.parametrize("ends,spacings,horizon", CASES)
def test_an_edge_in_the_layer_is_estimated_from_above(ends, spacings, horizon):
    dx = 1 / 400
    sc = beam(*ends, patch(spacings[0] * dx, spacings[1] * dx))
    r = run(sc, "pd-eb", points=401, horizon=horizon)
    est, err = edge_line(r.info.get("warnings", [])), shear_error(sc, r)
    assert err > 1e-3  # a line is needed
    assert est is not None and est >= err, (est, err)


def test_the_mirror_image_and_a_scaled_copy_read_the_same():
    dx = 1 / 400
    r = run(beam("clamped", "pinned", patch(6.3 * dx, 15.3 * dx)), "pd-eb", points=401, horizon=5)
    m = run(beam("pinned", "clamped", patch(1 - 15.3 * dx, 1 - 6.3 * dx)), "pd-eb", points=401, horizon=5)
    s = run(beam("clamped", "pinned", patch(6.3 * dx * 1e3, 15.3 * dx * 1e3, -1e3 / 1e3), 1e3), "pd-eb", points=401,
            horizon=5)  # fmt: skip
    line = [w for w in r.info["warnings"] if "ghosts reach" in w][0]
    assert "left end (clamped)" in line
    assert [w for w in m.info["warnings"] if "ghosts reach" in w][0].count("right end (clamped)") == 1
    assert edge_line(m.info["warnings"]) == edge_line(r.info["warnings"]) == edge_line(s.info["warnings"])


def test_an_edge_past_two_horizons_costs_nothing_and_is_not_named():
    """Past 2 m spacings the shear's error is the clamp's own, as with the patch far from it."""
    dx = 1 / 400
    errors = []
    for at in (11, 60):  # 2 m + 1 spacings, and far
        sc = beam("clamped", "pinned", patch(at * dx, (at + 9) * dx))
        r = run(sc, "pd-eb", points=401, horizon=5)
        assert edge_line(r.info.get("warnings", [])) is None
        errors.append(shear_error(sc, r))
    assert errors[0] < 1.2 * errors[1] < 1e-4


def test_at_a_fixed_horizon_length_the_line_names_a_shorter_horizon():
    dx = 1 / 400
    sc = beam("clamped", "pinned", patch(8.4 * dx, 17 * dx))
    r = run(sc, "pd-eb", points=401, horizon_length=6 * dx)
    line = [w for w in r.info["warnings"] if "ghosts reach" in w][0]
    assert "give horizon_length below" in line
    assert edge_line(r.info["warnings"]) >= shear_error(sc, r) > 1e-3


def test_the_fitted_ends_own_line_is_not_repeated():
    dx = 1 / 400
    r = run(beam("guided", "clamped", patch(3.3 * dx, 0.5)), "pd-eb", points=401, horizon=3)
    lines = r.info.get("warnings", [])
    assert any(w.startswith("loads[0] has an edge at") for w in lines)
    assert edge_line(lines) is None
