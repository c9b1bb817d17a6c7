"""exact-higher-order: the exact solution of the local higher-order beam theory (Yang et al. 2020, Eq. 2-9), the
reference pd-higher-order converges to."""

import numpy as np
import pytest

from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.exact.higher_order import Solution
from pdverify.registry import get_model, run
from pdverify.theory.higher_order import D0, D1, coefficients

E, NU, B = 2e11, 0.3, 0.05
EXACT = get_model("exact-higher-order")


def _scene(left, right, loads, length=2.0, h=0.1):
    return parse_scene(
        {
            "name": f"{left}-{right}",
            "beam": {"length": length},
            "section": {"width": B, "height": h},
            "material": {"youngs_modulus": E, "poissons_ratio": NU},
            "supports": {"left": left, "right": right},
            "loads": loads,
        }
    )


UNIFORM = [{"type": "distributed", "value": -1000.0}]
MIXED = [
    {"type": "point_force", "position": 0.7, "value": -800.0},
    {"type": "point_moment", "position": 1.3, "value": 150.0},
    {"type": "distributed", "value": 400.0, "start": 0.2, "end": 1.1},
    {"type": "distributed", "value": -300.0, "shape": "sine"},
]


def test_pure_bending_is_the_plane_stress_solution():
    """An end moment as a linear traction is the exact 2D pure-bending load, which the theory's kinematics contain:
    beyond the clamp's layer theta' = -C / EI (E, not E': the section is free to contract), w* = -nu theta' / 2
    (e_zz = -nu e_xx = 2 z w*), theta* = 0 and M = C everywhere."""
    C, h = 50.0, 0.1
    f = EXACT.evaluate(
        _scene("clamped", "free", [{"type": "point_moment", "position": 2.0, "value": C}]),
        {},
        X := np.linspace(0.5, 2.0, 31),
    )
    EI = E * B * h**3 / 12
    curvature = np.gradient(f["theta"], X, edge_order=2)
    assert np.allclose(curvature, -C / EI, rtol=1e-9, atol=0)
    assert np.allclose(f["w_star"], -NU * curvature / 2, rtol=1e-9, atol=0)
    assert np.abs(f["theta_star"]).max() * h * h < 1e-12 * np.abs(f["theta"]).max()
    assert np.allclose(f["M"][:-1], C, rtol=1e-9, atol=0)
    assert abs(f["M"][-1]) <= 1e-9 * C  # the free end point gives its support's side (docs/contract.md)


@pytest.mark.parametrize(
    "pair", [("pinned", "pinned"), ("clamped", "free"), ("guided", "pinned"), ("clamped", "roller")]
)
@pytest.mark.slow
def test_euler_lagrange_equations(pair):
    """The fields satisfy the theory's equations between the loads: N = b (K11 y' + K10 y) and N' = b (K10^T y' +
    K00 y) - f (module docstring), checked with finite differences of the exact fields (relative 1e-6; their
    truncation error at this spacing is ~1e-8)."""
    h, q = 0.1, -1000.0
    sol = Solution(_scene(*pair, UNIFORM, h=h))
    x = np.linspace(0.3, 1.7, 14001)
    z = sol.states(x)  # units of h and E' b h
    xs = x / h
    y, N = z[:, :4], z[:, 4:]
    dy, dN = (np.gradient(v, xs, axis=0, edge_order=2) for v in (y, N))
    C = coefficients(1 - NU * NU, NU, E / (2 * (1 + NU)) / (E / (1 - NU * NU)), 1.0)
    K11, K10, K00 = D1.T @ C @ D1, D1.T @ C @ D0, D0.T @ C @ D0
    qh = q / (E / (1 - NU * NU) * B)
    f = np.array([0.0, 0.0, qh, qh / 4])
    inner = slice(5, -5)
    for terms in ((dy @ K11.T, y @ K10.T, -N), (dN, -dy @ K10, -y @ K00.T, np.broadcast_to(f, y.shape))):
        scale = max(np.abs(t[inner]).max() for t in terms)  # the largest term of the equation
        assert np.abs(sum(terms)[inner]).max() < 1e-6 * scale


