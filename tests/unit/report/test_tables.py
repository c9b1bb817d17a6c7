"""The report's tables: what a cell shows of a row's options and of a convergence series."""

import json

import pandas as pd

from pdverify.registry import get_model
from pdverify.report.tables import table
from pdverify.report.text import options_text


def test_options_show_what_differs_from_the_models_defaults():
    """A row's options name the variant and what differs from its model's defaults; without a known model, all."""
    defaults = {o.name: o.default for o in get_model("pd-eb").options}
    assert options_text(json.dumps(defaults), "pd-eb") == f"variant={defaults['variant']}"
    changed = {**defaults, "horizon": defaults["horizon"] + 1, "variant": "paper"}
    assert options_text(json.dumps(changed), "pd-eb") == f"horizon={changed['horizon']}, variant=paper"
    defaults = {o.name: o.default for o in get_model("fem-eb").options}  # a model without variants
    assert options_text(json.dumps(defaults), "fem-eb") == "defaults"
    assert options_text(json.dumps({"a": 1, "b": "x"}), "no-such-model") == "a=1, b=x"
    assert options_text("not json", "pd-eb") == "not json"


def test_a_series_shows_one_grid_a_line():
    df = pd.DataFrame({"points": ["401 201 101"], "errors": ["1.0e-04 4.0e-04 1.6e-03"], "name": ["a b"]})
    page = str(table(df, ["name", "points", "errors"]))
    assert '<td class="nw">401<br>201<br>101</td>' in page and "1.0e-04<br>4.0e-04<br>1.6e-03" in page
    assert '<td class="l">a b</td>' in page
