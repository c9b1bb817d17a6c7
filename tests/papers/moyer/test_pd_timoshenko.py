"""pd-rod / pd-timoshenko (Moyer & Miraglia): the paper's three examples, any scene, locking, dynamics."""

import subprocess
import sys

import numpy as np
import pytest
from helpers import MIXED_LOADS, OFF_GRID_LOADS, PAIRS, ROOT, scene_dict

from pdverify.core.errors import InputError, SolveError
from pdverify.core.scene import Distributed, PointForce
from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.exact.vibration import TimoshenkoBeam
from pdverify.papers.moyer.kernels import rod_kernel, shear_kernel
from pdverify.papers.moyer.model import simulate
from pdverify.papers.moyer.operator import beam_operator
from pdverify.papers.moyer.spectrum import stable_time_step
from pdverify.papers.moyer.transient import STABILISATION, integrate
from pdverify.registry import run

TABLE1 = load_scene(ROOT / "studies/paper_moyer/cantilever_table1.toml")
ROD = load_scene(ROOT / "studies/paper_moyer/rod_example1.toml")
BEAM = load_scene(ROOT / "studies/paper_moyer/beam_example2.toml")
# Table 1's data (P, L, E, I, k, G, A): exact Timoshenko tip deflection P L^3 / (3 E I) + P L / (k G A)
# = 1.042445 in (the paper plots it in Fig. 13 and prints no number)
TIP_EXACT = -(975.0 * 20.0**3 / (3 * 3.0e7 * 0.0833) + 975.0 * 20.0 / (0.833 * 1.1538e7 * 1.0))


def err(scene, model="pd-timoshenko", **opts):
    r = run(scene, model, **opts)
    ex = solve_straight(scene, True).fields(r.x)["w"]
    return np.abs(r.w - ex).max() / np.abs(ex).max()


# -- kernels ---------------------------------------------------------------------------------


@pytest.mark.parametrize("m", [1, 2, 3, 4, 10])
def test_kernels_are_consistent(m):
    """B I = E u'' for a quadratic (Σ c_j 2 j² = m²) and C1 I = kG ψ' for a linear ψ (Σ a_j 2 s_j = 2m)."""
    c = rod_kernel(m)
    assert np.sum(c * 2 * np.arange(1, m + 1) ** 2) == pytest.approx(m**2, rel=1e-14)
    for variant in ("paper", "corrected"):
        s, a = shear_kernel(m, variant)
        assert np.sum(a * 2 * s) == pytest.approx(2 * m, rel=1e-14)


def _trapezoid_pv(psi, m: int, l1_of_k) -> float:
    """PV ∫_{-m}^{m} ψ(ε)/ε dε by Eq. 47's recipe, written out with Eq. 16's interval indices: the centre
    interval [-1, 1] as ψ(1) - ψ(-1), and the trapezoid on [l1, l2] (l2 = l1 + 1) and its mirror for k = 1..m-1."""
    total = psi(1.0) - psi(-1.0)
    for k in range(1, m):
        l1 = l1_of_k(k)
        l2 = l1 + 1
        total += 0.5 * (psi(l1) / l1 + psi(l2) / l2) + 0.5 * (psi(-l2) / -l2 + psi(-l1) / -l1)
    return total


@pytest.mark.parametrize("m", [2, 3, 4])
def test_eq16_index_as_printed_divides_by_zero(m):
    """Eq. 16 prints l1 = 1 + k - m (k = 1..m-1): at k = m - 1 the interval starts at ε = 0 and ψ/ε divides
    by zero. With l1 = k - m - 1 (the intervals -m..-2, as Eq. 47/48 index them) the recipe is the
    implemented paper kernel, checked on a cubic ψ."""
    psi = np.polynomial.Polynomial([0.3, -1.2, 0.7, 2.1])
    s, a = shear_kernel(m, "paper")
    assert _trapezoid_pv(psi, m, lambda k: k - m - 1) == pytest.approx(np.sum(a * (psi(s) - psi(-s))), rel=1e-13)
    with pytest.raises(ZeroDivisionError):
        _trapezoid_pv(lambda e: float(psi(e)), m, lambda k: 1 + k - m)


# -- Example 3 (Section 4, Table 1) ----------------------------------------------------------


