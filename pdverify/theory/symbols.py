"""The continuous symbols of the PD beam, rod and torsion operators at a horizon delta, their gradient coefficients,
and the closed-form continuum solutions of mirror-ended members as series of the mirror modes
(docs/design/nonlocal.md; the solver that uses them: :mod:`pdverify.theory.continuum`).

With odd (point-reflection) ghost images at both ends, sin(kx), k = n pi / L, is an eigenfunction of a PD operator
whose sums become integrals over the horizon, so a member under any load is a sine series whose terms are the load's
sine coefficients times the operator's compliance 1 / lambda(k). An even image at one end makes the quarter-wave
modes sin((n - 1/2) pi x / L) (odd left) or cos((n - 1/2) pi x / L) (odd right) the eigenfunctions instead.

Each symbol is written as the local one times a factor f(z) of z = k delta, f = 1 - g z^2 + O(z^4): the PD member is
softer than the local one on a wave of number k by 1 / f = 1 + g (k delta)^2 + ..., and g is its gradient
coefficient (PD ~ local + g delta^2 d^2 / dx^2 of the local operator):

================  =====================================================================  ==========
model             factor f(z) (closed form: Si, Ci sine and cosine integrals)             g
================  =====================================================================  ==========
pd-eb             curvature S(k) = k^2 s(z), s = (1/z) ∫_0^z 4 sin^2(t/2) / t^2 dt;       1/18
                  lambda = EI S^2, f = s^2 (Diyaroglu et al. 2019, Eq. 11a, 13-15)
pd-bond-pair      (3 / z^3) ∫_0^z 16 sin^4(t/2) / t^2 dt  (O'Grady & Foster 2014, omega=1)  1/10
pd-rod, torsion   r(z) = (4 / z^2) ∫_0^z (1 - cos t) / t dt  (Moyer & Miraglia 2014,        1/24
                  Eq. 13-19: (2E/delta^2) ∫ (u(x+e) - u(x)) / |e| de)
pd-timoshenko     bending r(z) s1(z), shear s1(z) = Si(z) / z (Eq. 47: PV ∫ psi(x+e)/e de)  7/72, 1/18
pd-higher-order   the bond measures' averages: r(z) on every difference measure,          (1 - 4 nu^2)
                  p(z) = 2 (1 - cos z) / z^2 on the products of a difference with the     / (24 (1 - nu^2))
                  point measure s = 2 xi w* (Yang et al. 2020, Eq. 14-15)                  when slender
================  =====================================================================  ==========

pd-higher-order's symbol is a 4 x 4 matrix (theta, theta*, w, w*), :func:`higher_order_symbol`: the local theory's
(Yang et al. 2020, Eq. 9) with the two factors above on its entries; minimising over w* turns the bending energy's
E' h^3 / 12 (a^2 + 2 nu a s + s^2) into E h^3 / 12 (r - nu^2 p^2) / (1 - nu^2), hence g in the slender limit
(thicker beams: the shear and w* terms add a little, 0.0300 at L/h = 5, nu = 0.3, against 0.0293).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.special import sici

from ..core.scene import Distributed, PointForce, PointTorque, Scene

GRADIENT = {
    "curvature": 1.0 / 18.0,  # pd-eb: s(z)^2 = 1 - z^2/18 + ...
    "bond-pair": 1.0 / 10.0,  # pd-bond-pair, omega = 1
    "rod": 1.0 / 24.0,  # pd-rod, pd-torsion
    "timoshenko-bending": 7.0 / 72.0,  # pd-timoshenko, the bending part of w: 1 / (r s1)
    "timoshenko-shear": 1.0 / 18.0,  # pd-timoshenko, the shear part of w: 1 / s1
}


def higher_order_gradient(nu: float) -> float:
    """g of pd-higher-order's slender limit: (1 - 4 nu^2) / (24 (1 - nu^2)) (module docstring)."""
    return (1.0 - 4.0 * nu * nu) / (24.0 * (1.0 - nu * nu))


_GL_T, _GL_W = np.polynomial.legendre.leggauss(40)
SMALL = 2.0  # z below this: Gauss-Legendre on [0, z] (the closed forms cancel there)


def _quadrature(f: Callable, z: np.ndarray) -> np.ndarray:
    """∫_0^z f(t) dt for each z (a smooth integrand, z <= SMALL: 40 Gauss-Legendre points, exact to round-off)."""
    t = 0.5 * z[:, None] * (_GL_T[None, :] + 1.0)
    return 0.5 * z * (f(t) @ _GL_W)


