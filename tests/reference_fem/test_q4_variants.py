"""PLANE182 stand-ins (reference_fem/q4_variants.py): the plain 2x2 quad is scikit-fem's on rectangles, every
variant passes the patch test on distorted quads, and only the incompatible modes (QM6) and the reduced quad with
bending hourglass stiffness (q4-reduced, the same matrix on rectangles) do not lock."""

import numpy as np
import pytest
from helpers import ROOT

from pdverify.core.scene_file import load_scene
from pdverify.registry import run

skfem = pytest.importorskip("skfem")
from reference_fem import q4_variants  # noqa: E402

E, NU = 200e9, 0.3


def _mesh(distort: float):
    m = skfem.MeshQuad.init_tensor(np.linspace(0, 2, 6), np.linspace(0, 1, 4))
    p = m.p.copy()
    p[0] += distort * np.sin(3 * p[1]) * p[0] * (2 - p[0])
    m = skfem.MeshQuad(p, m.t)
    return m, skfem.Basis(m, skfem.ElementVector(skfem.ElementQuad1()))


def test_full_integration_is_scikit_fem_quad1_on_rectangles():
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    m, b = _mesh(0.0)
    lam, mu = lame_parameters(E, NU)
    K0 = linear_elasticity(2 * lam * mu / (lam + 2 * mu), mu).assemble(b)
    K1 = q4_variants.assemble(m, b, E, NU, "full")
    assert abs(K0 - K1).max() <= 1e-13 * abs(K0).max()


@pytest.mark.parametrize("variant", q4_variants.VARIANTS)
def test_patch_test_on_distorted_quads(variant):
    """A linear displacement field leaves no force on interior nodes (Taylor's correction makes QM6 pass)."""
    m, b = _mesh(0.15)
    u = np.zeros(b.N)
    u[b.nodal_dofs[0]] = 1e-3 * m.p[0] + 2e-3 * m.p[1]
    u[b.nodal_dofs[1]] = -3e-3 * m.p[0] + 0.5e-3 * m.p[1]
    K = q4_variants.assemble(m, b, E, NU, variant)
    f = K @ u
    inner = np.flatnonzero((m.p[0] > 1e-9) & (m.p[0] < 2 - 1e-9) & (m.p[1] > 1e-9) & (m.p[1] < 1 - 1e-9))
    assert abs(f[b.nodal_dofs[:, inner]]).max() <= 1e-12 * abs(f).max()
    assert abs(K - K.T).max() <= 1e-14 * abs(K).max()


def test_reduced_with_bending_hourglass_stiffness_is_qm6_on_rectangles():
    """On a rectangle the hourglass stiffness E (4ab/3) / a^2 of q4-reduced is what Wilson's incompatible modes leave
    after condensation (module docstring): the same matrix to round-off (measured 3.0e-16); distorted, they differ
    (measured 5.8e-2 of the largest entry on the quad below)."""
    m, b = _mesh(0.0)
    K6, Kr = (q4_variants.assemble(m, b, E, NU, v) for v in ("qm6", "reduced"))
    assert abs(K6 - Kr).max() <= 1e-14 * abs(K6).max()
    X = np.array([[[0.0, 0.0], [2.0, 0.1], [2.3, 1.4], [-0.2, 1.0]]])
    K6, Kr = (q4_variants.element_matrices(X, E, NU, v) for v in ("qm6", "reduced"))
    assert abs(K6 - Kr).max() > 1e-2 * abs(K6).max()


@pytest.mark.parametrize("variant", q4_variants.VARIANTS)
def test_no_spurious_zero_energy_modes(variant):
    """One distorted quad: rank 5 = 8 DOFs - 3 rigid-body modes (the one-point quad's two hourglass modes are
    stiffened; without K_hg the rank would be 3)."""
    X = np.array([[[0.0, 0.0], [2.0, 0.1], [2.3, 1.4], [-0.2, 1.0]]])
    ev = np.linalg.eigvalsh(q4_variants.element_matrices(X, E, NU, variant)[0])
    assert np.sum(ev > 1e-10 * ev.max()) == 5


@pytest.mark.slow
def test_reduced_converges_on_the_paper_cantilever():
    """L/h = 5 cantilever, tip force, q4-reduced on 25 x 2 .. 200 x 16 vs q8 201 x 16: tip errors 3.33e-3, 1.68e-3,
    6.12e-4, 1.85e-4 (orders 0.99, 1.45, 1.73: the clamped corners' singularity slows the coarse meshes)."""
    sc = load_scene(ROOT / "studies/paper_yang/cantilever_tip_force.toml")
    ref = run(sc, "fem-plane-stress", element="q8", points=201, layers=16).w[-1]
    e = [
        abs(run(sc, "fem-plane-stress", element="q4-reduced", points=n, layers=k).w[-1] / ref - 1)
        for n, k in ((26, 2), (51, 4), (101, 8), (201, 16))
    ]
    assert all(a > b for a, b in zip(e, e[1:])), e
    assert np.log2(e[2] / e[3]) > 1.5 and e[3] < 4e-4, e


@pytest.mark.parametrize("slenderness", [20, 100])
@pytest.mark.slow
def test_only_incompatible_modes_do_not_lock(slenderness):
    """Cantilever, tip force, the paper's mesh (100 x 8), tip deflection vs q8 201 x 16. Measured at L/h = 20 / 100:
    q4 (3x3) -1.71 / -27.4 %, q4-bbar -0.55 / -26.8 %, q4-qm6 -0.04 / -0.07 % (L/h = 1000: -97.5, -97.5, -3.4 %);
    q4-reduced as q4-qm6 (the same matrix on these rectangles)."""
    sc = load_scene(ROOT / "studies/paper_yang/cantilever_tip_force.toml").with_slenderness(slenderness)
    ref = run(sc, "fem-plane-stress", element="q8", points=201, layers=16).w[-1]
    e = {
        el: run(sc, "fem-plane-stress", element=el, points=101, layers=8).w[-1] / ref - 1
        for el in ("q4", "q4-bbar", "q4-qm6", "q4-reduced")
    }
    assert abs(e["q4-qm6"]) < 2e-3 and abs(e["q4-reduced"]) < 2e-3, e
    lock = 0.01 if slenderness == 20 else 0.2
    assert e["q4"] < -lock and e["q4-bbar"] < -lock / 2, e


def test_round_off_of_very_slender_strips_is_flagged():
    """L/h = 1e4 on 100 x 8 (element aspect 800): the incompatible-mode answer is round-off (measured -107 % vs
    exact Timoshenko, condition estimate 8.9e16, round-off bound 92): the run carries the round-off warning instead
    of a silent number."""
    sc = load_scene(ROOT / "studies/paper_yang/cantilever_tip_force.toml").with_slenderness(1e4)
    r = run(sc, "fem-plane-stress", element="q4-qm6", points=101, layers=8)
    assert r.info["cond"] * np.finfo(float).eps > 1.0 and r.info["error_bound"] > 1.0
    assert any("round-off bound" in w for w in r.info["warnings"])
