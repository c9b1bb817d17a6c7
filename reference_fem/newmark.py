"""Newmark's average-acceleration scheme (β = 1/4, γ = 1/2; trapezoidal rule) for M a + C v + K u = F from rest with
F constant in time (step loads at t = 0): unconditionally stable, second order in the step, no numerical damping
(the undamped energy ½ vᵀMv + ½ uᵀKu is conserved exactly). Arrays in, arrays out; the loop is over time steps,
each one sparse triangular solve with the matrix factorised once."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu


def newmark(K, M, C, F: np.ndarray, dt: float, steps: int, observe) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times, observe @ u at each time (steps + 1 rows), final u). ``K, M, C``: sparse (n, n); ``observe``:
    sparse (m, n) (e.g. the rows that pick the probes' DOFs)."""
    K, M, C = (sp.csc_matrix(A) for A in (K, M, C))
    step = splu((M + (dt / 2) * C + (dt * dt / 4) * K).tocsc())
    u, v = np.zeros(len(F)), np.zeros(len(F))
    a = splu(M).solve(F)  # from rest: M a0 = F
    out = np.empty((steps + 1, observe.shape[0]))
    out[0] = observe @ u
    for n in range(steps):
        u_pred, v_pred = u + dt * v + (dt * dt / 4) * a, v + (dt / 2) * a
        a = step.solve(F - C @ v_pred - K @ u_pred)
        u, v = u_pred + (dt * dt / 4) * a, v_pred + (dt / 2) * a
        out[n + 1] = observe @ u
    return dt * np.arange(steps + 1), out, u