@pytest.mark.parametrize("m", [2, 3, 4])
def test_table1_cantilever_tip_within_one_percent(m):
    """dx = 0.2 in, horizons 2, 3, 4 dx: measured tip error vs 1.0424 in: 5e-5 (the 4-digit target),
    vs exact-timoshenko ~1e-11 (the solution is a cubic, reproduced exactly by the collocation variant corrected;
    the default variant energy is not exact for cubics: tests/test_moyer_energy.py)."""
    r = run(TABLE1, "pd-timoshenko", spacing=0.2, horizon=m, variant="corrected")
    assert abs(r.w[-1] / TIP_EXACT - 1) < 1e-2
    ex = solve_straight(TABLE1, True).fields(r.x)["w"]
    assert abs(r.w[-1] / ex[-1] - 1) < 1e-8


@pytest.mark.parametrize("m", [2, 3, 4])
def test_table1_paper_variant_as_published_misses(m):
    """Section 4 as printed (end load as p/(AΔ) in the end cell, ghosts by second-order Taylor
    extrapolation of the interior) imposes no condition at the free end: measured tip 9.8, 2.0 and -5.3
    times the exact value for m = 2, 3, 4. Not reproducible as published; the corrected variant is."""
    r = run(TABLE1, "pd-timoshenko", spacing=0.2, horizon=m, variant="paper")
    assert abs(r.w[-1] / TIP_EXACT - 1) > 0.5


@pytest.mark.parametrize("m", [2, 3, 4])
def test_table1_section4_cell_centred_as_published_misses(m):
    """The literal Section 4 setup: 100 cells of 0.2 in, points at the cell centres, P/(AΔ) in the end cell,
    ghost cells by second-order Taylor expansion about the end faces (clamped face anchored at zero,
    derivatives by second-order one-sided differences). Measured tip (quadratic extrapolation of the last
    three cells): 19.6, 14.1, 10.6 times the exact 1.0424 in for m = 2, 3, 4."""
    r = run(TABLE1, "pd-timoshenko", spacing=0.2, horizon=m, variant="paper", grid="cells")
    assert len(r.x) == 100 and r.x[0] == pytest.approx(0.1)
    tip = np.polyval(np.polyfit(r.x[-3:], r.w[-3:], 2), 20.0)
    assert abs(tip / TIP_EXACT) > 2


def test_cell_centred_grid_converges_between_dirichlet_ends():
    """The same cell-centred implementation is sound where the paper's recipe has data: clamped-clamped,
    uniform load, L/h = 25: measured 1.1e-3, 2.8e-4, 7.0e-5 (m = 1; order 2)."""
    sc = parse_scene(scene_dict("clamped", "clamped", [{"type": "distributed", "value": -500.0}])).with_slenderness(25)
    e = []
    for n in (101, 201, 401):
        r = run(sc, "pd-timoshenko", points=n, horizon=1, variant="paper", grid="cells")
        ex = solve_straight(sc, True).fields(r.x)["w"]
        e.append(np.abs(r.w - ex).max() / np.abs(ex).max())
    assert e[0] < 2e-3 and np.log2(e[0] / e[1]) > 1.8 and np.log2(e[1] / e[2]) > 1.8
    with pytest.raises(InputError, match="grid = 'cells'"):
        run(sc, "pd-timoshenko", grid="cells")


# -- any straight scene -----------------------------------------------------------------------


@pytest.mark.parametrize("left,right", PAIRS)
def test_every_support_pair_and_load_within_two_percent(left, right):
    """Mixed loads (forces, moments also at the ends, partial uniform, sine) at 201 points, slenderness
    4, 10, 30, 100: measured max errors 2e-5 .. 5.5e-3 (the largest: thick beams, point force, m = 3)."""
    base = parse_scene(scene_dict(left, right, MIXED_LOADS))
    for s in (4, 10, 30, 100):
        assert err(base.with_slenderness(s), points=201) < 2e-2