def test_simply_supported_tends_to_timoshenko_at_second_order():
    """On simple supports the theory differs from Timoshenko's beam by (h/L)^2 (the section's own deformation;
    its parabolic shear gives kappa = 5/6): the difference falls 100x per decade of slenderness from L/h = 10 to
    10^5, so the solution keeps its digits on long beams (no shooting across the length)."""
    diffs = []
    for L in (1.0, 10.0, 100.0, 1000.0, 10000.0):
        sc = _scene("pinned", "pinned", UNIFORM, length=L)
        x = np.linspace(0.0, L, 101)
        w, wt = EXACT.evaluate(sc, {}, x)["w"], get_model("exact-timoshenko").evaluate(sc, {}, x)["w"]
        diffs.append(np.abs(w - wt).max() / np.abs(wt).max())
    rates = -np.diff(np.log10(diffs))
    assert np.all(np.abs(rates - 2.0) < 0.1), (diffs, rates)


def test_mirror_scene_mirrors_the_solution():
    sc = _scene("clamped", "pinned", MIXED)
    data = sc.model_dump()
    data["supports"] = {"left": "pinned", "right": "clamped"}
    flip = []
    for ld in MIXED:
        m = dict(ld)
        if "position" in m:
            m["position"] = 2.0 - m["position"]
            if m["type"] == "point_moment":
                m["value"] = -m["value"]
        elif "start" in m:
            m["start"], m["end"] = 2.0 - m["end"], 2.0 - m["start"]
        flip.append(m)
    data["loads"] = flip
    mirror = parse_scene(data)
    x = np.linspace(0.0, 2.0, 201)
    w, wm = EXACT.evaluate(sc, {}, x)["w"], EXACT.evaluate(mirror, {}, 2.0 - x)["w"]
    assert np.allclose(w, wm, rtol=0, atol=1e-12 * np.abs(w).max())


@pytest.mark.parametrize(
    "pair", [("clamped", "clamped"), ("pinned", "clamped"), ("clamped", "free"), ("guided", "pinned")]
)
def test_reactions_balance_the_loads(pair):
    """Sum of forces and of moments about x = 0 of the loads and the support reactions: zero (1e-9 relative)."""
    sc = _scene(*pair, MIXED)
    r = run(sc, EXACT, points=5).info["reactions"]
    # the loads: 0.7 m point force, the partial uniform load, the sine over the whole length, the point moment
    P, a, q1, (s0, s1), q2, C, L = -800.0, 0.7, 400.0, (0.2, 1.1), -300.0, 150.0, 2.0
    F = P + q1 * (s1 - s0) + q2 * 2 * L / np.pi
    Mz = P * a + q1 * (s1 - s0) * (s0 + s1) / 2 + q2 * L * L / np.pi + C  # ccw moments about x = 0
    assert abs(r["force_left"] + r["force_right"] + F) < 1e-9 * abs(F)
    assert abs(r["moment_left"] + r["moment_right"] + r["force_right"] * L + Mz) < 1e-9 * abs(Mz)


def test_pd_higher_order_converges_to_it():
    """The corrected pd-higher-order converges to the exact theory at second order under a point force on the grid
    (its bonds cut at the load) and a uniform load (error over the whole curve, relative to max |w|)."""
    for loads in ([{"type": "point_force", "position": 0.5, "value": -100.0}], UNIFORM):
        sc = _scene("pinned", "clamped", loads, length=1.0, h=0.2)
        x = np.linspace(0.0, 1.0, 41)
        ref = EXACT.evaluate(sc, {}, x)["w"]
        errs = []
        for n in (321, 641, 1281):
            r = run(sc, get_model("pd-higher-order"), points=n)
            errs.append(np.abs(np.interp(x, r.x, r.w) - ref).max() / np.abs(ref).max())
        rates = np.log2(np.array(errs[:-1]) / errs[1:])
        assert np.all(np.abs(rates - 2.0) < 0.1), (errs, rates)


