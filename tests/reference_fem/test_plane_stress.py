"""fem-plane-stress: against the exact Timoshenko cantilever, plane-stress constants, convergence orders,
the paper's five scenes, VTU output."""

import numpy as np
import pytest
from helpers import ROOT, scene_dict

from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.registry import run


def cantilever(sl):
    return parse_scene(
        scene_dict("clamped", "free", [{"type": "point_force", "position": 2.0, "value": -1000.0}])
    ).with_slenderness(sl)


@pytest.mark.parametrize("sl,tol", [(5, 2e-2), (20, 2e-2)])
def test_refined_q8_matches_exact_timoshenko(sl, tol):
    """Measured: -0.45 % (L/h = 5) and -0.11 % (L/h = 20): the 2D clamp and shear distribution differ
    slightly from Timoshenko's k = 5/6 beam."""
    sc = cantilever(sl)
    r = run(sc, "fem-plane-stress", element="q8", points=201, layers=16)
    ex = solve_straight(sc, True).fields(np.array([2.0]))["w"][0]
    assert abs(r.w[-1] / ex - 1) < tol


@pytest.mark.slow
def test_an_interior_couple_converges_to_the_beam_not_away_from_it():
    """An interior point moment is the bending stress's traction on its section line: the mid-line deflection
    then stays within the theories' O((h/L)^2) gap of exact Timoshenko on every mesh. The force pair on the
    neighbouring nodes it replaced drifted away under refinement, like a 2D point force (1.7e-2 at 101 points,
    1.1e-1 at 1601, pinned-pinned L/h = 20)."""
    sc = parse_scene(
        scene_dict("pinned", "pinned", [{"type": "point_moment", "position": 0.5, "value": 200.0}])
    ).with_slenderness(20)
    gap = (sc.section.depth / sc.length) ** 2
    errors = []
    for n in (101, 401, 1601):
        r = run(sc, "fem-plane-stress", points=n)
        ex = solve_straight(sc, True).fields(r.x)["w"]
        errors.append(np.abs(r.w - ex).max() / np.abs(ex).max())
    assert max(errors) < gap and errors[-1] < 1.1 * errors[0], errors
    assert r.info["load_resultant"][2] == pytest.approx(200.0, rel=1e-12)


@pytest.mark.slow
def test_long_fine_meshes_assemble_their_loads():
    """Edge loads go through scikit-fem's FacetBasis, whose inverse mapping stopped Newton at an absolute 1e-12 that
    float64 cannot reach once an element is ~1e-4 of the coordinates: 10001 points along a 1 m beam raised
    "Newton iteration didn't converge" (a bare Exception, no result). The mapping now stops at the coordinates'
    round-off, and the deflection is the same as a coarser mesh's to its discretisation error."""
    sc = parse_scene(scene_dict("clamped", "free", [{"type": "distributed", "value": -1000.0}]))
    fine = run(sc, "fem-plane-stress", element="q4", points=10001, layers=2)
    coarse = run(sc, "fem-plane-stress", element="q4", points=2001, layers=2)
    assert fine.w[-1] == pytest.approx(coarse.w[-1], rel=1e-4)


def test_plane_stress_not_plane_strain():
    """Plane strain would be stiffer by 1/(1 - nu^2) (~12 % for nu = 0.33) at L/h = 20: must be within 0.5 %."""
    sc = cantilever(20)
    r = run(sc, "fem-plane-stress", element="q9", points=101, layers=8)
    E, nu = sc.material.E, sc.material.poissons_ratio
    assert r.info["plane_stress_lambda"] == pytest.approx(E * nu / (1 - nu**2), rel=1e-12)
    ex = solve_straight(sc, True).fields(np.array([2.0]))["w"][0]
    assert abs(r.w[-1] / ex - 1) < 5e-3


