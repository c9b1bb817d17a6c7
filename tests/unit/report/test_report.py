"""HTML report: the summary first, figures that show errors (every scene's error along the beam, every
convergence series' log-log plot), units on every axis and column; it renders in headless Chromium with no
console errors and no request leaving the page, its filters hide what they should, links resolve, numbers trace
to results.csv, and re-running gives the same HTML apart from the timestamp."""

import json
import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser

import numpy as np
import pandas as pd
import pytest
from browser import Browser, find
from helpers import ROOT

import pdverify.core.errors
from pdverify.report import build_report
from pdverify.report.build import fmt
from pdverify.report.tables import cell_text
from pdverify.study import load_study, run_study


@pytest.fixture(scope="module")
def study_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    p = out / "study.toml.in"
    p.write_text(
        (ROOT / "studies/paper_diyaroglu.toml")
        .read_text()
        .replace('"paper_diyaroglu/', f'"{ROOT}/studies/paper_diyaroglu/')
        + '\n[papers]\npaper_diyaroglu = "Diyaroglu, Oterkus and Oterkus"\n'
    )
    p = p.rename(out / "diy.toml")
    run_study(load_study(p), out / "run", workers=1, progress=False)
    build_report(out / "run")
    return out / "run"


class Links(HTMLParser):
    """The links of a page, its inline SVG figures (paper pages) and its figures drawn from data (the index)."""

    def __init__(self):
        super().__init__()
        self.hrefs, self.svgs, self.figures, self.ids = [], 0, [], set()
        self._json = False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a":
            self.hrefs.append(a.get("href"))
        if tag == "svg":
            self.svgs += 1
        if tag == "figure" and "pfig" in a.get("class", ""):
            self.figures.append({"attrs": a})
        self._json = tag == "script" and a.get("type") == "application/json"

    def handle_data(self, data):
        if self._json:
            self.figures[-1]["spec"] = json.loads(data)
            self._json = False


def figures_of(page: str) -> list[dict]:
    """The index's figures: each one's attributes, its data (axes, series) and its title."""
    p = Links()
    p.feed(page)
    titles = re.findall(r'<figure class="pfig[^"]*"[^>]*>.*?<div class="ftitle">(.*?)</div>', page, flags=re.S)
    for f, t in zip(p.figures, titles, strict=True):
        f["title"] = t
    return p.figures


def resolves(study_dir, page, href) -> bool:
    """An href of ``page`` points at an existing file and, with a #fragment, at an element id of that file."""
    target, _, frag = href.partition("#")
    text = page if not target else (study_dir / target).read_text() if (study_dir / target).exists() else None
    if text is None:
        return False
    return not frag or f'id="{frag}"' in text


@pytest.mark.slow
def test_links_resolve_and_figures_present(study_dir):
    """Every link of the index resolves; its figures are data drawn by the page (3 scenes' errors, 6 convergence
    series, 3 work-precision plots), every one with axes and at least one line; nothing is loaded from a URL."""
    page = (study_dir / "index.html").read_text()
    p = Links()
    p.feed(page)
    figs = figures_of(page)
    assert len(figs) >= 12 and all(f["spec"]["s"] and f["spec"]["x"]["l"] and f["spec"]["y"]["l"] for f in figs)
    for h in p.hrefs:
        assert resolves(study_dir, page, h), h
    # no network requests: nothing is loaded from a URL (XML namespaces are names, not requests)
    assert not re.search(r'(src|href)="(https?:)?//', page) and "url(http" not in page
    assert "<svg" not in page.split("<script>")[0]  # no inline SVG: the page draws its figures