def test_the_dimple_under_a_point_force_is_the_theorys():
    """Issue #32: under a top-face point force the mid-line w of the continuous theory peaks beside the load
    (0.058 h off at L/h = 2, 0.044 h at 5: the section's w* under the load), and pd-higher-order's peak sits where
    the theory's does, within a spacing; the deflection at the load agrees to its discretisation error."""
    base = load_scene("studies/paper_yang/ss_centre_force.toml")
    for lh, offset in ((2, 0.0575), (5, 0.0436)):
        sc = base.with_slenderness(lh)
        h = sc.section.depth
        x = np.linspace(0.5 - 0.2 * h, 0.5, 4001)
        w = EXACT.evaluate(sc, {}, x)["w"]
        peak = x[np.argmax(np.abs(w))]
        assert abs((0.5 - peak) / h - offset) < 2e-4
        r = run(sc, get_model("pd-higher-order"), points=1001)
        pd_peak = r.x[np.argmax(np.abs(r.w))]
        assert abs(abs(pd_peak - 0.5) - (0.5 - peak)) <= r.x[1] - r.x[0]
        assert abs(r.w[500] / w[-1] - 1) < 1e-4


def test_a_point_load_between_grid_points_is_flagged():
    """pd-higher-order cuts its bonds only at point loads on a grid point; one between two points is split between
    them and converges at first order near it (ss centre force, L/h = 5, 801 points, whole-curve error vs the exact
    theory: 2.2e-5 on the grid, 2.6e-4 at x = 0.5015): its result says so, the on-grid one does not."""
    base = load_scene("studies/paper_yang/ss_centre_force.toml")
    errs, flagged = [], []
    for pos in (0.5, 0.5015):
        data = base.model_dump()
        data["loads"][0]["position"] = pos
        sc = parse_scene(data)
        r = run(sc, get_model("pd-higher-order"), points=801)
        ref = EXACT.evaluate(sc, {}, r.x)["w"]
        errs.append(np.abs(r.w - ref).max() / np.abs(ref).max())
        flagged.append(any("not on a cut grid point" in w for w in r.info.get("warnings", [])))
    assert flagged == [False, True]
    assert errs[1] > 5 * errs[0]


@pytest.mark.parametrize("nu", [0.0, 0.4, 0.45, 0.499])
def test_every_poissons_ratio_has_its_boundary_layer_and_pd_higher_order_converges_to_it(nu):
    """The layer's eigenvalues of Eq. 9's system are a complex pair below nu ~ 0.4, a double pair there and two real
    pairs above (exact/higher_order.py, modal_basis); each is a solution pd-higher-order converges to at second
    order (pinned-pinned, uniform load, L/h = 20)."""
    sc = _scene("pinned", "pinned", UNIFORM, length=1.0, h=0.05)
    sc = sc.model_copy(update={"material": sc.material.model_copy(update={"poissons_ratio": nu})})
    errors = []
    for n in (101, 201, 401):
        exact, pd = run(sc, "exact-higher-order", points=n), run(sc, "pd-higher-order", points=n)
        errors.append(np.abs(pd.w - exact.w).max() / np.abs(exact.w).max())
    assert abs(np.log2(errors[1] / errors[2]) - 2) < 0.1, errors


def _inner(left, right, inner, loads, h=0.05):
    """A 1 m beam of square section held inside the span by ``inner`` (a list of supports)."""
    return parse_scene(
        {
            "name": "held inside",
            "beam": {"length": 1.0},
            "section": {"width": h, "height": h},
            "material": {"youngs_modulus": E, "poissons_ratio": NU},
            "supports": {"left": left, "right": right, "inner": inner},
            "loads": loads,
        }
    )


