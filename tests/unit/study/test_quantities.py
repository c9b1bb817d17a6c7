"""A study measures more than the deflection: ``quantities = ["rotation", "moment", "shear", "axial"]`` (at the top
or in a run) gives one error column per quantity, a convergence row per quantity and order checks on any of them."""

import numpy as np
import pandas as pd
import pytest
from helpers import ROOT

from pdverify.core.errors import InputError
from pdverify.study import load_study, run_study
from pdverify.study.store import case_file, read_case

SCENE = ROOT / "studies/examples/cantilever_tip_load.toml"


def write(tmp_path, body):
    p = tmp_path / "q.toml"
    p.write_text(f'name = "q"\nscenes = ["{SCENE.as_posix()}"]\nreference = "exact-timoshenko"\n' + body)
    return p


def test_each_quantity_has_its_error_column_and_its_order(tmp_path):
    p = write(
        tmp_path,
        'quantities = ["rotation", "moment"]\n[[runs]]\nmodel = "fem-timoshenko"\npoints = [11, 21, 41]\n'
        '[[runs]]\nmodel = "pd-timoshenko"\npoints = [21, 41, 81]\n'
        '[[checks]]\nmodel = "pd-timoshenko"\nquantity = "rotation"\nobserved_order = { min = 1.9, max = 2.1 }\n',
    )
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    fem = df[df["model"] == "fem-timoshenko"]
    assert (fem["err_max_rotation"] < 1e-12).all()  # nodally exact rotations
    assert "missing_quantities" not in df or df["missing_quantities"].isna().all()
    conv = pd.read_csv(tmp_path / "out" / "convergence.csv")
    pd_rows = conv[conv["model"] == "pd-timoshenko"].set_index("quantity")
    assert {"w", "rotation", "moment"} <= set(pd_rows.index)
    assert abs(pd_rows.loc["rotation", "observed_order"] - 2) < 0.1
    checks = pd.read_csv(tmp_path / "out" / "checks.csv")
    assert list(checks["verdict"]) == ["pass"] and list(checks["quantity"]) == ["rotation"]
    # each case file keeps the reference of every other quantity at its points (the report draws the errors)
    row = fem.sort_values("points").iloc[-1]
    curve = read_case(case_file(tmp_path / "out" / "cases", row["case_id"]))["curve"]
    assert set(curve["references"]) == {"rotation", "moment"}
    assert np.max(np.abs(curve["rotation"] - curve["references"]["rotation"])) < 1e-12 * np.max(
        np.abs(curve["references"]["rotation"])
    )


def test_a_quantity_a_model_does_not_give_is_named_not_invented(tmp_path):
    p = write(tmp_path, 'quantities = ["axial"]\n[[runs]]\nmodel = "pd-eb"\npoints = [11, 21]\n')
    df = run_study(load_study(p), tmp_path / "out", workers=1, progress=False)
    assert df["err_max_axial"].isna().all() and (df["missing_quantities"] == "axial").all()


BEAM = ROOT / "studies/nonlocal/cp_sine.toml"  # clamped-pinned, a sine load


def test_a_finite_element_reference_gives_the_moment_and_shear(tmp_path):
    """fem-eb as the reference (the README's example) measures M and V as exact-eb does (they were "missing": its
    evaluator gave w and the rotation only)."""

    def rows(reference):
        p = tmp_path / f"{reference.split('-')[0]}.toml"
        p.write_text(
            f'name = "q"\nscenes = ["{BEAM.as_posix()}"]\nreference = {reference}\n'
            'quantities = ["moment", "shear"]\n[[runs]]\nmodel = "pd-eb"\npoints = [21, 41]\n'
        )
        return run_study(load_study(p), tmp_path / p.stem, workers=1, progress=False).sort_values("points")

    fem, exact = rows('{model = "fem-eb", points = 401}'), rows('"exact-eb"')
    assert "missing_quantities" not in fem or fem["missing_quantities"].isna().all()
    for q in ("moment", "shear"):  # pd-eb's own errors on this beam, either way
        assert (exact[f"err_max_{q}"] > 1e-4).all()
        np.testing.assert_allclose(fem[f"err_max_{q}"], exact[f"err_max_{q}"], rtol=1e-6)