@pytest.mark.parametrize("left,right", [("clamped", "free"), ("pinned", "guided"), ("clamped", "pinned")])
def test_rotation_moment_and_shear_fields(left, right):
    """rotation = γ, M = EIγ', V = M' = -kGA ψ (ψ as the operator sees it) against exact-timoshenko, uniform +
    sine loads, 201 points. Measured: rotation and M 1.2e-4 .. 4.7e-4, V 1.3e-4 .. 1.4e-4 at slenderness 10;
    at 1000 V is off by 1.1-2.1 % at the support point (a Dirichlet end's ghost ψ comes from the w and γ
    polynomials), 1e-4 elsewhere. (V from np.gradient(w) - γ was off by 64 % on the Table 1 cantilever.)"""
    loads = [{"type": "distributed", "value": -500.0}, {"type": "distributed", "value": 400.0, "shape": "sine"}]
    for s, v_end in ((10, 1e-3), (1000, 5e-2)):
        sc = parse_scene(scene_dict(left, right, loads)).with_slenderness(s)
        r = run(sc, "pd-timoshenko", points=201)
        ex = solve_straight(sc, True).fields(r.x)
        for key, v in (("rotation", r.rotation), ("M", r.fields["M"]), ("V", r.fields["V"])):
            e = np.abs(v - ex[key]) / np.abs(ex[key]).max()
            assert e.max() < (v_end if key == "V" else 1e-3), key
            assert e[5:-5].max() < 1e-3, key


def test_loads_between_points():
    sc = parse_scene(scene_dict("clamped", "pinned", OFF_GRID_LOADS))
    for s in (4, 100):
        assert err(sc.with_slenderness(s), points=201) < 5e-3


def test_smooth_loads_converge_at_order_two():
    sc = parse_scene(
        scene_dict(
            "clamped",
            "free",
            [
                {"type": "distributed", "value": 400.0, "shape": "sine"},
                {"type": "distributed", "value": -500.0, "start": 0.2, "end": 1.1},
            ],
        )
    )
    e = [err(sc.with_slenderness(10), points=n) for n in (101, 201, 401)]
    assert np.log2(e[0] / e[1]) > 1.8 and np.log2(e[1] / e[2]) > 1.8, e


def test_point_force_is_smeared_over_the_horizon():
    """Variant corrected (collocation of Eq. 47): the PV kernel 1/ε on a shear jump: a point force converges at
    first order for m > 1 (the nonlocal force spreads over the horizon); m = 1 (the finite-difference limit) is
    third order. Measured at slenderness 4: m = 3: 7.5e-3 / 3.7e-3 (201 / 401 points); m = 1: 3.4e-7 / 4.2e-8."""
    sc = parse_scene(scene_dict("clamped", "clamped", MIXED_LOADS[:1])).with_slenderness(4)
    e3 = [err(sc, points=n, horizon=3, variant="corrected") for n in (201, 401)]
    e1 = [err(sc, points=n, horizon=1, variant="corrected") for n in (201, 401)]
    assert 0.8 < np.log2(e3[0] / e3[1]) < 1.3
    assert e1[0] < 1e-5 and np.log2(e1[0] / e1[1]) > 2.5


def test_paper_variant_odd_even_decoupling():
    """Paper ψ by central differences (Eq. 45): a point force drives the odd–even mode, the error does not
    fall with refinement (measured 0.49 at slenderness 4, m = 1); a smooth load converges (order 2)."""
    sc = parse_scene(scene_dict("clamped", "clamped", MIXED_LOADS[:1])).with_slenderness(4)
    e = [err(sc, points=n, horizon=1, variant="paper") for n in (101, 401)]
    assert min(e) > 0.3
    smooth = parse_scene(scene_dict("clamped", "clamped", [{"type": "distributed", "value": -500.0}])).with_slenderness(
        25
    )
    e = [err(smooth, points=n, horizon=1, variant="paper") for n in (101, 201)]
    assert e[0] < 1e-3 and np.log2(e[0] / e[1]) > 1.8


@pytest.mark.parametrize("slenderness", [1000, 10000])
def test_no_shear_locking_at_high_slenderness(slenderness, record_property):
    """Uniformly loaded cantilever at 201 points. Before the free-end ψ̄ extrapolation (w and γ
    extrapolated separately) measured errors were 27 % / 13 % / 1.8 % (m = 1, 3, 6) at L/h = 1000 and
    2700 % / 98 % / 1.9 % at 1e4 (a larger horizon only dilutes the kGA-amplified ghost error); now
    3e-8 .. 4e-6 at 1000 and 3e-6 .. 1e-4 at 1e4 (round-off: cond ~1e13)."""
    sc = parse_scene(scene_dict("clamped", "free", [{"type": "distributed", "value": -500.0}])).with_slenderness(
        slenderness
    )
    for m in (1, 3, 6):
        e = err(sc, points=201, horizon=m)
        record_property(f"err_m{m}", e)
        assert e < 1e-3
    mixed = parse_scene(scene_dict("pinned", "guided", MIXED_LOADS)).with_slenderness(slenderness)
    assert err(mixed, points=201) < 5e-3


