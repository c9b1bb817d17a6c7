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

import numpy as np
from scipy.optimize import brentq

from ..scene import HELD


def rod_frequencies(length: float, wave_speed: float, held: tuple[bool, bool], count: int) -> np.ndarray:
    """The first ``count`` circular frequencies (rad/s) of a rod with ends ``held`` (left, right)."""
    if not any(held):
        raise ValueError("a rod free at both ends has a rigid-body mode")
    k = np.arange(1, count + 1, dtype=float)
    return (k if all(held) else k - 0.5) * np.pi * wave_speed / length


def beam_end(support: str) -> tuple[bool, bool]:
    """(deflection held, rotation held) of a support (pdverify.scene.HELD: normal displacement, rotation)."""
    return HELD[support][1], HELD[support][2]


class TimoshenkoBeam:
    """Free vibration of a uniform Timoshenko beam: ``left``, ``right`` = (w held, γ held) per end."""

    def __init__(self, EI, kGA, rhoA, rhoI, length, left: tuple[bool, bool], right: tuple[bool, bool]):
        self.EI, self.kGA, self.rA, self.rI, self.L = EI, kGA, rhoA, rhoI, length
        self.left, self.right = left, right

    @property
    def cutoff(self) -> float:
        """ω_c = sqrt(kGA / ρI): above it the second spectrum (both roots r < 0)."""
        return float(np.sqrt(self.kGA / self.rI))

    def _columns(self, omega: np.ndarray, x: float) -> np.ndarray:
        """(len(omega), 4 [w, w', γ, γ'], 4 functions) at x."""
        w2 = omega**2
        a, b = self.EI * self.kGA, w2 * (self.kGA * self.rI + self.EI * self.rA)
        c = self.rA * w2 * (self.rI * w2 - self.kGA)
        disc = np.sqrt(b * b - 4 * a * c)  # > 0 for ω > 0 (see the module docstring)
        r1 = 2 * c / (-b - disc)  # = (-b + disc) / 2a without its cancellation; changes sign at the cut-off
        r2 = (-b - disc) / (2 * a)
        q = self.rA * w2 / self.kGA
        out = np.empty((len(omega), 4, 4))
        out[:, :, 2:] = self._trig(np.sqrt(-r2), q, x)
        hyper = r1 > 0
        s = np.sqrt(np.abs(r1))
        out[:, :, :2] = np.where(hyper[:, None, None], self._hyper(s, q, x), self._trig(s, q, x))
        return out

    def _hyper(self, s, q, x):
        """w = e^{-s x}, e^{-s(L - x)}: γ = -ra w, +ra w with ra = (s² + q)/s."""
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            ra = (s * s + q) / s
            g1, g2 = np.exp(-s * x), np.exp(-s * (self.L - x))
        return np.stack(
            [np.stack([g1, g2], -1), np.stack([-s * g1, s * g2], -1), np.stack([-ra * g1, ra * g2], -1)]
            + [np.stack([ra * s * g1, ra * s * g2], -1)],
            1,
        )

    def _trig(self, s, q, x):
        """w = cos s x, sin s x: γ = sb sin, -sb cos with sb = (q - s²)/s."""
        with np.errstate(divide="ignore", invalid="ignore"):
            sb = (q - s * s) / s
        cs, sn = np.cos(s * x), np.sin(s * x)
        return np.stack(
            [
                np.stack([cs, sn], -1),
                np.stack([-s * sn, s * cs], -1),
                np.stack([sb * sn, -sb * cs], -1),
                np.stack([sb * s * cs, sb * s * sn], -1),
            ],
            1,
        )

    def determinant(self, omega) -> np.ndarray:
        """The characteristic determinant at ``omega`` (rad/s), each function's column scaled by the norm of
        its (w, w', γ, γ') at both ends (positive and never zero: the sign changes, and so the roots, are
        those of the unscaled determinant)."""
        omega = np.atleast_1d(np.asarray(omega, float))
        rows, scale = [], 0.0
        for x, (w_held, g_held) in ((0.0, self.left), (self.L, self.right)):
            C = self._columns(omega, x)
            scale = scale + (C * C).sum(1)
            rows.append(C[:, 0] if w_held else C[:, 1] - C[:, 2])  # w = 0, else the shear w' - γ = 0
            rows.append(C[:, 2] if g_held else C[:, 3])  # γ = 0, else the moment γ' = 0
        return np.linalg.det(np.stack(rows, 1) / np.sqrt(scale)[:, None, :])

    def frequencies(self, count: int, resolution: int = 256) -> np.ndarray:
        """The first ``count`` circular frequencies (rad/s): sign changes of :meth:`determinant` on a scan
        of z = L (ρA ω² / EI)^{1/4} (Euler–Bernoulli's βL, mode spacing ~π) in steps of π/``resolution``,
        each refined by Brent's method and kept when the determinant vanishes there (|det| below 1e-6 of its
        values at the bracket: a jump of the basis at the cut-off changes the sign too)."""
        to_omega = lambda z: (z / self.L) ** 2 * np.sqrt(self.EI / self.rA)  # noqa: E731
        found = []
        if self.left[0] and self.right[0] and not self.left[1] and not self.right[1]:
            found.append(self.cutoff)
        z0, span = 1e-3, np.pi * (count + 2)
        while True:
            z = np.linspace(z0, z0 + span, int(resolution * span / np.pi) + 1)
            d = self.determinant(to_omega(z))
            for i in np.flatnonzero(np.sign(d[1:]) * np.sign(d[:-1]) < 0):
                lo, hi = to_omega(z[i]), to_omega(z[i + 1])
                root = brentq(lambda w: self.determinant(w)[0], lo, hi, xtol=1e-14 * hi, rtol=4 * np.finfo(float).eps)
                jump = abs(self.determinant(root)[0]) > 1e-6 * max(abs(d[i]), abs(d[i + 1]))
                if not jump and not np.isclose(root, self.cutoff, rtol=1e-9):
                    found.append(root)
            found = sorted(set(found))
            if len(found) >= count:
                return np.array(found[:count])
            z0 += span
