"""Natural frequencies of the straight rod, torsion bar and Timoshenko beam (textbook closed forms; the
beam's as the roots of the characteristic determinant of its general solution).

Rod (axial u or twist θ): c² u'' = u_tt with c² = EA/ρA (GJ/ρI_p). A held end has u = 0, a free one
u' = 0: ω_k = k π c / L between two held ends, (k - 1/2) π c / L with one free end.

Timoshenko beam, free vibration w(x) e^{iωt}, γ(x) e^{iωt} of

    ρA w_tt = kGA (w'' - γ'),    ρI γ_tt = EI γ'' + kGA (w' - γ):

w = e^{λx} gives EI kGA λ⁴ + ω²(kGA ρI + EI ρA) λ² + ρA ω²(ρI ω² - kGA) = 0, whose roots r = λ² are
real, one always negative (w = cos/sin βx) and the other positive below the cut-off ω_c² = kGA/ρI
(w = cosh/sinh αx, written here as e^{-αx}, e^{-α(L-x)} to stay bounded) and negative above it. γ follows
from the first equation: γ' = w'' + (ρAω²/kGA) w. Each end holds w (else the shear w' - γ = 0) and γ
(else the moment γ' = 0); the four end conditions on the four functions give a 4 x 4 determinant whose
roots in ω are the natural frequencies. At the cut-off itself w = 0, γ = const is a mode when both ends
hold w and neither holds γ (pinned–pinned).
"""

from __future__ import annotations

import functools

import numpy as np

from ..core.errors import SolveError
from ..core.scene import HELD

ROWS = (0, 1, 2, 3)  # w, w', γ, γ': the rows of the general solution's columns
SCAN_LIMIT = 1e4  # per mode sought: the scan in z = L (rho A omega^2 / EI)^(1/4) stops at this times (count + 1)


def rod_frequencies(length: float, wave_speed: float, held: tuple[bool, bool], count: int) -> np.ndarray:
    """The first ``count`` circular frequencies (rad/s) of a rod with ends ``held`` (left, right)."""
    if not any(held):
        raise ValueError("a rod free at both ends has a rigid-body mode")
    k = np.arange(1, count + 1, dtype=float)
    return (k if all(held) else k - 0.5) * np.pi * wave_speed / length


def beam_end(support: str) -> tuple[bool, bool]:
    """(deflection held, rotation held) of a support (pdverify.core.scene.HELD: normal displacement, rotation)."""
    return HELD[support][1], HELD[support][2]