# -- rod ----------------------------------------------------------------------------------------

GX, GW = np.polynomial.legendre.leggauss(20)


def rod_reference(sc, x):
    """u(x) from the Green's function of -EA u'' = p with the scene's axial supports (Gauss quadrature)."""
    L, EA = sc.length, sc.EA
    fl, fr = sc.supports.left in ("clamped", "pinned"), sc.supports.right in ("clamped", "pinned")

    def g(x, xi):
        if fl and fr:
            return np.minimum(x, xi) * (L - np.maximum(x, xi)) / (L * EA)
        return np.minimum(x, xi) / EA if fl else (L - np.maximum(x, xi)) / EA

    u = np.zeros_like(x)
    for ld in sc.loads:
        if isinstance(ld, PointForce):
            u += ld.axial * g(x, ld.position)
        elif isinstance(ld, Distributed):
            a, b = sc.span(ld)
            for k, xk in enumerate(x):
                mid = min(max(xk, a), b)
                for lo, hi in ((a, mid), (mid, b)):
                    if hi > lo:
                        xi = (hi - lo) / 2 * GX + (hi + lo) / 2
                        p = ld.axial * (np.sin(np.pi * xi / L) if ld.shape == "sine" else 1.0)
                        u[k] += (hi - lo) / 2 * np.sum(GW * p * g(xk, xi))
    return u


ROD_LOADS = [
    {"type": "point_force", "position": 0.733, "value": 0.0, "axial": 3e5},
    {"type": "distributed", "value": 0.0, "axial": -7e5, "start": 0.311, "end": 1.29},
    {"type": "distributed", "value": 0.0, "axial": 4e5, "shape": "sine"},
]


@pytest.mark.parametrize(
    "left,right,end",
    [("clamped", "free", 2.0), ("free", "clamped", 0.0), ("clamped", "pinned", None), ("pinned", "guided", 2.0)],
)
def test_rod_static_any_supports(left, right, end):
    """Axial point forces (off-grid, at a free end), partial uniform and sine loads: measured at 201 points
    5e-6 .. 3.1e-5 (m = 1), 3e-3 .. 2e-2 (m = 3, order ~1.3: point force smeared). The mirror ghosts of the
    free ends (2026-11-26) cut m = 1's error 10-15x (was 6e-5 .. 9e-5 with the fitted ghosts); what is left
    is the cell averages at the partial load's ends, whose pairwise order depends on where the grid falls
    (1.61 .. 2.55 from 201 to 401 points). The sine load alone (and the end force) converges at exactly 2
    for every pair (measured 2.000; 7.6e-6 .. 1.0e-5 at 201 points, m = 1)."""
    end_force = [{"type": "point_force", "position": end, "value": 0.0, "axial": -2e5}] if end is not None else []
    e = {}
    for loads in ("mixed", "sine"):
        sc = parse_scene(scene_dict(left, right, (ROD_LOADS if loads == "mixed" else ROD_LOADS[2:]) + end_force))
        for m in (1, 3):
            for n in (201, 401):
                r = run(sc, "pd-rod", points=n, horizon=m)
                ex = rod_reference(sc, r.x)
                e[loads, m, n] = np.abs(r.fields["u"] - ex).max() / np.abs(ex).max()
    assert e["mixed", 1, 201] < 4e-5 and e["mixed", 1, 401] < e["mixed", 1, 201] / 2**1.5, e
    assert e["mixed", 3, 201] < 3e-2 and e["mixed", 3, 401] < e["mixed", 3, 201] / 2**0.9, e
    for m in (1, 3):
        assert abs(np.log2(e["sine", m, 201] / e["sine", m, 401]) - 2) < 0.05, e


