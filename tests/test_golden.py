"""Regression: every paper benchmark's curve against its golden file (rtol 1e-10 of the largest value).

Regenerate with `python -m pdverify.golden --regenerate` and explain the change in the commit message.
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
    assert np.abs(w - w0).max() <= 1e-10 * np.abs(w0).max()
    if "u" in want:
        u, u0 = np.array(got["u"]), np.array(want["u"])
        assert np.abs(u - u0).max() <= 1e-10 * np.abs(u0).max()


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
