"""A row measured against a reference of another theory says when its error may be the theories' difference
(pdverify/study/reference.py: theory_gap_warning)."""

import pandas as pd
from helpers import ROOT

from pdverify.study import load_study, run_study

SCENE = ROOT / "studies/examples/cantilever_tip_load.toml"
FLAG = "is of another theory"


def test_an_euler_bernoulli_model_against_a_timoshenko_reference_says_its_error_is_the_theories(tmp_path):
    """pd-eb against exact-timoshenko on a cantilever of L/h = 5: 3.0 % off at 41 and 81 points, all of it the
    theories' difference (exact-eb is as far); said on its rows (they said nothing). pd-timoshenko against the same
    reference, and pd-eb against exact-eb, are of one theory: nothing said."""
    p = tmp_path / "s.toml"
    p.write_text(
        f'name = "gap"\nscenes = ["{SCENE.as_posix()}"]\nreference = "exact-timoshenko"\n[sweep]\nslenderness = [5]\n'
        '[[runs]]\nmodel = "pd-eb"\npoints = [41, 81]\n[[runs]]\nmodel = "pd-timoshenko"\npoints = [41]\n'
        '[[runs]]\nmodel = "pd-eb"\npoints = [41]\nreference = "exact-eb"\n'
    )
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    said = df["warnings"].fillna("").str.contains(FLAG)
    gap = (df["model"] == "pd-eb") & df["reference"].str.contains("exact-timoshenko")
    assert said[gap].all() and not said[~gap].any(), df[["model", "reference", "warnings"]]
    assert (df.loc[gap, "err_max"] > 0.02).all()
    assert pd.read_csv(tmp_path / "out" / "results.csv")["warnings"].fillna("").str.contains(FLAG).sum() == 2
