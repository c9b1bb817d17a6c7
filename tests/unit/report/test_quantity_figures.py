"""The report's figures of the other quantities a study measures (pdverify.report.quantity_figures): per quantity
the error along the beam on a log axis with the quantity's unit, left out where the quantity jumps; on a curved
axis the deformed axis (equal scales) and the quantity along the arc; and the paper page's table of error
measures (pdverify.report.error_measures)."""

import json
import re
from types import SimpleNamespace

import numpy as np
import pandas as pd
from helpers import ROOT

from pdverify.core.scene_file import load_scene
from pdverify.report import quantity_figures as qf
from pdverify.report.beam_errors import Run
from pdverify.report.error_measures import scene_measures
from pdverify.report.summary import _range
from pdverify.report.sweeps import other_quantity

STRAIGHT = load_scene(ROOT / "studies/examples/cantilever_tip_load.toml")
CURVED = load_scene(ROOT / "studies/paper_curved/semicircle_normal.toml")


def spec_of(fig) -> dict:
    return json.loads(re.search(r'<script type="application/json">(.*?)</script>', fig.html(), flags=re.S).group(1))


def run(model, x, fields, references, err=None, rotation=None, **row):
    curve = {"x": x, "w": np.zeros_like(x), "w_ref": np.zeros_like(x), "fields": fields, "references": references}
    if rotation is not None:
        curve["rotation"] = rotation
    r = pd.Series({"model": model, "options": "{}", "points": len(x), "err_max": err, **row})
    return Run(r, x, "w", curve["w"], curve["w_ref"], curve)


def colour(row) -> int:
    return 0


def test_a_quantity_error_is_drawn_on_a_log_axis_in_its_unit_and_left_out_where_it_jumps():
    """|M − M_ref| in N m on a log axis, thinned to QUANTITY_POINTS; V jumps under the tip force (null there, a
    break in the line); a model without M is named in the caption, not drawn; no reference: no figure."""
    x = np.linspace(0.0, STRAIGHT.length, 1001)
    ref = {"moment": 1.0 - x / x[-1], "shear": np.ones_like(x)}
    good = run("pd-timoshenko", x, {"M": ref["moment"] + 1e-6 * (1 + x), "V": ref["shear"] + 1e-5}, ref)
    bare = run("pd-eb", x, {}, ref)
    fig = qf.quantity_error_figure([good, bare], "moment", "t", "x", "m", "SI", STRAIGHT, colour)
    spec = spec_of(fig)
    assert spec["y"] == {"l": "|M − M_ref| (N m)", "u": "N m", "log": 1} and spec["x"]["u"] == "m"
    (line,) = spec["s"]
    assert line["m"] == "pd-timoshenko" and len(line["y"]) <= qf.QUANTITY_POINTS + 2
    assert np.allclose(line["y"], 1e-6 * (1 + np.asarray(line["x"])), rtol=2e-3)  # 3 significant digits
    assert "No bending moment M" in fig.caption and "pd-eb" in fig.caption
    shear = spec_of(qf.quantity_error_figure([good], "shear", "t", "x", "m", "SI", STRAIGHT, colour))
    assert shear["y"]["u"] == "N" and shear["s"][0]["y"][-1] is None  # the tip force: V jumps at x = L
    rotation = run("pd-eb", x, {}, {"rotation": np.zeros_like(x)}, rotation=1e-3 * x)
    assert (
        spec_of(qf.quantity_error_figure([rotation], "rotation", "t", "x", "m", "SI", None, colour))["y"]["u"] == "rad"
    )
    assert qf.quantity_error_figure([bare], "axial", "t", "x", "m", "SI", STRAIGHT, colour) is None
    assert [f.title for f in qf.quantity_error_figures([good], "t", "x", "m", "SI", STRAIGHT, colour)] == [
        "t: bending moment M, error along the beam",
        "t: shear force V, error along the beam",
    ]


