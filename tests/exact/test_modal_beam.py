"""exact-modal-timoshenko (the Timoshenko beam's transient from rest as a sum of its modes) and fem-timoshenko's
Newmark transient, the two transient references of the beam."""

import numpy as np
import pytest
import scipy.linalg as sla
from helpers import ROOT, scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.exact.modal_beam import BeamModes, beam_response
from pdverify.registry import get_model, run

STEEL = {"youngs_modulus": 200e9, "poissons_ratio": 0.3, "density": 7850.0}
SLOW = pytest.mark.slow  # point loads (and load ends) converge like 1/modes: 1024 modes for the estimate, 4-6 s
CASES = [
    pytest.param("clamped", "free", [{"type": "point_force", "position": 2.0, "value": -1000.0}], marks=SLOW),
    pytest.param(
        "clamped", "clamped", [{"type": "distributed", "value": -800.0, "start": 0.3, "end": 1.1}], marks=SLOW
    ),
    pytest.param("pinned", "pinned", [{"type": "point_moment", "position": 0.5, "value": 300.0}], marks=SLOW),
    ("guided", "pinned", [{"type": "distributed", "value": -500.0, "shape": "sine"}]),
    pytest.param("pinned", "guided", [{"type": "point_force", "position": 2.0, "value": 700.0}], marks=SLOW),
]
UNIFORM = [{"type": "distributed", "value": -1000.0}]


def _scene(left, right, loads, slenderness=10.0, dynamics=None):
    d = scene_dict(left, right, loads, material=dict(STEEL))
    d["dynamics"] = {"end_time": 0.01, **(dynamics or {})}
    return parse_scene(d).with_slenderness(slenderness)


@pytest.mark.parametrize("left, right, loads", CASES)
def test_the_modal_sum_of_the_static_load_is_the_static_solution(left, right, loads):
    """Σ p_k w_k (the time average of the undamped response) is exact-timoshenko's deflection to within the
    truncation estimate the model reports (measured 1.5-5x below it), which is itself below 2e-4 here."""
    sc = _scene(left, right, loads)
    modes = BeamModes(sc)
    omega, coef, p, est = modes.truncated(1e-5)
    x = np.linspace(0.0, sc.length, 301)
    w = p @ modes.fields(omega, coef, x)[0]
    ex = run(sc.model_copy(update={"dynamics": None}), "exact-timoshenko", points=301).w
    err = np.abs(w - ex).max() / np.abs(ex).max()
    assert err <= est < 2e-4, (err, est, len(omega))


def test_pinned_pinned_sine_load_is_the_two_mode_closed_form():
    """Pinned-pinned under q0 sin(πx/L): w = W(t) sin(λx), γ = Γ(t) cos(λx), λ = π/L, and (W, Γ) obey
    diag(ρA, ρI) (W, Γ)'' + [[kGA λ², -kGA λ], [-kGA λ, EI λ² + kGA]] (W, Γ) = (q0, 0): a 2 x 2 problem solved here
    by scipy's generalised eigensolver, independent of the determinant's roots and the modes' quadrature."""
    q0, L = -2000.0, 2.0
    sc = _scene("pinned", "pinned", [{"type": "distributed", "value": q0, "shape": "sine"}], slenderness=5.0)
    lam, rho = np.pi / L, STEEL["density"]
    EI, kGA, A, inertia = sc.EI, sc.kGA, sc.section.A, sc.section.I
    K = np.array([[kGA * lam**2, -kGA * lam], [-kGA * lam, EI * lam**2 + kGA]])
    M = np.diag([rho * A, rho * inertia])
    w2, phi = sla.eigh(K, M)  # mass-normalised
    t = np.linspace(0.0, 0.01, 57)
    amp = phi @ np.diag(phi.T @ [q0, 0.0] / w2)  # (W, Γ) per mode
    W = (amp[0] * (1 - np.cos(np.outer(t, np.sqrt(w2))))).sum(1)
    x = np.array([0.3, 1.0, 1.7])
    w, g, info = beam_response(sc, x, t, tolerance=1e-10)
    want = np.outer(W, np.sin(lam * x))
    assert np.abs(w - want).max() < 1e-9 * np.abs(want).max() and info["truncation_error"] < 1e-10


@pytest.mark.parametrize(
    "dynamics, loads, words",
    [
        ({"damping_ratio": 0.05, "damping_on": "translations"}, UNIFORM, "couples the beam's modes"),
        ({"left": {"displacement": {"type": "step", "amplitude": 0.01}}}, UNIFORM, "no prescribed end motions"),
        ({}, [{"type": "point_force", "position": 2.0, "value": 0.0, "axial": 100.0}], "no axial displacement"),
    ],
)
def test_what_it_cannot_represent_is_declined_in_one_line(dynamics, loads, words):
    sc = _scene("clamped", "free", loads, dynamics=dynamics)
    why = get_model("exact-modal-timoshenko").check(sc)
    assert len(why) == 1 and words in why[0], why


