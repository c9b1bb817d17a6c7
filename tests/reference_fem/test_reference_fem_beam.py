"""fem-eb and fem-timoshenko: nodally exact references; the naive Timoshenko element locks."""

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, ROOT, scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.registry import get_model, run

LOADS = MIXED_LOADS + [{"type": "distributed", "value": -250.0, "shape": "sine", "start": 0.35, "end": 1.7}]


def rel(model, scene, shear, **opts):
    r = run(scene, model, **opts)
    ex = solve_straight(scene, shear).fields(r.x)
    return np.abs(r.w - ex["w"]).max() / np.abs(ex["w"]).max(), np.abs(r.rotation - ex["rotation"]).max() / np.abs(
        ex["rotation"]
    ).max()


@pytest.mark.parametrize("left,right", PAIRS)
def test_fem_eb_nodally_exact(left, right):
    sc = parse_scene(scene_dict(left, right, LOADS))
    ew, er = rel("fem-eb", sc, False, points=11)
    assert ew < 1e-9 and er < 1e-9


@pytest.mark.parametrize("left,right", PAIRS)
@pytest.mark.parametrize("slenderness", [5, 100, 10_000])
def test_fem_timoshenko_iie_locking_free(left, right, slenderness):
    sc = parse_scene(scene_dict(left, right, LOADS)).with_slenderness(slenderness)
    ew, _ = rel("fem-timoshenko", sc, True, points=101)
    assert ew < 1e-6  # nodally exact up to round-off (measured 2e-14 .. 8e-9)


def test_naive_linear_element_locks_reduced_does_not():
    sc = parse_scene(scene_dict("clamped", "free", LOADS)).with_slenderness(10_000)
    full, _ = rel("fem-timoshenko", sc, True, points=101, variant="full")
    reduced, _ = rel("fem-timoshenko", sc, True, points=101, variant="reduced")
    assert full > 0.9  # locked: the deflection is ~1e-4 of the true one
    assert reduced < 1e-3


def test_fem_eb_evaluate_between_nodes_is_the_fe_solution():
    sc = parse_scene(scene_dict("clamped", "pinned", LOADS))
    m = get_model("fem-eb")
    x = np.linspace(0, 2, 333)
    f = m.evaluate(sc, m.resolve(sc, {"points": 41}), x)
    ex = solve_straight(sc, False).fields(x)["w"]
    assert np.abs(f["w"] - ex).max() / np.abs(ex).max() < 1e-3  # cubic interpolation error between nodes


def test_closed_form_hermite_equals_scikit_fem():
    """Above 20,001 nodes fem-eb assembles the same cubic Hermite element in closed form."""
    sc = parse_scene(scene_dict("clamped", "pinned", LOADS))
    m = get_model("fem-eb")
    params = m.resolve(sc, {"points": 41})
    (K1, F1, _), (K2, F2, _) = (m.assemble_band(sc, params, use_skfem=u) for u in (True, False))
    K1, K2 = K1.tocsr(), K2.tocsr()  # before the supports: every DOF compared
    assert abs(K1 - K2).max() < 1e-10 * abs(K1).max()
    # scikit-fem inverts a global-coordinate Vandermonde per element: agreement to ~1e-12, not 1e-16
    assert np.abs(F1 - F2).max() < 1e-10 * np.abs(F1).max()