def test_the_summary_comes_first_and_links_to_its_evidence(study_dir):
    """The first section is the summary: one row per model and variant with its observed orders (linking to its
    convergence plots), its worst error at the finest grid (linking to that scene's error figure) and the cost
    (linking to that scene's work-precision figure); then the papers' benchmarks."""
    page = (study_dir / "index.html").read_text()
    sections = re.findall(r'<h2 id="([^"]+)"', page)
    assert sections[:2] == ["summary", "benchmarks"]
    summary = page[page.index('id="summary"') : page.index('id="benchmarks"')]
    rows = re.findall(
        r'<tr class="f [^"]*" data-model="([^"]*)" data-variant="([^"]*)".*?</td><td class="l">(.*?)</td>', summary
    )
    assert sorted(rows) == [
        ("fem-eb", "", "defaults"),
        ("pd-eb", "corrected", "variant=corrected"),
        ("pd-eb", "paper", "reading=layer, variant=paper"),
        ("pd-eb", "paper", "reading=literal, variant=paper"),
        ("pd-eb", "paper", "variant=paper"),
    ]
    p = Links()
    p.feed(page)
    for anchor in ("conv-pd-eb-corrected", "conv-pd-eb-paper", "scene-", "wp-"):
        links = re.findall(rf'href="#({anchor}[^"]*)"', summary)
        assert links and all(a in p.ids for a in links), anchor
    # the numbers: the corrected variant's fitted orders, but for a series at round-off on every grid (clamped-free:
    # the corrected operator reproduces its cubic deflection, so refining only adds round-off: a "slope" of -2)
    from pdverify.report.summary import ROUND_OFF

    conv = pd.read_csv(study_dir / "convergence.csv")
    conv = conv[conv["variant"] == "corrected"]
    exact = [max(float(e) for e in errors.split()) < ROUND_OFF for errors in conv["errors"]]
    assert exact.count(True) == 1
    lo, hi = conv[[not x for x in exact]]["observed_order"].agg(["min", "max"])
    text = f"{lo:.2f}" if f"{lo:.2f}" == f"{hi:.2f}" else f"{lo:.2f} to {hi:.2f}"
    assert f'href="#conv-pd-eb-corrected">{text}</a>' in summary


def test_every_scene_has_its_error_along_the_beam_on_a_log_axis(study_dir):
    """Per scene a figure of |w - w_ref| along the beam: a log vertical axis with its unit, one line per model and
    variant at its finest grid (their values are |w - w_ref| of the case file)."""
    from pdverify.study.store import case_file, read_curve

    page = (study_dir / "index.html").read_text()
    res = pd.read_csv(study_dir / "results.csv")
    figs = [f for f in figures_of(page) if "error along the beam" in f["title"]]
    assert sorted(f["attrs"]["data-scene"] for f in figs) == sorted(res["scene"].unique())
    for f in figs:
        spec = f["spec"]
        assert spec["y"]["log"] == 1 and spec["y"]["l"] == "|w − w_ref| (m)" and spec["x"]["l"] == "x (m)"
        rows = res[res["scene"] == f["attrs"]["data-scene"]]
        finest = rows.sort_values("points").groupby(["model", "options"]).tail(1)
        assert len(spec["s"]) == len(finest)
        assert all(s["m"] in set(finest["model"]) and "n=" in s["n"] for s in spec["s"])
        # the line of fem-eb's finest grid is its error, to the digits drawn
        r = finest[finest["model"] == "fem-eb"].iloc[0]
        c = read_curve(case_file(study_dir / "cases", r["case_id"]))
        line = next(s for s in spec["s"] if s["m"] == "fem-eb")
        err = np.abs(c["w"] - c["w_ref"])
        drawn = np.array([np.nan if v is None else v for v in line["y"]], float)
        assert len(drawn) == len(err) and np.allclose(drawn, err, rtol=5e-3, atol=0)


def test_every_convergence_series_has_a_log_log_plot_with_its_order(study_dir):
    """One small log-log plot per row of convergence.csv: errors against spacing, the fitted order written on it
    (the table's, two decimals) and beside it the slope of the series' order check (the middle of its band) where
    the study checks it, else the order the model promises."""
    from pdverify.report.text import label

    page = (study_dir / "index.html").read_text()
    conv = pd.read_csv(study_dir / "convergence.csv")
    checks = pd.read_csv(study_dir / "checks.csv")
    figs = [f for f in figures_of(page) if "small" in f["attrs"]["class"] and f["spec"]["x"]["l"] == "Δx (m)"]
    assert len(figs) == len(conv)
    by_series = {(f["attrs"]["data-scene"], f["spec"]["s"][0]["n"]): f["spec"] for f in figs}
    titles = {(f["attrs"]["data-scene"], f["spec"]["s"][0]["n"]): f["title"] for f in figs}
    checked = 0
    for _, r in conv.iterrows():
        spec = by_series[(r["scene"], label(r))]
        assert ("exact to round-off, no order" in titles[(r["scene"], label(r))]) == r["at_round_off"]
        assert spec["x"]["log"] == 1 and spec["y"]["log"] == 1
        assert np.all(np.array([float(v) for v in r["errors"].split()]) < 1e-7) == r["at_round_off"]
        if r["at_round_off"]:  # an exact quantity: no order fitted, and the figure says why
            assert pd.isna(r["observed_order"]) and "a" not in spec and len(spec["s"]) == 1
            continue
        assert [a["t"] for a in spec["a"]] == [f"p = {r['observed_order']:.2f}"]
        check = checks[(checks["scene"] == r["scene"]) & (checks["options"] == r["options"])]
        if len(check):
            lo, hi = check.iloc[0][["min", "max"]]
            slope = f"slope {(lo + hi) / 2:g} (order check: {lo:g} to {hi:g})"
            checked += 1
        else:
            slope = "slope 2 (promised)"
        assert [s["n"] for s in spec["s"]][1:] == [f"fit: p = {r['observed_order']:.2f}", slope]
        assert np.allclose(spec["s"][0]["y"], [float(v) for v in r["errors"].split()], rtol=5e-3)
    assert checked == len(checks) == 2


