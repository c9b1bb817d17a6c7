"""pd-curved (PDDO curved Timoshenko–Ehrenfest beam) and exact-curved-cantilever.

References: exact-timoshenko (closed form, straight scenes), exact-curved-cantilever (statics +
quadrature), itself checked against a sympy closed form of the semicircle and Clapeyron's theorem."""

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, ROOT, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.exact.curved import Cantilever
from pdverify.registry import get_model, run

EXACT_T = get_model("exact-timoshenko")
EXACT_C = get_model("exact-curved-cantilever")


def rel(a, b):
    return np.linalg.norm(a - b) / np.linalg.norm(b)


def disp_error(res, f):
    """relative L2 error of the displacement vector (global components) over the particles"""
    d = np.hypot(res.fields["ux"] - f["ux"], res.fields["uy"] - f["uy"])
    return np.linalg.norm(d) / np.linalg.norm(np.hypot(f["ux"], f["uy"]))


# -- straight scenes vs exact-timoshenko ---------------------------------------------------------


@pytest.mark.parametrize("form, tol", [("mixed", 1e-6), ("primal", 2e-4)])
@pytest.mark.parametrize("pair", PAIRS)
def test_straight_every_support_pair_and_load_type(pair, form, tol):
    """Point forces and moments between particles and at the ends, partial uniform and sine loads."""
    sc = parse_scene(scene_dict(*pair, MIXED_LOADS))
    res = run(sc, "pd-curved", points=201, degree=4, form=form)
    f = EXACT_T.evaluate(sc, {}, res.x)
    scale = np.abs(f["w"]).max()
    assert np.abs(res.w - f["w"]).max() <= tol * scale
    assert np.abs(res.rotation - f["rotation"]).max() <= tol * np.abs(f["rotation"]).max()
    # at the ends and at point loads the exact M, V give one side or the other of the jump
    inner = np.ones(len(res.x), bool)
    inner[[0, -1]] = False
    for load in MIXED_LOADS:
        inner &= np.abs(res.x - load.get("position", -1.0)) > 1e-9
    assert np.abs(res.fields["M"] - f["M"])[inner].max() <= 50 * tol * np.abs(f["M"]).max()
    assert np.abs(res.fields["V"] - f["V"])[inner].max() <= 50 * tol * np.abs(f["V"]).max()
    assert np.abs(res.fields["u"]).max() <= 1e-9 * scale  # no axial load, no axial displacement


def test_straight_loads_off_the_grid_and_unequal_segments():
    loads = [
        {"type": "point_force", "position": 0.123, "value": -300.0},
        {"type": "distributed", "value": 700.0, "start": 0.4567, "end": 1.9, "shape": "sine"},
    ]
    sc = parse_scene(scene_dict("pinned", "clamped", loads))
    res = run(sc, "pd-curved", points=101, degree=5)  # measured 1.6e-13 (force) and 7.5e-10 (load)
    f = EXACT_T.evaluate(sc, {}, res.x)
    assert rel(res.w, f["w"]) < 1e-8
    assert res.info["solves"] == 2 and res.info["segments"] == 3  # one solve per load, each with its own breaks


def test_straight_axial_loads():
    """Axial point force (local and global frame) and a uniform axial load on a cantilever:
    u = P x / EA + p (L x - x²/2) / EA."""
    loads = [
        {"type": "point_force", "position": 2.0, "value": 0.0, "axial": 5e4},
        {"type": "point_force", "position": 1.0, "value": 0.0, "axial": -2e4, "frame": "global"},
        {"type": "distributed", "value": 0.0, "axial": 3e4},
    ]
    sc = parse_scene(scene_dict("clamped", "free", loads))
    res = run(sc, "pd-curved", points=101, degree=4)
    x, L, EA = res.x, sc.length, sc.EA
    u = (5e4 * x - 2e4 * np.minimum(x, 1.0) + 3e4 * (L * x - x**2 / 2)) / EA
    assert np.abs(res.fields["u"] - u).max() < 1e-8 * np.abs(u).max()
    assert np.abs(res.w).max() < 1e-9 * np.abs(u).max()
    # the point on the force inside the span carries the mean of its sides, the free end point its support's side
    # (docs/contract.md): nothing
    N = 5e4 - 2e4 * np.where(np.abs(x - 1.0) < 1e-12, 0.5, x < 1.0) + 3e4 * (L - x)
    N[-1] = 0.0
    assert np.abs(res.fields["N"] - N).max() < 1e-6 * np.abs(N).max()


