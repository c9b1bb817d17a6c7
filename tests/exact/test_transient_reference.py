"""The exact modal transient of the rod (exact-modal-rod) and pd-rod's time-history error
against it: order 2 in dx and in dt."""

import numpy as np
import pytest
from helpers import ROOT, scene_dict
from transients import PROBES, semi_discrete

from pdverify.core.scene_file import parse_scene
from pdverify.exact.modal import rod_response
from pdverify.papers.moyer import operator as O
from pdverify.papers.moyer import spectrum as S
from pdverify.papers.moyer import transient as TR
from pdverify.registry import run

MATERIAL = {"youngs_modulus": 70e9, "poissons_ratio": 0.33, "density": 2700.0}
T_END = 2e-3
SINE = [{"type": "distributed", "value": 0.0, "axial": 3000.0, "shape": "sine"}]
UNIFORM = [{"type": "distributed", "value": 0.0, "axial": 3000.0}]
PARTIAL = [{"type": "distributed", "value": 0.0, "axial": 3000.0, "start": 0.3, "end": 1.2}]


def _scene(loads, left="clamped", right="free", **dyn):
    return parse_scene(
        scene_dict(left, right, loads, material=MATERIAL, dynamics=dict({"end_time": T_END, "probes": PROBES}, **dyn))
    )


def test_modal_sum_meets_its_static_limit_and_the_truncation_estimate():
    """Damped to rest (ζ = 1: every mode decays as e^{-ω1 t}, t = 2 s), the modal sum is the static solution
    of the clamped-free rod under q on [a, b]: EA u' = N(x) = q (b - max(x, a))⁺, integrated exactly (the grid
    holds a and b). Measured 5.9e-6 with 64 modes (estimate 7.7e-5), 3.6e-9 with 1024 (estimate 3.0e-7): the
    estimate bounds the error (it also covers the dynamic part's overshoot)."""
    sc = _scene(PARTIAL, damping_ratio=1.0)
    EA, a, b, q = sc.EA, 0.3, 1.2, 3000.0
    x = np.linspace(0, 2, 81)
    N = q * np.clip(b - np.maximum(x, a), 0, None)
    u_static = np.concatenate([[0], np.cumsum((N[1:] + N[:-1]) / 2 * np.diff(x))]) / EA  # N linear per piece
    for tolerance, bound in ((1e-4, 2e-5), (1e-6, 1e-8)):
        u, info = rod_response(sc, x, [2.0], tolerance=tolerance)
        err = np.abs(u[0] - u_static).max() / np.abs(u_static).max()
        assert info["truncation_error"] < tolerance and err < bound and err < info["truncation_error"]


def test_exact_modal_rod_is_a_dynamic_reference_model():
    sc = _scene(SINE, output_interval=1e-5)
    r = run(sc, "exact-modal-rod", points=41)
    h = r.info["history"]
    assert len(h["t"]) == 201 and set(h["series"]) == {"u(x=1)", "u(x=2)"}
    u, _ = rod_response(sc, PROBES, h["t"])
    assert np.allclose(np.column_stack(list(h["series"].values())), u, rtol=1e-12, atol=0)  # BLAS blocking
    assert r.fields["u"][-1] == pytest.approx(h["series"]["u(x=2)"][-1], rel=1e-12)


def _pd(sc, n, dt_steps, record_every, m=3):
    disc = O.rod_operator(sc, n, m, "corrected")
    return disc, TR.integrate(
        disc, {}, None, dt=T_END / dt_steps, steps=dt_steps, stabilisation=0.0, probes=PROBES, record_every=record_every
    )