def test_table_rows_carry_what_the_filters_match(study_dir):
    """Each row of a table is tagged with its model, variant (from its options where the table has no variant
    column: the trust table's paper rows are 'paper', not the default), scene and paper."""
    page = (study_dir / "index.html").read_text()
    trust = page[page.index('<h2 id="trust">') : page.index('<h2 id="plane-stress">')]
    tagged = re.findall(r'<tr class="f" data-model="([^"]*)" data-variant="([^"]*)"', trust)
    want = [
        (r["model"], json.loads(r["options"]).get("variant", ""))
        for _, r in pd.read_csv(study_dir / "trust.csv").iterrows()
    ]
    assert tagged == want and ("pd-eb", "paper") in tagged and ("pd-eb", "corrected") in tagged
    results = re.findall(
        r'<tr class="\w+ f" id="case-[^"]+" data-model="([^"]*)" data-variant="([^"]*)" '
        r'data-scene="([^"]*)" data-paper="([^"]*)"',
        page,
    )
    res = pd.read_csv(study_dir / "results.csv", keep_default_na=False)
    assert results == [(m, v, s, "paper_diyaroglu") for m, v, s in zip(res["model"], res["variant"], res["scene"])]


def test_units_on_every_axis_and_numeric_column(study_dir):
    """Every axis label names its unit ('(m)', '(s)', '(–)' for a ratio); every numeric column header too."""
    page = (study_dir / "index.html").read_text()
    for f in figures_of(page):
        for axis in ("x", "y"):
            assert re.search(r"\([^)]+\)$", f["spec"][axis]["l"]), (f["title"], f["spec"][axis]["l"])
    from pdverify.report.tables import COLUMNS

    heads = re.findall(r'<th class="[^"]*" title="([^"]+)">([^<]*)</th>', page)
    assert heads
    for name, text in heads:
        if name in COLUMNS and COLUMNS[name].unit:
            assert re.search(r"\([^)]+\)$", text), (name, text)


@pytest.mark.slow
def test_one_page_per_paper_linked_both_ways(study_dir):
    index = (study_dir / "index.html").read_text()
    page_file = study_dir / "paper-paper-diyaroglu.html"
    assert 'href="paper-paper-diyaroglu.html"' in index and "Diyaroglu, Oterkus and Oterkus" in index
    page = page_file.read_text()
    p = Links()
    p.feed(page)
    assert "index.html" in p.hrefs and p.svgs >= 6  # 3 deflection + 3 convergence (+ horizon)
    assert all(resolves(study_dir, page, h) for h in p.hrefs), [h for h in p.hrefs if not resolves(study_dir, page, h)]
    # the page's benchmark rows are the study's rows for this paper: every computed value is shown
    bench = pd.read_csv(study_dir / "benchmarks.csv")
    for _, b in bench.iterrows():
        assert f">{fmt(b['computed'])}<" in page


def test_time_histories_plotted_and_written_as_csv(tmp_path, monkeypatch):
    """A dynamic model's history (info["history"]) becomes a figure on the report and a CSV file."""
    from pdverify import registry
    from pdverify.core.contract import Model, Option
    from pdverify.core.result import Result

    class Ringing(Model):
        name = "ringing-test"
        kind = "dynamic"
        options = (Option("points", int, 11, minimum=2),)

        def solve(self, scene, params):
            x = np.linspace(0, scene.length, params["points"])
            t = np.linspace(0, 1, 201)
            mid = 0.1 * (1 - np.cos(2 * np.pi * 5 * t) * np.exp(-t))
            return Result(
                scene.name,
                self.name,
                dict(params),
                x,
                0 * x,
                dofs=len(x),
                info={"history": {"t": t, "series": {"midpoint": mid}}},
            )

    monkeypatch.setitem(registry.models(), "ringing-test", Ringing())
    p = tmp_path / "dyn.toml"
    p.write_text(
        f'name = "dyn"\nscenes = ["{ROOT}/studies/paper_diyaroglu/clamped_clamped.toml"]\nreference = "none"\n'
        '[[runs]]\nmodel = "ringing-test"\npoints = [11, 21]\n'
    )  # two cases: a serial run's recorder path
    df = run_study(load_study(p), tmp_path / "run", workers=1, progress=False)
    for case_id in df["case_id"]:
        h = pd.read_csv(tmp_path / "run" / "histories" / f"{case_id}.csv")
        assert list(h.columns) == ["t", "midpoint"] and len(h) == 201
        assert np.allclose(h["midpoint"], 0.1 * (1 - np.cos(2 * np.pi * 5 * h["t"]) * np.exp(-h["t"])), rtol=1e-15)
    build_report(tmp_path / "run")
    page = (tmp_path / "run" / "paper-paper-diyaroglu.html").read_text()  # the paper's page draws the histories
    assert "time history" in page and "t (s)" in page


