"""The node-health figure of a load path (pdverify/report/path_figures.py)."""

import numpy as np

from pdverify.report.path_figures import health_figures


def test_no_health_no_figure():
    assert health_figures([], "beam", "m") == []


def test_one_figure_of_every_runs_health():
    x = np.linspace(0.0, 2.0, 21)
    h = np.where(np.abs(x - 1.0) < 0.2, 0.5, 1.0)
    figs = health_figures([("pd-bond-pair", x, h), ("exact-eb", x, h)], "Fig. 7", "m")
    assert len(figs) == 1 and "<svg" in figs[0] and "node health" in figs[0]
