"""Newmark's average-acceleration scheme (β = 1/4, γ = 1/2; trapezoidal rule) for M a + C v + K u = F from rest with
F constant in time (step loads at t = 0): unconditionally stable, second order in the step, no numerical damping
(the undamped energy ½ vᵀMv + ½ uᵀKu is conserved exactly). Arrays in, arrays out; the loop is over time steps,
each one pair of triangular solves with the step's matrix factorised once: a banded Cholesky factorisation (LAPACK
``pbtrf``/``pbtrs``) of a symmetric positive definite matrix with a narrow band (beam elements numbered along the axis:
a quarter of a sparse LU solve's time per step), else a sparse LU."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError, cholesky_banded, lapack
from scipy.sparse.linalg import splu

from pdverify.numerics.band import Band, bandwidths

BANDED_MAX = 64  # the widest half-band factorised as a band (beam elements: 3; a band this wide is still cheap)


def factorised(S) -> callable:
    """``solve(r)`` = S⁻¹ r for a sparse square S: by its banded Cholesky factor when S is symmetric (to the bit),
    positive definite and at most :data:`BANDED_MAX` wide, else by its sparse LU factors."""
    S = sp.csr_matrix(S)
    lower, upper = bandwidths(S)
    if lower == upper <= BANDED_MAX and (S != S.T).nnz == 0:
        try:
            upper_rows = Band.from_sparse(S, lower, upper).data[: upper + 1]  # LAPACK's upper form: ab[u + i - j, j]
            factor = cholesky_banded(upper_rows, check_finite=False)
        except LinAlgError:  # not positive definite: the LU below
            pass
        else:
            return lambda r: lapack.dpbtrs(factor, r)[0]
    return splu(S.tocsc()).solve


def newmark(K, M, C, F: np.ndarray, dt: float, steps: int, observe) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times, observe @ u at each time (steps + 1 rows), final u). ``K, M, C``: sparse (n, n); ``observe``:
    sparse (m, n) (e.g. the rows that pick the probes' DOFs)."""
    K, M, C = (sp.csr_matrix(A) for A in (K, M, C))
    step = factorised(M + (dt / 2) * C + (dt * dt / 4) * K)
    u, v = np.zeros(len(F)), np.zeros(len(F))
    a = factorised(M)(F)  # from rest: M a0 = F
    out = np.empty((steps + 1, observe.shape[0]))
    out[0] = observe @ u
    for n in range(steps):
        u_pred, v_pred = u + dt * v + (dt * dt / 4) * a, v + (dt / 2) * a
        a = step(F - C @ v_pred - K @ u_pred)
        u, v = u_pred + (dt * dt / 4) * a, v_pred + (dt / 2) * a
        out[n + 1] = observe @ u
    return dt * np.arange(steps + 1), out, u
