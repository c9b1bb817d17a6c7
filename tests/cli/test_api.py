"""The public Python API (pdverify.load_scene, run, run_study): what the README's notebook example uses."""

import doctest
import os

import numpy as np
from helpers import ROOT

import pdverify


def test_module_doctest_runs_from_the_repository_root(monkeypatch):
    monkeypatch.chdir(ROOT)
    failed, attempted = doctest.testmod(pdverify)
    assert attempted >= 3 and failed == 0


def test_run_takes_a_path_or_a_scene_and_matches_the_closed_form():
    path = ROOT / "studies/examples/cantilever_tip_load.toml"
    scene = pdverify.load_scene(path)
    a = pdverify.run(scene, "exact-eb", points=11)
    b = pdverify.run(path, "pd-eb", points=11)
    # tip deflection P L^3 / (3 EI) of the scene's 10 x 10 mm steel cantilever under 50 N
    tip = -50 * 1.0**3 / (3 * 200e9 * 0.01**4 / 12)
    assert abs(a.w[-1] / tip - 1) < 1e-12
    assert np.abs(b.w - a.w).max() < 1e-8 * abs(tip)  # the corrected pd-eb reproduces cubics (round-off)


def test_run_study_returns_the_results_table(tmp_path):
    study = tmp_path / "s.toml"
    scene = ROOT / "studies/examples/cantilever_tip_load.toml"
    study.write_text(
        f'name = "api"\nscenes = ["{scene.as_posix()}"]\nreference = "exact-eb"\n'
        '[[runs]]\nmodel = "pd-eb"\npoints = [11, 21, 41]\n'
    )
    df = pdverify.run_study(study, out=tmp_path / "out", workers=1)
    assert list(df["status"]) == ["ok"] * 3
    assert (tmp_path / "out" / "results.csv").exists()
    assert os.path.isdir(tmp_path / "out" / "cases")