@pytest.mark.parametrize("right", ["free", "guided", "roller"])
def test_rod_paper_variant_refuses_an_end_that_does_not_hold_u(right):
    """Section 4's recipe for a rod end that does not hold u (end force as body force, second-order extrapolation)
    sets no traction condition: its static system is singular (condition estimate ~1e17-1e18, and exactly singular
    at 81 points) and its transient runs away (21 times max |u| off exact-modal-rod, studies/paper_moyer/
    rod_transient.toml): refused before any work, whatever the points, static or transient."""
    sc = parse_scene(
        scene_dict("clamped", right, [{"type": "point_force", "position": 2.0, "value": 0.0, "axial": 10.0}])
    )
    for n in (8, 81, 101):
        with pytest.raises(InputError, match=f"supports.right = {right}: variant paper sets no traction condition at"):
            run(sc, "pd-rod", points=n, variant="paper")
    transient = load_scene(ROOT / "studies/paper_moyer/rod_transient.toml")
    with pytest.raises(InputError, match="so its system is singular; use variant corrected"):
        run(transient, "pd-rod", points=41, variant="paper")
    if right == "free":
        assert run(sc, "pd-rod", points=101).fields["u"][-1] == pytest.approx(10.0 * 2.0 / sc.EA, rel=1e-9)


def test_load_inside_the_boundary_layer_is_flagged():
    sc = parse_scene(scene_dict("pinned", "pinned", [{"type": "point_force", "position": 0.01, "value": -100.0}]))
    r = run(sc, "pd-timoshenko", points=201)
    assert any("boundary layer" in w for w in r.info.get("warnings", []))


def test_rod_rejects_transverse_loads():
    with pytest.raises(InputError, match="axial only"):
        run(parse_scene(scene_dict("clamped", "free", MIXED_LOADS[:1])), "pd-rod")


# -- Example 1: rod dynamics --------------------------------------------------------------------


@pytest.mark.slow
def test_example1_rod_settles_and_larger_horizon_disperses():
    """δ = 1 in as δ = dx (101 points) and δ = 10 dx (1001 points): the centre settles at 0.05 in (measured
    5.6e-10 / 6.0e-10 off). Dispersion, same grid dx = 0.1 in, δ = 10 dx vs δ = dx (local): measured
    max difference 1.65e-3 in during the drive (1.1 % of the 0.148 in peak; 2.4e-3, 1.6 %, when
    simulate() ignored output_interval), the nonlocal front arriving
    ~8 µs early; at the end both agree to 1e-9."""
    h1 = simulate(ROD, {"points": 101, "horizon": 1}, model="pd-rod")
    h10 = simulate(ROD, {"points": 1001, "horizon": 10}, model="pd-rod")
    for h in (h1, h10):
        assert h.values[-1, 0] == pytest.approx(0.05, abs=1e-7)
        assert h.omega1 / (2 * np.pi) == pytest.approx(np.sqrt(3e7 / 7.324e-4) / 200, rel=1e-3)
    local = simulate(ROD, {"points": 1001, "horizon": 1}, model="pd-rod", t_end=2e-3)
    t = np.linspace(0, 2e-3, 2001)
    diff = np.interp(t, h10.t, h10.values[:, 0]) - np.interp(t, local.t, local.values[:, 0])
    assert np.abs(diff).max() > 1e-3  # dispersion visible (>> the settled error)
    assert np.abs(h10.values[-1, 0] - h1.values[-1, 0]) < 1e-8


# -- Example 2: beam dynamics -----------------------------------------------------------------


def timoshenko_cc_frequency(scene) -> float:
    """First natural frequency (Hz) of the clamped-clamped Timoshenko beam (the characteristic determinant
    of pdverify.exact.vibration)."""
    rho = scene.material.density
    beam = TimoshenkoBeam(
        scene.EI, scene.kGA, rho * scene.section.A, rho * scene.section.I, scene.length, (True, True), (True, True)
    )
    return beam.frequencies(1)[0] / (2 * np.pi)


@pytest.mark.slow
def test_example2_follows_drive_rings_at_resonance_and_settles():
    """101 points, δ = dx = 1 in (the paper's CCM approximation). Measured: analytic f1 = 82.307 Hz
    (paper ~82.4), operator 82.307 Hz, ring-down zero crossings 82.20 Hz (= f1 sqrt(1 - 0.05²)),
    crossing rate during the 100 Hz drive 106 Hz, centre settles at 0.05 in (4e-8 off at 0.6 s)."""
    h = simulate(BEAM, {"points": 101, "horizon": 1})
    f1 = timoshenko_cc_frequency(BEAM)
    assert f1 == pytest.approx(82.4, rel=5e-3)
    t, w = h.t, h.values[:, 0]
    s = (t > 0.1) & (t < 0.45)
    y = w[s] - 0.05
    i = np.flatnonzero(np.sign(y[1:]) != np.sign(y[:-1]))
    tc = t[s][i] - y[i] * (t[s][i + 1] - t[s][i]) / (y[i + 1] - y[i])
    f_ring = 1 / (2 * np.diff(tc).mean()) / np.sqrt(1 - 0.05**2)
    assert f_ring == pytest.approx(f1, rel=2e-2)
    d = t < 0.0925
    yd = w[d] - w[d].mean()
    f_drive = 1 / (2 * np.diff(t[d][np.flatnonzero(np.sign(yd[1:]) != np.sign(yd[:-1]))]).mean())
    assert abs(f_drive - 100) < abs(f_drive - f1)
    assert w[-1] == pytest.approx(0.05, abs=1e-5)