# measured relative L2 error of w at 81 points (straight_sine.toml, slenderness 10), x 3 as the bound
SINE_81 = {
    "mixed": {2: 2.6e-3, 3: 1.3e-6, 4: 1.9e-6, 5: 1.2e-9, 6: 1.7e-10},  # P = 6: 7 members (default_horizon)
    "primal": {2: 1.5e-2, 3: 1.5e-2, 4: 1.2e-5, 5: 8.1e-6, 6: 8.0e-9},
}


@pytest.mark.parametrize("form", ["mixed", "primal"])
@pytest.mark.parametrize("P", [2, 3, 4, 5, 6])
def test_straight_sine_clamped_clamped_each_degree(P, form):
    """Seed 004 §4.1 at slenderness 10."""
    sc = load_scene("studies/paper_curved/straight_sine.toml")
    res = run(sc, "pd-curved", points=81, degree=P, form=form)
    f = EXACT_T.evaluate(sc, {}, res.x)
    assert rel(res.w, f["w"]) < 3 * SINE_81[form][P]


@pytest.mark.slow
def test_mixed_degree_6_has_no_error_floor_growing_with_the_particles():
    """Mixed form, P = 6, straight sine: with the default family (7 members, default_horizon) the error stays at
    round-off from 401 to 6401 particles (measured 4.0e-13, 5.3e-13, 1.8e-12); the 9-member family it replaced
    (horizon 4) has an error floor growing with n (3.9e-8, 2.2e-7, 1.2e-6)."""
    sc = load_scene("studies/paper_curved/straight_sine.toml")
    new, old = [], []
    for n in (401, 1601, 6401):
        for out, opts in ((new, {}), (old, {"horizon": 4})):
            res = run(sc, "pd-curved", points=n, degree=6, form="mixed", **opts)
            out.append(rel(res.w, EXACT_T.evaluate(sc, {}, res.x)["w"]))
    assert max(new) < 2e-11, new
    assert old[-1] > 10 * old[0] and old[-1] > 1e4 * new[-1], old


# -- the exact curved cantilever -----------------------------------------------------------------


def _sympy_semicircle(R, Px, Py, EA, kGA, EI):
    """Closed form (sympy) of the semicircle r = R (cos a, sin a), clamped at a = 0, force (Px, Py) at a = pi."""
    import sympy as sy

    a, b = sy.symbols("a b", real=True)
    t = sy.Matrix([-sy.sin(b), sy.cos(b)])
    n = sy.Matrix([-sy.cos(b), -sy.sin(b)])
    r = lambda v: R * sy.Matrix([sy.cos(v), sy.sin(v)])  # noqa: E731
    P = sy.Matrix([Px, Py])
    N, Q = P.dot(t), P.dot(n)
    d = r(sy.pi) - r(b)
    M = d[0] * Py - d[1] * Px
    ez = lambda v: sy.Matrix([-v[1], v[0]])  # noqa: E731
    integrand = (N / EA) * t + (Q / kGA) * n + (M / EI) * ez(r(a) - r(b))
    u = sy.integrate(integrand * R, (b, 0, a))
    phi = sy.integrate(M / EI * R, (b, 0, a))
    return sy.lambdify(a, [u[0], u[1], phi], "numpy")


@pytest.mark.parametrize("case", ["tangential", "normal"])
def test_exact_cantilever_matches_the_sympy_closed_form(case):
    sc = load_scene(f"studies/paper_curved/semicircle_{case}.toml")
    load = sc.loads[0]
    fn = _sympy_semicircle(1.0, load.axial, load.value, sc.EA, sc.kGA, sc.EI)
    s = np.linspace(0, np.pi, 37)
    ux, uy, phi = (np.broadcast_to(v, s.shape) for v in fn(s))
    f = Cantilever(sc).fields(s)
    scale = np.abs(np.r_[ux, uy]).max()
    assert np.abs(f["ux"] - ux).max() < 1e-12 * scale
    assert np.abs(f["uy"] - uy).max() < 1e-12 * scale
    assert np.abs(f["rotation"] - phi).max() < 1e-12 * np.abs(phi).max()