def test_numbers_trace_to_results(study_dir):
    page = (study_dir / "index.html").read_text()
    res = pd.read_csv(study_dir / "results.csv")
    bench = pd.read_csv(study_dir / "benchmarks.csv")
    for _, b in bench.iterrows():
        row = res[res["case_id"] == b["case_id"]].iloc[0]
        assert b["computed"] == row["w_at_max"] and b["err_max"] == row["err_max"]
        assert f">{fmt(row['w_at_max'])}<" in page
        assert f">{cell_text('err_max', row['err_max'])}<" in page  # an error to the 3 digits it carries


@pytest.mark.slow
def test_rebuild_is_identical_apart_from_timestamp(study_dir, tmp_path):
    a = (study_dir / "index.html").read_text()
    b = build_report(study_dir, tmp_path).read_text()
    strip = lambda s: re.sub(r'<span id="generated">[^<]*</span>', "", s)  # noqa: E731
    assert strip(a) == strip(b)


def find_chromium() -> str:
    """The Chromium executable; the test skips without one, unless PDVERIFY_REQUIRE_BROWSER=1 (set by .ci/run,
    which installs it), where a missing browser fails. Nothing is installed here."""
    chromium = find()
    if chromium:
        return chromium
    if os.environ.get("PDVERIFY_REQUIRE_BROWSER") == "1":
        pytest.fail("PDVERIFY_REQUIRE_BROWSER=1 but no chromium or chromium-browser on PATH (.ci/run installs it)")
    pytest.skip(
        "Chromium is not installed (apt-get install chromium, or run .ci/run); the report's rendering "
        "in a browser is not checked"
    )


def test_browser_test_skips_or_fails_by_the_environment(monkeypatch):
    """Without a browser: a skip with the reason, or a failure under PDVERIFY_REQUIRE_BROWSER=1."""
    monkeypatch.setattr(shutil, "which", lambda name: None)
    monkeypatch.delenv("PDVERIFY_REQUIRE_BROWSER", raising=False)
    with pytest.raises(pytest.skip.Exception, match="Chromium is not installed"):
        find_chromium()
    monkeypatch.setenv("PDVERIFY_REQUIRE_BROWSER", "1")
    with pytest.raises(pytest.fail.Exception, match="PDVERIFY_REQUIRE_BROWSER=1"):
        find_chromium()


# The page's state as the browser has it: every filterable row and figure, hidden or not (inside a hidden block
# counts as hidden; a closed <details> does not), the lines each figure draws and its legend.
STATE = """(function () {
  function hidden(e) { return e.closest('[hidden]') !== null; }
  return {
    rows: Array.from(document.querySelectorAll('tr.f')).map(function (r) {
      return {model: r.dataset.model, scene: r.dataset.scene, hidden: hidden(r), result: r.id.startsWith('case-')};
    }),
    figures: Array.from(document.querySelectorAll('figure.pfig')).map(function (f) {
      return {scene: f.dataset.scene, hidden: hidden(f), paths: f.querySelectorAll('svg path').length,
              lines: f._spec.s.filter(function (s) { return !s.g && !s._hidden; }).map(function (s) { return s.m; }),
              legend: Array.from(f.querySelectorAll('.legend li')).map(function (li) { return li.textContent; })}; }),
    scenes: Array.from(document.querySelectorAll('section.scene')).map(function (s) {
      return {id: s.id, hidden: hidden(s)}; })
  };
})()"""


def choose(browser: Browser, name: str, value: str) -> dict:
    """Pick ``value`` in the filter ``name`` as a user does (the select's value, then its change event); the
    page's state after it."""
    browser.evaluate(
        f"(function () {{ var s = document.querySelector('#filters select[name={name}]');"
        f" s.value = {json.dumps(value)}; s.dispatchEvent(new Event('change', {{bubbles: true}})); }})()"
    )
    return browser.evaluate(STATE)


