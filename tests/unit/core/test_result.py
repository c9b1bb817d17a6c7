"""core.result: merging a solve's info into what a model gathered before it; a quantity a result lacks."""

import pytest
from helpers import ROOT

from pdverify.core.result import merge_info


def test_merge_info_keeps_the_warnings_of_both_and_updates_the_rest():
    """An update would keep only the solve's list: a model's own warning (gathered before the solve) would vanish
    whenever the solve also warns (a round-off bound), as pd-timoshenko's couple-on-two-points warning did."""
    info = {"warnings": ["the model's"], "cond": 1.0}
    solve = {"warnings": ["the solve's", "the model's"], "cond": 2.0}
    got = merge_info(info, solve, analysis="static")
    assert got is info and info["warnings"] == ["the model's", "the solve's"]
    assert info["cond"] == 2.0 and info["analysis"] == "static"
    assert "warnings" not in merge_info({}, {"cond": 3.0})


def test_comment_lines_stay_one_line_whatever_the_scene_name():
    """A scene name with a newline or a NUL is written escaped in the table's and the CSV's # lines."""
    from helpers import scene_dict

    from pdverify.apps.output import result_table
    from pdverify.core.scene_file import parse_scene
    from pdverify.registry import run

    d = scene_dict("clamped", "free", [{"type": "point_force", "position": 2.0, "value": -50.0}], name="a\nb\x00c")
    text = result_table(run(parse_scene(d), "exact-eb", points=3))
    head = [line for line in text.splitlines() if not line.lstrip()[:1].isdigit() and not line.lstrip().startswith("-")]
    assert all(line.startswith("#") for line in head[:-1]) and "a\\nb\\x00c" in head[0], head


def test_a_quantity_the_model_does_not_give_is_an_input_error():
    """``Result.measured`` of a quantity the model does not give: one line naming the quantity and those it gives,
    an InputError (exit 2 on the command line) that a KeyError handler also catches (it was a bare KeyError)."""
    from pdverify.core.errors import InputError
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import run

    r = run(load_scene(ROOT / "studies/examples/cantilever_tip_load.toml"), "pd-eb", points=21)
    for q in ("u", "bogus", "", None):
        with pytest.raises(InputError, match="gives no such output; it gives w, rotation, moment, shear") as exc:
            r.measured(q)
        assert isinstance(exc.value, KeyError) and len(exc.value.lines) == 1