def test_exact_cantilever_clapeyron_on_a_quintic_axis():
    """P·u(L) + C φ(L) = ∫ (N²/EA + Q²/kGA + M²/EI) ds, independently integrated (Simpson)."""
    from scipy.integrate import simpson

    d = scene_dict("clamped", "free", [{"type": "point_force", "position": 0.0, "value": 0.0}])
    d["axis"] = {"type": "polynomial", "coefficients": [0.0, 0.75, -2.25, 1.5, -1.5, 1.5], "x_range": [0.0, 1.0]}
    from pdverify.core.geometry import axis_length
    from pdverify.core.scene import Axis

    L = axis_length(Axis(**d["axis"]))
    d["beam"] = {"length": L}
    d["loads"] = [
        {"type": "point_force", "position": L, "value": -800.0, "axial": 300.0, "frame": "global"},
        {"type": "point_moment", "position": L, "value": 120.0},
    ]
    sc = parse_scene(d)
    c = Cantilever(sc)
    s = np.linspace(0, L, 2001)
    N, Q, M, *_ = c.resultants(s)
    U = simpson(N**2 / sc.EA + Q**2 / sc.kGA + M**2 / sc.EI, x=s)
    end = c.fields(np.array([L]))
    W = 300.0 * end["ux"][0] - 800.0 * end["uy"][0] + 120.0 * end["rotation"][0]
    assert abs(W - U) < 1e-8 * U


def test_exact_cantilever_matches_exact_timoshenko_on_straight_scenes():
    loads = [
        {"type": "point_force", "position": 0.7, "value": -300.0},
        {"type": "point_moment", "position": 1.3, "value": 150.0},
        {"type": "point_force", "position": 2.0, "value": 80.0},
    ]
    for pair in (("clamped", "free"), ("free", "clamped")):
        sc = parse_scene(
            scene_dict(
                *pair, [dict(l, position=(l["position"] if pair[1] == "free" else 2.0 - l["position"])) for l in loads]
            )
        )
        x = np.linspace(0, 2, 41)
        f, g = EXACT_T.evaluate(sc, {}, x), EXACT_C.evaluate(sc, {}, x)
        assert rel(g["w"], f["w"]) < 1e-13 and rel(g["rotation"], f["rotation"]) < 1e-13
        assert np.abs(g["M"] - f["M"])[1:-1].max() < 1e-12 * np.abs(f["M"]).max()


# -- the semicircle ------------------------------------------------------------------------------


@pytest.mark.parametrize("form", ["mixed", "primal"])
@pytest.mark.parametrize("case", ["tangential", "normal"])
def test_semicircle_slenderness_10_401_points_degree_4(case, form):
    """The issue's target: relative displacement error below 1e-4 (P = 4, 401 points, L/h = 10)."""
    sc = load_scene(f"studies/paper_curved/semicircle_{case}.toml")
    res = run(sc, "pd-curved", points=401, degree=4, form=form)
    f = EXACT_C.evaluate(sc, {}, res.x)
    assert disp_error(res, f) < 1e-4
    assert rel(res.rotation, f["rotation"]) < 1e-4
    assert rel(res.fields["M"], f["M"]) < 1e-4
    assert rel(res.fields["N"], f["N"]) < 1e-3


def test_semicircle_converges_with_points():
    sc = load_scene("studies/paper_curved/semicircle_tangential.toml")
    errs = []
    for n in (41, 81):
        res = run(sc, "pd-curved", points=n, degree=4)
        errs.append(disp_error(res, EXACT_C.evaluate(sc, {}, res.x)))
    assert np.log2(errs[0] / errs[1]) > 3.5


# -- inputs ----------------------------------------------------------------------------------------


def test_bad_inputs():
    sc = parse_scene(scene_dict("clamped", "free", [{"type": "point_force", "position": 2.0, "value": -1.0}]))
    with pytest.raises(InputError, match="horizon"):
        run(sc, "pd-curved", degree=6, horizon=2)
    with pytest.raises(InputError, match="points"):
        run(sc, "pd-curved", points=5, degree=6)
    with pytest.raises(InputError, match="degree"):
        run(sc, "pd-curved", degree=1)
    with pytest.raises(InputError, match="cantilevers"):
        run(parse_scene(scene_dict("clamped", "clamped", [])), "exact-curved-cantilever")


def test_reports_condition_number_and_parameters():
    sc = load_scene("studies/paper_curved/semicircle_normal.toml")
    res = run(sc, "pd-curved", points=41, degree=3)
    assert np.isfinite(res.info["cond"]) and res.info["cond"] > 1
    assert res.info["family"] == 5 and res.info["degree"] == 3
    assert res.dofs == 6 * 41  # mixed form, resultants as unknowns
    assert run(sc, "pd-curved", points=41, degree=3, form="primal").dofs == 3 * 41


