"""pd-rod / pd-timoshenko / pd-torsion at scale: the stencil-extended operator is the whole-grid assembly,
the banded and matrix-free paths give the answers of the sparse ones."""

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, ROOT, scene_dict

from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.numerics.linalg import solve_linear
from pdverify.papers.moyer import model as T
from pdverify.papers.moyer import operator as O
from pdverify.papers.moyer import spectrum as S
from pdverify.papers.moyer import steps as ST
from pdverify.papers.moyer import system as SY
from pdverify.papers.moyer import transient as TR
from pdverify.papers.moyer.kernels import EndPatched, node_loads
from pdverify.registry import run

AXIAL_LOADS = [
    {"type": "point_force", "position": 0.7, "value": 0.0, "axial": 300.0},
    {"type": "distributed", "value": 0.0, "axial": -70.0, "start": 0.2, "end": 1.1},
    {"type": "point_force", "position": 2.0, "value": 0.0, "axial": 50.0},
    {"type": "point_force", "position": 0.0, "value": 0.0, "axial": -20.0},
]
FORMS = [("corrected", "nodes"), ("paper", "nodes"), ("paper", "cells")]


def _whole_beam(sc, n, m, variant, grid):
    """K, b, ψ op and constant of the beam assembled on the whole grid (the route of the paper's notation)."""
    nn, x = O._grid(sc, n, grid, variant, "pd-timoshenko")
    dx = x[1] - x[0]
    q, mu, ends = node_loads(sc, x, "transverse", ends_apart=(variant == "corrected"))
    K, bw_parts, bg_parts, P, p0 = O._beam_core(sc, nn, dx, m, variant, grid, ends)
    bw, bg = q, mu
    for v in bw_parts:
        bw = bw + v
    for v in bg_parts:
        bg = bg + v
    if variant == "paper":
        for side in (0, 1):
            end = 0 if side == 0 else nn - 1
            bw[end] += ends[side][0] / dx
            bg[end] += ends[side][1] / dx
    b = np.empty(2 * nn)
    b[0::2], b[1::2] = bw, bg
    return K, b, P, p0


@pytest.mark.parametrize("m", [1, 3, 4, 10])
@pytest.mark.parametrize("variant,grid", FORMS)
def test_beam_operator_is_the_whole_grid_assembly_bit_for_bit(variant, grid, m):
    """Every support pair with mixed loads (also at the ends) on a grid three times the short one: the
    stencil-extended K, b and ψ operator equal the whole-grid sparse assembly exactly."""
    n = 3 * O._core_points(m) + 7
    for left, right in PAIRS:
        sc = parse_scene(scene_dict(left, right, MIXED_LOADS))
        d = O.beam_operator(sc, n, m, variant, grid)
        assert d.op.L > 0 and d.op.R > 0 and d.op.blocks  # the long grid does use the stencil
        K, b, P, p0 = _whole_beam(sc, n, m, variant, grid)
        assert (d.K != K).nnz == 0, (left, right)
        assert np.array_equal(d.b, b), (left, right)
        assert (d.psi[0].tocsr() != P).nnz == 0 and np.array_equal(d.psi[1], p0)
        u = np.random.default_rng(0).standard_normal(K.shape[1])
        assert np.allclose(d.op @ u, K @ u, rtol=0, atol=1e-13 * np.abs(K @ u).max())
        assert np.allclose(d.psi[0] @ u, P @ u, rtol=0, atol=1e-13 * np.abs(P @ u).max())


@pytest.mark.parametrize("kind", ["axial", "torsion"])
@pytest.mark.parametrize("variant,grid", FORMS)
def test_rod_operator_is_the_whole_grid_assembly_bit_for_bit(variant, grid, kind):
    for m in (1, 3, 10):
        n = 3 * O._core_points(m) + 5
        for left, right in PAIRS:
            loads = (
                AXIAL_LOADS
                if kind == "axial"
                else [{"type": "point_torque", "position": p, "value": 30.0} for p in (0.0, 0.7, 2.0)]
            )
            sc = parse_scene(scene_dict(left, right, loads))
            d = O.rod_operator(sc, n, m, variant, kind, grid)
            nn, x = O._grid(sc, n, grid, variant, "pd-rod")
            dx = x[1] - x[0]
            stiff = sc.EA if kind == "axial" else sc.material.G * sc.section.J
            q, _, ends = node_loads(
                sc, x, "axial" if kind == "axial" else "torque", ends_apart=(variant == "corrected")
            )
            K, bb = O._rod_core(sc, nn, dx, m, variant, stiff, ends, grid)
            b = q + bb
            if variant == "paper":
                for side in (0, 1):
                    b[0 if side == 0 else nn - 1] += ends[side][0] / dx
            assert (d.K != K).nnz == 0 and np.array_equal(d.b, b), (m, left, right)