@pytest.mark.parametrize("quantity, key", [("rotation", "rotation"), ("M", "moment"), ("moment", "moment")])
def test_a_benchmark_of_a_measured_quantity_takes_its_reference_as_target(tmp_path, quantity, key):
    """A benchmark of a quantity the study measures needs no target: the case keeps that quantity's reference ("the
    reference gives w only; give a target" was refused before, though the study measured it against that reference)."""
    bench = f'[[benchmarks]]\nname = "b"\nscene = "{SCENE.as_posix()}"\nmodel = "pd-timoshenko"\npoints = 41\n'
    bench += f'quantity = "{quantity}"\nposition = 0.5\n'
    run = '[[runs]]\nmodel = "pd-timoshenko"\npoints = [41]\n'
    with pytest.raises(InputError, match=f'add "{key}" to the study\'s quantities, or give a target'):
        load_study(write(tmp_path, run + bench))
    run_study(load_study(write(tmp_path, f'quantities = ["{key}"]\n' + run + bench)), tmp_path / "o", workers=1)
    b = pd.read_csv(tmp_path / "o" / "benchmarks.csv").iloc[0]
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import get_model

    exact = get_model("exact-timoshenko").evaluate(load_scene(SCENE), {}, np.array([0.5]))
    field = {"rotation": "rotation", "moment": "M"}[key]
    assert b["target"] == pytest.approx(float(exact[field][0]), rel=1e-12) and b["verdict"] == "pass"


@pytest.mark.parametrize("where", ["top", "run"])
def test_an_unknown_quantity_is_one_line(tmp_path, where):
    run = '[[runs]]\nmodel = "pd-eb"\npoints = [11]\n'
    body = ('quantities = ["curvature"]\n' + run) if where == "top" else run + 'quantities = ["curvature"]\n'
    with pytest.raises(InputError, match="quantities = \\['curvature'\\]: give a list of w, rotation"):
        load_study(write(tmp_path, body))


def test_a_benchmark_of_a_quantity_its_run_does_not_measure_says_so(tmp_path):
    """Another run of the model measures the moment, the benchmark's case's run does not: its row is missing and says
    that (it said the reference gives no moment, which exact-timoshenko does)."""
    run = '[[runs]]\nmodel = "pd-timoshenko"\npoints = [41]\n'
    other = '[[runs]]\nmodel = "pd-timoshenko"\npoints = [41]\nhorizon = 2\nquantities = ["moment"]\n'
    bench = f'[[benchmarks]]\nname = "b"\nscene = "{SCENE.as_posix()}"\nmodel = "pd-timoshenko"\npoints = 41\n'
    bench += 'horizon = 3\nquantity = "moment"\nposition = 0.5\n'
    run_study(load_study(write(tmp_path, run + other + bench)), tmp_path / "o", workers=1, progress=False)
    b = pd.read_csv(tmp_path / "o" / "benchmarks.csv").iloc[0]
    assert b["verdict"] == "missing" and b["message"].startswith("the run of its case does not measure moment")


def test_a_benchmark_where_the_reference_is_zero_measures_against_its_largest_value(tmp_path):
    """The moment at a cantilever's free end is zero (to round-off in the reference): its relative error was
    |computed - 1e-14| / 1e-14 and failed whatever the model did; it is now relative to the largest moment on the beam,
    and the row says so."""
    run = '[[runs]]\nmodel = "pd-timoshenko"\npoints = [41]\nquantities = ["moment"]\n'
    bench = f'[[benchmarks]]\nname = "b"\nscene = "{SCENE.as_posix()}"\nmodel = "pd-timoshenko"\npoints = 41\n'
    bench += 'quantity = "moment"\nposition = 1.0\ntolerance = 1e-6\n'
    run_study(load_study(write(tmp_path, run + bench)), tmp_path / "o", workers=1, progress=False)
    b = pd.read_csv(tmp_path / "o" / "benchmarks.csv").iloc[0]
    assert b["verdict"] == "pass" and b["message"].startswith("the reference's moment is zero here to round-off")
