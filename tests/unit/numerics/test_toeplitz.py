"""The pieces of the large-horizon solver (pdverify/numerics/toeplitz.py, krylov.py) against dense matrices: the sine
transforms solve the reflected interior operator exactly, the FFT product is the truncated Toeplitz product, the
plan reads the stencil, the ends and the end correction off a band and refuses what is not Toeplitz away from its
ends."""

import numpy as np
import pytest

from pdverify.numerics.band import Band
from pdverify.numerics.krylov import gmres, pcg, plan
from pdverify.numerics.toeplitz import SineSolve, ToeplitzProduct, symbol, symbol_on_grid

EPS = np.finfo(float).eps


def stencil(p: int, R: int, seed: int = 0) -> np.ndarray:
    """An even block stencil T_q = T_-q (symmetric blocks) whose symbol is positive definite: a diagonally
    dominant centre."""
    rng = np.random.default_rng(seed)
    T = rng.standard_normal((R + 1, p, p))
    T = 0.5 * (T + T.transpose(0, 2, 1))
    full = np.concatenate([T[:0:-1], T])
    full[R] += (2 * np.abs(T[1:]).sum(axis=0).max() + 2 * p) * np.eye(p)
    return full


def reflected(T: np.ndarray, npos: int, parities) -> np.ndarray:
    """The dense matrix of the stencil on npos points with the ends' reflections written out: odd through the
    point one step beyond the last unknown (zero there), even through the last unknown."""
    R, p = (len(T) - 1) // 2, T.shape[1]
    A = np.zeros((npos * p, npos * p))
    for i in range(npos):
        for q in range(-R, R + 1):
            j, sign = i + q, 1.0
            if j < 0:
                if parities[0] == "odd":
                    j, sign = (None, 0.0) if j == -1 else (-2 - j, -1.0)
                else:
                    j = -j
            elif j > npos - 1:
                if parities[1] == "odd":
                    j, sign = (None, 0.0) if j == npos else (2 * npos - j, -1.0)
                else:
                    j = 2 * (npos - 1) - j
            if j is not None:
                A[i * p : i * p + p, j * p : j * p + p] += sign * T[q + R]
    return A


@pytest.mark.parametrize("p", [1, 2])
@pytest.mark.parametrize("parities", [("odd", "odd"), ("odd", "even"), ("even", "odd")])
def test_sine_transform_solves_the_reflected_operator(p, parities):
    """With odd (point-reflection) ends DST-I, with an odd and an even end the DST-III/DST-II pair diagonalise
    the interior operator: the solve of M x gives x to a few eps times cond(M), and the solve is symmetric (with an
    even end it is V Λ^-1 V^T, M^-1 times the inverse of the end point's weight 1/2)."""
    T, npos = stencil(p, 3), 11
    A = reflected(T, npos, parities)
    x = np.random.default_rng(1).standard_normal(npos * p)
    solve = SineSolve(T, npos, parities)
    assert solve.definite
    W = np.ones(npos * p)  # an even end point's weight 1/2 in the transform's inner product (V^T W V = I npos/2)
    if parities[1] == "even":
        W[-p:] = 0.5
    if parities[0] == "even":
        W[:p] = 0.5
    got = solve(W * (A @ x))  # the symmetric form V Λ^-1 V^T (2/npos) = A^-1 W^-1
    assert np.abs(got - x).max() <= 50 * np.linalg.cond(A) * EPS * np.abs(x).max()
    Mi = np.array([solve(e) for e in np.eye(npos * p)]).T
    assert np.abs(Mi - Mi.T).max() <= 50 * EPS * np.abs(Mi).max()


@pytest.mark.parametrize("p", [1, 2])
def test_fft_product_is_the_truncated_toeplitz_product(p):
    T, npos = stencil(p, 4, seed=2), 13
    R = 4
    A = np.zeros((npos * p, npos * p))
    for i in range(npos):
        for q in range(-R, R + 1):
            if 0 <= i + q < npos:
                A[i * p : i * p + p, (i + q) * p : (i + q) * p + p] = T[q + R]
    x = np.random.default_rng(3).standard_normal(npos * p)
    got = ToeplitzProduct(T, npos)(x)
    assert np.abs(got - A @ x).max() <= 50 * EPS * (np.abs(A) @ np.abs(x)).max()


