"""pdverify advise: physics decisions, a-posteriori estimate confirmed by the exact error, auto solve."""

import subprocess
import sys
from pathlib import Path

import pytest

from pdverify.advise import advise, estimate
from pdverify.errors import InputError
from pdverify.scene import load_scene, parse_scene

from conftest import scene_dict

ROOT = Path(__file__).parents[1]


def test_thick_beam_excludes_euler_bernoulli_models():
    a = advise(load_scene(ROOT / "studies/paper_yang/cc_uniform.toml"), 1e-3)
    assert a.choice.model == "fem-timoshenko"
    assert any("pd-eb" in r and "shear" in r for r in a.rejected)
    assert a.choice.exact_error < 1e-3


def test_slender_beam_loose_tolerance_admits_euler_bernoulli():
    a = advise(load_scene(ROOT / "studies/paper_diyaroglu/clamped_clamped.toml"), 5e-2)
    assert "Euler–Bernoulli is enough" in a.needs[0]
    models = {a.choice.model, a.runner_up.model}
    assert models & {"pd-eb", "pd-bond-pair", "fem-eb"}


@pytest.mark.parametrize("model,opts", [("pd-eb", {"variant": "corrected"}),
                                        ("pd-bond-pair", {"variant": "corrected", "ends": "taylor"})])
def test_richardson_estimate_brackets_the_true_error(model, opts):
    """The three-grid estimate is within a factor 3 of the true error (second-order models)."""
    sc = parse_scene(scene_dict("clamped", "pinned", [{"type": "distributed", "value": -800.0},
                                                      {"type": "point_force", "position": 1.0, "value": -300.0}]))
    c = estimate(sc, model, opts, tol=1e-4, budget=30)
    assert c is not None and 1.7 < c.order < 2.3
    assert c.estimate < 1e-4 and c.exact_error / 3 < c.estimate < 3 * c.exact_error


def test_bad_tolerance():
    with pytest.raises(InputError, match="tolerance = 2"):
        advise(parse_scene(scene_dict("clamped", "free")), 2.0)


def test_solve_model_auto():
    r = subprocess.run([sys.executable, "-m", "pdverify.cli", "solve", "studies/paper_yang/cantilever_tip_force.toml",
                        "--model", "auto", "--tolerance", "1e-3", "--format", "json"], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    assert "auto: fem-timoshenko" in r.stderr and '"model": "fem-timoshenko"' in r.stdout
    r = subprocess.run([sys.executable, "-m", "pdverify.cli", "solve", "studies/paper_yang/cantilever_tip_force.toml",
                        "--model", "auto"], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 2 and "needs --tolerance" in r.stderr