@pytest.mark.slow
def test_opens_in_headless_chromium_and_its_filters_work(study_dir, tmp_path, record_property):
    """In headless Chromium: no console error and no request but the page itself (index and paper page); the
    figures drawn as they come near the screen; the model filter hides the other models' rows, figures and lines
    (and legends), the scene filter the other scenes; "show all" brings everything back; hovering a point shows
    its values with units. Screenshots of the top of the page and one figure or table per section go to the
    test's tmp folder."""
    chromium = find_chromium()
    shots = tmp_path / "screenshots"
    shots.mkdir()
    index = (study_dir / "index.html").as_uri()
    with Browser(chromium, tmp_path / "profile") as browser:
        browser.open(index)
        assert not browser.console_errors(), browser.console_errors()
        assert browser.requests() == [index]  # nothing else: no font, script, image or data fetched
        # a figure is drawn when it comes near the screen: the last one is not, until it is scrolled to
        state = browser.evaluate(STATE)
        assert state["figures"] and state["figures"][-1]["paths"] == 0
        browser.evaluate(
            "new Promise(function (done) { var f = document.querySelectorAll('figure.pfig');"
            " f[f.length - 1].scrollIntoView();"
            " requestAnimationFrame(function () { requestAnimationFrame(done); }); })"
        )
        assert browser.evaluate(STATE)["figures"][-1]["paths"] >= 1
        browser.evaluate("window.scrollTo(0, 0); window.pdvFigures.drawAll()")
        state = browser.evaluate(STATE)
        assert all(f["paths"] >= 1 and not f["hidden"] for f in state["figures"])
        assert state["rows"] and not any(r["hidden"] for r in state["rows"])
        browser.screenshot(shots / "top.png")
        for name, selector in (
            ("summary", "#summary ~ .wide"),
            ("benchmarks", "#benchmarks ~ .wide"),
            ("errors", "section.scene figure.pfig"),
            ("convergence", "#convergence ~ section figure.pfig"),
            ("work-precision", "#cost ~ .multiples figure.pfig"),
        ):
            assert browser.screenshot(shots / f"{name}.png", selector).stat().st_size > 5_000, name
        record_property("screenshots", str(shots))

        # the model filter: fem-eb only
        state = choose(browser, "model", "fem-eb")
        rows = state["rows"]
        assert any(r["model"] == "fem-eb" for r in rows) and any(r["model"] == "pd-eb" for r in rows)
        assert all(r["hidden"] == (r["model"] != "fem-eb") for r in rows)
        results = [r for r in rows if r["result"]]  # the results table's rows among them (and the summary's, ...)
        assert len(results) == len(pd.read_csv(study_dir / "results.csv")) and len(rows) > len(results)
        shown = [f for f in state["figures"] if not f["hidden"]]
        assert shown and len(shown) < len(state["figures"])  # the pd-eb convergence plots are gone
        for f in shown:
            assert set(f["lines"]) == {"fem-eb"}, f
            assert not any(text.startswith("pd-eb") for text in f["legend"]), f["legend"]
        assert all(not f["lines"] or "fem-eb" not in f["lines"] for f in state["figures"] if f["hidden"])
        browser.screenshot(shots / "filtered-errors.png", "section.scene figure.pfig:not([hidden])")

        # the scene filter (with the model filter off): one scene's section, rows and figures
        choose(browser, "model", "")
        scene = pd.read_csv(study_dir / "results.csv")["scene"].iloc[0]
        state = choose(browser, "scene", scene)
        assert [s["hidden"] for s in state["scenes"]].count(False) == 1
        assert all(r["hidden"] == (scene not in (r["scene"] or "").split("|")) for r in state["rows"])
        assert all(f["hidden"] == (f["scene"] != scene) for f in state["figures"])

        # show all
        browser.evaluate("document.querySelector('#filters button[type=reset]').click()")
        state = browser.evaluate(STATE)
        assert not any(r["hidden"] for r in state["rows"]) and not any(f["hidden"] for f in state["figures"])

        # hover: the point under the mouse, its values and units
        point = browser.evaluate(
            "(function () { var c = document.querySelector('#convergence ~ section figure.pfig circle');"
            " c.scrollIntoView({block: 'center'}); var r = c.getBoundingClientRect();"
            " return {x: r.left + r.width / 2, y: r.top + r.height / 2}; })()"
        )
        browser.send("Input.dispatchMouseEvent", type="mouseMoved", x=point["x"], y=point["y"])
        tip = browser.evaluate("document.querySelector('#convergence ~ section figure.pfig .tip').textContent")
        assert re.search(r"Δx = [0-9.e-]+ m\nmax rel. error = [0-9.e-]+", tip), tip
        assert not browser.console_errors(), browser.console_errors()

        # the paper's page
        paper = (study_dir / "paper-paper-diyaroglu.html").as_uri()
        browser.open(paper)
        assert not browser.console_errors() and browser.requests() == [paper]
        assert browser.evaluate("document.querySelectorAll('svg path').length") > 50


