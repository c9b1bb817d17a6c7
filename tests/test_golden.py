"""Regression: every paper benchmark's curve against its golden file (rtol 1e-10 of the largest value).

Regenerate with `python -m pdverify.golden --regenerate` and explain the change in the commit message.

One exception, for round-off the model cannot control: pd-curved's primal form builds its operator from
PDDO weights computed by LAPACK QR, whose last bits depend on the CPU's BLAS kernels (OpenBLAS picks
Haswell or SkylakeX kernels at run time); the solution then moves by up to cond * eps. Measured between
the two kernels on the same inputs: semicircle, 401 particles, 5.6e-10 = 8e-3 cond eps (cond 3.2e8).
Those cases are compared at max(1e-10, cond * eps), cond being the run's own condition estimate. The
mixed form is not widened: its weights come from the same QR but its answers moved by 1e-14 (its
estimate of 1e13 describes the resultant unknowns, not w), and every other model's operator has exact
coefficients (pd-eb and pd-bond-pair compute their ghost maps in rational arithmetic for this reason).
"""

import json

import numpy as np
import pytest

from pdverify.golden import CASES, GOLDEN, compute, key


@pytest.mark.parametrize("scene,model,options", CASES, ids=[key(*c) for c in CASES])
def test_golden(scene, model, options):
    path = GOLDEN / f"{key(scene, model, options)}.json"
    assert path.exists(), f"missing golden file {path.name}: run python -m pdverify.golden --regenerate"
    want = json.loads(path.read_text())
    got = compute(scene, model, options)
    assert np.allclose(got["x"], want["x"], rtol=0, atol=1e-14)
    w, w0 = np.array(got["w"]), np.array(want["w"])
    rtol = 1e-10
    if model.startswith("pd-curved") and options.get("form") == "primal":
        rtol = max(rtol, got["cond"] * np.finfo(float).eps)
    assert np.abs(w - w0).max() <= rtol * np.abs(w0).max()
    if "u" in want:
        u, u0 = np.array(got["u"]), np.array(want["u"])
        assert np.abs(u - u0).max() <= rtol * np.abs(u0).max()


def test_same_inputs_same_numbers_bitwise():
    """Reproducibility: the stable time step comes from an eigenvalue solve (ARPACK, whose default start
    vector is random); two runs of a transient and of a static solve give identical bits."""
    from pdverify.golden import ROOT
    from pdverify.registry import run
    from pdverify.scene import load_scene

    sc = load_scene(ROOT / "studies" / "paper_moyer" / "beam_example2.toml")
    a, b = (run(sc, "pd-timoshenko", points=41, horizon=1) for _ in range(2))
    assert a.info["dt"] == b.info["dt"] and np.array_equal(a.w, b.w)
    sc = load_scene(ROOT / "studies" / "paper_curved" / "semicircle_normal.toml")
    a, b = (run(sc, "pd-curved", points=101) for _ in range(2))
    assert np.array_equal(a.w, b.w) and a.info.get("cond") == b.info.get("cond")