@pytest.mark.slow
def test_convergence_orders_q4_q8(record_property):
    """Tip deflection of the clamped cantilever (L/h = 10), meshes 12x2 .. 48x8, against q9 200 x 32
    (2e-5 from 400 x 64).
    Measured: q4 errors 2.3e-1, 7.0e-2, 1.9e-2 (order 1.9, as expected); q8 3.6e-3, 1.1e-3, 3.7e-4
    (order ~1.5, NOT the 3-4 the issue expected): the fully clamped face has stress singularities at its
    two corners, which cap the rate of every element order (q9 also gives 1.6). The q8 error is still
    50x smaller than q4's on the same mesh."""
    sc = cantilever(10)
    ref = run(sc, "fem-plane-stress", element="q9", points=201, layers=32).w[-1]  # 2e-5 from 400 x 64
    orders = {}
    for el in ("q4", "q8"):
        errs = [
            abs(run(sc, "fem-plane-stress", element=el, points=n + 1, layers=l).w[-1] / ref - 1)
            for n, l in ((12, 2), (24, 4), (48, 8))
        ]
        orders[el] = float(np.log2(errs[1] / errs[2]))
        record_property(f"order_{el}", orders[el])
        record_property(f"errors_{el}", errs)
    assert orders["q4"] > 1.7 and orders["q8"] > 1.3, orders


@pytest.mark.parametrize(
    "name", ["ss_uniform", "ss_centre_force", "cc_uniform", "cantilever_tip_force", "cantilever_tip_moment"]
)
def test_yang_scenes_solve_with_paper_mesh(name, tmp_path):
    sc = load_scene(ROOT / f"studies/paper_yang/{name}.toml")
    r = run(sc, "fem-plane-stress", element="q4")  # 100 x 8 q4, the paper's PLANE182 mesh
    assert r.info["mesh"] == "100 x 8 q4" or r.info["mesh"].endswith("x 8 q4")
    ex = solve_straight(sc, True).fields(r.x)["w"]
    i = np.argmax(np.abs(ex))
    assert abs(r.w[i] / ex[i] - 1) < 5e-2  # thick beam (L/h = 5): 2D and Timoshenko differ by a few %
    import meshio

    r.writers[".vtu"](str(tmp_path / "r.vtu"))
    m = meshio.read(tmp_path / "r.vtu")
    assert m.point_data["displacement"].shape[1] == 3 and np.all(m.point_data["von_mises"] >= 0)
    assert list(m.cells_dict) == ["quad"]


def test_pvd_collection_of_a_load_series(tmp_path):
    """Three load levels written as VTU and collected in a .pvd that ParaView (and meshio) can follow."""
    import xml.etree.ElementTree as ET

    from reference_fem.plane_stress import write_pvd

    files = []
    for k, P in enumerate((-100.0, -200.0, -300.0)):
        sc = parse_scene(scene_dict("clamped", "free", [{"type": "point_force", "position": 2.0, "value": P}]))
        r = run(sc, "fem-plane-stress", points=11, layers=2)
        f = tmp_path / f"step{k}.vtu"
        r.writers[".vtu"](str(f))
        files.append((k + 1, str(f)))
    write_pvd(str(tmp_path / "series.pvd"), files)
    sets = ET.parse(tmp_path / "series.pvd").getroot().findall("./Collection/DataSet")
    assert [d.get("file") for d in sets] == ["step0.vtu", "step1.vtu", "step2.vtu"]
    assert [float(d.get("timestep")) for d in sets] == [1.0, 2.0, 3.0]


def test_locking_elements_warn_and_the_default_does_not_lock():
    """q4 and q4-bbar (full integration) lock in bending: every result says so. The default, q8, is within
    1e-3 of exact Timoshenko on the README's cantilever (L/h = 100, 100 x 8; measured -3.8e-4, q4 -27.9 %)."""
    sc = load_scene(ROOT / "studies/examples/cantilever_tip_load.toml")
    tip = solve_straight(sc, True).fields(np.array([sc.length]))["w"][0]
    default = run(sc, "fem-plane-stress")
    assert default.parameters["element"] == "q8" and abs(default.w[-1] / tip - 1) < 1e-3
    assert not any("locks" in w for w in default.info.get("warnings", []))
    for el in ("q4", "q4-bbar"):
        r = run(sc, "fem-plane-stress", element=el)
        assert abs(r.w[-1] / tip - 1) > 0.2  # locked (measured -27.9 % / -26.8 %)
        assert any(w.startswith(f"element = {el}: full integration locks in bending") for w in r.info["warnings"])