@pytest.mark.slow
def test_plane_stress_images_and_vtu_links(tmp_path):
    """A study with a plane-stress case writes its VTU and an off-screen PNG; the paper's page inlines the
    picture and links the VTU; the index links to them."""
    p = tmp_path / "ps.toml"
    p.write_text(f'''name = "ps"
scenes = ["{ROOT}/studies/paper_yang/cantilever_tip_force.toml"]
reference = "exact-timoshenko"
[[runs]]
model = "fem-plane-stress"
points = [21, 31]
layers = 4
''')  # two cases: a serial run's recorder path (the pictures are drawn by the solving process)
    run_study(load_study(p), tmp_path / "run", workers=1, progress=False)
    pngs = list((tmp_path / "run" / "vtu").glob("*.png"))
    assert len(pngs) == 2 and all(png.stat().st_size > 2000 for png in pngs)
    index = build_report(tmp_path / "run").read_text()
    assert 'href="paper-paper-yang.html#plane-stress"' in index and "data:image/png" not in index
    page = (tmp_path / "run" / "paper-paper-yang.html").read_text()  # the pictures are on the paper's page
    for png in pngs:
        assert f'href="vtu/{png.stem}.vtu"' in page and (tmp_path / "run" / "vtu" / f"{png.stem}.vtu").exists()
    assert page.count("data:image/png;base64,") == 2 and 'id="plane-stress"' in page


def test_case_ids_link_to_their_rows(study_dir):
    """Every case id of a benchmark row links to that case's row of the results table (index.html#case-<id>)."""
    index = (study_dir / "index.html").read_text()
    paper = (study_dir / "paper-paper-diyaroglu.html").read_text()
    bench = pd.read_csv(study_dir / "benchmarks.csv")
    assert len(bench) > 0
    for cid in bench["case_id"].dropna():
        assert f'<tr id="case-{cid}"' in index or f'id="case-{cid}"' in index
        assert f'href="#case-{cid}"' in index and f'href="index.html#case-{cid}"' in paper


def test_references_and_what_was_run_are_text(study_dir):
    """No JSON object in the page's text: references as 'model (k=v)', meta values as 'numpy 2.4.6, ...'."""
    page = (study_dir / "index.html").read_text()
    text = re.sub(r"<(script|style|svg)\b.*?</\1>", "", page, flags=re.S)
    text = re.sub(r"<pre>.*?</pre>", "", text, flags=re.S)  # the study file itself, as written
    assert "{&#34;" not in text and '{"' not in text and "{&quot;" not in text
    meta = json.loads((study_dir / "meta.json").read_text())
    assert f"numpy {meta['versions']['numpy']}" in page


def _one_case_study(tmp_path, name, scene_text, description=""):
    tmp_path.mkdir(parents=True, exist_ok=True)
    scene = tmp_path / "beam.toml"
    scene.write_text(scene_text)
    study = tmp_path / "s.toml"
    study.write_text(
        f'name = {json.dumps(name)}\ndescription = {json.dumps(description)}\nscenes = ["beam.toml"]\n'
        'reference = "exact-eb"\n[[runs]]\nmodel = "fem-eb"\npoints = [11]\n'
    )
    run_study(load_study(study), tmp_path / "run", workers=1, progress=False)
    return build_report(tmp_path / "run").read_text()


def test_markup_in_the_study_name_is_escaped(tmp_path):
    """The study's name (and the study file shown) is text: a tag in it is not markup (was: autoescape=False)."""
    tag = "<img src=x onerror=console.log('INJECTED')>"
    scene = (ROOT / "studies/examples/cantilever_tip_load.toml").read_text()
    scene = scene.replace('name = "cantilever, tip load"', 'name = "<b>bold</b> beam"')
    page = _one_case_study(tmp_path, tag, scene, description="<script>alert(1)</script>")
    assert tag not in page and "<img src=x" not in page and "<b>bold" not in page and "<script>alert" not in page
    assert "&lt;img src=x onerror=console.log(&#39;INJECTED&#39;)&gt;" in page
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in page and "&lt;b&gt;bold&lt;/b&gt; beam" in page
    paper = next(p for p in (tmp_path / "run").glob("paper-*.html"))
    assert "<img src=x" not in paper.read_text() and "<b>bold" not in paper.read_text()