def _factor(z, small: Callable, large: Callable) -> np.ndarray:
    z = np.abs(np.asarray(z, float))
    out = np.ones_like(z)
    lo = (z > 0) & (z <= SMALL)
    hi = z > SMALL
    if lo.any():
        out[lo] = small(z[lo])
    if hi.any():
        out[hi] = large(z[hi])
    return out


def curvature_factor(z) -> np.ndarray:
    """s(z) = S(k) / k^2 of the PD curvature (1/delta) ∫_0^delta (w(x+xi) + w(x-xi) - 2w(x)) / xi^2 dxi on sin(kx):
    (1/z) ∫_0^z 4 sin^2(t/2) / t^2 dt = (2/z) (Si(z) - (1 - cos z) / z) = 1 - z^2/36 + z^4/1800 - ..."""

    def large(z):
        si, _ = sici(z)
        return 2.0 / z * (si - (1.0 - np.cos(z)) / z)

    return _factor(z, lambda z: _quadrature(lambda t: _sinc2(t), z) / z, large)


def _sinc2(t):
    """4 sin^2(t/2) / t^2, 1 at t = 0."""
    return np.sinc(t / (2 * np.pi)) ** 2


def bond_pair_factor(z) -> np.ndarray:
    """lambda / (EI k^4) of the bond-pair beam with omega = 1 and alpha = 3 EI / delta^3:
    (3/z^3) ∫_0^z 16 sin^4(t/2) / t^2 dt = 1 - z^2/10 + ..."""

    def large(z):
        return (
            3.0 / z**3 * (-(6.0 - 8.0 * np.cos(z) + 2.0 * np.cos(2 * z)) / z + 8.0 * sici(z)[0] - 4.0 * sici(2 * z)[0])
        )

    return _factor(z, lambda z: 3.0 / z**3 * _quadrature(lambda t: t**2 * _sinc2(t) ** 2, z), large)


def rod_factor(z) -> np.ndarray:
    """r(z) of the rod kernel: (2E/delta^2) ∫_{-delta}^{delta} (u(x+e) - u(x)) / |e| de on sin(kx) is -E k^2 r(k delta)
    sin(kx), r = (4/z^2) ∫_0^z (1 - cos t) / t dt = (4/z^2) (gamma + ln z - Ci(z)) = 1 - z^2/24 + ..."""

    def large(z):
        return 4.0 / z**2 * (np.euler_gamma + np.log(z) - sici(z)[1])

    return _factor(z, lambda z: 4.0 / z**2 * _quadrature(lambda t: 0.5 * t * _sinc2(t), z), large)


def shear_factor(z) -> np.ndarray:
    """s1(z) = Si(z) / z: the principal value ∫_{-delta}^{delta} psi(x+e) / e de on cos(kx) is -2 Si(k delta) sin(kx),
    against the local 2 delta psi' (Moyer & Miraglia 2014, Eq. 47) = 1 - z^2/18 + ..."""
    return _factor(z, lambda z: _quadrature(lambda t: np.sinc(t / np.pi), z) / z, lambda z: sici(z)[0] / z)


# the factor f(k delta) = lambda / lambda_local of each kernel (module docstring): a wave of number k vibrates at
# sqrt(f) times its local frequency
FACTORS: dict[str, Callable] = {
    "curvature": lambda z: curvature_factor(z) ** 2,
    "bond-pair": bond_pair_factor,
    "rod": rod_factor,
}


def frequency_shift(kernel: str, k, delta: float) -> np.ndarray:
    """sqrt(f(k delta)) - 1: the relative frequency shift of a wave of number k in the continuum of ``kernel``'s
    operator at the horizon delta (exact for the mirror modes, whose shape is that wave; the bulk wave's otherwise)."""
    return np.sqrt(FACTORS[kernel](np.asarray(k, float) * delta)) - 1.0


# -- closed forms: series of the mirror modes ------------------------------------------------------------------


@dataclass(frozen=True)
class Series:
    """The continuum of a member whose ends are mirror images: ``left`` / ``right`` ``"odd"`` (the end holds the
    unknown: point reflection) or ``"even"`` (reflection: the end's slope of the unknown is zero); ``compliance(k)``
    the response of the measured quantity to a unit load ``component`` on the mode of wave number k (1 / lambda);
    ``slope(k)`` the rotation's per unit load (the derivative of the mode over k; None: k compliance(k), the slope of
    w); ``quantity``: w, u or twist."""

    left: str
    right: str
    compliance: Callable[[np.ndarray], np.ndarray]
    component: str = "value"  # value (transverse), axial, torque
    quantity: str = "w"
    slope: Callable[[np.ndarray], np.ndarray] | None = None