@pytest.mark.parametrize("parities", [("odd", "odd"), ("odd", "even")])
def test_symbol_by_fft_is_the_cosine_sum(parities):
    T, npos = stencil(2, 5, seed=4), 20
    k = np.arange(npos)
    theta = np.pi * ((k + 1) / (npos + 1) if parities == ("odd", "odd") else (2 * k + 1) / (2 * npos))
    assert np.abs(symbol_on_grid(T, npos, parities) - symbol(T, theta)).max() <= 100 * EPS * np.abs(T).sum()


def band_of(A: np.ndarray, reach: int) -> Band:
    n = len(A)
    B = Band(n, reach, reach)
    rows, cols = np.nonzero(A)
    B.add_entries(rows, cols, A[rows, cols])
    return B


def beam(n: int, R: int, left: str = "held", right: str = "held", vary: float = 0.0) -> np.ndarray:
    """A fourth-difference-like operator Σ_j c_j (δ_j)² with reach 2R: held ends (unknowns past the ends zero,
    odd reflection exact) or a free end (the family truncated: rows annihilate constants); ``vary`` scales the
    stencil of the rows past the middle (a non-uniform grid)."""
    c = 1.0 / np.arange(1, R + 1) ** 2
    A = np.zeros((n, n))
    for i in range(n):
        s = 1.0 + (vary if i > n // 2 else 0.0)
        for j, cj in enumerate(c, 1):
            for off, w in ((-2 * j, 1), (-j, -4), (0, 6), (j, -4), (2 * j, 1)):
                k = i + off
                if 0 <= k < n:
                    A[i, k] += s * cj * w
                elif right == "free" and k >= n:
                    A[i, n - 1] += s * cj * w  # constant extrapolation: translations cost nothing
    return 0.5 * (A + A.T) if vary == 0.0 else A


def test_plan_reads_stencil_ends_and_correction():
    n, R = 200, 5
    pl, why = plan(band_of(beam(n, R), 2 * R), forced=True)
    assert pl is not None, why
    assert (pl.period, pl.parities, pl.symmetric) == (1, ("odd", "odd"), True)
    assert pl.reach == 2 * R
    rows = np.flatnonzero(np.diff(pl.correction.indptr))
    assert np.all((rows < 4 * (2 * R + 1)) | (rows >= n - 4 * (2 * R + 1)))


def test_plan_refuses_a_non_uniform_operator():
    pl, why = plan(band_of(beam(200, 5, vary=0.3), 10), forced=True)
    assert pl is None and "non-uniform" in why


def test_plan_auto_thresholds():
    """Automatic: a narrow band or a small system stays banded (and says why)."""
    pl, why = plan(band_of(beam(200, 5), 10))
    assert pl is None and "half-bandwidth" in why


def test_pcg_and_gmres_solve_a_preconditioned_system():
    """On the odd-reflected operator itself the preconditioner is exact (one iteration, two at round-off); on the
    truncated one (no ghosts: a low-rank change at each end) both methods converge to the tolerance."""
    n, R = 120, 3
    A = beam(n, R)
    T = np.zeros((4 * R + 1, 1, 1))
    T[:, 0, 0] = A[n // 2, n // 2 - 2 * R : n // 2 + 2 * R + 1]
    M = SineSolve(T, n, ("odd", "odd"))
    b = np.random.default_rng(5).standard_normal(n)
    for method in (pcg, gmres):
        for op, exact in ((reflected(T, n, ("odd", "odd")), True), (A, False)):
            x, its, ok = method(lambda v, op=op: op @ v, b, M, 1e-10)
            assert ok and (its <= 2 or not exact)
            # the recursive residual drifts from the true one by the products' rounding, ~ n eps |A| |x|
            floor = n * EPS * np.linalg.norm(np.abs(op) @ np.abs(x))
            assert np.linalg.norm(op @ x - b) <= 1e-10 * np.linalg.norm(b) + floor
