"""core.text: numbers in messages."""

from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.core.text import PRACTICAL_POINTS, more_points
from pdverify.numerics.features import unresolved_features_warnings


def test_advice_of_more_points_stops_at_a_practical_grid():
    """A point load 1e-15 m beside a support asked for "at least 7205759403792795 points" (sweep 13): past
    PRACTICAL_POINTS the advice says no practical grid does it, and what to do instead."""
    assert more_points(1000.2) == "use at least 1001 points"
    assert more_points(PRACTICAL_POINTS) == f"use at least {PRACTICAL_POINTS} points"
    assert more_points(7.2e15).startswith("no practical grid does it (about 7.2e+15 points): move the two apart")
    d = scene_dict("clamped", "pinned", [{"type": "point_force", "position": 1.0 + 1e-8, "value": -1.0}])
    d["supports"]["inner"] = [{"position": 1.0, "type": "pinned"}]
    (line,) = unresolved_features_warnings(parse_scene(d), 0.01)
    assert "no practical grid does it" in line and "use at least" not in line


def test_an_estimate_printed_is_rounded_up():
    """Sweep 18: an estimate 0.01748 printed "0.017" read below its error 0.01710: upper estimates round up."""
    from pdverify.core.text import rounded_up

    assert [rounded_up(v) for v in (0.01748, 0.017, 1e-3, 0.00099999, 0.1)] == [
        "0.018",
        "0.017",
        "0.001",
        "0.001",
        "0.1",
    ]


def test_a_count_of_one_is_singular_and_a_limit_is_rounded_down():
    """Sweep 33 N3: "the layer is 2 horizons and 1 spacings wide"; a limit "below X" rounded to 3 digits is not above
    itself, and a value a rounding lower (a mirror image's) reads the same."""
    from pdverify.core.text import counted, rounded_down, spacings

    assert [spacings(1.0), spacings(1), spacings(2.5), spacings(0.999999, ".3g")] == [
        "1 spacing",
        "1 spacing",
        "2.5 spacings",
        "1 spacing",
    ]
    assert counted(2, "horizon") == "2 horizons" and counted(1.0, "horizon") == "1 horizon"
    assert [rounded_down(v) for v in (0.0066289, 0.00663, 0.006629999999999999, 1e-3)] == [
        "0.00662",
        "0.00663",
        "0.00663",
        "0.001",
    ]