def test_short_core_is_refused():
    sc = parse_scene(scene_dict("clamped", "free", MIXED_LOADS))
    _, x = O._grid(sc, 14, "nodes", "corrected", "x")  # m = 3: 4 end rows each side, reach 4: 19 points needed
    _, _, ends = node_loads(sc, x, "transverse", ends_apart=True)
    K, *_ = O._beam_core(sc, 14, x[1] - x[0], 3, "corrected", "nodes", ends)
    with pytest.raises(RuntimeError, match="holds no stencil rows"):
        EndPatched.from_core(K, 2, 2, 1000)


@pytest.mark.parametrize("left,right", [("clamped", "free"), ("pinned", "guided"), ("free", "clamped")])
@pytest.mark.slow
def test_largest_eigenvalue_from_the_short_grid_and_the_symbol(monkeypatch, left, right):
    """The large-grid time step: the end modes from the operator shortened to EIG_DOFS (same end rows), the
    interior from the stencil's symbol, against ARPACK on the whole operator (1400-1800 DOFs, EIG_DOFS
    lowered to 400 for the comparison). Measured agreement 1e-6 or better (ARPACK's tol = 1e-6)."""
    sc = parse_scene(
        scene_dict(
            left, right, MIXED_LOADS, material={"youngs_modulus": 2e11, "poissons_ratio": 0.3, "density": 7850.0}
        )
    )
    for d in (O.beam_operator(sc, 700, 3, "corrected"), O.rod_operator(sc, 1800, 2, "corrected")):
        whole = S._eig_max(d)
        with monkeypatch.context() as mp:
            mp.setattr(S, "EIG_DOFS", 400)
            assert S.largest_eigenvalue(d) == pytest.approx(whole, rel=1e-5)


@pytest.mark.parametrize("model,scene,horizon", [("pd-timoshenko", "beam_example2", 3), ("pd-rod", "rod_example1", 2)])
@pytest.mark.slow
def test_matrix_free_step_equals_the_csr_step(monkeypatch, model, scene, horizon):
    """The blockwise stencil step (small blocks: many of them, end rows in the first and last) against one
    CSR product per step: prescribed end motion, damping ratio, 3000 steps. Measured 8e-14 (rounding of
    the different summation order, accumulated)."""
    m = {"pd-timoshenko": T.PDTimoshenko(), "pd-rod": T.PDRod()}[model]
    sc = load_scene(ROOT / "studies" / "paper_moyer" / f"{scene}.toml")
    disc = m.operator(sc, m.resolve(sc, {"points": 301, "horizon": horizon}))
    motions = SY.prescribed_motions(sc, disc)
    assert any(v is not None for v in motions.values())
    out = {}
    for whole, chunk in ((10**9, ST.CHUNK), (0, 7)):
        monkeypatch.setattr(TR, "WHOLE_DOFS", whole)
        monkeypatch.setattr(ST, "CHUNK", chunk)
        out[whole] = TR.integrate(
            disc, motions, None, steps=3000, damping_ratio=0.05, record_every=50, damp_rotations=True
        )
    a, b = out[10**9], out[0]
    assert a.dt == b.dt and len(a.t) == len(b.t)
    assert np.abs(a.values - b.values).max() <= 1e-12 * np.abs(a.values).max()
    assert np.abs(a.final - b.final).max() <= 1e-12 * np.abs(a.final).max()


def test_in_place_band_solve_equals_the_refined_sparse_solve():
    """12,001 points (24,002 unknowns: LU in place, no refinement) against the refined banded solve of the
    free rows and columns of the same operator (assemble()): they differ by the unrefined LU's round-off,
    below cond eps (measured 0.006-0.06 cond eps; cond 7e9..1e11)."""
    for left, right in [("clamped", "free"), ("pinned", "pinned"), ("guided", "clamped")]:
        sc = parse_scene(scene_dict(left, right, MIXED_LOADS))
        r = run(sc, "pd-timoshenko", points=12_001)
        assert r.info["solver"].startswith("banded LU") and "refinement" not in r.info
        model = T.PDTimoshenko()
        system = model.assemble(sc, model.resolve(sc, {"points": 12_001}))
        K, b = system.reduced()
        sol, info = solve_linear(K, b, condition=True, refinement=True)
        u = np.zeros(2 * 12_001)
        u[system.free] = sol
        scale = np.abs(u[0::2]).max()
        assert np.abs(r.w - u[0::2]).max() <= info["cond"] * np.finfo(float).eps * scale, (left, right)
