"""Loops the input sizes are refused before they start: a transient run's steps (end_time / time_step), a
modal history's samples (end_time / output_interval) and a nonlinear path's load steps, past their stated limits
(pdverify/numerics/timeint.py, steps.py), are one line naming the field and the fix, exit 2; each case asks for
~1e27 steps or more."""

import pytest
from helpers import ROOT, cli

from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene
from pdverify.numerics.steps import MAX_STEPS, step_count
from pdverify.papers.diyaroglu.transient import simulate_eb

BEAM = (ROOT / "studies/examples/cantilever_tip_load.toml").read_text()
ROD = (ROOT / "studies/paper_moyer/rod_transient.toml").read_text().split("[dynamics]")[0]


def scene(tmp_path, base: str, **dynamics) -> str:
    """The scene file ``base`` with a [dynamics] table of end_time 2 ms and ``dynamics``."""
    table = {"end_time": 2e-3, **dynamics}
    path = tmp_path / "scene.toml"
    path.write_text(base + "\n[dynamics]\n" + "".join(f"{k} = {v!r}\n" for k, v in table.items()))
    return str(path)


@pytest.mark.parametrize(
    "model, base, dynamics, text",
    [
        ("pd-rod", ROD, {"time_step": 1e-30}, "give a larger dynamics.time_step"),
        ("pd-rod", ROD, {"end_time": 1e30}, "give a shorter dynamics.end_time or use fewer points"),
        ("pd-timoshenko", BEAM, {"time_step": 1e-30}, "give a larger dynamics.time_step"),
        ("pd-timoshenko", BEAM, {"end_time": 1e30}, "give a shorter dynamics.end_time"),
        ("fem-timoshenko", BEAM, {"time_step": 1e-30}, "give a larger dynamics.time_step"),
        ("fem-timoshenko", BEAM, {"end_time": 1e30}, "give a shorter dynamics.end_time"),
        ("exact-modal-timoshenko", BEAM, {"output_interval": 1e-30}, "lengthen output_interval"),
        ("exact-modal-rod", ROD, {"output_interval": 1e-30}, "lengthen output_interval"),
        ("pd-timoshenko", BEAM, {"output_interval": 1e-12}, "lengthen output_interval"),
        ("pd-rod", ROD, {"output_interval": 1e-12}, "lengthen output_interval"),
        ("pd-eb", BEAM, {"output_interval": 1e-12}, "lengthen output_interval"),
    ],
)
def test_a_run_of_too_many_steps_is_refused_before_it_starts(model, base, dynamics, text, tmp_path, capsys):
    code, out, err = cli(["solve", scene(tmp_path, base, **dynamics), "-m", model], capsys)
    assert code == 2 and out == "" and "Traceback" not in err, (code, err)
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: dynamics.") and text in lines[0], err


def test_pd_eb_central_differences_are_bounded():
    """pd-eb's explicit integrator (pdverify.papers.diyaroglu.transient.simulate_eb, the Python API's)."""
    sc = load_scene(ROOT / "studies/examples/cantilever_tip_load.toml")
    with pytest.raises(InputError, match="give a larger dynamics.time_step"):
        simulate_eb(sc, {"points": 21}, t_end=1.0, dt=1e-30)


def test_nonlinear_load_steps_are_bounded(capsys):
    argv = ["solve", ROOT / "studies/examples/cantilever_tip_load.toml", "-m", "pd-bond-pair"]
    code, _, err = cli([*argv, "-o", "nonlinear=true", "-o", "steps=1000000000"], capsys)
    assert code == 2 and "steps <= 100000" in err, err


def test_the_count_at_the_limit():
    """A whole number of steps within rounding is that number; one over the limit is refused; nan is refused."""
    assert step_count(2e-3, 2e-3 / 7, "default") == 7
    assert step_count(1.0, 1.0 / MAX_STEPS, "time_step") == MAX_STEPS
    for end in (1.0 + 1e-6, float("nan")):
        with pytest.raises(InputError, match="more than the limit"):
            step_count(end, 1.0 / MAX_STEPS, "time_step")


@pytest.mark.parametrize(
    "model, base",
    [(m, BEAM) for m in ("pd-eb", "pd-bond-pair", "pd-timoshenko", "pd-higher-order")] + [("pd-rod", ROD)],
)
def test_a_time_step_above_the_stable_limit_is_warned(model, base, tmp_path):
    """An explicit run whose given time_step is above its stable limit is unstable; one that ends before its growth
    shows has not blown up, but its history is wrong: it carries a warning naming the limit (none at the limit)."""
    from pdverify.registry import run

    first = run(load_scene(scene(tmp_path, base, end_time=1e-3)), model, points=21)
    limit = float(first.info["dt_limit"])
    assert not any("stable limit" in w for w in first.info.get("warnings", []))
    at = run(load_scene(scene(tmp_path, base, end_time=3 * limit, time_step=limit)), model, points=21)
    assert not any("stable limit" in w for w in at.info.get("warnings", []))
    over = run(load_scene(scene(tmp_path, base, end_time=6 * limit, time_step=3 * limit)), model, points=21)
    flags = [w for w in over.info.get("warnings", []) if "stable limit" in w]
    assert len(flags) == 1 and f"{limit:.4g}" in flags[0] and "3 x" in flags[0], over.info.get("warnings")