@pytest.mark.parametrize("case, P", [("straight_sine", 4), ("semicircle_tangential", 6)])
def test_mixed_form_is_free_of_locking_and_of_the_slenderness_round_off(case, P):
    """Mixed form, 401 points: the error does not grow from L/h = 10 to 10^4 when N, Q, M are unknowns
    (measured: straight P = 4 3.1e-9 / 3.4e-9, semicircle P = 6 1.3e-11 at every slenderness); with them
    substituted (3 unknowns per particle, condition ~ (L/h)^2) round-off takes over (straight 4.6e-6,
    semicircle 6e-3 at L/h = 10^4)."""
    base = load_scene(f"studies/paper_curved/{case}.toml")
    ref = EXACT_T if case == "straight_sine" else EXACT_C
    errs = {}
    for S in (10.0, 1e4):
        sc = base.with_slenderness(S)
        for un in ("resultants", "displacements"):
            res = run(sc, "pd-curved", points=401, degree=P, unknowns=un)
            f = ref.evaluate(sc, {}, res.x)
            errs[S, un] = rel(res.w, f["w"])
    assert errs[1e4, "resultants"] < 10 * errs[10.0, "resultants"] + 1e-10
    assert errs[1e4, "resultants"] < 1e-8
    assert errs[1e4, "displacements"] > 100 * errs[1e4, "resultants"]


# -- curved scenes with every load type ----------------------------------------------------------

CURVED_LOADS = [
    {"type": "distributed", "value": -2000.0, "start": 0.5, "end": 2.5},
    {"type": "distributed", "value": 300.0, "axial": -700.0, "shape": "sine", "frame": "global"},
    {"type": "distributed", "value": 0.0, "axial": 400.0, "start": 1.0, "end": 3.141592653589793},
    {"type": "point_force", "position": 1.234, "value": 500.0, "axial": -200.0},
    {"type": "point_force", "position": 0.777, "value": 100.0, "axial": 250.0, "frame": "global"},
    {"type": "point_moment", "position": 2.0, "value": 300.0},
    {"type": "point_moment", "position": 3.141592653589793 / 2, "value": -100.0},
]


@pytest.mark.parametrize("pair", [("clamped", "free"), ("free", "clamped")])
def test_semicircle_every_load_type_both_orientations(pair):
    """Local and global frames, partial spans, sine, forces and couples on and off the grid, vs the
    exact cantilever; measured displacement errors (P = 4) 4.6e-6 / 3.5e-8 / 8.6e-9 / 4.7e-10 at 101 / 201 /
    401 / 801 points (clamped-free), 2.3e-6 / 8.0e-8 / 2.1e-9 / 1.1e-10 (free-clamped); each load alone
    converges at order 4 (the sum's errors partly cancel, so its ratios vary)."""
    d = load_scene("studies/paper_curved/semicircle_normal.toml").to_dict()
    d["loads"], d["supports"] = CURVED_LOADS, {"left": pair[0], "right": pair[1]}
    sc = parse_scene(d)
    errs = []
    for n in (101, 401):
        res = run(sc, "pd-curved", points=n, degree=4)
        f = EXACT_C.evaluate(sc, {}, res.x)
        errs.append(disp_error(res, f))
        assert np.abs(res.rotation - f["rotation"]).max() < 1e-4 * np.abs(f["rotation"]).max()
    assert errs[1] < 3e-8 and errs[0] / errs[1] > 100


def test_straight_agrees_with_pd_timoshenko():
    """pd-timoshenko (its defaults) and pd-curved on the same straight scenes: both converge to
    exact-timoshenko, pd-curved much faster; their difference is pd-timoshenko's own error."""
    for pair in (("clamped", "clamped"), ("pinned", "guided"), ("free", "clamped")):
        sc = parse_scene(scene_dict(*pair, MIXED_LOADS))
        a, b = run(sc, "pd-timoshenko", points=201), run(sc, "pd-curved", points=201)
        f = EXACT_T.evaluate(sc, {}, a.x)
        scale = np.abs(f["w"]).max()
        assert np.allclose(a.x, b.x)
        assert np.abs(b.w - a.w).max() < 2e-3 * scale
        assert np.abs(b.w - f["w"]).max() < 1e-2 * np.abs(a.w - f["w"]).max()


# -- curved, statically indeterminate: exact-curved (force method) ---------------------------------


def test_exact_curved_matches_exact_timoshenko_for_every_support_pair():
    x = np.linspace(0, 2, 41)
    inner = np.ones(41, bool)
    inner[[0, -1]] = False
    for load in MIXED_LOADS:
        inner &= np.abs(x - load.get("position", -1.0)) > 1e-9
    for pair in PAIRS:
        sc = parse_scene(scene_dict(*pair, MIXED_LOADS))
        f, g = EXACT_T.evaluate(sc, {}, x), get_model("exact-curved").evaluate(sc, {}, x)
        assert rel(g["w"], f["w"]) < 1e-12 and rel(g["rotation"], f["rotation"]) < 1e-12
        assert np.abs(g["M"] - f["M"])[inner].max() < 1e-12 * np.abs(f["M"]).max()