def test_pd_rod_history_converges_at_order_two_in_dx():
    """Sine load (smooth; clamped-free), m = 3, dt = 0.5 of the stable step (the time error falls as dx² with
    it and is ~7 % of the total), the history at two probes against exact-modal-rod: measured max errors
    3.2e-3, 8.3e-4, 2.1e-4, 5.3e-5 at 41..321 points, orders 1.96, 1.98, 2.00. (A load with a jump, or one
    not zero at the clamped end, starts wave fronts: orders 1.2-1.35, docs/models/moyer.md.)"""
    sc = _scene(SINE)
    err = []
    for n in (41, 81, 161, 321):
        disc = O.rod_operator(sc, n, 3, "corrected")
        steps = int(np.ceil(T_END / (0.5 * S.stable_time_step(disc))))
        _, h = _pd(sc, n, steps, max(1, steps // 100))
        ref, _ = rod_response(sc, PROBES, h.t)
        err.append(np.abs(h.values - ref).max() / np.abs(ref).max())
    rate = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(rate - 2) < 0.3), (err, rate)


@pytest.mark.parametrize("loads", [SINE, UNIFORM, PARTIAL], ids=["sine", "uniform", "partial"])
def test_pd_rod_history_converges_at_order_two_in_dt(loads):
    """81 points, m = 3, dt = T/N with N = 4 N0 .. 32 N0 (N0 from 0.8 of the stable step: dt = 0.2 to 0.025 of
    it), sampled at the same 50 times. Against exact-modal-rod the space error (~1e-3 here) hides the time
    error at every stable dt (an explicit step is at most ~dx/c, so both fall as dx²), so the reference is the
    exact time solution of the same operator (_semi_discrete; its space error is the dx test's). The error is
    the RMS over the samples at both probes: measured orders 1.79-2.00 (sine), 1.99-2.00 (uniform, partial).
    The max over the samples is noisier (sine: 1.98, 2.04, 1.22, 1.97, 2.01 from 0.8 of the step down), and
    at 0.8 and 0.4 of the step the partial load's is pre-asymptotic (1.40, 1.70)."""
    sc = _scene(loads)
    disc = O.rod_operator(sc, 81, 3, "corrected")
    n0 = 50 * int(np.ceil(T_END / (0.8 * S.stable_time_step(disc)) / 50))
    err = []
    for j in range(2, 6):
        _, h = _pd(sc, 81, n0 * 2**j, n0 * 2**j // 50)
        ref = semi_discrete(disc, h.t)
        err.append(np.sqrt(((h.values - ref) ** 2).mean() / (ref**2).mean()))
    rate = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(rate - 2) < 0.3), (err, rate)


@pytest.mark.slow
def test_transient_study_measures_the_histories(tmp_path):
    """studies/paper_moyer_transient.toml: the runner measures a transient against exact-modal-rod (-timoshenko) on the
    histories (study.runner.history_errors), not on the final w (0 for a rod). pd-rod runs without the
    stabilisation (its closures have a real spectrum), so the dx series converges at second order (measured
    with the mirror-image ghosts 1.27e-3, 3.17e-4, 8.17e-5, 2.08e-5: 1.97; with the fitted ghosts 3.1e-3 .. 5.0e-5;
    with the stabilisation 0.98-0.99). The dt series at 81 points is mostly the space error (7.1e-4, 7.9e-4,
    8.1e-4 at 4, 2, 1 us); the time error is the differences, (e4 - e1) / (e2 - e1) = 5.48, i.e. order 2.16 in dt
    (5 for order 2)."""
    import pandas as pd

    from pdverify import run_study
    from pdverify.core.scene_file import load_scene
    from pdverify.papers.moyer.model import simulate

    root = ROOT / "studies"
    df = run_study(root / "paper_moyer_transient.toml", out=tmp_path / "s", workers=1, progress=False)
    sc = load_scene(root / "paper_moyer" / "rod_transient.toml")
    h = simulate(sc, {"points": 81, "horizon": 3}, model="pd-rod")
    ref, _ = rod_response(sc, PROBES, h.t)
    row = df[(df.scene_file == "paper_moyer/rod_transient.toml") & (df.points == 81)].iloc[0]
    assert row.err_max == pytest.approx(np.abs(h.values - ref).max() / np.abs(ref).max(), rel=1e-9)
    dt_rows = df[df.scene_file.str.contains("_dt")].sort_values("scene_file")  # dt1us, dt2us, dt4us
    e1, e2, e4 = dt_rows.err_max.to_numpy()
    assert len(dt_rows) == 3 and max(e1, e2, e4) / min(e1, e2, e4) < 1.2  # measured 1.14: the space error
    order = np.log2((e4 - e1) / (e2 - e1) - 1)  # (4^p - 1) / (2^p - 1) = 2^p + 1
    assert abs(order - 2) < 0.25, (e1, e2, e4, order)
    checks = pd.read_csv(tmp_path / "s" / "checks.csv")
    assert checks.verdict[0] == "pass" and abs(checks.observed_order[0] - 2) < 0.1, checks
    # the beam against exact-modal-timoshenko: m = 1, 2 first order (the stabilisation), m = 3, 4 blow up somewhere
    assert list(checks.verdict[1:5]) == ["expected-fail"] * 4 and (checks.observed_order[1:3] < 1.6).all(), checks
    # the FEM stand-in (Newmark) converges to the exact modal solution: an independent check of both (1.80)
    assert checks.verdict[5] == "pass" and abs(checks.observed_order[5] - 2) < 0.3, checks
    beam = df[df.scene_file == "paper_moyer/beam_transient.toml"]
    assert set(beam[beam.status == "failed"].horizon_factor) == {3, 4}, beam[["points", "horizon_factor", "status"]]
    # pinned-guided: mirror-image ghosts, no stabilisation, every case runs; m = 2, 3, 4 at second order (measured
    # 1.96, 1.95, 1.94; 7.4e-4 .. 1.3e-5 at m = 2), m = 1 below 1e-5 on every grid (6.2e-6 .. 3.2e-7), and the FEM
    # stand-in at 1.98
    pg = df[df.scene_file == "paper_moyer/beam_transient_pinned_guided.toml"]
    assert (pg.status == "ok").all() and len(pg) == 20, pg[["model", "points", "horizon_factor", "status"]]
    assert (pg[(pg.model == "pd-timoshenko") & (pg.horizon_factor == 1)].err_max < 1e-5).all()
    assert list(checks.verdict[6:10]) == ["pass"] * 4 and (abs(checks.observed_order[6:10] - 2) < 0.1).all(), checks
    # the cantilever with variant energy (symmetric: no growing mode), no stabilisation and no damping: every case
    # runs and m = 1..4 converge at second order (measured 2.00, 1.98, 1.96, 1.92)
    en = beam[beam.variant == "energy"]
    assert (en.status == "ok").all() and len(en) == 16, en[["points", "horizon_factor", "status"]]
    assert list(checks.verdict[10:14]) == ["pass"] * 4 and (abs(checks.observed_order[10:14] - 2) < 0.1).all(), checks