INSIDE = [
    {"type": "distributed", "value": -1000.0, "start": 0.1, "end": 0.6},
    {"type": "point_force", "position": 0.8, "value": -300.0},
]


@pytest.mark.parametrize("loads", ["faces", "mid"])
def test_a_support_inside_the_span_holds_what_pd_higher_order_holds_and_balances_the_loads(loads):
    """A clamp holds the mid-line w and the section's mean rotation theta + 3 h^2/20 theta* (the work-conjugates of
    its reactions, as pd-higher-order's multipliers: pdverify/papers/yang/supports.py), a roller the mid-line w: zero
    to round-off (cond eps of the fields' size); the reactions balance the loads (forces, and moments about x = 0)."""
    h = 0.05
    inner = [{"position": 0.3, "type": "clamped"}, {"position": 0.55, "type": "roller"}]
    sc = _inner("free", "pinned", inner, INSIDE, h)
    r = run(sc, EXACT, points=401, loads=loads)
    tol = r.info["cond"] * np.finfo(float).eps
    at = [int(np.argmin(np.abs(r.x - s["position"]))) for s in inner]
    assert np.abs(r.w[at]).max() < tol * np.abs(r.w).max()
    mean = r.fields["theta"] + 3 * h * h / 20 * r.fields["theta_star"]
    assert abs(mean[at[0]]) < tol * np.abs(r.fields["theta"]).max()
    R = r.info["reactions"]
    F = -1000.0 * 0.5 - 300.0
    Mz = -1000.0 * 0.5 * 0.35 - 300.0 * 0.8  # ccw moments of the loads about x = 0
    forces = R["force_right"] + R["force_inner_0"] + R["force_inner_1"]
    moments = R["force_right"] * 1.0 + R["force_inner_0"] * 0.3 + R["force_inner_1"] * 0.55 + R["moment_inner_0"]
    assert abs(forces + F) < 1e-9 * abs(F) and abs(moments + Mz) < 1e-9 * abs(Mz), R


def test_a_rollers_reaction_is_the_point_force_that_holds_the_beam_there():
    """With loads on the mid-line (``loads = mid``: a point force acts on w alone, as a support's reaction does), the
    beam held by a roller inside is the beam without it under its reaction as a point force: the same deflection to
    round-off."""
    held = _inner("clamped", "free", [{"position": 0.6, "type": "roller"}], INSIDE)
    r = run(held, EXACT, points=201, loads="mid")
    force = {"type": "point_force", "position": 0.6, "value": r.info["reactions"]["force_inner_0"]}
    free = _inner("clamped", "free", [], INSIDE + [force])
    f = run(free, EXACT, points=201, loads="mid")
    tol = max(r.info["cond"], f.info["cond"]) * np.finfo(float).eps
    assert np.abs(f.w - r.w).max() < 100 * tol * np.abs(r.w).max(), np.abs(f.w - r.w).max() / np.abs(r.w).max()


def test_a_mirror_scene_with_supports_inside_mirrors_the_solution():
    inner = [{"position": 0.3, "type": "clamped"}, {"position": 0.55, "type": "roller"}]
    sc = _inner("free", "pinned", inner, INSIDE)
    flipped = [{**s, "position": 1.0 - s["position"]} for s in inner]
    loads = [{**INSIDE[0], "start": 0.4, "end": 0.9}, {**INSIDE[1], "position": 0.2}]
    mirror = _inner("pinned", "free", flipped, loads)
    x = np.linspace(0.0, 1.0, 201)
    w, wm = EXACT.evaluate(sc, {}, x)["w"], EXACT.evaluate(mirror, {}, 1.0 - x)["w"]
    assert np.allclose(w, wm, rtol=0, atol=1e-12 * np.abs(w).max())