def modes(left: str, right: str, L: float, n: int) -> tuple[np.ndarray, str]:
    """(k, kind): the first n wave numbers of the mirror modes and whether they are sines or cosines of k x:
    odd-odd sin(n pi x / L); odd-even sin((n - 1/2) pi x / L); even-odd cos((n - 1/2) pi x / L)."""
    j = np.arange(1, n + 1, dtype=float)
    if left == "odd" and right == "odd":
        return j * np.pi / L, "sin"
    return (j - 0.5) * np.pi / L, ("sin" if left == "odd" else "cos")


def _mode(kind: str, k, x):
    return np.sin(k * x) if kind == "sin" else np.cos(k * x)


def _mode_slope(kind: str, k, x):
    """The mode's derivative over k."""
    return np.cos(k * x) if kind == "sin" else -np.sin(k * x)


def _amount(load, component: str) -> float:
    if component == "value":
        return 0.0 if isinstance(load, PointTorque) else float(load.value)
    if component == "torque":
        return float(load.value) if isinstance(load, PointTorque) else float(getattr(load, "torque", 0.0))
    return float(getattr(load, component, 0.0))


def load_coefficients(scene: Scene, series: Series, k: np.ndarray, kind: str) -> np.ndarray | None:
    """q_n = (2/L) ∫_0^L q phi_n dx of the scene's loads on the modes (point forces and torques, uniform and sine
    distributed loads on any span), or None when a load has no closed form here (a point moment)."""
    L = scene.length
    q = np.zeros_like(k)
    for load in scene.loads:
        v = _amount(load, series.component)
        if v == 0.0:
            continue
        if isinstance(load, (PointForce, PointTorque)):
            q += 2.0 / L * v * _mode(kind, k, load.position)
        elif isinstance(load, Distributed):
            a, b = scene.span(load)
            q += 2.0 / L * v * _span_integral(load.shape, a, b, L, k, kind)
        else:  # a point moment: the derivative of a delta, left to the extrapolation
            return None
    return q


def _integral_cos(c: np.ndarray, a: float, b: float) -> np.ndarray:
    """∫_a^b cos(c x) dx (b - a at c = 0)."""
    zero = np.abs(c) < 1e-300
    c_ = np.where(zero, 1.0, c)
    return np.where(zero, b - a, (np.sin(c_ * b) - np.sin(c_ * a)) / c_)


def _integral_sin(c: np.ndarray, a: float, b: float) -> np.ndarray:
    """∫_a^b sin(c x) dx (0 at c = 0)."""
    zero = np.abs(c) < 1e-300
    c_ = np.where(zero, 1.0, c)
    return np.where(zero, 0.0, (np.cos(c_ * a) - np.cos(c_ * b)) / c_)


def _span_integral(shape: str, a: float, b: float, L: float, k: np.ndarray, kind: str) -> np.ndarray:
    """∫_a^b shape(x) phi(k x) dx: shape 1 (uniform) or sin(pi x / L) (sine, as :mod:`pdverify.numerics.loads` has
    it), phi sin or cos (products to sums)."""
    if shape == "uniform":
        return _integral_sin(k, a, b) if kind == "sin" else _integral_cos(k, a, b)
    p = np.pi / L
    if kind == "sin":  # sin(px) sin(kx) = [cos((k-p)x) - cos((k+p)x)] / 2
        return 0.5 * (_integral_cos(k - p, a, b) - _integral_cos(k + p, a, b))
    return 0.5 * (_integral_sin(k + p, a, b) - _integral_sin(k - p, a, b))  # sin(px) cos(kx)


def _periods(x: np.ndarray, L: float) -> int | None:
    """M when the points are x_j = j L / M (a whole number of intervals from 0): every mode's values there repeat
    with period 2M in its index, so a series is summed from its coefficients folded modulo 2M."""
    if len(x) < 2 or x[0] != 0.0:
        return None
    M = round(L / (x[1] - x[0]))
    if M < 1 or np.abs(x - np.arange(len(x)) * (L / M)).max() > 1e-12 * L:
        return None
    return int(M)


def _out_of_reach(history: list, terms: int, block: int, most: int, need: float) -> bool:
    """Whether estimates falling at the better of their last two rates per block (each block doubles the terms) stay
    above twice ``need`` when the summing ends (the first block boundary at ``most`` terms or past it; ``terms``
    summed so far, ``block`` the next block's size)."""
    rates = [b / a if a > 0 else 0.0 for a, b in zip(history[-3:-1], history[-2:])]
    blocks = 0
    while terms < most:
        terms, block, blocks = terms + block, 2 * block, blocks + 1
    return history[-1] * min(rates) ** blocks > 2.0 * need


