"""The README's examples are tests: its scene, its study file and its Python snippet run as written."""

import re
import tomllib

import pandas as pd
import pytest
from helpers import ROOT

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model

README = (ROOT / "README.md").read_text()
BLOCKS = re.findall(r"```(\w+)\n(.*?)```", README, flags=re.S)


def blocks(lang):
    return [text for kind, text in BLOCKS if kind == lang]


def test_the_scene_is_valid_and_solves():
    scene = parse_scene(tomllib.loads(blocks("toml")[0]))
    assert not get_model("exact-eb").check(scene)


def test_the_study_file_runs_and_passes(tmp_path):
    from pdverify.apps.cli import main

    text = blocks("toml")[1].replace('"paper_diyaroglu/', f'"{ROOT}/studies/paper_diyaroglu/')
    study = tmp_path / "my_study.toml"
    study.write_text(text)
    with pytest.raises(SystemExit) as exit_:
        main(["study", str(study), "--out", str(tmp_path / "out"), "--quiet", "--junit", str(tmp_path / "j.xml")])
    assert exit_.value.code == 0
    checks = pd.read_csv(tmp_path / "out" / "checks.csv")
    assert (checks["verdict"] == "pass").all() and len(checks) == 2  # one order check, two scenes
    assert (tmp_path / "j.xml").exists()


@pytest.mark.slow
def test_the_python_snippet_runs(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(ROOT)
    code = blocks("python")[0].replace('"reports/diyaroglu"', repr(str(tmp_path / "diy")))
    namespace = {}
    exec(compile(code, "README.md", "exec"), namespace)  # noqa: S102 - the README's own example
    assert (namespace["df"]["status"] != "failed").all() and len(namespace["df"]) > 10