@pytest.mark.parametrize(
    "supports",
    [
        ("pinned", "pinned", [{"position": 0.5, "type": "pinned"}]),
        ("pinned", "roller", [{"position": 0.35, "type": "pinned"}, {"position": 0.7, "type": "roller"}]),
        ("free", "pinned", [{"position": 0.7, "type": "clamped"}]),
    ],
)
def test_pd_higher_order_converges_to_it_with_supports_inside_the_span(supports):
    """Second order on a slender beam (L/h = 100) under a uniform load, over the whole curve (measured 2.02-2.31 from
    201 to 1601 points on the continuous beams; from 801 on beside the clamp, 1.72 and 2.22 at the last two pairs:
    its section's layer, ~0.1 h wide, is resolved from a spacing below it)."""
    left, right, inner = supports
    sc = _inner(left, right, inner, [{"type": "distributed", "value": -1000.0}], h=0.01)
    opts = get_model("pd-higher-order").reference_options({})
    errs = []
    for n in (401, 801, 1601):
        r, e = run(sc, "pd-higher-order", points=n), run(sc, EXACT, points=n, **opts)
        errs.append(np.abs(r.w - e.w).max() / np.abs(e.w).max())
    assert abs(np.log2(errs[1] / errs[2]) - 2.0) < 0.25, errs


def test_springs_hold_what_a_rigid_support_would_elastically():
    """A spring inside the span or at an end gives R = -k times what its rigid support would hold (pd-higher-order's
    springs: the mid-line w inside, the end's w + h^2/20 w* with pin = face, the section's mean rotation); as k grows
    the deflection tends to the rigid support's, its distance falling like the spring's compliance 1/k."""
    h = 0.05
    spring_end = {"type": "spring", "stiffness": 1e6, "rotational_stiffness": 1e4}
    inner = [{"position": 0.5, "type": "spring", "stiffness": 2e6, "rotational_stiffness": 3e4}]
    sc = _inner("pinned", spring_end, inner, INSIDE, h)
    x = np.array([0.5, 1.0])
    f = EXACT.evaluate(sc, {}, x)
    R = run(sc, EXACT, points=3).info["reactions"]
    mean = f["theta"] + 3 * h * h / 20 * f["theta_star"]  # -(the rotation the couple's traction works on)
    assert R["force_inner_0"] == pytest.approx(-2e6 * f["w"][0], rel=1e-9)
    assert R["moment_inner_0"] == pytest.approx(3e4 * mean[0], rel=1e-9)
    assert R["force_right"] == pytest.approx(-1e6 * (f["w"][1] + h * h / 20 * f["w_star"][1]), rel=1e-9)
    assert R["moment_right"] == pytest.approx(1e4 * mean[1], rel=1e-9)
    EI, xs = E * h**4 / 12, np.linspace(0.0, 1.0, 101)
    rigid = EXACT.evaluate(_inner("pinned", "free", [{"position": 0.5, "type": "clamped"}], INSIDE, h), {}, xs)["w"]
    apart = []
    for k in (1e6, 1e9):  # k L^3 / EI and k_r L / EI
        stiff = [{"position": 0.5, "type": "spring", "stiffness": k * EI, "rotational_stiffness": k * EI}]
        w = EXACT.evaluate(_inner("pinned", "free", stiff, INSIDE, h), {}, xs)["w"]
        apart.append(np.abs(w - rigid).max() / np.abs(rigid).max())
    assert apart[0] / apart[1] == pytest.approx(1e3, rel=1e-2), apart  # the compliance: 1/k (measured 1.3e-4, 1.3e-7)


