"""HTML report: renders in headless Chromium with no console errors, links resolve, numbers trace to
results.csv, and re-running gives the same HTML apart from the timestamp."""

import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdverify.report import build_report
from pdverify.report.build import fmt
from pdverify.study import load_study, run_study

ROOT = Path(__file__).parents[1]


@pytest.fixture(scope="module")
def study_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    p = out / "study.toml.in"
    p.write_text((ROOT / "studies/paper_diyaroglu.toml").read_text().replace('"paper_diyaroglu/', f'"{ROOT}/studies/paper_diyaroglu/')
                 + '\n[papers]\npaper_diyaroglu = "Diyaroglu, Oterkus and Oterkus"\n')
    p = p.rename(out / "diy.toml")
    run_study(load_study(p), out / "run", workers=1, progress=False)
    build_report(out / "run")
    return out / "run"


class Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.hrefs, self.svgs = [], 0

    def handle_starttag(self, tag, attrs):
        if tag == "a":
            self.hrefs.append(dict(attrs).get("href"))
        if tag == "svg":
            self.svgs += 1


def test_links_resolve_and_figures_present(study_dir):
    page = (study_dir / "index.html").read_text()
    p = Links()
    p.feed(page)
    assert p.svgs >= 5  # 3 deflection + 3 convergence + speed/error
    ids = set(re.findall(r'id="([^"]+)"', page))
    for h in p.hrefs:
        if h.startswith("#"):
            assert h[1:] in ids, h
        else:
            assert (study_dir / h).exists(), h
    # no network requests: nothing is loaded from a URL (XML namespaces are names, not requests)
    assert not re.search(r'(src|href)="(https?:)?//', page) and "url(http" not in page


def test_one_page_per_paper_linked_both_ways(study_dir):
    index = (study_dir / "index.html").read_text()
    page_file = study_dir / "paper-paper-diyaroglu.html"
    assert 'href="paper-paper-diyaroglu.html"' in index and "Diyaroglu, Oterkus and Oterkus" in index
    page = page_file.read_text()
    p = Links()
    p.feed(page)
    assert "index.html" in p.hrefs and p.svgs >= 6  # 3 deflection + 3 convergence (+ horizon)
    ids = set(re.findall(r'id="([^"]+)"', page))
    assert all((h[1:] in ids) if h.startswith("#") else (study_dir / h).exists() for h in p.hrefs)
    # the page's benchmark rows are the study's rows for this paper: every computed value is shown
    bench = pd.read_csv(study_dir / "benchmarks.csv")
    for _, b in bench.iterrows():
        assert f">{fmt(b['computed'])}<" in page


def test_time_histories_plotted_and_written_as_csv(tmp_path, monkeypatch):
    """A dynamic model's history (info["history"]) becomes a figure on the report and a CSV file."""
    from pdverify import registry
    from pdverify.registry import Model, Option
    from pdverify.result import Result

    class Ringing(Model):
        name = "ringing-test"
        kind = "dynamic"
        options = (Option("points", int, 11, minimum=2),)

        def solve(self, scene, params):
            x = np.linspace(0, scene.length, params["points"])
            t = np.linspace(0, 1, 201)
            mid = 0.1 * (1 - np.cos(2 * np.pi * 5 * t) * np.exp(-t))
            return Result(scene.name, self.name, dict(params), x, 0 * x, dofs=len(x),
                          info={"history": {"t": t, "series": {"midpoint": mid}}})

    monkeypatch.setitem(registry.models(), "ringing-test", Ringing())
    p = tmp_path / "dyn.toml"
    p.write_text(f'name = "dyn"\nscenes = ["{ROOT}/studies/paper_diyaroglu/clamped_clamped.toml"]\nreference = "none"\n'
                 '[[runs]]\nmodel = "ringing-test"\npoints = [11, 21]\n')  # two cases: a serial run's recorder path
    df = run_study(load_study(p), tmp_path / "run", workers=1, progress=False)
    for case_id in df["case_id"]:
        h = pd.read_csv(tmp_path / "run" / "histories" / f"{case_id}.csv")
        assert list(h.columns) == ["t", "midpoint"] and len(h) == 201
        assert np.allclose(h["midpoint"], 0.1 * (1 - np.cos(2 * np.pi * 5 * h["t"]) * np.exp(-h["t"])), rtol=1e-15)
    page = build_report(tmp_path / "run").read_text()
    assert "time history" in page and "t (s)" in page


def test_numbers_trace_to_results(study_dir):
    page = (study_dir / "index.html").read_text()
    res = pd.read_csv(study_dir / "results.csv")
    bench = pd.read_csv(study_dir / "benchmarks.csv")
    for _, b in bench.iterrows():
        row = res[res["case_id"] == b["case_id"]].iloc[0]
        assert b["computed"] == row["w_at_max"] and b["err_max"] == row["err_max"]
        assert f">{fmt(row['w_at_max'])}<" in page and f">{fmt(row['err_max'])}<" in page


def test_rebuild_is_identical_apart_from_timestamp(study_dir, tmp_path):
    a = (study_dir / "index.html").read_text()
    b = build_report(study_dir, tmp_path).read_text()
    strip = lambda s: re.sub(r'<span id="generated">[^<]*</span>', "", s)  # noqa: E731
    assert strip(a) == strip(b)


def test_opens_in_headless_chromium_without_console_errors(study_dir, tmp_path):
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    assert chromium, "Debian chromium is required for this test (.ci/run installs it)"
    shot = ROOT / "reports" / "_scratch" / "report_screenshot.png"
    shot.parent.mkdir(parents=True, exist_ok=True)
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={tmp_path / 'profile'}", "--enable-logging=stderr", "--v=0"]
    url = (study_dir / "index.html").as_uri()
    r = subprocess.run([chromium, *flags, f"--screenshot={shot}", "--window-size=1280,2400", url],
                       capture_output=True, text=True, timeout=120)
    assert shot.exists() and shot.stat().st_size > 10_000
    console = [l for l in r.stderr.splitlines() if "CONSOLE" in l or "Uncaught" in l]
    assert not console, console
    # the DOM after scripts ran: every inline SVG figure is in it, with a non-empty drawing
    dom = subprocess.run([chromium, *flags, "--dump-dom", url], capture_output=True, text=True, timeout=120).stdout
    assert dom.count("<svg") >= 5 and dom.count("<path") > 50
    # the per-paper page too
    url = (study_dir / "paper-paper-diyaroglu.html").as_uri()
    r = subprocess.run([chromium, *flags, "--dump-dom", url], capture_output=True, text=True, timeout=120)
    console = [l for l in r.stderr.splitlines() if "CONSOLE" in l or "Uncaught" in l]
    assert not console and r.stdout.count("<svg") >= 6, console


def test_plane_stress_images_and_vtu_links(tmp_path):
    """A study with a plane-stress case writes its VTU and an off-screen PNG; the report inlines the
    picture and links the VTU."""
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
    page = build_report(tmp_path / "run").read_text()
    for png in pngs:
        assert f'href="vtu/{png.stem}.vtu"' in page and (tmp_path / "run" / "vtu" / f"{png.stem}.vtu").exists()
    assert "data:image/png;base64," in page