def test_a_curved_scene_draws_its_deformed_axis_and_its_moment_along_the_arc():
    """The axis (dotted), the exact run (grey, always shown) and the runs with the largest error, with equal
    scales; displacements scaled to SHAPE_SCALE of the length; the moment along the arc: the reference and the
    worst runs by err_max_moment."""
    s = np.linspace(0.0, CURVED.length, 41)
    exact_u = {"ux": 1e-4 * s, "uy": -2e-4 * s, "M": 1.0 - s}
    ref = {"moment": exact_u["M"]}
    runs = [run("exact-curved-cantilever", s, exact_u, ref, err=0.0, err_max_moment=0.0)]
    for i, e in enumerate([1e-2, 1e-4, 1e-3, 1e-5]):
        f = {"ux": exact_u["ux"] * (1 + e), "uy": exact_u["uy"], "M": exact_u["M"] + e}
        runs.append(run("pd-curved", s, f, ref, err=e, err_max_moment=e, degree=i))
    shape = qf.deformed_axis_figure(runs, "t", "m", CURVED, colour)
    spec = spec_of(shape)
    assert spec["eq"] == 1 and spec["x"]["u"] == spec["y"]["u"] == "m" and spec["y"]["log"] == 0
    assert [line.get("k") for line in spec["s"][:2]] == ["dot", None] and spec["s"][1]["g"] == 1
    assert len(spec["s"]) == 2 + qf.SHAPE_LINES
    k = qf.SHAPE_SCALE * CURVED.length / float(np.hypot(runs[1].curve["fields"]["ux"], exact_u["uy"]).max())
    assert f"× {k:.3g}" in shape.title
    moment = qf.along_arc_figure(runs, "moment", "t", "m", "SI", colour)
    names = [line.name for line in moment.series]
    assert names[0] == "reference" and len(names) == 1 + qf.SHAPE_LINES
    assert [r.row["degree"] for r in qf._worst(runs, "err_max_moment")] == [0, 2, 1]
    assert spec_of(moment)["y"] == {"l": "M (N m)", "u": "N m", "log": 0}
    assert qf.deformed_axis_figure(runs, "t", "m", None, colour) is None


def test_the_error_measures_table_has_a_column_per_measured_quantity_and_names_the_missing():
    rows = pd.DataFrame(
        {
            "scene_file": "a.toml",
            "scene": "a",
            "model": ["pd-curved", "pd-curved", "pd-eb"],
            "options": ["{}", "{}", "{}"],
            "degree": [2, 4, None],
            "slenderness": 10.0,
            "points": [51, 51, 51],
            "err_max": [1e-3, 1e-5, 1e-2],
            "err_max_rotation": [1e-3, 1e-5, 1e-2],
            "err_max_axial": [2e-3, 2e-5, np.nan],
            "err_max_shear": np.nan,
            "missing_quantities": [None, None, "axial"],
            "case_id": ["c1", "c2", "c3"],
        }
    )
    table, note = scene_measures(SimpleNamespace(ok=rows), "a.toml")
    assert [c for c in table.columns if c.startswith("err_max")] == ["err_max", "err_max_rotation", "err_max_axial"]
    assert list(table["case_id"]) == ["c1", "c2", "c3"] and note == "No axial force N from pd-eb or its reference"
    assert (
        scene_measures(SimpleNamespace(ok=rows.drop(columns=["err_max_rotation", "err_max_axial"])), "a.toml") is None
    )


def test_orders_per_quantity_are_named_by_their_quantity():
    assert other_quantity({"quantity": "moment"}) == "moment" and other_quantity({"quantity": "w"}) is None
    assert other_quantity({"quantity": float("nan")}) is None and other_quantity({}) is None
    assert _range([1.951, 2.18]) == "1.95 to 2.18" and _range([2.001, 1.999]) == "2.00"


def test_the_summary_gives_each_quantitys_orders_a_line_of_its_own():
    """The observed-orders cell: the model's own quantity first, then one line per other quantity, each unbroken."""
    from pdverify.report.summary import Row, _measured_cells, conv_anchor

    row = Row(
        "pd-curved", {}, "pd-curved", "", orders=[1.96, 5.66], quantity_orders={"moment": [1.99], "rotation": [2.0]}
    )
    cell = _measured_cells(row, {conv_anchor("pd-curved")}, set(), set())[0]
    assert cell.startswith('<td title="') and 'class="orders"' in cell
    shown = cell.split(f'href="#{conv_anchor("pd-curved")}">')[1].split("</a>")[0]
    assert shown.split("<br>") == ["1.96 to 5.66", "rotation: 2.00", "M: 1.99"]