def test_a_strip_met_again_takes_its_kept_assembly_and_gives_the_same_bits():
    """Two loads on one strip: the second solve takes the first's basis and stiffness (reference_fem/plane_stress.py,
    basis_and_stiffness) and its supports' reduced operator (plane_conditions.constrained_system), and its result is
    the same to the bit as a solve with nothing kept."""
    from pdverify.numerics import factorcache
    from reference_fem import plane_conditions, plane_stress

    sc = cantilever(20)
    other = sc.model_copy(update={"loads": sc.loads[:0] + [sc.loads[0].model_copy(update={"value": 250.0})]})
    plane_stress._KEPT.clear()
    plane_conditions._REDUCED.clear()
    run(sc, "fem-plane-stress", points=41)
    kept = run(other, "fem-plane-stress", points=41)
    assert len(plane_stress._KEPT) == 1 and len(plane_conditions._REDUCED) == 1  # made once
    plane_stress._KEPT.clear()
    plane_conditions._REDUCED.clear()
    factorcache.clear()
    apart = run(other, "fem-plane-stress", points=41)
    assert np.array_equal(kept.w, apart.w) and kept.info["error_bound"] == apart.info["error_bound"]


def test_a_line_load_met_again_on_the_same_edges_takes_its_kept_facet_basis_and_gives_the_same_bits():
    """Two line loads on the same edges of one strip: the second takes the first's FacetBasis
    (reference_fem/curved_mesh.py) and its result is the same to the bit as a solve with nothing kept."""
    from pdverify.numerics import factorcache
    from reference_fem import curved_mesh, plane_stress

    sc = cantilever(20)
    line = [{"type": "distributed", "value": -1000.0, "start": 0.2, "end": 0.6}]
    first = sc.model_copy(update={"loads": parse_scene(scene_dict("clamped", "free", line)).loads})
    line[0]["value"] = 250.0
    other = sc.model_copy(update={"loads": parse_scene(scene_dict("clamped", "free", line)).loads})
    curved_mesh._FACETS.clear()
    run(first, "fem-plane-stress", points=41)
    kept = run(other, "fem-plane-stress", points=41)
    assert len(curved_mesh._FACETS) == 1  # one set of edges: its basis made once
    curved_mesh._FACETS.clear()
    plane_stress._KEPT.clear()
    factorcache.clear()
    apart = run(other, "fem-plane-stress", points=41)
    assert np.array_equal(kept.w, apart.w) and kept.info["error_bound"] == apart.info["error_bound"]


@pytest.mark.parametrize("element", ["ElementQuad1", "ElementQuadS2", "ElementQuad2"])
@pytest.mark.parametrize("lam", [1.2e11, -3e9])  # a negative lambda*: Poisson's ratio below 0
def test_the_batched_elasticity_form_is_scikit_fems(element, lam):
    """reference_fem.plane_stress.elasticity (every element's A W Aᵀ in one batched product) assembles scikit-fem's
    ``linear_elasticity`` on a distorted mesh; the two sum the same products in another order, so they agree to a
    few eps of the largest entry (a 16-term quadrature sum of products: 1e-14 is ~50 eps)."""
    import skfem
    from skfem.models.elasticity import linear_elasticity

    from reference_fem.plane_stress import elasticity

    m = skfem.MeshQuad.init_tensor(np.linspace(0, 2, 9), np.linspace(0, 0.3, 5))
    p = m.p.copy()
    p[0] += 0.1 * np.sin(3 * p[1]) * p[0] * (2 - p[0])
    b = skfem.Basis(skfem.MeshQuad(p, m.t), skfem.ElementVector(getattr(skfem, element)()))
    K0, K1 = linear_elasticity(lam, 8e10).assemble(b), elasticity(b, lam, 8e10)
    assert abs(K0 - K1).max() <= 1e-14 * abs(K0).max() and K1.nnz == K0.nnz
