"""The figures of a load path (pdverify/report/path_figures.py): node health and load factor against deflection."""

import numpy as np
from helpers import ROOT

from pdverify.report.path_figures import health_figures


def test_no_health_no_figure():
    assert health_figures([], "beam", "m") == []


def test_one_figure_of_every_runs_health():
    x = np.linspace(0.0, 2.0, 21)
    h = np.where(np.abs(x - 1.0) < 0.2, 0.5, 1.0)
    figs = health_figures([("pd-bond-pair", x, h), ("exact-eb", x, h)], "Fig. 7", "m")
    assert len(figs) == 1 and "<svg" in figs[0] and "node health" in figs[0]


def test_the_load_path_figure_draws_every_runs_factor_against_its_peak_deflection(tmp_path):
    """A study of O'Grady & Foster's Fig. 7 scene (loaded to 1.316 first yield, unloaded): each case keeps its path's
    load factor and peak deflection, and the paper page draws them, the classical residual deflection at the end."""
    import pandas as pd

    from pdverify import run_study
    from pdverify.report import build_report
    from pdverify.report.path_figures import load_path_figures
    from pdverify.study.store import case_file, read_curve

    assert load_path_figures([], "beam", "m") == []
    study = tmp_path / "s.toml"
    scene = ROOT / "studies" / "paper_ogrady_plastic" / "fig7_unloaded.toml"
    study.write_text(
        f'name = "path"\nscenes = ["{scene}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "exact-eb"\npoints = 41\n'
    )
    run_study(study, out=tmp_path / "out", workers=1, progress=False)
    case = pd.read_csv(tmp_path / "out" / "results.csv")["case_id"].iloc[0]
    path = read_curve(case_file(tmp_path / "out" / "cases", case))["load_path"]
    assert path["x"] == 1.0 and path["factor"][0] == 0.0 and path["factor"][-1] == 0.0 and max(path["factor"]) == 1.0
    # the classical values of the scene's description: -1.16563e-4 loaded, -1.23958e-5 unloaded
    assert abs(min(path["w"]) / -1.16563e-4 - 1) < 1e-5 and abs(path["w"][-1] / -1.23958e-5 - 1) < 1e-5
    build_report(tmp_path / "out")
    page = (tmp_path / "out" / "paper-paper-ogrady-plastic.html").read_text()
    assert "load path" in page and "load factor" in page