@pytest.mark.parametrize("pair", PAIRS)
@pytest.mark.slow
def test_quintic_axis_every_support_pair_partial_load(pair):
    """Quintic axis (L/h = 10), uniform load on [0.874, 1.098] m and an oblique force, vs exact-curved;
    measured P = 4, mixed, 41 / 161 / 321 particles: worst over the pairs 1.2e-1 / 1.4e-4 / 4.8e-6 (pinned-
    pinned); the primal form 75 / 6.8e-2 / 2.8e-3 (membrane locking already at L/h = 10). A load ending
    0.22 m before a free end gave 170 % at 41 particles before the interface rows were fixed."""
    d = load_scene("studies/paper_curved/quintic_manufactured.toml").to_dict()
    L = d["beam"]["length"]
    d["supports"] = {"left": pair[0], "right": pair[1]}
    d["loads"] = [
        {"type": "distributed", "value": -2000.0, "start": 2.5 * L / np.pi, "end": L},
        {"type": "point_force", "position": 0.4 * L, "value": 300.0, "axial": 200.0},
    ]
    sc = parse_scene(d)
    res = run(sc, "pd-curved", points=321, degree=4)
    assert disp_error(res, get_model("exact-curved").evaluate(sc, {}, res.x)) < 2e-5


# -- band assembly -----------------------------------------------------------------------


def _sparse_resultant_system(model, sc, params, body=None):
    """The mixed form with resultant unknowns built by scipy.sparse products, as pd-curved did before it
    wrote its band directly: (K interleaved CSR, b, column scales)."""
    import scipy.sparse as sp

    from pdverify.papers.curved import pddo as _pddo
    from pdverify.papers.curved.assembly import conditions, resultant_units, unit_load
    from pdverify.papers.curved.particles import axis_frame, distributed_loads

    segs, inner, ends, m, size = model.discretise(sc, params)
    s = np.concatenate(segs)
    N = len(s)
    t, nv, kap, _, xa = axis_frame(sc, s)
    offs = np.cumsum([0] + [len(g) for g in segs])
    D1 = sp.block_diag([_pddo.derivative_matrices(g, params["degree"], size, (1,))[1] for g in segs], format="csr")
    I, Z, K_ = sp.identity(N, format="csr"), sp.csr_matrix((N, N)), sp.diags(kap)
    Eps, Gam, Chi = (sp.hstack(h, format="csr") for h in ([D1, -K_, Z], [K_, D1, -I], [Z, Z, D1]))
    C = sp.hstack([sp.vstack([Eps, Gam, Chi]), -sp.diags(np.repeat([1 / sc.EA, 1 / sc.kGA, 1 / sc.EI], N))])
    Eq = sp.hstack([sp.csr_matrix((3 * N, 3 * N)), sp.bmat([[D1, -K_, None], [K_, D1, None], [None, I, D1]])])
    K = sp.vstack([C, Eq], format="csr")
    pt, pn, mm = np.zeros(N), np.zeros(N), np.zeros(N)
    for i, g in enumerate(segs):
        sl = slice(offs[i], offs[i + 1])
        pt[sl], pn[sl] = distributed_loads(sc, g, t[sl], nv[sl], 0.5 * (g[0] + g[-1]))
    if body is not None:
        bt, bn, bm = body(s, xa)
        pt, pn, mm = pt + bt, pn + bn, mm + bm
    b = np.concatenate([np.zeros(3 * N), -pt, -pn, -mm])
    rows, vals, (rr, rc, rv) = conditions(
        sc, N, offs, segs, inner, ends, t, nv, 3 * N, True, lambda c, k: (np.array([(3 + c) * N + k]), np.array([1.0]))
    )
    keep = np.ones(6 * N)
    keep[rows] = 0.0
    K = (sp.diags(keep) @ K + sp.csr_matrix((rv, (rr, rc)), shape=K.shape)).tocsr()
    b = b * keep
    b[rows] = vals
    units = resultant_units(sc.length, np.full(N, sc.EA), np.full(N, sc.EI)).reshape(N, 6).T.ravel()
    K = (K @ sp.diags(units)).tocsr()  # the unknowns in the beam's units
    scale = 1.0 / abs(K).max(axis=1).toarray().ravel()
    K, b = (sp.diags(scale) @ K).tocsr(), b * scale
    cscale = 1.0 / abs(K).max(axis=0).toarray().ravel()
    K = (K @ sp.diags(cscale)).tocsr()
    cscale = cscale * units
    perm = np.arange(6 * N).reshape(6, N).T.ravel()
    inv = np.empty_like(perm)
    inv[perm] = np.arange(6 * N)
    Cm = K.tocoo()
    K = sp.csr_matrix((Cm.data, (inv[Cm.row], inv[Cm.col])), shape=K.shape)
    K.eliminate_zeros()
    beta = unit_load(b)
    return K, b[perm] / beta, cscale[perm] * beta