class TimoshenkoBeam:
    """Free vibration of a uniform Timoshenko beam: ``left``, ``right`` = (w held, γ held) per end."""

    def __init__(self, EI, kGA, rhoA, rhoI, length, left: tuple[bool, bool], right: tuple[bool, bool]):
        self.EI, self.kGA, self.rA, self.rI, self.L = EI, kGA, rhoA, rhoI, length
        self.left, self.right = left, right
        self._scans: dict[int, list] = {}  # resolution -> [z0, roots found below it] (:meth:`scan`)

    @property
    def cutoff(self) -> float:
        """ω_c = sqrt(kGA / ρI): above it the second spectrum (both roots r < 0)."""
        return float(np.sqrt(self.kGA / self.rI))

    def _columns(self, omega: np.ndarray, x, rows: tuple = ROWS) -> np.ndarray:
        """(len(omega), len(rows), 4 functions) at a point x, or (..., len(x)) at the points x: the ``rows`` of
        [w, w', γ, γ'] (all four by default; a mode's shape needs w and γ only)."""
        w2 = omega**2
        a, b = self.EI * self.kGA, w2 * (self.kGA * self.rI + self.EI * self.rA)
        c = self.rA * w2 * (self.rI * w2 - self.kGA)
        disc = np.sqrt(b * b - 4 * a * c)  # > 0 for ω > 0 (see the module docstring)
        r1 = 2 * c / (-b - disc)  # = (-b + disc) / 2a without its cancellation; changes sign at the cut-off
        r2 = (-b - disc) / (2 * a)
        q = self.rA * w2 / self.kGA
        xs = np.atleast_1d(np.asarray(x, float))
        col = lambda v: v[:, None, None]  # noqa: E731 - per frequency, broadcast over (function, x)
        out = np.empty((len(omega), len(rows), 4, len(xs)))
        out[:, :, 2:] = self._trig(col(np.sqrt(-r2)), col(q), xs, rows)
        s = np.sqrt(np.abs(r1))
        hyper = col(r1 > 0)[..., None]
        out[:, :, :2] = np.where(hyper, self._hyper(col(s), col(q), xs, rows), self._trig(col(s), col(q), xs, rows))
        return out if np.ndim(x) else out[..., 0]

    def _hyper(self, s, q, x, rows: tuple = ROWS):
        """w = e^{-s x}, e^{-s(L - x)}: γ = -ra w, +ra w with ra = (s² + q)/s. (n, len(rows), 2, len(x))."""
        sign = np.array([-1.0, 1.0])[:, None]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # s = 0 at the cut-off: NaN, unused
            ra = (s * s + q) / s
            g = np.concatenate([np.exp(-s * x), np.exp(-s * (self.L - x))], 1)  # (n, 2, len(x))
            make = (lambda: g, lambda: sign * s * g, lambda: sign * ra * g, lambda: ra * s * g)
            return np.stack([make[r]() for r in rows], 1)

    def _trig(self, s, q, x, rows: tuple = ROWS):
        """w = cos s x, sin s x: γ = sb sin, -sb cos with sb = (q - s²)/s. (n, len(rows), 2, len(x))."""
        cs, sn = np.cos(s * x), np.sin(s * x)
        w = np.concatenate([cs, sn], 1)
        with np.errstate(divide="ignore", invalid="ignore"):  # s = 0 at the cut-off: NaN, unused
            sb = (q - s * s) / s
            make = (
                lambda: w,
                lambda: np.concatenate([-s * sn, s * cs], 1),
                lambda: np.concatenate([sb * sn, -sb * cs], 1),
                lambda: sb * s * w,
            )
            return np.stack([make[r]() for r in rows], 1)

    def end_conditions(self, omega) -> tuple[np.ndarray, np.ndarray]:
        """(len(omega), 4, 4) the four end conditions (rows) on the four functions of the general solution
        (columns), each column scaled by the norm of its (w, w', γ, γ') at both ends; and that scale."""
        omega = np.atleast_1d(np.asarray(omega, float))
        rows, scale = [], 0.0
        for x, (w_held, g_held) in ((0.0, self.left), (self.L, self.right)):
            C = self._columns(omega, x)
            scale = scale + (C * C).sum(1)
            rows.append(C[:, 0] if w_held else C[:, 1] - C[:, 2])  # w = 0, else the shear w' - γ = 0
            rows.append(C[:, 2] if g_held else C[:, 3])  # γ = 0, else the moment γ' = 0
        scale = np.sqrt(scale)
        with np.errstate(invalid="ignore"):  # NaN at the cut-off's s = 0
            return np.stack(rows, 1) / scale[:, None, :], scale

    def determinant(self, omega) -> np.ndarray:
        """The characteristic determinant at ``omega`` (rad/s) of the scaled :meth:`end_conditions` (the scale is
        positive and never zero: the sign changes, and so the roots, are those of the unscaled determinant)."""
        with np.errstate(invalid="ignore"):  # NaN at the cut-off's s = 0: no sign change is read there
            return np.linalg.det(self.end_conditions(omega)[0])

    def frequencies(self, count: int, resolution: int = 256) -> np.ndarray:
        """The first ``count`` circular frequencies (rad/s), found on the dimensionless beam (length, EI and rho A
        one; x = L xi, t = tau / omega_0, omega_0^2 = EI / (rho A L^4)) and scaled back: the same roots whatever the
        units (a modulus of 1e-30 or a density of 1e-300 would otherwise under- or overflow omega^2)."""
        w0 = np.sqrt(self.EI / (self.rA * self.L**4))
        unit = TimoshenkoBeam(
            1.0, self.kGA * self.L**2 / self.EI, 1.0, self.rI / (self.rA * self.L**2), 1.0, self.left, self.right
        )
        if not (np.isfinite(w0) and w0 > 0 and np.isfinite(unit.kGA) and np.isfinite(unit.rI) and unit.rI > 0):
            raise SolveError(
                "the beam's natural frequencies are out of the floating-point range in these units; give the scene "
                "in units that keep its numbers within about 1e-100..1e100"
            )
        return w0 * _unit_scan(unit.kGA, unit.rI, self.left, self.right, count, resolution)

    def scan(self, count: int, resolution: int = 256) -> np.ndarray:
        """The first ``count`` circular frequencies (rad/s): sign changes of :meth:`determinant` on a scan, all
        brackets refined at once by bisection to the last bits, kept when the determinant vanishes there (|det|
        below 1e-6 of its values at the bracket: a jump of the basis at the cut-off changes the sign too); close
        pairs are found by :meth:`_brackets`.
        The scan steps by π/``resolution`` in z = L (ρA ω² / EI)^{1/4} (Euler–Bernoulli's βL, mode spacing
        ~π) while that is finer than π c / (L ``resolution``) in ω, c the lower of the shear and bending wave
        speeds (the spacing of each spectrum where shear dominates), and by the latter above. The scan's state is
        kept per ``resolution``: asked for more modes, it goes on from where it stopped, through the same chunks as a
        scan from the start (the same roots)."""
        to_omega = lambda z: (z / self.L) ** 2 * np.sqrt(self.EI / self.rA)  # noqa: E731
        to_z = lambda w: self.L * (self.rA * w * w / self.EI) ** 0.25  # noqa: E731
        wave_step = np.pi * min(np.sqrt(self.kGA / self.rA), np.sqrt(self.EI / self.rI)) / (self.L * resolution)
        # where the z step, d omega = 2 omega / z dz, reaches wave_step: z = L^2 wave_step / (2 sqrt(EI/rhoA) dz)
        z_cross = self.L**2 * wave_step * resolution / (2 * np.pi * np.sqrt(self.EI / self.rA))
        first = [self.cutoff] if self.left[0] and self.right[0] and not self.left[1] and not self.right[1] else []
        state = self._scans.setdefault(resolution, [1e-3, first])  # [z0, roots found below it]
        z0, found, chunk = state[0], state[1], 8192
        z_limit = SCAN_LIMIT * (count + 1)
        # the cut-off (a mode of w = 0 and uniform rotation where both ends hold w and free the rotation) is known
        # before the scan reaches it: it counts among the lowest modes only once the scan has passed it
        while sum(w <= to_omega(z0) for w in found) < count:
            if not z0 < z_limit:
                raise SolveError(
                    f"the characteristic determinant changed sign {len(found)} times up to z = {z_limit:g} (its "
                    f"{count} lowest modes lie below z ~ {count + 1} pi for any real beam); check the section and "
                    "material"
                )
            if z0 < z_cross:
                z = np.minimum(z0 + np.pi / resolution * np.arange(chunk + 1), z_cross)
                omega = to_omega(np.unique(z))
            else:
                omega = to_omega(z0) + wave_step * np.arange(chunk + 1)
            lo, hi, d_lo, d_hi = self._brackets(omega[None, :])
            root = self._bisect(lo, hi, d_lo)
            real = np.abs(self.determinant(root)) <= 1e-6 * np.maximum(np.abs(d_lo), np.abs(d_hi))
            found += [w for w in root[real] if not np.isclose(w, self.cutoff, rtol=1e-9)]
            z0 = state[0] = to_z(omega[-1])
        return np.array(sorted(found)[:count])

    def _brackets(self, omega: np.ndarray, depth: int = 3, sub: int = 64) -> tuple:
        """(lo, hi, det(lo), det(hi)) of the sign changes of the determinant along each row of the grid ``omega``
        (rows x points). Two roots closer than a step (the two spectra cross) change no sign: where |det| has a
        local minimum between values of one sign, that step pair is scanned again ``sub`` times finer, down to
        ``depth`` levels (pairs ~1e-7 of the step apart are still found)."""
        d = self.determinant(omega.ravel()).reshape(omega.shape)
        sign, size = np.sign(d), np.abs(d)
        r, i = np.nonzero(sign[:, 1:] * sign[:, :-1] < 0)
        out = [omega[r, i], omega[r, i + 1], d[r, i], d[r, i + 1]]
        hidden = (size[:, 1:-1] < size[:, :-2]) & (size[:, 1:-1] < size[:, 2:])
        hidden &= (sign[:, :-2] == sign[:, 1:-1]) & (sign[:, 1:-1] == sign[:, 2:])
        r, k = np.nonzero(hidden)
        if depth and r.size:
            a, b = omega[r, k], omega[r, k + 2]
            finer = self._brackets(a[:, None] + (b - a)[:, None] * np.linspace(0.0, 1.0, sub + 1), depth - 1, sub)
            out = [np.concatenate(pair) for pair in zip(out, finer, strict=True)]
        return tuple(out)

    def _bisect(self, lo: np.ndarray, hi: np.ndarray, d_lo: np.ndarray) -> np.ndarray:
        """Bisection of every bracket [lo, hi] of a sign change at once, until each is one float wide."""
        s_lo = np.sign(d_lo)
        for _ in range(64):  # 64 halvings of a bracket of relative width < 1 reach the spacing of floats
            mid = 0.5 * (lo + hi)
            left = np.sign(self.determinant(mid)) == s_lo
            lo, hi = np.where(left, mid, lo), np.where(left, hi, mid)
        return 0.5 * (lo + hi)


@functools.lru_cache(maxsize=256)
def _unit_beam(kGA: float, rhoI: float, left: tuple, right: tuple) -> TimoshenkoBeam:
    """The dimensionless beam, kept with its scan (:meth:`TimoshenkoBeam.scan`): a convergence series asks for the
    same beam's frequencies on every grid, and a modal sum asks for twice as many modes at each octave."""
    return TimoshenkoBeam(1.0, kGA, 1.0, rhoI, 1.0, left, right)


def _unit_scan(kGA: float, rhoI: float, left: tuple, right: tuple, count: int, resolution: int) -> np.ndarray:
    """The dimensionless beam's first ``count`` roots (:meth:`TimoshenkoBeam.scan`)."""
    return _unit_beam(float(kGA), float(rhoI), tuple(left), tuple(right)).scan(count, resolution)