@pytest.mark.parametrize("variant, gauss", [("reduced", [0.5]), ("full", [0.5 - 0.5 / 3**0.5, 0.5 + 0.5 / 3**0.5])])
def test_linear_timoshenko_in_scikit_fem_is_the_textbook_element(variant, gauss):
    """The scikit-fem form of the linear variants equals the element matrix written out (uneven elements):
    EI/l [theta' theta'] + kGA l sum_g wt_g B_g B_g^T, B = (-1/l, -(1 - xi), 1/l, -xi), DOFs (w, theta) per node."""
    from reference_fem.beam_elements import element_band, linear_timoshenko

    nodes = np.array([0.0, 0.3, 0.45, 1.0, 1.2])
    EI, kGA, l = 3.0, 700.0, np.diff(nodes)
    ke = EI / l[:, None, None] * np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0], [0, -1, 0, 1]], float)
    for xi in gauss:
        B = np.stack([-1 / l, -(1 - xi) * np.ones_like(l), 1 / l, -xi * np.ones_like(l)], axis=1)
        ke = ke + kGA / len(gauss) * l[:, None, None] * B[:, :, None] * B[:, None, :]
    want = element_band(ke, len(nodes)).tocsr().toarray()
    got = linear_timoshenko(nodes, EI, kGA, variant).tocsr().toarray()
    assert np.abs(got - want).max() < 1e-13 * np.abs(want).max()


def test_diagonal_assembly_equals_triplet_assembly():
    """assemble_elements accumulates diagonals by strided slices; it must equal the COO scatter."""
    import scipy.sparse as sp

    from reference_fem.beam_elements import assemble_elements

    rng = np.random.default_rng(0)
    ne = 9
    ke, fe = rng.normal(size=(ne, 4, 4)), rng.normal(size=(ne, 4))
    K, F = assemble_elements(ke, fe, ne + 1)
    dofs = 2 * np.arange(ne)[:, None] + np.arange(4)[None, :]
    K0 = sp.csr_matrix(
        (ke.reshape(ne, -1).ravel(), (np.repeat(dofs, 4, axis=1).ravel(), np.tile(dofs, (1, 4)).ravel())), shape=K.shape
    )
    assert abs(K - K0).max() < 1e-15 and np.allclose(F, np.bincount(dofs.ravel(), fe.ravel()))


def test_nodes_hold_every_load_position_and_element_loads_do_not_depend_on_the_block_size():
    """beam_nodes inserts load positions into the uniform grid (a position within 1e-12 L of a node is
    that node); element_loads integrates in blocks of elements: any block size gives the same vectors."""
    from reference_fem.beam_elements import beam_nodes, element_loads, hermite_shapes

    sc = parse_scene(scene_dict("clamped", "pinned", LOADS))
    x = beam_nodes(sc, 11)
    want = [v for l in LOADS for k, v in l.items() if k in ("position", "start", "end")]
    assert all(np.abs(x - p).min() < 1e-12 for p in want) and np.all(np.diff(x) > 0)
    assert len(beam_nodes(sc, 11)) == len(np.unique(np.r_[np.linspace(0, sc.length, 11), want]))
    assert np.array_equal(element_loads(sc, x, hermite_shapes), element_loads(sc, x, hermite_shapes, chunk=3))
    sc0 = parse_scene(scene_dict("clamped", "free", [{"type": "point_force", "position": 2.0, "value": -1.0}]))
    assert not element_loads(sc0, beam_nodes(sc0, 5), hermite_shapes).any()


@pytest.mark.parametrize("form", ["mixed", "direct"])
@pytest.mark.parametrize("left,right", PAIRS)
def test_nodal_moment_and_shear_are_the_exact_ones(left, right, form):
    """M and V at the nodes from each element's end forces ke u_e - fe: exact as the nodal values are (within 1e-9
    of their largest values: the direct form's round-off); at an inner node the mean of its two sides, at the end
    nodes their support's side, every load on them acting (MIXED_LOADS has a couple at x = 0 and a force at x = L),
    as exact-eb and exact-timoshenko give them."""
    sc = parse_scene(scene_dict(left, right, MIXED_LOADS))
    for exact, fem in (("exact-eb", "fem-eb"), ("exact-timoshenko", "fem-timoshenko")):
        r = run(sc, fem, points=41, form=form)
        ex = get_model(exact).evaluate(sc, {}, r.x)
        for key in ("M", "V"):
            assert np.abs(r.fields[key] - ex[key]).max() <= 1e-9 * np.abs(ex[key]).max(), (fem, key)