def test_example2_static_state_independent_of_grid_at_fixed_horizon():
    """δ = 1 in with dx = δ (101 points, m = 1) and dx = δ/10 (1001 points, m = 10): the same static state."""
    a = run(BEAM, "pd-timoshenko", points=101, horizon=1, analysis="static", variant="corrected")
    b = run(BEAM, "pd-timoshenko", points=1001, horizon=10, analysis="static", variant="corrected")
    assert a.w[50] == pytest.approx(0.05, abs=1e-12)
    assert np.abs(b.w[::10] - a.w).max() < 1e-8


@pytest.mark.parametrize("variant", ["corrected", "paper"])
@pytest.mark.slow
def test_damped_dynamics_reach_the_direct_solve(variant, record_property):
    """The same operator: damped leapfrog (ζ = 0.2 on w, 0.6 s) and the sparse direct solve agree to 1e-6
    (measured 6e-14). As published (no stabilisation, damping on w only, Eq. 36-37) the shear-rotation
    modes keep ringing: measured 1.1e-5 at 0.6 s."""
    params = {"points": 101, "horizon": 2, "variant": variant}
    static = run(BEAM, "pd-timoshenko", analysis="static", **params)
    h = simulate(BEAM, params, damping_ratio=0.2)
    assert np.abs(h.final[0::2] - static.w).max() < 1e-6 * np.abs(static.w).max()
    assert np.abs(h.final[1::2] - static.rotation).max() < 1e-6 * np.abs(static.rotation).max()
    paper = simulate(BEAM, params, damping_ratio=0.2, stabilisation=0.0)
    record_property("as_published_residual", np.abs(paper.final[0::2] - static.w).max() / 0.1)


@pytest.mark.slow
def test_table1_step_load_settles_to_static():
    sc = parse_scene(dict(TABLE1.to_dict(), material=dict(TABLE1.to_dict()["material"], density=7.324e-4)))
    params = {"points": 26, "horizon": 2}
    static = run(sc, "pd-timoshenko", **params)
    h = simulate(sc, params, t_end=0.3, damping_ratio=0.5, probes=[20.0])
    assert h.values[-1, 0] == pytest.approx(static.w[-1], rel=1e-6)


# -- time step --------------------------------------------------------------------------------


def test_stable_time_step_and_blow_up():
    """dt_limit = 2 / (ω_max sqrt(1 + 2κ)) with the stabilisation κ: 0.99 of it runs, 1.05 of it blows up."""
    disc = beam_operator(BEAM, 51, 2, "corrected")
    limit = stable_time_step(disc) / np.sqrt(1 + 2 * STABILISATION)
    motions = {100: BEAM.dynamics.right.displacement}
    ok = integrate(disc, motions, t_end=3000 * limit, dt=0.99 * limit)
    assert ok.dt_limit == pytest.approx(limit, rel=1e-9)
    assert np.all(np.isfinite(ok.final)) and np.abs(ok.values).max() < 1.0
    with pytest.raises(SolveError, match="stable limit"):
        integrate(disc, motions, t_end=3000 * limit, dt=1.05 * limit)


