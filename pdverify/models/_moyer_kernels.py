"""Kernels of the Moyer & Miraglia PD rod / Timoshenko beam (seed 001): arrays in, arrays out.

Quadrature weights of the peridynamic integrals for a horizon delta = m dx (integer m), the
extension of the real points to ghost points (Taylor extrapolation as published, or a polynomial
that satisfies the support's conditions), and the line loads of a scene on a node grid.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..scene import Distributed, PointForce, PointMoment, PointTorque, Scene
from .pd_eb import _cell_integral, stencil_operator


def trapezoid_weights(m: int) -> np.ndarray:
    """Composite trapezoidal weights of the nodes j = 1..m of ∫_0^m (unit spacing): 1 inside, 1/2 at m."""
    w = np.ones(m)
    w[-1] = 0.5
    return w


def rod_kernel(m: int) -> np.ndarray:
    """c_j of I_i = Σ_j c_j (u_{i+j} + u_{i-j} - 2 u_i) (Eq. 14–19 with the index of Eq. 16 corrected).

    The trapezoidal rule of ∫_{-δ}^{δ} (u(x+ε) - u(x)) / |ε| dε puts weight Δ (Δ/2 at ε = ±δ) on the
    node at jΔ, and the integrand there is (u_{i±j} - u_i) / (jΔ): c_j = w_j / j. The limits at ε -> 0±
    cancel (Eq. 14). Σ_j c_j 2 j² = m², so B I_i = (2E/(δ²ρ)) (m² Δ² u''/2 ... ) = E u''/ρ exactly for a quadratic."""
    j = np.arange(1, m + 1)
    return trapezoid_weights(m) / j


def shear_kernel(m: int, variant: str) -> tuple[np.ndarray, np.ndarray]:
    """(offsets, weights) of I_i = PV ∫_{-δ}^{δ} ψ(x_i + ε)/ε dε = Σ_j a_j (ψ(x_i + s_j Δ) - ψ(x_i - s_j Δ)).

    ``paper`` (Eq. 47): ψ at the nodes (s_j = j), trapezoidal rule on [1, m], and the centre interval
    [-1, 1] as ψ_{i+1} - ψ_{i-1}: a_j = w_j / j + (1/2 if j = 1).
    ``corrected``: ψ at the half points (s_j = j - 1/2, where w' is a compact difference), midpoint
    rule on each unit interval: a_j = 1 / (j - 1/2). Both give I = 2δψ' for a linear ψ."""
    j = np.arange(1, m + 1)
    if variant == "paper":
        a = trapezoid_weights(m) / j
        a[0] += 0.5
        return j.astype(float), a
    return j - 0.5, 1.0 / (j - 0.5)


def toeplitz(n_rows: int, row0: int, n_cols: int, offsets, coefs) -> sp.csr_matrix:
    """Row r holds ``coefs`` at columns r + row0 + offsets (repeated offsets add up); the shared
    diagonal-wise builder of pd-eb."""
    return stencil_operator(n_rows, row0, n_cols, offsets, coefs)


# -- ghost points --------------------------------------------------------------------------


def taylor_ghosts(n_ghost: int, order: int) -> np.ndarray:
    """Ghost values f(t), t = 1..n_ghost spacings outside the end, from the first four real values
    (f_0 at the end, f_k k spacings inside): f(t) = f_0 + t f'(0) + t² f''(0)/2 (``order`` 1 or 2),
    the derivatives by second-order one-sided differences (Eq. 20–21, 53)."""
    t = np.arange(1, n_ghost + 1, dtype=float)[:, None]
    d1 = np.array([1.5, -2.0, 0.5, 0.0])  # outward first derivative times Δ
    d2 = np.array([2.0, -5.0, 4.0, -1.0])  # second derivative times Δ²
    G = np.zeros((n_ghost, 4))
    G[:, 0] = 1.0
    G += t * d1
    if order >= 2:
        G += t**2 / 2 * d2
    return G


def taylor_ghosts_cells(n_ghost: int, order: int, anchored: bool) -> np.ndarray:
    """Section 4 ghost cells: f(s) = f(0) + f'(0) s + f''(0) s²/2 (``order`` 1 or 2) about the end face
    s = 0, ghosts at s = (t - 1/2)Δ, the real cells at s = -(k + 1/2)Δ. The face value and derivatives
    come from the polynomial of degree order + 1 through the face value (``anchored``: the support
    fixes it to zero) and the first cells (second-order one-sided differences). Returns G (n_ghost x 4)
    on the first four cells."""
    deg = order + 1
    sr = -(np.arange(4) + 0.5)
    need = deg if anchored else deg + 1  # cells used
    pts = sr[:need]
    X = np.concatenate([[0.0], pts]) if anchored else pts
    V = X[:, None] ** np.arange(deg + 1)
    C = np.linalg.inv(V)  # coefficients from the values (face first when anchored)
    if anchored:
        C = C[:, 1:]  # the face value is zero
    sg = np.arange(1, n_ghost + 1) - 0.5
    Vg = sg[:, None] ** np.arange(order + 1)  # Taylor series truncated at ``order``
    G = np.zeros((n_ghost, 4))
    G[:, :need] = Vg @ C[: order + 1]
    return G


def constrained_ghosts(n_fields: int, degree: int, npts: int, n_ghost: int,
                       constraints: list[tuple[dict, dict, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Ghost values as an affine map of the real values near an end: ghosts = R d + r0.

    Each field is a polynomial p_f(t) = Σ_q c_{f,q} t^q in the outward coordinate t = s/Δ (t = 0 at
    the end, t = -k at the k-th real point inward), fitted by least squares to its first ``npts`` real
    values d (field-major) subject to ``constraints``: each (coefficient terms {(f, q): factor},
    data terms {(f, k): factor}, constant) meaning Σ factor c_{f,q} = Σ factor d_{f,k} + constant.
    Returns R (n_fields n_ghost × n_fields npts) and r0 (per unit of the constants, summed)."""
    nc = degree + 1
    tr = -np.arange(npts, dtype=float)
    tg = np.arange(1, n_ghost + 1, dtype=float)
    Vr = tr[:, None] ** np.arange(nc)
    Vg = tg[:, None] ** np.arange(nc)
    V = np.kron(np.eye(n_fields), Vr)
    Vgh = np.kron(np.eye(n_fields), Vg)
    C = np.zeros((len(constraints), n_fields * nc))
    D = np.zeros((len(constraints), n_fields * npts))
    r = np.zeros(len(constraints))
    for i, (cterms, dterms, const) in enumerate(constraints):
        for (f, q), v in cterms.items():
            C[i, f * nc + q] += v
        for (f, k), v in dterms.items():
            D[i, f * npts + k] += v
        r[i] = const
    nk = len(constraints)
    KKT = np.block([[V.T @ V, C.T], [C, np.zeros((nk, nk))]])
    Z = np.linalg.inv(KKT)
    Z11, Z12 = Z[: n_fields * nc, : n_fields * nc], Z[: n_fields * nc, n_fields * nc:]
    Rc = Z11 @ V.T + Z12 @ D
    c0 = Z12 @ r
    return Vgh @ Rc, Vgh @ c0


def average_ghosts(degree: int, n_real: int, n_ghost: int) -> tuple[np.ndarray, np.ndarray]:
    """Interval averages of a polynomial p(s) = Σ a_q s^q extrapolated outward: the averages over the
    unit intervals centred at s = -(k + 1/2) (real, k = 0..n_real-1) are fitted by least squares with
    p(0) = v fixed; returns (R, r) with ghost averages (centres t + 1/2, t = 0..n_ghost-1) = R d + r v."""
    q = np.arange(degree + 1)

    def avg(c):
        c = np.asarray(c, float)[:, None]
        return ((c + 0.5) ** (q + 1) - (c - 0.5) ** (q + 1)) / (q + 1)

    Vr = avg(-(np.arange(n_real) + 0.5))
    Vg = avg(np.arange(n_ghost) + 0.5)
    pinv = np.linalg.pinv(Vr[:, 1:])
    R = Vg[:, 1:] @ pinv
    r = Vg[:, 0] - R @ Vr[:, 0]
    return R, r


# -- loads on a node grid ----------------------------------------------------------------------


def node_loads(scene: Scene, x: np.ndarray, component: str, ends_apart: bool):
    """Line loads on the nodes (per length): q (force) and mu (couple, ccw), and the loads applied
    exactly at the ends {0: (P, C), 1: (P, C)}.

    ``component``: "transverse" (load.value), "axial" (load.axial) or "torque" (point_torque, load.torque).
    Distributed loads: cell
    averages over [x - Δ/2, x + Δ/2] ∩ [0, L]; point forces and moments: P/Δ (C/Δ) split linearly
    between the two nearest nodes (the paper's body force p/(AΔ) in the loaded cell). ``ends_apart``:
    loads exactly at an end are returned in the end table instead (they enter the ghost conditions)."""
    n = len(x)
    dx = x[1] - x[0]
    L = scene.length
    q, mu = np.zeros(n), np.zeros(n)
    ends = {0: [0.0, 0.0], 1: [0.0, 0.0]}
    lo, hi = np.clip(x - dx / 2, 0, L), np.clip(x + dx / 2, 0, L)
    for load in scene.loads:
        if isinstance(load, Distributed):
            v = {"transverse": load.value, "axial": load.axial, "torque": load.torque}[component]
            if v != 0.0:
                q += _cell_integral(load, scene, lo, hi, v) / (hi - lo)
            continue
        if isinstance(load, PointTorque):
            if component != "torque":
                continue
            v, target, slot = load.value, q, 0
        elif isinstance(load, PointForce):
            if component == "torque":
                continue
            v, target, slot = (load.value if component == "transverse" else load.axial), q, 0
        elif isinstance(load, PointMoment):
            if component != "transverse":
                continue
            v, target, slot = load.value, mu, 1
        else:  # pragma: no cover - the scene format has no other type
            continue
        if v == 0.0:
            continue
        pos = (load.position - x[0]) / dx  # x[0] = Δ/2 on a cell-centred grid
        i = int(np.clip(np.floor(pos + 1e-9), 0, n - 1))
        t = pos - i
        if abs(t) < 1e-9 or i == n - 1 or t < 0:
            t = 0.0
        if ends_apart and t == 0.0 and i in (0, n - 1):
            ends[0 if i == 0 else 1][slot] += v
            continue
        target[i] += v * (1 - t) / dx
        if t > 0:
            target[i + 1] += v * t / dx
    return q, mu, ends


def motion_value(motion, t):
    """Prescribed end motion at times t (array): sine_ramp = A sin(2π f t) until hold_after, then the
    value reached there (A for the paper's quarter-period endings); sine = A sin(2π f t); step = A."""
    t = np.asarray(t, dtype=float)
    A = motion.amplitude
    if motion.type == "step":
        return np.full_like(t, A)
    f = motion.frequency
    if motion.type == "sine":
        return A * np.sin(2 * np.pi * f * t)
    th = motion.hold_after
    return np.where(t < th, A * np.sin(2 * np.pi * f * t), A * np.sin(2 * np.pi * f * th))


def motion_final(motion, end_time: float) -> float:
    """The value a prescribed motion settles at (the value at end_time for an endless sine)."""
    if motion.type == "sine":
        return float(motion_value(motion, end_time))
    return float(motion_value(motion, 1e300 if motion.type == "step" else motion.hold_after + 1.0))