def test_solve_gives_histories_at_the_probes_and_the_final_field():
    sc = _scene("clamped", "free", UNIFORM, dynamics={"probes": [1.0, 2.0], "output_interval": 1e-3})
    r = run(sc, "exact-modal-timoshenko", points=21)
    series = r.info["history"]["series"]
    assert list(series) == ["w(x=1)", "w(x=2)"] and len(r.info["history"]["t"]) == 11
    w, _, _ = beam_response(sc, [2.0], [0.01])
    assert r.w[-1] == pytest.approx(w[0, 0], rel=1e-12) and r.rotation is not None


def test_newmark_is_the_trapezoidal_rule_exactly():
    """One DOF, M = 1, K = ω², F from rest: the average-acceleration scheme gives u_n = F/K (1 - cos ω̃ t_n) with
    ω̃ = (2/dt) atan(ω dt / 2) (its phase error, no amplitude error), here to round-off over 400 steps."""
    import scipy.sparse as sp

    from reference_fem.newmark import newmark

    w, F, dt = 30.0, 2.0, 0.02
    t, u, _ = newmark(sp.eye(1) * w**2, sp.eye(1), sp.csr_matrix((1, 1)), np.array([F]), dt, 400, sp.eye(1))
    wt = 2 / dt * np.arctan(w * dt / 2)
    assert np.abs(u[:, 0] - F / w**2 * (1 - np.cos(wt * t))).max() < 1e-12 * F / w**2


@pytest.mark.parametrize("shift", [4.0, -1.0])  # positive definite (banded Cholesky), negative definite (sparse LU)
@pytest.mark.parametrize("half_band", [1, 3, 70])  # 70: wider than BANDED_MAX (sparse LU)
def test_newmark_step_solves_are_the_matrix_inverse(shift, half_band):
    """The step's factorisation (reference_fem.newmark.factorised) solves S u = r to round-off whichever path it takes:
    a symmetric matrix with a narrow band, positive definite or not, and one too wide to factorise as a band."""
    import scipy.sparse as sp

    from reference_fem.newmark import factorised

    n = 300
    rng = np.random.default_rng(half_band)
    bands = {k: rng.uniform(-1, 1, n - k) / (2 * half_band) for k in range(1, half_band + 1)}
    S = sp.diags([np.full(n, shift), *bands.values(), *bands.values()], [0, *bands, *(-k for k in bands)])
    r = rng.standard_normal(n)
    u = factorised(S)(r)
    cond = np.linalg.cond(S.toarray())
    assert np.abs(S @ u - r).max() < 10 * n * cond * np.finfo(float).eps * np.abs(r).max()
    assert np.abs(u - np.linalg.solve(S.toarray(), r)).max() < 10 * n * cond * np.finfo(float).eps * np.abs(u).max()


@pytest.mark.slow
def test_fem_transient_converges_to_the_exact_modal_solution():
    """fem-timoshenko's Newmark transient (IIE stiffness, consistent linear mass, dt = the Courant-1 step) against
    exact-modal-timoshenko on a cantilever (studies/paper_moyer/beam_transient.toml): second order, 1.4e-3 ..
    3.3e-5 at 21 .. 161 nodes (measured; 8.5e-6 at 321): two independent methods agreeing."""

    from pdverify.core.scene_file import load_scene

    sc = load_scene(ROOT / "studies/paper_moyer/beam_transient.toml")
    ex = get_model("exact-modal-timoshenko")
    errs = []
    for n in (21, 41, 81):
        h = run(sc, "fem-timoshenko", points=n).info["history"]
        got = np.column_stack(list(h["series"].values()))
        want = ex.history_at(sc, ex.resolve(sc, {}), [1.0, 2.0], np.asarray(h["t"]))
        errs.append(np.abs(got - want).max() / np.abs(want).max())
    rates = np.log2(np.array(errs[:-1]) / errs[1:])
    assert np.all(np.abs(rates - 2) < 0.3) and errs[-1] < 2e-4, (errs, rates)


