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


def test_the_moment_curvature_figure_sets_the_pairs_law_over_the_fibre_theory():
    """pd-bond-pair's load path carries its section's law (Eq. 7's pairs, from zero to six first-yield curvatures).
    With weight = fibre it is the fibre theory's to second order in the members per horizon (measured 1.6e-2, 4.1e-3,
    1.0e-3 at m = 4.95, 9.95, 19.95); the paper's weight (Eq. 6) stays below it, its shape factor being 1.41 at
    m = 9.95 (weights.shape_factors), not the rectangle's 1.5."""
    from pdverify.core.scene_file import load_scene
    from pdverify.papers.ogrady.weights import shape_factors
    from pdverify.registry import run
    from pdverify.report.path_figures import moment_curvature_figures

    sc = load_scene(ROOT / "studies" / "paper_ogrady_plastic" / "fig7_unloaded.toml")
    profile, E, sy = sc.section.profile, sc.material.E, sc.material.yield_stress

    def law(weight, m):
        got = run(sc, "pd-bond-pair", weight=weight, points=41, horizon=m).info["moment_curvature"]
        kappa, moment = np.asarray(got["kappa"]), np.asarray(got["moment"])
        assert kappa[-1] == 6 * sy / (E * profile.extreme_fibre)
        fibre = profile.fibre_moment(kappa, E, sy)
        return got, np.abs(moment - fibre).max() / fibre.max(), moment[-1] / fibre[-1]

    fibre, e10, _ = law("fibre", 9.95)
    _, e20, _ = law("fibre", 19.95)
    assert e10 < 1 / 9.95**2 and abs(np.log(e10 / e20) / np.log(19.95 / 9.95) - 2) < 0.1
    paper, _, end = law("paper", 9.95)
    assert shape_factors(profile, "paper", 9.95, 2.0 / 40, "corrected")["pd"] < 1.45 and end < 0.95
    figs = moment_curvature_figures([("fibre", fibre), ("paper", paper)], sc, "Fig. 7", "N m", "m")
    assert len(figs) == 1 and "fibre theory" in figs[0] and "curvature (1/m)" in figs[0]
    assert moment_curvature_figures([], sc, "Fig. 7", "N m", "m") == []
