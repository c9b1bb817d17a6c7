"""Every study file in studies/ validates (scenes, models, options, references) before anything runs."""

from pathlib import Path

import pytest

from pdverify.study import load_study

ROOT = Path(__file__).parents[1]
STUDIES = sorted(p for p in (ROOT / "studies").glob("*.toml"))


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_study_validates(path):
    s = load_study(path)
    assert s.cases


def test_main_job_study_has_benchmarks():
    s = load_study(ROOT / "studies" / "papers.toml")
    assert len(s.benchmarks) >= 8
