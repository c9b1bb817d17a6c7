"""Plug-in models: a package built here (a .dist-info with entry_points.txt on PYTHONPATH) whose model runs
through `pdverify models`, `solve`, a study and `verify`; broken entry points cost one warning line each."""

import json
import os
import shutil
import subprocess
import sys
import textwrap
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest
from helpers import ROOT

SCENE = ROOT / "studies" / "examples" / "cantilever_tip_load.toml"


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """A site folder holding the example plug-in fd_beam, a module of bad entries and their dist-info."""
    site = tmp_path_factory.mktemp("site")
    shutil.copytree(ROOT / "examples" / "plugin_model" / "src" / "fd_beam", site / "fd_beam")
    (site / "bad_plugins.py").write_text(
        textwrap.dedent("""
        from pdverify.registry import Model

        class Clash(Model):
            name = "exact-eb"

        NOT_A_MODEL = 42
    """)
    )
    info = site / "pdverify_fd_beam-0.1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: pdverify-fd-beam\nVersion: 0.1.0\n")
    (info / "entry_points.txt").write_text(
        textwrap.dedent("""
        [pdverify.models]
        fd-eb = fd_beam:FDBeam
        broken = no_such_module:Model
        wrong = bad_plugins:NOT_A_MODEL
        clash = bad_plugins:Clash
    """)
    )
    return site


def cli(site, *args, timeout=300):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(site), str(ROOT)])}
    env.pop("PDVERIFY_MODELS_PATH", None)
    return subprocess.run(
        [sys.executable, "-m", "pdverify.apps.cli", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=timeout,
        cwd=site,
    )


@pytest.mark.slow
def test_models_lists_the_plugin_and_warns_once_per_broken_entry_point(site):
    r = cli(site, "models")
    assert r.returncode == 0, r.stderr
    assert any(line.startswith("fd-eb ") for line in r.stdout.splitlines())
    assert any(line.startswith("exact-eb ") for line in r.stdout.splitlines())  # the built-in one kept
    warnings = r.stderr.splitlines()
    assert len(warnings) == 3 and all(w.startswith("warning: plug-in entry point ") for w in warnings)
    assert "broken = no_such_module:Model (pdverify-fd-beam): ModuleNotFoundError" in warnings[0]
    assert "clash = bad_plugins:Clash (pdverify-fd-beam): model name 'exact-eb' is already taken" in warnings[1]
    assert "wrong = bad_plugins:NOT_A_MODEL (pdverify-fd-beam) is int, not a pdverify.registry.Model" in warnings[2]


@pytest.mark.slow
def test_solve_converges_at_order_2(site):
    errs = []
    for n in (41, 81):
        r = cli(site, "solve", str(SCENE), "--model", "fd-eb", "--points", str(n), "--format", "json")
        assert r.returncode == 0, r.stderr
        res = json.loads(r.stdout)
        w = np.array(res["w"])
        ref = json.loads(
            cli(site, "solve", str(SCENE), "--model", "exact-eb", "--points", str(n), "--format", "json").stdout
        )
        errs.append(np.abs(w - np.array(ref["w"])).max() / np.abs(ref["w"]).max())
    assert abs(np.log2(errs[0] / errs[1]) - 2) < 0.05  # central differences: second order


@pytest.mark.slow
def test_study_and_verify_run_the_plugin(site, tmp_path):
    shutil.copy(SCENE, tmp_path / "scene.toml")
    (tmp_path / "study.toml").write_text(
        textwrap.dedent("""
        name = "plug-in"
        scenes = ["scene.toml"]
        reference = "exact-eb"
        [[runs]]
        model = "fd-eb"
        points = [21, 41, 81]
    """)
    )
    r = cli(site, "study", str(tmp_path / "study.toml"), "--out", str(tmp_path / "study"), "--quiet", "--workers", "2")
    assert r.returncode == 0, r.stderr
    df = pd.read_csv(tmp_path / "study" / "results.csv").sort_values("points")
    assert (df["status"] == "ok").all() and len(df) == 3
    e = df["err_max"].to_numpy()
    assert np.allclose(np.log2(e[:-1] / e[1:]), 2, atol=0.05)
    r = cli(site, "verify", "fd-eb", "--out", str(tmp_path / "card"), "--quiet", "--workers", "2")
    assert r.returncode == 0, r.stdout + r.stderr
    card = json.loads((tmp_path / "card" / "card.json").read_text())
    checks = {c["check"]: c for c in card["checks"]}
    assert card["verdict"] == "pass" and card["failed_cases"] == 0
    assert checks["convergence (straight)"]["lowest_order"] > 1.9
    assert checks["symmetry (mirror scenes)"]["verdict"] == "pass"
    suite = ET.parse(tmp_path / "card" / "junit.xml").getroot()
    assert suite.get("failures") == "0" and int(suite.get("tests")) == len(card["checks"])
    assert "fd-eb: pass" in r.stdout


def test_missing_own_metadata_is_one_warning_naming_the_fem_references(monkeypatch, capsys):
    """Without pdverify's installed metadata its entry points are gone, and with them the finite-element
    references: the registry says so (one warning line) instead of leaving 'unknown model fem-eb' to explain it."""
    from importlib.metadata import PackageNotFoundError

    from pdverify import registry
    from pdverify.registry import plugins

    def absent(name):
        raise PackageNotFoundError(name)

    monkeypatch.setattr(plugins, "distribution", absent)
    monkeypatch.setattr(registry, "_REGISTRY", None)
    registry.models()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "fem-eb" in err[0] and "pip install" in err[0], err