@pytest.mark.parametrize("right,n,m", [("free", 26, 2), ("free", 101, 3), ("free", 101, 1), ("clamped", 101, 10)])
def test_time_stepping_is_stable_with_the_non_symmetric_closures(right, n, m, record_property):
    """Spectral radius of the undamped one-step map (u, v) -> (u', v') on the free DOFs. Without the
    stabilisation (κ = 0) the complex eigenvalues of the boundary closures make it grow: measured
    1 + 1.9e-2, 2.0e-2, 2.4e-3, 1.3e-3; with κ = 0.2 it is <= 1."""
    from pdverify.papers.moyer.spectrum import mass_scaled

    sc = parse_scene(
        dict(
            TABLE1.to_dict(),
            material=dict(TABLE1.to_dict()["material"], density=7.324e-4),
            supports={"left": "clamped", "right": right},
        )
    )
    disc = beam_operator(sc, n, m, "corrected")
    A = mass_scaled(disc, disc.free).toarray()
    w_max = np.sqrt(np.abs(np.linalg.eigvals(A)).max())
    N = len(A)
    I = np.eye(N)
    radius = {}
    for kappa in (0.0, STABILISATION):
        dt = 0.9 * 2 / (w_max * np.sqrt(1 + 2 * kappa))
        Mu, Mv = -dt * A, I - dt * kappa * dt * A
        Z = np.block([[I + dt * Mu, dt * Mv], [Mu, Mv]])
        radius[kappa] = np.abs(np.linalg.eigvals(Z)).max()
    record_property("radius_minus_one_unstabilised", radius[0.0] - 1)
    assert radius[0.0] > 1 + 1e-4
    assert radius[STABILISATION] <= 1 + 1e-12


# -- input and CLI ------------------------------------------------------------------------------


def test_bad_inputs():
    with pytest.raises(InputError, match="points = 7"):
        run(TABLE1, "pd-timoshenko", points=7, horizon=4)
    with pytest.raises(InputError, match="no \\[dynamics\\] table"):
        run(TABLE1, "pd-timoshenko", analysis="dynamic")
    with pytest.raises(InputError, match="material.density"):
        simulate(TABLE1, {}, t_end=1.0)
    bad = scene_dict(
        "clamped", "free", [], dynamics={"end_time": 1.0, "right": {"displacement": {"type": "step", "amplitude": 1.0}}}
    )
    with pytest.raises(InputError, match="dynamics.right.displacement: a free end"):
        parse_scene(bad)


@pytest.mark.slow
def test_cli_dynamic_scene_writes_time_history(tmp_path):
    out = tmp_path / "rod.csv"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "pdverify.apps.cli",
            "solve",
            str(ROOT / "studies/paper_moyer/rod_example1.toml"),
            "--model",
            "pd-rod",
            "--horizon",
            "1",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    lines = [line for line in out.read_text().splitlines() if not line.startswith("# warning: ")]  # (the history's
    # difference from half the points: registry/history_check.py)
    assert lines[0].startswith("t,u(x=50),")  # the columns as info.history names them (pd-rod: u)
    data = np.loadtxt(lines[1:], delimiter=",")
    assert data[-1, 1] == pytest.approx(0.05, abs=1e-7)


# -- torsion (Section 5) ------------------------------------------------------------------------


def test_torsion_matches_the_rod_solution_with_GJ():
    """Point torques (off-grid, at the free end) and a partial distributed torque: the twist is the rod
    solution with EA -> GJ (J of the 2:1 rectangle: 0.229 a b³). Measured at 201 points 5e-7 (m = 1),
    1.4e-3 (m = 3; 5.7e-4 at 401)."""
    loads = [
        {"type": "point_torque", "position": 0.733, "value": 300.0},
        {"type": "distributed", "value": 0.0, "torque": -700.0, "start": 0.311, "end": 1.29},
        {"type": "point_torque", "position": 2.0, "value": -200.0},
    ]
    sc = parse_scene(scene_dict("clamped", "free", loads))
    assert sc.section.J == pytest.approx(0.2289 * 0.1 * 0.05**3, rel=1e-3)
    axial = parse_scene(
        scene_dict(
            "clamped",
            "free",
            [
                {"type": "point_force", "position": 0.733, "value": 0.0, "axial": 300.0},
                {"type": "distributed", "value": 0.0, "axial": -700.0, "start": 0.311, "end": 1.29},
                {"type": "point_force", "position": 2.0, "value": 0.0, "axial": -200.0},
            ],
        )
    )
    e = {}
    for m, n in ((1, 201), (3, 201), (3, 401)):
        r = run(sc, "pd-torsion", points=n, horizon=m)
        ex = rod_reference(axial, r.x) * axial.EA / (sc.material.G * sc.section.J)
        e[m, n] = np.abs(r.fields["twist"] - ex).max() / np.abs(ex).max()
    assert e[1, 201] < 1e-5 and e[3, 201] < 5e-3 and e[3, 401] < e[3, 201] / 2
    with pytest.raises(InputError, match="has no twist"):
        run(sc, "pd-timoshenko")