def _groups(sc):
    """The scenes solve() assembles: one per group of loads needing the same breaks."""
    from pdverify.papers.curved.particles import breakpoints

    groups = {}
    for load in sc.loads:
        bps, _, _ = breakpoints(sc.model_copy(update={"loads": [load]}))
        groups.setdefault(tuple(np.round(bps / sc.length, 12)), []).append(load)
    return [sc.model_copy(update={"loads": g}) for g in groups.values()] or [sc]


@pytest.mark.parametrize("P, points", [(2, 41), (4, 61), (5, 41), (6, 81)])
@pytest.mark.slow
def test_band_assembly_equals_the_sparse_route_bit_for_bit(P, points):
    """The band (block stencils, boundary and interface entries, row and column equilibration on the written
    diagonals only) holds the same numbers as the sparse products it replaced: every support pair with
    mixed loads (one system per load group), both semicircles, the quintic with the manufactured loads."""
    from pdverify.theory.curved_manufactured import body

    m = get_model("pd-curved")
    scenes = [(g, None) for pair in PAIRS for g in _groups(parse_scene(scene_dict(*pair, MIXED_LOADS)))]
    scenes += [(load_scene(f"studies/paper_curved/semicircle_{c}.toml"), None) for c in ("normal", "tangential")]
    q = load_scene("studies/paper_curved/quintic_manufactured.toml")
    scenes.append((q, body(q)))
    for sc, bd in scenes:
        params = m.resolve(sc, {"points": points, "degree": P})
        B, b, d = m.assemble_band(sc, params, bd)
        K0, b0, c0 = _sparse_resultant_system(m, sc, params, bd)
        K = B.tocsr()
        assert K.nnz == K0.nnz and (K != K0).nnz == 0
        assert np.array_equal(b, b0) and np.array_equal(d["cscale_i"], c0)
        assert B.lower == B.upper == 6 * (d["family"] - 1)  # the end families' reach, as the CSR's bandwidth


def test_band_solve_above_small_equals_the_csr_route_and_is_the_bench_limit():
    """Above 20,000 unknowns solve() factorises the band in place: the same bits as the CSR banded LU of
    the same matrix; assemble() (the System pdverify bench times) is that band and right-hand side,
    manufactured loads included."""
    from pdverify.numerics.linalg import SMALL, solve_linear
    from pdverify.theory.curved_manufactured import body

    sc = load_scene("studies/paper_curved/quintic_manufactured.toml")
    m = get_model("pd-curved-mms")
    params = m.resolve(sc, {"points": 4001})
    s = m.assemble(sc, params)
    B, b = s.matrix, s.rhs
    B1, b1, _ = m.assemble_band(sc, params, body(sc))
    K = B.tocsr()
    assert B.n > SMALL and s.unknowns == B.n and np.array_equal(b, b1) and np.abs(b).max() > 0
    assert (B1.tocsr() != K).nnz == 0
    u_band, info = solve_linear(B, b)
    assert info["solver"].startswith("banded LU (LAPACK gbtrf/gbtrs, assembled in place)")
    u_csr, _ = solve_linear(K, b, condition=False, refinement=False)
    assert np.array_equal(u_band, u_csr)


