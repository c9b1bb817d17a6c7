"""The index's δ–Δx planes (pdverify/report/planes.py): a study whose PD runs give their horizon as a length gets,
per model and variant, a figure per scene with the three paths (discretisation error against Δx at each δ, the model
error against δ, the total against δ at each m) and nonlocal.csv's orders in its title; a study without such runs
gets no section."""

import pytest
from helpers import ROOT
from test_report import figures_of

from pdverify.report import build_report
from pdverify.study import load_study, run_study

pytestmark = pytest.mark.slow  # two studies and their reports

STUDY = """name = "plane"
scenes = ["{root}/studies/nonlocal/pp_sine.toml"]
reference = "exact-eb"
[[runs]]
model = "pd-eb"
variant = "paper"
horizon_length = 0.2
points = [21, 41, 81]
[[runs]]
model = "pd-eb"
variant = "paper"
horizon_length = 0.1
points = [41, 81, 161]
[[runs]]
model = "pd-eb"
variant = "paper"
horizon_length = 0.05
points = [81, 161, 321]
"""


@pytest.fixture(scope="module")
def plane_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("plane")
    p = out / "plane.toml"
    p.write_text(STUDY.format(root=ROOT))
    run_study(load_study(p), out / "run", workers=1, progress=False)
    build_report(out / "run")
    return out / "run"


def test_one_plane_per_model_with_the_three_paths(plane_dir):
    page = (plane_dir / "index.html").read_text()
    assert 'id="delta-dx"' in page and 'href="#delta-dx"' in page
    figs = [f for f in figures_of(page) if "orders:" in f["title"]]
    assert len(figs) == 1
    names = [s["n"] for s in figs[0]["spec"]["s"]]
    assert [n for n in names if n.startswith("discretisation")] == [
        "discretisation, δ = 0.2",
        "discretisation, δ = 0.1",
        "discretisation, δ = 0.05",
    ]
    assert "model error (continuum − local) against δ" in names
    assert {"total at m = 4 against δ", "total at m = 8 against δ", "total at m = 16 against δ"} <= set(names)
    # the orders of nonlocal.csv: the paper variant's full-volume sums are first order at fixed delta, its model
    # error second order in delta
    assert "m 0.9" in figs[0]["title"] and "model 2.0" in figs[0]["title"]


def test_no_section_without_horizon_lengths(tmp_path):
    p = tmp_path / "local.toml"
    p.write_text(STUDY.format(root=ROOT).split("[[runs]]")[0] + '[[runs]]\nmodel = "pd-eb"\npoints = [41, 81]\n')
    run_study(load_study(p), tmp_path / "run", workers=1, progress=False)
    build_report(tmp_path / "run")
    assert 'id="delta-dx"' not in (tmp_path / "run" / "index.html").read_text()
