"""The bench command runs and reports ratios; no timing assertions (numbers belong in the report)."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from pdverify.bench import bench_case, cost_slope

ROOT = Path(__file__).parents[1]


def test_bench_json_lines():
    r = subprocess.run([sys.executable, "-m", "pdverify.cli", "bench", "-m", "exact-eb", "--points", "101",
                        "--points", "1001", "--format", "json"], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    rows = [json.loads(l) for l in r.stdout.splitlines()]
    assert [row.get("points") for row in rows[:2]] == [101, 1001]
    assert all(row["status"] == "ok" and row["total_s"] > 0 for row in rows[:2])
    assert rows[-1]["model"] == "exact-eb" and "cost_slope" in rows[-1]


def test_limit_is_banded_solve_of_the_models_matrix(monkeypatch):
    """A model with assemble() gets limit_s from the banded solve of exactly that matrix."""
    from pdverify import registry
    from pdverify.exact.models import ExactBeam

    class Tridiag(ExactBeam):
        def assemble(self, scene, params):
            n = params["points"]
            K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()
            return K, np.ones(n)

    m = Tridiag("tridiag-test", False, "test")
    monkeypatch.setitem(registry.models(), "tridiag-test", m)
    row = bench_case("tridiag-test", 2001)
    assert row["bandwidth"] == 3 and row["limit_s"] > 0 and row["ratio"] == row["total_s"] / row["limit_s"]


def test_cost_slope_recovers_power():
    rows = [{"model": "m", "status": "ok", "points": n, "total_s": 1e-6 * n**1.5} for n in (10, 100, 1000)]
    assert abs(cost_slope(rows)["m"] - 1.5) < 1e-12