@pytest.mark.parametrize("left,right", PAIRS)
def test_moment_and_shear_between_the_nodes_are_the_exact_ones(left, right):
    """Between the nodes a reference's w, rotation, M and V are its elements' left ends carried across by their loads
    (statics, then the rotation and w integrated): exact as the nodal values are (within 1e-9), on 41 nodes. A study
    with fem-eb as its reference had no moment and shear (its evaluator gave w and the rotation only, a Hermite
    cubic); fem-timoshenko's, cubic splines through the nodal values, were 0.4-1 % off in M and V beside the point
    loads at 161 points from 401 nodes, and 0.68 % in the rotation from 101."""
    sc = parse_scene(scene_dict(left, right, MIXED_LOADS))
    x = np.linspace(0.0, sc.length, 1237)  # off the 41 grid's nodes but at its ends
    for exact, fem in (("exact-eb", "fem-eb"), ("exact-timoshenko", "fem-timoshenko")):
        fields = get_model(fem).evaluator(sc, get_model(fem).resolve(sc, {"points": 41}))(x)
        ex = get_model(exact).evaluate(sc, {}, x)
        keep = ~np.isin(x, [ld["position"] for ld in MIXED_LOADS if "position" in ld])  # a jump's two sides
        for key in ("w", "rotation", "M", "V"):
            assert np.abs(fields[key] - ex[key])[keep].max() <= 1e-9 * np.abs(ex[key]).max(), (fem, key)


def test_transient_probes_on_held_deflections_read_zero():
    """fem-timoshenko's transient observes each probe's w among the free unknowns: a probe on a held end (pinned at
    0, clamped at L) reads 0, and the others read what they read alone (before, a probe at the clamped end indexed
    past the free unknowns, and one at the pinned end read its rotation)."""
    import numpy as np
    from helpers import scene_dict

    from pdverify.core.scene_file import parse_scene
    from pdverify.registry import run

    def history(probes):
        d = scene_dict("pinned", "clamped", [{"type": "point_force", "position": 0.6, "value": -10.0}])
        d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3, "density": 7850.0}
        d["dynamics"] = {"end_time": 2e-3, "probes": probes, "output_interval": 1e-4}
        return run(parse_scene(d), "fem-timoshenko", points=41).info["history"]["series"]

    both, alone = history([0.0, 1.0, 2.0]), history([1.0])
    assert not np.any(both["w(x=0)"]) and not np.any(both["w(x=2)"])
    assert np.array_equal(both["w(x=1)"], alone["w(x=1)"]) and np.abs(alone["w(x=1)"]).max() > 0


def test_transient_probe_beside_a_node_is_read_inside_its_element():
    """A probe 1e-7 m from a node of a 2 m beam at 21 nodes was a node of its own: a 1e-7 m element whose Courant
    step (1.96e-11 s) asked for 2.5e9 steps and was refused with "use fewer points". It is now read inside its
    element (reference_fem.beam_transient.PROBE_SNAP): same default step as the probe on the node, and its history
    is the node's within 1e-7 m times the slope, a few 1e-7 of max |w| here (2 m cantilever, w' <= 2 max|w| / L)."""
    from pdverify.core.scene_file import load_scene

    sc = load_scene(ROOT / "studies/paper_moyer/beam_transient.toml")

    def history(probes):
        d = sc.dynamics.model_copy(update={"probes": probes, "end_time": 0.005})
        return run(sc.model_copy(update={"dynamics": d}), "fem-timoshenko", points=21).info

    near, on = history([1.0000001]), history([1.0])
    assert near["steps"] == on["steps"]
    a, b = near["history"]["series"]["w(x=1)"], on["history"]["series"]["w(x=1)"]
    assert np.abs(a - b).max() <= 1e-6 * np.abs(b).max()