@pytest.mark.slow
def test_damped_modal_reference_and_both_transients_agree():
    """Mass-proportional damping (damping_on = "all", the default) keeps the modes uncoupled, so the modal sum is
    exact with it: ζ = 0.2 of the first mode on the pinned-guided beam of the transient study. fem-timoshenko
    (its own ω1) converges to it at second order (measured 2.38e-4, 6.05e-5, 1.56e-5 at 41 .. 161 nodes: 1.97,
    1.96) and so does pd-timoshenko m = 3 (2.77e-4, 6.88e-5, 1.78e-5 at 81 .. 321 points: 2.01, 1.95); with ζ = 1 the
    sum settles to exact-timoshenko's static deflection (after 20 first periods: 2.3e-11, its truncation estimate
    7.6e-9). damping_on = "translations" couples the modes: the reference declines it."""

    from pdverify.core.scene_file import load_scene

    base = load_scene(ROOT / "studies/paper_moyer/beam_transient_pinned_guided.toml")
    sc = base.model_copy(update={"dynamics": base.dynamics.model_copy(update={"damping_ratio": 0.2})})
    ex = get_model("exact-modal-timoshenko")
    for model, grids, order in (("fem-timoshenko", (41, 81, 161), 2), ("pd-timoshenko", (81, 161, 321), 2)):
        errs = []
        for n in grids:
            h = run(sc, model, points=n).info["history"]
            got = np.column_stack(list(h["series"].values()))[:, :2]
            want = ex.history_at(sc, ex.resolve(sc, {}), [1.0, 2.0], np.asarray(h["t"]))
            errs.append(np.abs(got - want).max() / np.abs(want).max())
        rates = np.log2(np.array(errs[:-1]) / errs[1:])
        assert np.all(np.abs(rates - order) < 0.2), (model, errs, rates)
    T1 = 2 * np.pi / BeamModes(sc).beam.frequencies(1)[0]
    w, _, info = beam_response(
        sc.model_copy(update={"dynamics": sc.dynamics.model_copy(update={"damping_ratio": 1.0})}),
        [1.0, 2.0],
        [20 * T1],
        1e-8,
    )
    static = run(sc.model_copy(update={"dynamics": None}), "exact-timoshenko", points=3).w[1:]
    assert np.abs(w[0] - static).max() < max(info["truncation_error"], 1e-8) * np.abs(static).max()
    bad = sc.model_copy(update={"dynamics": sc.dynamics.model_copy(update={"damping_on": "translations"})})
    assert any("damping_on" in m for m in ex.check(bad))


@pytest.mark.slow
@pytest.mark.parametrize("left, right", [("clamped", "free"), ("pinned", "guided"), ("clamped", "clamped")])
def test_damped_fem_transient_settles_to_the_static_solve(left, right):
    """A damped run settles to the direct static solve on the same mesh: ζ = 1 of the first mode, 20 first
    periods, dt = T1/2000. With the damping on every DOF (damping_on = "all", the default: C = 2ζω1 M, every mode
    decays like e^{-ζ ω1 t}) to round-off: measured 3.6e-13, 2.1e-12, 8.9e-14. On the translations alone (Moyer &
    Miraglia's Eq. 36-37) the rotation-dominated modes of the second spectrum are barely damped and keep ringing:
    4.0e-7, 4.5e-7, 6.3e-6. (At dt = T1/200 even the damping on every DOF leaves 2.6e-6 / 4.8e-7 / 1.0e-10: the
    trapezoidal rule's amplification of the modes with ω dt >> 1 tends to -1, so they hardly decay.)"""
    loads = [{"type": "distributed", "value": -1000.0}, {"type": "point_moment", "position": 0.7, "value": 50.0}]
    static = _scene(left, right, loads, dynamics=None).model_copy(update={"dynamics": None})
    r0 = run(static, "fem-timoshenko", points=41)
    T1 = 2 * np.pi / BeamModes(_scene(left, right, loads)).beam.frequencies(1)[0]  # the first period
    off = {}
    for on in ("all", "translations"):
        dyn = {"end_time": 20 * T1, "damping_ratio": 1.0, "time_step": T1 / 2000, "damping_on": on}
        r = run(_scene(left, right, loads, dynamics=dyn), "fem-timoshenko", points=41)
        off[on] = np.abs(r.w - r0.w).max() / np.abs(r0.w).max()
    assert off["all"] < 1e-10 and off["translations"] > 1e-7, off


def test_fem_modes_use_the_consistent_mass_and_converge_at_order_two():
    """fem-timoshenko gives its transient's K and consistent mass (modes = True); `pdverify modes` solves
    K φ = λ M φ densely up to 300 free DOFs and with ARPACK above (101 and 201 nodes here: both paths): the lowest
    three frequencies against the analytic ones fall 4x per halving (measured ratios 3.99-4.00)."""
    from pdverify.measure.modes import modes

    sc = _scene("clamped", "free", UNIFORM)
    tables = [modes(sc, "fem-timoshenko", {"points": n}, 3) for n in (101, 201)]
    err = [np.abs(t.omega / t.analytic - 1) for t in tables]
    assert np.all(np.abs(err[0] / err[1] - 4) < 0.1), err


def test_fem_transient_writes_its_histories_as_csv(tmp_path):
    """`pdverify solve ... --out h.csv` on a transient writes the probes' histories (as pd-timoshenko's do)."""
    sc = _scene("clamped", "free", UNIFORM, dynamics={"probes": [1.0, 2.0], "output_interval": 1e-3})
    r = run(sc, "fem-timoshenko", points=21)
    r.writers[".csv"](str(tmp_path / "h.csv"))
    lines = (tmp_path / "h.csv").read_text().splitlines()
    t = r.info["history"]["t"]
    assert lines[0] == "t,w(x=1),w(x=2)" and len(lines) == 1 + len(t) == 12  # 0 ... end_time by output_interval
    np.testing.assert_allclose(t, np.arange(11) * 1e-3, rtol=0, atol=1e-12 * sc.dynamics.end_time)
    assert t[-1] == pytest.approx(sc.dynamics.end_time, rel=1e-12)  # the run's last step is always recorded
