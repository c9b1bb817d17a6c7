"""The split of a study row (pdverify/study/split.py): every grid of one horizon is measured against one continuum,
extrapolated from m = 8 up on the coarsest grid with m >= 8 that it holds, at that grid's points."""

import numpy as np
from helpers import ROOT

from pdverify.core.scene_file import load_scene
from pdverify.registry import get_model, run
from pdverify.study import load_study, run_study
from pdverify.theory.continuum import coarsest_nested

SCENE = ROOT / "studies/nonlocal/cc_sine.toml"


def test_coarsest_nested_grid():
    """m = 32 at delta = 0.2 (161 points): the m = 8 grid (41 points, every 4th); m = 4 (21 points): itself."""
    s, model = load_scene(SCENE), get_model("pd-eb")
    for n, want, stride in ((161, 41, 4), (41, 41, 1), (21, 21, 1)):
        params = model.resolve(s, {"points": n, "horizon_length": 0.2})
        x = np.linspace(0.0, 1.0, n)
        points, at = coarsest_nested(model, s, params, x)
        assert points == want and np.array_equal(at, np.arange(0, n, stride))


def test_rows_of_one_horizon_share_the_continuum(tmp_path):
    """Each row's err_disc is its solution against the continuum of the m = 8 grid (levels m = 8 ... 32), at that
    grid's points: the same numbers computed here by hand."""
    p = tmp_path / "s.toml"
    p.write_text(
        f'name = "s"\nscenes = ["{SCENE.as_posix()}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "pd-eb"\n'
        "horizon_length = 0.2\npoints = [41, 81, 161]\ncontinuum_m = 32\n"
    )
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False).sort_values("points")
    s = load_scene(SCENE)
    c = run(s, "pd-eb", points=41, horizon_length=0.2, continuum=True, continuum_m=32)
    assert c.info["continuum_levels"] == [8.0, 16.0, 32.0]
    for n, got, points, own in zip(df["points"], df["err_disc"], df["split_points"], df["continuum_error"]):
        w = np.asarray(run(s, "pd-eb", points=int(n), horizon_length=0.2).w)[:: (int(n) - 1) // 40]
        assert points == 41 and own == c.info["error_bound"]
        want = np.abs(w - c.w).max() / np.abs(c.w).max()
        assert abs(got - want) <= 1e-12 * want  # the same operations: equal but for their order


def test_a_series_without_a_limit_says_so(tmp_path):
    """pd-bond-pair with mirror ends on a clamped-clamped beam has no limit at fixed delta (docs/nonlocal.md): its
    rows carry the reason, nonlocal.csv's m-convergence and model-error rows give no order and say why, and the
    δ–Δx plane's title names it."""
    import pandas as pd

    from pdverify.report.planes import _orders
    from pdverify.study.nonlocal_table import series_options

    p = tmp_path / "s.toml"
    p.write_text(
        f'name = "s"\nscenes = ["{SCENE.as_posix()}"]\nreference = "exact-eb"\n[[runs]]\nmodel = "pd-bond-pair"\n'
        'ends = "mirror"\nhorizon_length = [0.2, 0.1, 0.05]\npoints = [41, 81, 161]\ncontinuum_m = 16\n'
    )
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert df["continuum_no_limit"].str.contains("clamped end").all()
    table = pd.read_csv(tmp_path / "out" / "nonlocal.csv")
    split = table[table["path"].isin(["m-convergence", "model error"])]
    assert len(split) and split["no_limit"].str.contains("ln m").all() and split["observed_order"].isna().all()
    dm = table[table["path"] == "dm-convergence"]
    assert len(dm) and dm["observed_order"].notna().all()  # at a fixed m it still converges
    title = _orders(table, df["scene"].iloc[0], "pd-bond-pair", series_options(df["options"].iloc[0]))
    assert "m none (no limit at fixed δ)" in title