def test_the_delta_dx_plane_has_its_section_when_its_figures_come(tmp_path, monkeypatch):
    """The hook of the per-PD-model δ–Δx figures: a study without horizon lengths has no such section; given
    figures, the index shows them under "The δ–Δx plane" with a link in its navigation (the figures themselves:
    test_delta_dx_planes.py)."""
    from pdverify.report import sweeps
    from pdverify.report.plots import Axis, Figure, Series

    scene = (ROOT / "studies/examples/cantilever_tip_load.toml").read_text()
    page = _one_case_study(tmp_path / "none", "plain", scene)
    assert 'id="delta-dx"' not in page

    def planes(data, palette):
        fig = Figure("pd-eb: the δ–Δx plane", Axis("Δx (m)", "m", log=True), Axis("δ (m)", "m", log=True))
        fig.series.append(Series("pd-eb", np.array([0.01, 0.02]), np.array([0.03, 0.06]), "pd-eb", "corrected", 0))
        return [sweeps.Group("pd-eb corrected", "dd-pd-eb", [fig.html()])]

    monkeypatch.setattr(sweeps, "delta_dx_planes", planes)
    page = build_report(tmp_path / "none" / "run").read_text()
    section = page[page.index('<h2 id="delta-dx">') :]
    assert 'href="#delta-dx"' in page and 'id="dd-pd-eb"' in section and "pd-eb: the δ–Δx plane" in section


@pytest.mark.slow
def test_axis_labels_carry_the_scene_units(tmp_path):
    """An inch-pound scene (Moyer's) labels lengths in inches; an SI scene in metres: on the index's figures (the
    error along the beam) and tables, and on the paper's page (the deflection). The page's drawing code is not
    text of the page."""

    def text(page):
        return re.sub(r"<script>.*?</script>", "", page, flags=re.S)

    scene = (ROOT / "studies/paper_moyer/cantilever_table1.toml").read_text()
    assert 'units = "inch-pound"' in scene
    page = text(_one_case_study(tmp_path / "in", "moyer", scene.replace("fem-timoshenko", "fem-eb")))
    paper = (tmp_path / "in" / "run" / "paper-scenes.html").read_text()
    assert '"x (in)"' in page and '"|w − w_ref| (in)"' in page and "Δx (in)" in page and "(m)" not in page
    assert "w (in)" in paper and "(m)" not in paper
    page = text(
        _one_case_study(tmp_path / "si", "si", (ROOT / "studies/examples/cantilever_tip_load.toml").read_text())
    )
    paper = (tmp_path / "si" / "run" / "paper-scenes.html").read_text()
    assert '"x (m)"' in page and '"|w − w_ref| (m)"' in page and "Δx (m)" in page and "(in)" not in page
    assert "w (m)" in paper and "(in)" not in paper


