"""`pdverify bench --large-horizon` (pdverify/apps/bench_horizon.py): the Krylov and the banded solve of the same
PD system at a fixed horizon length, each timed in its own process, and their difference. At the bench's own size
(2^14 + 1 points) it is a benchmark, not a test; here a small grid checks the row, the agreement and the page."""

import json

import pytest
from helpers import cli

from pdverify.apps.bench_horizon import AGREE


@pytest.mark.slow
def test_rows_agree_and_the_page_shows_them(tmp_path, capsys):
    code, out, err = cli(["bench", "--large-horizon", "--points", "161", "--format", "json", "--out", tmp_path], capsys)
    assert code in (0, None), err
    rows = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    assert [r["model"] for r in rows] == ["pd-eb", "pd-bond-pair"]
    for r in rows:
        assert r["status"] == "ok" and r["m"] == pytest.approx(16.0)
        assert r["difference"] <= AGREE and r["agrees"]
        assert r["krylov_s"] > 0 and r["banded_s"] > 0
    page = (tmp_path / "index.html").read_text()
    assert "Krylov beside banded" in page and "krylov_s" in page
    assert len((tmp_path / "bench_large_horizon.jsonl").read_text().splitlines()) == 2


def test_a_model_without_the_krylov_path_is_refused(capsys):
    code, _, err = cli(["bench", "--large-horizon", "-m", "pd-rod"], capsys)
    assert code == 2 and "--model pd-rod: --large-horizon times pd-eb, pd-bond-pair" in err