@pytest.mark.parametrize(
    "coefficients, x_range", [([0.0, 0.75, -2.25, 2.25, -2.25, 1.5], [0.0, 1.0]), ([0.3, -1.0, 0.0, 2.0], [-1.0, 1.5])]
)
@pytest.mark.slow
def test_axis_abscissae_is_the_geometry_inversion(coefficients, x_range):
    """pd-curved inverts s(x) once per assembly, integrating each Newton step from a table node: the root
    of s(x) = s to round-off, like geometry's inversion (from x0). Measured against 40-digit roots (mpmath)
    at 40 positions: 1 / 2 ulp (geometry 0.5 / 2 ulp) on the quintic / the steep cubic (|y'| up to 13.5),
    checked here at 12; the two inversions differ by up to 4 ulp on 3,000 positions."""
    import mpmath as mp

    from pdverify.core.geometry import AxisGeometry, axis_abscissae, axis_length
    from pdverify.core.scene import Axis

    axis = Axis(type="polynomial", coefficients=coefficients, x_range=x_range)
    L = axis_length(axis)
    sc = parse_scene(dict(scene_dict("clamped", "free"), beam={"length": L}, axis=axis.model_dump()))
    ulp = np.spacing(max(abs(x_range[0]), abs(x_range[1])))
    s = np.r_[0.0, np.sort(np.random.default_rng(5).uniform(0, L, 2000)), np.linspace(0, L, 1001), L]
    x = axis_abscissae(sc, s)
    assert np.abs(x - AxisGeometry(axis, L)._x_of_s(s)).max() <= 4 * ulp
    mp.mp.dps = 30
    c = [mp.mpf(v) for v in coefficients]
    ds = lambda v: mp.sqrt(1 + sum(i * c[i] * v ** (i - 1) for i in range(1, len(c))) ** 2)  # noqa: E731
    k = np.linspace(0, len(s) - 1, 12).astype(int)
    root = [float(mp.findroot(lambda v, si=mp.mpf(s[i]): mp.quad(ds, [x_range[0], v]) - si, mp.mpf(x[i]))) for i in k]
    assert np.abs(x[k] - root).max() <= 2 * ulp


def test_equilibrated_columns_and_interleaved_resultants():
    """After the row and column equilibration every column's largest entry is 1 (read from the written
    diagonals only); the resultant unknowns come back scaled by their column factors."""
    sc = parse_scene(scene_dict("pinned", "guided", MIXED_LOADS))
    m = get_model("pd-curved")
    for g in _groups(sc):
        B, b, d = m.assemble_band(g, m.resolve(g, {"points": 51, "degree": 4}))
        K = B.tocsr()
        assert np.abs(abs(K).max(axis=0).toarray().ravel() - 1.0).max() <= np.finfo(float).eps  # v * (1 / v)
        assert np.array_equal(d["cscale"][d["perm"]], d["cscale_i"])


# -- non-uniform particles (the curved PDDO paper: "not limited to uniform distributions") -------------------


def _steep_error(n, **opts):
    """Max displacement-vector error relative to the largest displacement: y = 10 x^5 cantilever, uniform load."""
    sc = load_scene("studies/paper_curved/steep_quintic_uniform.toml")
    r = run(sc, "pd-curved", points=n, **opts)
    e = get_model("exact-curved-cantilever").evaluate(sc, {}, r.x)
    return float(np.hypot(r.fields["ux"] - e["ux"], r.fields["uy"] - e["uy"]).max() / np.hypot(e["ux"], e["uy"]).max())


def test_graded_particles_reach_1e_3_with_four_times_fewer_on_the_steep_quintic():
    """y = 10 x^5, mixed P = 4: particles graded by curvature (ratio 20) reach 1e-3 with 53 particles (measured
    9.0e-4; 55: 7.7e-4), uniform ones need more than 4 x 53 = 212 (measured 1.55e-3 at 212, 1.04e-3 at 216,
    5.3e-4 at 220). The primal form gains as much: graded 101 particles 1.5e-4, uniform 221 1.1e-3."""
    assert _steep_error(53, grading=20.0) < 1e-3
    assert _steep_error(4 * 53) > 1e-3
    assert _steep_error(101, form="primal", grading=20.0) < 0.2 * _steep_error(221, form="primal")


@pytest.mark.parametrize("form", ["mixed", "primal"])
def test_grading_ratio_1_is_the_uniform_discretisation_bit_for_bit(form):
    """grading = 1 (the default) places the particles as before: the three paper examples give the same bits."""
    for name, model in (
        ("straight_sine", "pd-curved"),
        ("semicircle_normal", "pd-curved"),
        ("quintic_manufactured", "pd-curved-mms"),
    ):
        sc = load_scene(f"studies/paper_curved/{name}.toml")
        a = run(sc, model, points=81, degree=4, form=form)
        b = run(sc, model, points=81, degree=4, form=form, grading=1.0, graded_by="ends")
        for k in ("ux", "uy", "N", "Q", "M"):
            assert np.array_equal(a.fields[k], b.fields[k]), (name, k)


