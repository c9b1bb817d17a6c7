"""The figures the report page draws from data (pdverify.report.plots): lines thinned to what an axis shows with
their extremes kept, compact numbers, uniform grids as three numbers, data that cannot end its script."""

import json
import re

import numpy as np

from pdverify.report.plots import MAX_POINTS, Axis, Figure, Series, number, positions, thin


def spec_of(html: str) -> dict:
    return json.loads(re.search(r'<script type="application/json">(.*?)</script>', html, flags=re.S).group(1))


def test_a_thinned_line_keeps_its_ends_extremes_and_zeros():
    """At most MAX_POINTS points of 100,001; the ends, the largest and smallest value and a zero (a break on a log
    axis) among them, in order."""
    x = np.linspace(0.0, 1.0, 100_001)
    y = np.abs(np.sin(40 * x)) * np.exp(x) + 1e-12
    y[31_234] = 0.0
    y[77_777] = 50.0
    keep = thin(x, y, log=True)
    assert len(keep) <= MAX_POINTS + 2 and np.all(np.diff(keep) > 0)
    assert {0, len(x) - 1, 31_234, 77_777} <= set(keep.tolist())
    assert np.array_equal(thin(x[:100], y[:100], log=True), np.arange(100))  # short lines are kept whole


def test_a_figure_of_many_long_lines_stays_small():
    """14 lines of 4001 points (the main job's worst scene is 14 lines of up to 1001): each line at most
    MAX_POINTS points of a few bytes each, so the figure is tens of kilobytes, not megabytes."""
    x = np.linspace(0, 1, 4001)
    series = [Series(f"model {i}", x, np.abs(np.sin((i + 1) * 7 * x)) * 10.0**-i, "m", "v", i) for i in range(14)]
    html = Figure("t", Axis("x (m)", "m"), Axis("|w − w_ref| (m)", "m", log=True), series).html()
    assert len(html) < 14 * MAX_POINTS * 2 * 9
    spec = spec_of(html)
    assert all(len(s["x"]) == len(s["y"]) <= MAX_POINTS + 2 for s in spec["s"])


def test_numbers_and_grids_are_compact():
    assert number(1.2345e-5, 3) == "1.23e-5" and number(1e21, 3) == "1e21" and number(float("nan"), 3) == "null"
    assert number(0.5, 4) == "0.5" and number(-1234.5, 4) == "-1234"
    grid = json.loads(positions(np.linspace(0.0, 2.0, 401)))
    assert grid == {"a": 0, "d": 0.005, "n": 401}
    assert json.loads(positions(np.array([0.0, 0.1, 0.3]))) == [0, 0.1, 0.3]


def test_names_cannot_end_the_data_script():
    """A scene named '</script><script>alert(1)' stays data: the page's JSON holds it, escaped, whole."""
    name = "</script><script>alert(1)</script><!--"
    html = Figure(name, Axis("x (m)", "m"), Axis("y (m)", "m"), [Series(name, np.arange(3.0), np.ones(3))]).html()
    assert html.count("</script>") == 1 and "<" not in html.split(">", 2)[2].split("</script>")[0]
    assert spec_of(html)["s"][0]["n"] == name