@pytest.mark.parametrize("variant", ["iie", "reduced"])
def test_transient_probe_read_inside_its_element_stays_within_the_history_error(variant):
    """A probe PROBE_SNAP of an element from a node, read through the element's w interpolation instead of made a
    node, moves its history by about PROBE_SNAP times the history's own error against exact-modal-timoshenko
    (measured 0.05 iie, 0.094 reduced at 21 nodes, one time step for both); asserted: under a fifth of it."""
    import reference_fem.beam_transient as bt
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import get_model

    sc = load_scene(ROOT / "studies/paper_moyer/beam_transient.toml")
    p = 1.0 + 0.99 * bt.PROBE_SNAP * 0.1  # 21 nodes: h = 0.1 m
    sc = sc.model_copy(
        update={"dynamics": sc.dynamics.model_copy(update={"probes": [p], "end_time": 0.02, "time_step": 1e-5})}
    )
    inside = run(sc, "fem-timoshenko", points=21, variant=variant).info["history"]
    original = bt.PROBE_SNAP
    try:
        bt.PROBE_SNAP = 0.0
        node = run(sc, "fem-timoshenko", points=21, variant=variant).info["history"]
    finally:
        bt.PROBE_SNAP = original
    exact = get_model("exact-modal-timoshenko")
    ref = exact.history_at(sc, {o.name: o.default for o in exact.options}, [p], inside["t"])[:, 0]
    (a,), (b,) = inside["series"].values(), node["series"].values()
    assert np.abs(a - b).max() <= 0.2 * np.abs(b - ref).max()


@pytest.mark.parametrize("model", ["fem-eb", "fem-timoshenko"])
@pytest.mark.parametrize("points, gap", [(41, 1e-8), (641, 1e-6), (20001, 0.0)])
def test_moment_and_shear_are_exact_beside_a_short_element_and_on_fine_grids(model, points, gap):
    """The two-field form's M and V come from its element moments (first differences), not from k u (third
    differences of w, k ~ EI / h³): a point force ``gap`` L past a node left an element that short, and fem-eb's V was
    0.36 of max |V| off at 641 points and gap 1e-6 L, 1.1e6 at 1e-8 L (round-off bound 3.6e-15, no warning); on
    uniform grids V lost digits like N³ eps (8.3e-5 at 20001 nodes, 1.3 % at 10^5). Now within a hundred eps of the
    largest value, the evaluator between the nodes too. ``form = direct`` keeps k u and warns (its bound); with an
    element that short it assembles by the closed form (scikit-fem's Hermite basis was singular: a traceback)."""
    L = 2.0
    at = (points // 3) * L / (points - 1) + gap * L
    sc = parse_scene(scene_dict("clamped", "clamped", [{"type": "point_force", "position": at, "value": -1000.0}]))
    exact = solve_straight(sc, model == "fem-timoshenko")
    r = run(sc, model, points=points)
    keep = np.abs(r.x - at) > 1e-12 * L  # V jumps at the force: its node carries the mean of the two sides
    x = np.linspace(0.0, L, 997)
    between = get_model(model).evaluator(sc, dict(get_model(model).with_defaults({}), points=points))(x)
    for key in ("M", "V"):
        top = np.abs(exact.fields(r.x)[key]).max()
        assert np.abs(r.fields[key] - exact.fields(r.x)[key])[keep].max() <= 100 * np.finfo(float).eps * top
        assert np.abs(between[key] - exact.fields(x)[key]).max() <= 100 * np.finfo(float).eps * top
    if gap:
        direct = run(sc, model, points=points, form="direct")
        err = (
            np.abs(direct.fields["V"] - exact.fields(direct.x)["V"])[keep].max() / np.abs(exact.fields(r.x)["V"]).max()
        )
        assert err <= 1e-6 or any(w.startswith("round-off bound") for w in direct.info.get("warnings", [])), err