def test_pd_higher_order_converges_to_it_on_springs():
    """The card's beam on springs (a pinned end, a spring end of 1e6 N/m and 1e4 N m/rad, a 2e6 N/m spring at L/2) at
    L/h = 100: second order (measured 1.98, 1.96, 2.02 from 101 to 801 points)."""
    from pdverify.verify.suite import engineering_scenes

    (d,) = [s for s in engineering_scenes() if s["name"] == "on springs"]
    d = {**d, "section": {"width": 0.01, "height": 0.01}, "loads": [{"type": "distributed", "value": -1000.0}]}
    sc = parse_scene(d)
    opts = get_model("pd-higher-order").reference_options({})
    errs = []
    for n in (201, 401, 801):
        r, e = run(sc, "pd-higher-order", points=n), run(sc, EXACT, points=n, **opts)
        errs.append(np.abs(r.w - e.w).max() / np.abs(e.w).max())
    rates = np.log2(np.array(errs[:-1]) / errs[1:])
    assert np.all(np.abs(rates - 2.0) < 0.1), (errs, rates)


@pytest.mark.parametrize(
    "supports",
    [
        {"left": "clamped", "right": "free"},
        {"left": "guided", "right": "pinned"},
        {"left": "pinned", "right": "free", "inner": [{"position": 0.6, "type": "clamped"}]},
    ],
)
def test_its_round_off_on_very_slender_beams_is_in_its_bound(supports):
    """The slow block's float64 Jordan chain meets M z_(j+1) = z_j only to eps |M| |z|, a defect the polynomial
    solutions carry as eps (L/h)^2 (module constant ROUNDOFF): at L/h = 1e6, where the theory is within about h/L of
    Timoshenko's, its distance from exact-timoshenko (measured up to 5.1 eps (L/h)^2) is within the bound it reports,
    and the result warns; at L/h = 1e4 the bound is below the warning's limit."""
    for lh, warned in ((1e6, True), (1e4, False)):
        h = 1.0 / lh
        sc = parse_scene(
            {
                "name": "slender",
                "beam": {"length": 1.0},
                "section": {"width": h, "height": h},
                "material": {"youngs_modulus": E, "poissons_ratio": NU},
                "supports": supports,
                "loads": [
                    {"type": "distributed", "value": -1.0},
                    {"type": "point_force", "position": 0.3, "value": -0.2},
                ],
            }
        )
        r, t = run(sc, EXACT, points=201), run(sc, "exact-timoshenko", points=201)
        apart = np.abs(r.w - t.w).max() / np.abs(t.w).max()
        assert apart <= r.info["error_bound"] + h, (apart, r.info["error_bound"])
        assert bool(r.info.get("warnings")) == warned


def test_dependent_conditions_are_refused_and_a_poor_condition_is_in_the_bound():
    """A spring of 1e-300 N/m under a pinned-free beam leaves its pieces' system dependent at working precision
    (condition 9.5e14, past exact-eb's rank tolerance 1e-10): one line, exit 3, as exact-eb refuses it. Two supports
    1e-7 apart are a beam, solved with their system's condition (4.4e8) times 64 eps in the round-off bound, warned."""
    from pdverify.core.errors import SolveError

    soft = [{"position": 0.5, "type": "spring", "stiffness": 1e-300, "rotational_stiffness": 1e-300}]
    with pytest.raises(SolveError, match="dependent at working precision"):
        run(_inner("pinned", "free", soft, INSIDE), EXACT, points=11)
    close = [{"position": 0.5, "type": "pinned"}, {"position": 0.5000001, "type": "clamped"}]
    r = run(_inner("pinned", "pinned", close, INSIDE), EXACT, points=11)
    assert r.info["error_bound"] >= 64 * r.info["cond"] * np.finfo(float).eps > 1e-6
    assert any("pieces' system" in w for w in r.info["warnings"])