def test_graded_particles_keep_the_order_of_the_degree():
    """Irregular families (fixed count, so each particle's horizon follows its spacing) keep the PDDO order:
    straight sine, mixed P = 4, particles gathered at the clamped ends (ratio 4), 41 -> 161 particles
    (measured orders 3.98, 3.99; errors 2.3e-5, 1.5e-6, 9.1e-8: the interpolating stencil, P + 1 members)."""
    sc = load_scene("studies/paper_curved/straight_sine.toml")
    n = np.array([41, 81, 161])
    err = []
    for k in n:
        r = run(sc, "pd-curved", points=int(k), degree=4, grading=4.0, graded_by="ends")
        err.append(rel(r.w, EXACT_T.evaluate(sc, {}, r.x)["w"]))
    order = np.log(np.array(err[:-1]) / np.array(err[1:])) / np.log(2)
    assert np.all((order > 3.7) & (order < 4.6)), (err, order)


def test_graded_segment_grids_follow_the_density():
    """segment_grids with a density: the segment ends are kept, particles increase, and the spacing ratio is the
    grading ratio: ρ lies in [1, ratio], so no two spacings differ by more than the ratio, and a narrow bend
    comes close to it (curvature grading on the steep quintic, ratio 20: measured 14.6 at 201 particles)."""
    from pdverify.papers.curved.particles import grading_density, segment_grids

    sc = load_scene("studies/paper_curved/steep_quintic_uniform.toml")
    L = sc.length
    segs = segment_grids(L, np.array([0.3 * L]), 201, 5, grading_density(sc, 20.0, "curvature"))
    assert segs[0][0] == 0.0 and segs[0][-1] == segs[1][0] == 0.3 * L and segs[1][-1] == L
    s = np.concatenate(segs)
    h = np.diff(s)[np.diff(s) > 0]
    assert np.all(h > 0) and len(s) == 202
    assert 10 < h.max() / h.min() <= 20 * (1 + 1e-9)


def test_given_positions_reproduce_the_uniform_and_the_graded_particles():
    """positions = the particles' arc lengths (as a study or the CLI gives them): the uniform grid written out gives
    the same bits as points = 81; the graded grid written out gives the graded run; with a point load inside the
    beam the break is added to the given positions."""
    from pdverify.papers.curved.particles import grading_density, segment_grids

    sc = load_scene("studies/paper_curved/semicircle_normal.toml")
    text = lambda s: ", ".join(repr(float(v)) for v in s)  # noqa: E731
    a = run(sc, "pd-curved", points=81, degree=4)
    b = run(sc, "pd-curved", points=81, degree=4, positions=text(np.linspace(0, sc.length, 81)))
    assert np.array_equal(a.fields["ux"], b.fields["ux"]) and np.array_equal(a.fields["N"], b.fields["N"])
    st = load_scene("studies/paper_curved/steep_quintic_uniform.toml")
    g = segment_grids(st.length, np.array([]), 53, 7, grading_density(st, 20.0, "curvature"))[0]
    a = run(st, "pd-curved", points=53, grading=20.0)
    b = run(st, "pd-curved", points=53, positions=text(g))
    assert np.array_equal(a.fields["ux"], b.fields["ux"])
    d = sc.to_dict()
    d["loads"] = [{"type": "point_force", "position": 1.0, "value": -1000.0}]
    r = run(parse_scene(d), "pd-curved", points=81, degree=4, positions=text(np.linspace(0, sc.length, 41)))
    assert r.info["segments"] == 2 and r.info["particles"] == 43  # 41 given + the break on both sides


@pytest.mark.parametrize(
    "positions, match",
    [
        ("0, 0.5, x", "separated by commas"),
        ("0, 0.5, 9", r"\[0, L\]"),
        ("0, 0.5, 0.4, 1", "increase strictly"),
        ("0, 1, 2", "fewer than one family"),
    ],
)
def test_bad_positions_are_refused_with_one_line_naming_the_option(positions, match):
    sc = load_scene("studies/paper_curved/semicircle_normal.toml")
    with pytest.raises(InputError, match=match) as exc:
        run(sc, "pd-curved", points=81, degree=4, positions=positions)
    assert str(exc.value).startswith("positions") and "\n" not in str(exc.value)


def test_the_primal_form_says_it_locks():
    """form = primal locks (docs/models/curved.md, "Locking"; errors near 1 on coarse thick arcs went unwarned): every
    result says so, the default mixed form's does not."""
    sc = load_scene(ROOT / "studies/curved/quarter_circle_tip_force.toml")
    primal = run(sc, "pd-curved", form="primal", points=21)
    assert any(w.startswith("form = primal") and "locks" in w for w in primal.info["warnings"])
    mixed = run(sc, "pd-curved", points=21)
    assert not any("locks" in w for w in mixed.info.get("warnings", []))
