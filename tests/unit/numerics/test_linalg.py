import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from pdverify.core.errors import SolveError
from pdverify.numerics.linalg import solve_linear


def lap(n):
    return sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()


@pytest.mark.parametrize("n", [50, 2000])
def test_banded_and_sparse_agree(n):
    K = lap(n)
    b = np.sin(np.arange(n))
    u1, i1 = solve_linear(K, b)
    u2, i2 = solve_linear(K, b, banded_max=0)
    assert i1["solver"].startswith("banded") and i2["solver"].startswith("sparse")
    assert np.allclose(u1, u2, rtol=1e-10, atol=1e-10 * np.abs(u1).max())
    exact = np.linalg.cond(K.toarray(), 1) if n <= 400 else None
    if exact:
        assert i1["cond"] == pytest.approx(exact, rel=1e-8)
    assert i1["residual"] < 1e-13


def test_singular_is_one_clear_error():
    K = lap(30).tolil()
    K[0, 0] = 1.0  # Neumann-Neumann: singular (constant mode)
    K[-1, -1] = 1.0
    with pytest.raises(SolveError) as e:
        solve_linear(K.tocsr(), np.ones(30), what="test beam")
    assert "test beam" in str(e.value) and "singular" in str(e.value)


def test_banded_lu_of_the_scaled_matrix_solves_both_directions():
    """banded_lu writes diag(s) K diag(s) straight into LAPACK's band array: its solves (plain and
    transposed) must equal dense solves of the scaled matrix, and the band storage must hold K."""
    import scipy.sparse as sp

    from pdverify.numerics.band import Band
    from pdverify.numerics.linalg import banded_lu, bandwidths, scale_symmetric

    rng = np.random.default_rng(3)
    n = 40
    K = sp.random(n, n, density=0.3, random_state=4, format="csr")
    K = sp.csr_matrix(K.multiply(abs(np.subtract.outer(np.arange(n), np.arange(n))) <= 3)) + 4 * sp.eye(n, format="csr")
    s = rng.uniform(0.5, 2.0, n)
    lo, up = bandwidths(K)
    solve, solve_t = banded_lu(K, lo, up, s)
    Ks = scale_symmetric(K, s).toarray()
    y = rng.normal(size=n)
    assert np.allclose(solve(y), np.linalg.solve(Ks, y), rtol=1e-12, atol=0)
    assert np.allclose(solve_t(y), np.linalg.solve(Ks.T, y), rtol=1e-12, atol=0)
    assert np.array_equal(Band.from_sparse(K, lo, up).diag(0), K.diagonal())


def _fourth_difference(n):
    """The clamped-ends fourth difference (integer entries, stored exactly), condition ~ (n / pi)^4."""
    e = np.ones(n)
    K = sp.diags([e[:-2], -4 * e[:-1], 6 * e, -4 * e[:-1], e[:-2]], [-2, -1, 0, 1, 2]).tolil()
    K[0, 0] = K[n - 1, n - 1] = 5
    return K.tocsr()


def test_refinement_goes_on_while_it_contracts():
    """A correction solved by a single-precision LU of a fourth difference with condition ~ 2e6 gains about
    cond * eps32 ~ 1/8 a step: past the three default steps refinement goes on while each step at least halves the
    last (up to REFINE_MOST), and ends far closer than three steps to the limit of refinement (forty steps)."""
    from pdverify.numerics.linalg import REFINE_MOST, refine

    K = _fourth_difference(120)
    b = K @ (np.sin(np.linspace(0.0, 3.0, 120)) + 0.1)
    lu = spla.splu(K.tocsc().astype(np.float32))

    def solve(r):
        return lu.solve(np.asarray(r, np.float32)).astype(float)

    u, steps = refine(K, b, solve(b), solve)
    three, _ = refine(K, b, solve(b), solve, steps=3, most=3)
    limit, _ = refine(K, b, solve(b), solve, steps=40, most=40)
    assert 3 < len(steps) <= REFINE_MOST
    assert all(b_ <= 0.5 * a for a, b_ in zip(steps[:-2], steps[1:-1]))  # each step but the last halved the one before
    assert np.abs(u - limit).max() < 0.1 * np.abs(three - limit).max()


def test_the_sparse_condition_estimate_is_the_same_on_every_run():
    """A sparse system's condition estimate is deterministic (Hager's method from a fixed start, not scipy's
    onenormest, whose random start gave pd-bond-pair's mirror-end system 15,733 to 15,812 from run to run and between
    two loads on one operator)."""
    from helpers import ROOT

    from pdverify.core.scene_file import load_scene
    from pdverify.numerics import factorcache
    from pdverify.registry import run

    got = []
    for seed, scene in ((1, "pp_sine"), (2, "pp_uniform"), (3, "pp_sine")):
        np.random.seed(seed)  # the global state onenormest drew from
        factorcache.clear()
        sc = load_scene(str(ROOT / "studies" / "nonlocal" / f"{scene}.toml"))
        got.append(run(sc, "pd-bond-pair", ends="mirror", horizon_length=0.2, points=161).info["cond"])
    assert got[0] == got[1] == got[2]
