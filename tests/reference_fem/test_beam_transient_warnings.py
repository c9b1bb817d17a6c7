"""fem-timoshenko's transient: the warning of a step force beside a clamp (reference_fem/beam_transient.py)."""

import numpy as np
import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run


def strip(position: float, inner=()) -> dict:
    """A roller-clamped timber strip, L/h = 100, a step force at ``position`` (sweep 11's dynbeam14)."""
    return {
        "name": "timber strip",
        "beam": {"length": 0.546},
        "section": {"width": 0.0048486, "height": 0.00546},
        "material": {"youngs_modulus": 1.1e10, "poissons_ratio": 0.35, "density": 500.0},
        "supports": {"left": "roller", "right": "clamped", "inner": list(inner)},
        "loads": [{"type": "point_force", "position": position, "value": -0.002427}],
        "dynamics": {"end_time": 0.02415, "probes": [0.20202, 0.44226], "output_interval": 0.0002415},
    }


def test_a_step_force_beside_a_clamp_is_warned_with_the_points_that_part_them():
    """Within 10 spacings of a clamp (an end, or a clamp inside the span) a step force's history converges at about
    first order (2.4 %, 1.25 %, 0.44 % of max |w| at 161, 321, 641 points 3 depths from the clamp, unwarned); the
    warning names the points that part them by 10 spacings, beside a roller or at mid-span it says nothing."""
    from reference_fem.beam_transient import step_beside_clamp

    (said,) = step_beside_clamp(parse_scene(strip(0.5296)), 161)
    assert said.startswith("loads[0], a step force 4.8 spacings from the clamp at the right end")
    more = int(said.rsplit("at least ", 1)[1].split()[0])
    assert not step_beside_clamp(parse_scene(strip(0.5296)), more)
    assert step_beside_clamp(parse_scene(strip(0.5296)), more - 1)
    assert not step_beside_clamp(parse_scene(strip(0.00764)), 161)  # beside the roller
    assert not step_beside_clamp(parse_scene(strip(0.273)), 161)
    inside = strip(0.2, inner=[{"position": 0.21, "type": "clamped"}])
    assert "from the clamp at supports.inner[0]" in step_beside_clamp(parse_scene(inside), 161)[0]


@pytest.mark.slow
def test_the_step_force_beside_a_clamp_is_off_as_its_warning_says():
    """The history 3 depths from the clamp at 161 points: 2.4 % of max |w| off exact-modal-timoshenko, warned."""
    sc = parse_scene(strip(0.5296))
    r = run(sc, "fem-timoshenko", points=161)
    h = r.info["history"]
    t, got = np.asarray(h["t"], float), np.column_stack(list(h["series"].values()))
    modal = get_model("exact-modal-timoshenko")
    want = modal.history_at(sc, modal.resolve(sc, {}), list(sc.dynamics.probes), t)
    assert 0.02 < np.abs(got - want).max() / np.abs(want).max() < 0.03
    assert any("a step force 4.8 spacings from the clamp" in w for w in r.info["warnings"])


@pytest.mark.slow
def test_the_samples_fall_on_the_output_interval_whatever_the_grid():
    """Where the elements' Courant step is shorter than dynamics.output_interval, the step is one that divides the
    interval, so every grid samples the same times (at 641 points the step did not: 102 samples, the last two
    4.5e-7 s apart, and the times differed from 161 points'; over these ten intervals, a step that divides the end
    time only put the samples up to 3.9e-7 s off at 161 points and gave 12 samples at 321)."""
    d = strip(0.273)
    d["dynamics"]["end_time"] = 0.002415  # ten intervals
    times = [np.asarray(run(parse_scene(d), "fem-timoshenko", points=n).info["history"]["t"]) for n in (161, 321)]
    expected = np.arange(11) * d["dynamics"]["output_interval"]
    for t in times:
        np.testing.assert_allclose(t, expected, rtol=0, atol=1e-12 * d["dynamics"]["end_time"])
