"""Every study file in studies/ validates (scenes, models, options, references) before anything runs."""

import pytest
from helpers import ROOT

from pdverify.study import load_study

STUDIES = sorted(p for p in (ROOT / "studies").glob("*.toml"))


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_study_validates(path):
    s = load_study(path)
    assert s.cases


def test_main_job_study_has_benchmarks():
    s = load_study(ROOT / "studies" / "papers.toml")
    assert len(s.benchmarks) >= 8


def test_main_job_measures_every_paper_against_a_reference():
    """Every static case of the main job has a reference and every paper folder a benchmark row, so each
    paper's report page shows numbers (the O'Grady large-rotation runs had reference = "none").
    Transient runs (a [dynamics] table: Moyer's time histories) are shown as histories, without one."""
    s = load_study(ROOT / "studies" / "papers.toml")
    unmeasured = [c.scene_file for c in s.cases if c.reference["model"] == "none" and "[dynamics]" not in c.scene_text]
    assert not unmeasured
    folders = {c.scene_file.split("/")[0] for c in s.cases}
    for folder in folders:
        assert any(b["scene"].startswith(folder + "/") for b in s.benchmarks), folder