def series_solution(
    scene: Scene, series: Series, x: np.ndarray, tol: float = 1e-11, most: int = 2**20, need: float | None = None
):
    """(quantity, rotation, error estimate) of the series at the points x, or None when a load has no coefficients.
    Terms are added in doubling blocks until the last block's largest term times the number of terms so far (a
    bound of the rest for terms falling like n^-2 or faster) is below ``tol`` times the largest value, or ``most``
    terms; the estimate is that bound, relative. On a uniform grid from 0 the coefficients are folded modulo 2M
    (:func:`_periods`), so the cost grows like the number of terms, not times the number of points.

    ``need``: the estimate the caller can use; from the fourth block on, the summing stops when the estimate, falling
    at the better of its last two rates per block, would still be above twice ``need`` at ``most`` terms (a uniform load
    on the bond-pair beam's symbol, which grows like |k|, or on pd-higher-order's, like ln k); the estimate returned
    is the one reached."""
    L = scene.length
    x = np.asarray(x, float)
    M = _periods(x, L)
    period = 2 * M if M else None
    acc_w = np.zeros(period) if period else np.zeros_like(x)
    acc_r = np.zeros(period) if period else np.zeros_like(x)
    n0, block = 0, 256
    estimate, history = np.inf, []
    if period:  # the modes at the points, one period of them: the same for every block
        kp, kind = modes(series.left, series.right, L, period)
        kp = kp[None, :]
        at = _mode(kind, kp, x[:, None])
    while n0 < most:
        k_all, kind = modes(series.left, series.right, L, n0 + block)
        k = k_all[n0:]
        q = load_coefficients(scene, series, k, kind)
        if q is None:
            return None
        a = q * series.compliance(k)
        b = q * (series.slope(k) if series.slope is not None else k * series.compliance(k))
        if period:
            idx = np.arange(n0, n0 + block) % period  # mode j = n0 + 1 + i sits at residue (j - 1) mod 2M
            acc_w += np.bincount(idx, a, period)
            acc_r += np.bincount(idx, b, period)
            values = at @ acc_w
        else:
            acc_w += _mode(kind, k[None, :], x[:, None]) @ a
            acc_r += _mode_slope(kind, k[None, :], x[:, None]) @ b
            values = acc_w
        scale = max(float(np.abs(values).max()), 1e-300)
        history.append(float(np.abs(a).max() * (n0 + block) / scale))
        estimate = history[-1]
        n0 += block
        block *= 2
        if estimate <= tol:
            break
        if need is not None and len(history) >= 4 and _out_of_reach(history, n0, block, most, need):
            break
    if period:
        return at @ acc_w, _mode_slope(kind, kp, x[:, None]) @ acc_r, estimate
    return acc_w, acc_r, estimate


def mirror_ends(scene: Scene, odd: tuple, even: tuple) -> tuple[str, str] | None:
    """("odd" | "even", "odd" | "even") of the scene's two supports, given the supports a model closes by odd and
    by even mirror images; None when an end is closed otherwise or both ends are even (no held unknown)."""
    out = []
    for sup in (scene.supports.left, scene.supports.right):
        if sup in odd:
            out.append("odd")
        elif sup in even:
            out.append("even")
        else:
            return None
    if out == ["even", "even"] or scene.supports.inner or scene.segments or not scene.is_straight:
        return None
    return out[0], out[1]


BEAM_FACTORS = {"curvature": lambda z: curvature_factor(z) ** 2, "bond-pair": bond_pair_factor}


def beam_series(scene: Scene, delta: float, kernel: str) -> Series | None:
    """The series of an Euler-Bernoulli PD beam whose pinned (roller) ends are odd and guided ends even mirror images:
    compliance 1 / (EI k^4 f(k delta)), f of ``kernel`` (:data:`BEAM_FACTORS`); None for other ends."""
    ends = mirror_ends(scene, ("pinned", "roller"), ("guided",))
    if ends is None:
        return None
    EI, f = scene.EI, BEAM_FACTORS[kernel]
    return Series(*ends, lambda k: 1.0 / (EI * k**4 * f(k * delta)))