@pytest.mark.parametrize("material", [{"shear_modulus": 1e6}, {"shear_modulus": 1e9}, {"poissons_ratio": -0.99}])
def test_the_modal_basis_holds_for_any_ratio_of_shear_to_young_s_modulus(material):
    """The boundary layer's eigenvalues were told from the slow block's zeros by a gap of 1e-3 of the largest entry
    of M: with G / E below about 0.005, or nu = -0.99, they fell under it and the basis was singular (exit 70, an
    internal error). The gap is now between the two sets' own eigenvalues. The result is finite and, with G far
    below E / 2.6, softer than Euler-Bernoulli's (the section shears)."""
    d = {"name": "b", "beam": {"length": 2.0}, "section": {"width": 0.05, "height": 0.1},
         "material": {"youngs_modulus": 200e9, "poissons_ratio": 0.3, **material},
         "supports": {"left": "clamped", "right": "pinned"},
         "loads": [{"type": "point_force", "position": 0.7, "value": -1000.0}]}  # fmt: skip
    sc = parse_scene(d)
    w = np.asarray(run(sc, "exact-higher-order", points=41).w)
    eb = np.asarray(run(sc, "exact-eb", points=41).w)
    assert np.all(np.isfinite(w)) and np.abs(w).max() > 0
    if "shear_modulus" in material:
        assert np.abs(w).max() > np.abs(eb).max()


END_LOADS = [
    {"type": "point_force", "position": 0.0, "value": -400.0},
    {"type": "point_moment", "position": 0.0, "value": 100.0},
]


@pytest.mark.parametrize("left,right", [("free", "clamped"), ("guided", "pinned"), ("pinned", "clamped")])
@pytest.mark.parametrize("mirror", [False, True])
def test_end_points_give_their_support_side(left, right, mirror):
    """Sweep 14: at an end point carrying a force and a couple the fields held the beam's side (a free end's M = -200,
    V = 1000 where its support side is 0, 0), against docs/contract.md and the model's own reactions. The end values
    now read the reactions: M(0) = -moment_left, V(0) = force_left, M(L) = moment_right, V(L) = -force_right, to the
    round-off of the solution (its error_bound), relative to the largest value."""
    loads = (
        [
            {**ld, "position": 2.0 - ld["position"], "value": (-1) ** (ld["type"] == "point_moment") * ld["value"]}
            for ld in END_LOADS
        ]
        if mirror
        else END_LOADS
    )
    sc = _scene(right if mirror else left, left if mirror else right, loads + UNIFORM)
    r = run(sc, "exact-higher-order", points=41)
    R, M, V = r.info["reactions"], r.fields["M"], r.fields["V"]
    tol = 10 * max(r.info["error_bound"], np.finfo(float).eps)
    assert abs(M[0] + R["moment_left"]) <= tol * np.abs(M).max()
    assert abs(M[-1] - R["moment_right"]) <= tol * np.abs(M).max()
    assert abs(V[0] - R["force_left"]) <= tol * np.abs(V).max()
    assert abs(V[-1] + R["force_right"]) <= tol * np.abs(V).max()
    ref = get_model("exact-timoshenko").evaluate(sc, {}, np.array([0.0, 2.0]))
    side = -1 if mirror else 0  # the loaded end: the Timoshenko beam's support side, within the theories' distance
    # there, about (h / L)^2 = 2.5e-3 of the largest moment on this beam (L/h = 20)
    assert abs(M[side] - ref["M"][side]) <= 1e-2 * np.abs(M).max()


@pytest.mark.parametrize("length", [1e100, 1e308])
def test_a_beam_whose_numbers_overflow_is_refused_in_one_line(length):
    """Sweep 16: a clamped-free beam of length 1e100 (and up to 1e308) ended in LinAlgError (exit 70, an internal
    error) where every other model refuses such numbers (exit 3). Now SolveError, one line naming the length."""
    from pdverify.core.errors import SolveError

    sc = _scene("clamped", "free", [{"type": "point_force", "position": length, "value": -1.0}], length=length, h=5e-5)
    with pytest.raises(SolveError) as e:
        run(sc, "exact-higher-order", points=41)
    assert len(e.value.lines) == 1 and "overflows" in e.value.lines[0] and f"length {length:g}" in e.value.lines[0]