@pytest.mark.slow
def test_damaged_case_file_is_named(tmp_path):
    """`pdverify report` on a folder with a damaged case file: one line naming it, exit code 2, no traceback."""
    _one_case_study(tmp_path, "damaged", (ROOT / "studies/examples/cantilever_tip_load.toml").read_text())
    case = next((tmp_path / "run" / "cases").iterdir())
    case.write_bytes(case.read_bytes()[:-7])
    r = subprocess.run(
        [sys.executable, "-m", "pdverify", "report", str(tmp_path / "run")], capture_output=True, text=True, cwd=ROOT
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stderr.count("\n") == 1 and r.stderr.startswith(f"error: {case}:") and "pdverify study" in r.stderr


@pytest.mark.slow
def test_unwritable_report_out(tmp_path):
    """`report --out` below a file: exit code 4, one line naming the path, nothing written."""
    _one_case_study(tmp_path, "unwritable", (ROOT / "studies/examples/cantilever_tip_load.toml").read_text())
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = subprocess.run(
        [sys.executable, "-m", "pdverify", "report", str(tmp_path / "run"), "--out", str(blocker / "rep")],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 4 and "Traceback" not in r.stderr and r.stderr.count("\n") == 1
    assert str(blocker) in r.stderr and blocker.read_text() == "x"
    with pytest.raises(pdverify.core.errors.OutputError, match="rep"):
        build_report(tmp_path / "run", blocker / "rep")


def test_ci_requires_the_browser():
    """.ci/run installs chromium when missing and makes the browser test fail (not skip) without it."""
    text = (ROOT / ".ci" / "run").read_text()
    assert "apt-get install" in text and "chromium" in text
    run_line = next(i for i, l in enumerate(text.splitlines()) if "pytest" in l)
    assert any("export PDVERIFY_REQUIRE_BROWSER=1" in l for l in text.splitlines()[:run_line])


@pytest.fixture(scope="module")
def curved_dir(tmp_path_factory):
    """A curved study measuring rotation, moment and axial force (the curved PDDO paper's error measures)."""
    tmp_path = tmp_path_factory.mktemp("curved")
    p = tmp_path / "c.toml"
    p.write_text(f'''name = "c"
scenes = ["{ROOT}/studies/paper_curved/semicircle_normal.toml"]
reference = "exact-curved-cantilever"
quantities = ["rotation", "moment", "axial"]
[papers]
paper_curved = "Curved PDDO beam 2024"
[[runs]]
model = "pd-curved"
degree = 2
form = ["primal", "mixed"]
points = 41
slenderness = [10, 100]
[[runs]]
model = "pd-curved"
degree = 2
points = 21
slenderness = [10]
[[runs]]
model = "exact-curved-cantilever"
points = 41
slenderness = [10, 100]
''')
    run_study(load_study(p), tmp_path / "run", workers=1, progress=False)
    build_report(tmp_path / "run")
    return tmp_path / "run"


@pytest.mark.slow
def test_curved_page_draws_axial_and_shear_forces_and_its_locking_table(curved_dir):
    """Seed 004's page: N and Q beside the deflection for the curves that return them (pd-curved and the exact
    curved beam, whose range sets the axes), and the page's own locking table; a grid run at one slenderness
    draws no locking line, an exact model (error 0) none either."""
    page = (curved_dir / "paper-paper-curved.html").read_text()
    for sl in ("10", "100"):
        for name in ("axial force N", "shear force Q"):
            assert f"semicircle, normal tip force, L/h = {sl}: {name}" in page
    assert "locking_slope" in page and page.count("pd-curved primal n=41") >= 3  # deflection, N, Q (+ locking)
    lock = page[page.index('id="locking"') :]
    lock = lock[: lock.index("</svg>")]
    assert "pd-curved primal n=41" in lock and "pd-curved n=41" in lock
    assert "n=21" not in lock and "exact-curved-cantilever" not in lock
    # the paper's four error measures: a table per scene, a column per quantity
    measures = page[page.index("<h4>Error measures</h4>") :]
    measures = measures[: measures.index("</table>")]
    for column in ("err_max", "err_max_rotation", "err_max_moment", "err_max_axial"):
        assert f'title="{column}"' in measures
    # the index: each quantity's error along the arc, the deformed axis, rotation and moment along the arc
    titles = [f["title"] for f in figures_of((curved_dir / "index.html").read_text())]
    for sl in ("10", "100"):
        head = f"semicircle, normal tip force, L/h = {sl}: "
        for name in ("rotation", "bending moment M", "axial force N"):
            assert head + f"{name}, error along the beam" in titles
        assert any(t.startswith(head + "deformed axis") for t in titles)
        assert head + "bending moment M along the curved axis" in titles


@pytest.mark.slow
def test_curved_quantity_figures_draw_in_chromium(curved_dir, tmp_path):
    """The quantities' error figures and the deformed axis draw in headless Chromium without a console error; the
    model filter keeps the exact run's deformed axis (a guide) and hides its lines elsewhere."""
    chromium = find_chromium()
    with Browser(chromium, tmp_path / "profile") as browser:
        browser.open((curved_dir / "index.html").as_uri())
        browser.evaluate("window.pdvFigures.drawAll()")
        assert not browser.console_errors(), browser.console_errors()
        titles = browser.evaluate(
            "Array.from(document.querySelectorAll('figure.pfig .ftitle')).map(function (t) { return t.textContent; })"
        )
        state = browser.evaluate(STATE)
        drawn = dict(zip(titles, state["figures"], strict=True))
        ours = [t for t in titles if "bending moment M" in t or "axial force N, error" in t or "deformed axis" in t]
        assert len(ours) == 2 * 4 and all(drawn[t]["paths"] >= 1 for t in ours)
        state = choose(browser, "model", "pd-curved")
        shape = next(f for t, f in zip(titles, state["figures"], strict=True) if "deformed axis" in t)
        assert not shape["hidden"] and "exact-curved-cantilever" not in shape["lines"]
        assert any("exact-curved-cantilever" in text for text in shape["legend"])


def test_a_scenes_file_that_is_a_fifo_is_not_read(tmp_path):
    """scenes.json as a FIFO: its read blocked the report (the case files' and meta.json's twin); it reads as a
    study run before scenes.json was written."""
    from pdverify.report.inputs import SCENES, StudyFolder

    os.mkfifo(tmp_path / SCENES)
    assert StudyFolder(tmp_path, {}, pd.DataFrame())._scene_texts == {}