def rod_series(
    scene: Scene, delta: float, stiffness: float, held: tuple, component: str, quantity: str
) -> Series | None:
    """The series of a PD rod (or torsion bar) whose ``held`` ends are odd and other ends even mirror images:
    compliance 1 / (stiffness k^2 r(k delta))."""
    free = tuple(s for s in ("clamped", "pinned", "roller", "guided", "free") if s not in held)
    ends = mirror_ends(scene, held, free)
    if ends is None:
        return None
    return Series(*ends, lambda k: 1.0 / (stiffness * k**2 * rod_factor(k * delta)), component, quantity)


def higher_order_symbol(k: np.ndarray, delta: float, C: np.ndarray) -> np.ndarray:
    """K(k) (len(k) x 4 x 4): pd-higher-order's continuous energy density on the mode (theta, theta*, w, w*) =
    (T cos kx, T* cos kx, W sin kx, W* sin kx), the average over x of ∫ Q / (|xi| delta^2) dxi = (1/2) yᵀ K y (the
    model's constant factor left out: it cancels against the load's); C the 5 x 5 matrix of
    Q = mᵀ C m (:func:`pdverify.theory.higher_order.coefficients`). The corrected variant's interior bond measures
    (a, s, c, g, e) = (T Δcos, 2 xi W* sin kx, T* Δcos, (W + T / k) Δsin, (W* + 3 T* / k) Δsin), Δ the change over the
    bond (g and e along the bond's path, Yang et al. 2020, Eq. 14), weighted 1 / (|xi| delta^2): averaged, each
    product of two differences is the local one times r(k delta), each difference times s the local times
    p(k delta) = 2 (1 - cos k delta) / (k delta)^2, s^2 the local."""
    k = np.asarray(k, float)
    z = k * delta
    r, p = rod_factor(z), _sinc2(z)
    one = np.ones_like(k)
    scale = np.stack([np.stack(row, -1) for row in ((r, p, r), (p, one, p), (r, p, r))], -2)  # (n, 3, 3)
    Mb = np.zeros((len(k), 3, 4))  # the local measures' amplitudes: a = -k T, s = 2 W*, c = -k T*
    Mb[:, 0, 0], Mb[:, 1, 3], Mb[:, 2, 1] = -k, 2.0, -k
    Ms = np.zeros((len(k), 2, 4))  # g = k W + T, e = k W* + 3 T*
    Ms[:, 0, 0], Ms[:, 0, 2], Ms[:, 1, 1], Ms[:, 1, 3] = 1.0, k, 3.0, k
    bend = C[None, :3, :3] * scale
    shear = C[None, 3:, 3:] * r[:, None, None]
    return Mb.transpose(0, 2, 1) @ bend @ Mb + Ms.transpose(0, 2, 1) @ shear @ Ms


def higher_order_series(scene: Scene, delta: float, C: np.ndarray) -> Series | None:
    """The series of pd-higher-order's corrected variant with mirror layers (pinned and roller ends odd, guided even:
    w and w* images of one sign, theta and theta* of the other) under distributed loads on the mid-line: w per unit
    load the W of K(k) y = (0, 0, h / A, 0) (:func:`higher_order_symbol`; the energies are per unit cross-section
    area, h = Section.depth), the section's rotation -theta; None for other ends or loads."""
    ends = mirror_ends(scene, ("pinned", "roller"), ("guided",))
    if ends is None or not all(isinstance(q, Distributed) for q in scene.loads):
        return None
    unit = scene.section.depth / scene.section.A

    def solve(k):
        F = np.zeros((len(k), 4, 1))
        F[:, 2, 0] = unit
        return np.linalg.solve(higher_order_symbol(k, delta, C), F)[:, :, 0]

    return Series(*ends, lambda k: solve(k)[:, 2], slope=lambda k: -solve(k)[:, 0])


def timoshenko_series(scene: Scene, delta: float) -> Series | None:
    """The series of the PD Timoshenko beam with pinned (roller) and guided mirror ends under sine loads over the span
    (which vanish at the ends, so the ends' Taylor terms of the load vanish too): w per unit load
    1 / (EI k^4 r s1) + 1 / (kGA k^2 s1), the section rotation 1 / (EI k^3 r s1)."""
    ends = mirror_ends(scene, ("pinned", "roller"), ("guided",))
    span = (0.0, scene.length)
    if ends is None or not all(
        isinstance(q, Distributed) and q.shape == "sine" and scene.span(q) == span for q in scene.loads
    ):
        return None
    EI, kGA = scene.EI, scene.kGA

    def bending(k):
        return 1.0 / (EI * k**3 * rod_factor(k * delta) * shear_factor(k * delta))

    return Series(*ends, lambda k: bending(k) / k + 1.0 / (kGA * k**2 * shear_factor(k * delta)), slope=bending)
