"""pdverify.testing: assertions a PD code's CI can use, and their failure messages."""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.testing import assert_converges, assert_matches, convergence_table

UNIFORM = [{"type": "distributed", "value": -1000.0}]


def test_fem_timoshenko_full_integration_fails_order_2_with_the_table():
    """Linear elements with full integration lock (L/h = 100): the message shows every grid's error and order."""
    scene = scene_dict("clamped", "free", UNIFORM, section={"width": 0.05, "height": 0.02})
    with pytest.raises(AssertionError) as exc:
        assert_converges("fem-timoshenko", scene, order=2, grids=(11, 21, 41), variant="full")
    msg = str(exc.value)
    rows = convergence_table("fem-timoshenko", scene, (11, 21, 41), variant="full")
    assert msg.startswith("fem-timoshenko on 'test beam' against the exact solution: fitted order")
    lines = msg.splitlines()
    assert lines[1].split() == ["points", "spacing", "error", "order"]
    for r, line in zip(rows, lines[2:], strict=True):  # the table holds each grid's measured error
        assert line.split()[:3] == [str(r["points"]), f"{r['spacing']:.3e}", f"{r['error']:.3e}"]
    assert rows[-1]["error"] > 0.1  # locked: far from the answer on every grid


def test_pd_eb_converges_at_order_2():
    scene = scene_dict("clamped", "clamped", [{"type": "distributed", "value": -1000.0, "shape": "sine"}])
    rows = assert_converges("pd-eb", scene, order=2, grids=(21, 41, 81))
    assert all(abs(r["order"] - 2) < 0.1 for r in rows[1:])


def test_a_higher_order_theory_converges_against_itself_by_default():
    """pd-higher-order has no exact solution here: the default reference is the model on a 4x finer nested grid
    (as pdverify verify), where it is second order on a pinned-pinned beam; against exact Timoshenko it would
    stall at the theories' O((h/L)^2) difference."""
    scene = scene_dict("pinned", "pinned", UNIFORM)
    rows = assert_converges("pd-higher-order", scene, order=2, grids=(21, 41, 81, 161))
    assert rows[-1]["error"] < 1e-4
    gap = convergence_table("pd-higher-order", scene, (21, 41, 81, 161), reference="exact-timoshenko")
    assert gap[-1]["error"] > 10 * rows[-1]["error"] and abs(gap[-1]["order"]) < 1  # stalls at the gap


def test_assert_matches_passes_and_fails_with_the_worst_points():
    scene = scene_dict("pinned", "pinned", UNIFORM)
    e = assert_matches("fem-eb", "exact-eb", scene, rtol=1e-8, points=41)
    assert e < 1e-8  # Hermite cubics are nodally exact for EB beams (round-off apart)
    with pytest.raises(AssertionError) as exc:
        assert_matches("pd-eb", "exact-eb", scene, rtol=1e-6, points=21, variant="paper")
    msg = str(exc.value).splitlines()
    assert msg[0].startswith("pd-eb on 'test beam' against exact-eb: error") and "(21 points)" in msg[0]
    assert msg[1].split() == ["x", "w", "w_ref", "|diff|/max|w_ref|"] and len(msg) == 2 + 8


def test_a_function_as_reference():
    """Pinned-pinned beam under q0 sin(pi x / L): w = q0 (L / pi)^4 sin(pi x / L) / EI (Timoshenko & Gere)."""
    d = scene_dict("pinned", "pinned", [{"type": "distributed", "value": -1000.0, "shape": "sine"}])
    L, EI = d["beam"]["length"], d["material"]["youngs_modulus"] * 0.05 * 0.1**3 / 12

    def sine_deflection(x):
        return -1000.0 * (L / np.pi) ** 4 * np.sin(np.pi * x / L) / EI

    assert assert_matches("exact-eb", sine_deflection, d, rtol=1e-12, points=11) < 1e-12
    assert_converges("pd-eb", d, order=2, grids=(41, 81, 161), reference=sine_deflection)
    with pytest.raises(
        AssertionError, match=r"against sine_deflection: fitted order 1\.9\d, expected 1 ± 0\.1\n +points"
    ):
        assert_converges("pd-eb", d, order=1, grids=(41, 81, 161), reference=sine_deflection)
