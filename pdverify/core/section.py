"""A scene's ``[section]`` table (:class:`Section`) and its geometry from a width profile b(y): area, centroid, second
moment, shear coefficient, elastic and plastic section moduli, and the fibre moment-curvature law of an
elastic-perfectly plastic section.

Every shape is a piecewise-linear width b(y) over the height (a point list (y_i, b_i), bottom to top; a repeated y is
a step): a rectangle is two points, an I-section eight (flange, web, flange). Every integral is exact (polynomials on
each piece) except the shear coefficient's (Gauss-Legendre, 24 points per piece). Arrays in, arrays out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, Strict, model_validator

Real = Annotated[float, Strict()]  # as pdverify.core.scene's: an int may give it, never a boolean or a string
Finite = Annotated[Real, Field(allow_inf_nan=False)]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


def rectangle(width: float, height: float) -> tuple[np.ndarray, np.ndarray]:
    """(y, b) of a rectangle, centred on y = 0."""
    return np.array([-height / 2, height / 2]), np.array([width, width])


def i_section(height: float, flange_width: float, flange_thickness: float, web_thickness: float):
    """(y, b) of a doubly symmetric I-section, centred on y = 0."""
    h, tf = height / 2, flange_thickness
    y = np.array([-h, -h + tf, -h + tf, h - tf, h - tf, h])
    b = np.array([flange_width, flange_width, web_thickness, web_thickness, flange_width, flange_width])
    return y, b


@dataclass(frozen=True)
class Profile:
    """A section as its width b(y), linear between the points (``y`` non-decreasing: a repeated y is a step)."""

    y: tuple
    b: tuple

    @cached_property
    def pieces(self) -> np.ndarray:
        """(m, 4) rows (y0, y1, b0, b1) of the pieces of positive length."""
        y, b = np.asarray(self.y, float), np.asarray(self.b, float)
        rows = np.stack([y[:-1], y[1:], b[:-1], b[1:]], axis=1)
        return rows[rows[:, 1] > rows[:, 0]]

    def width(self, y) -> np.ndarray:
        """b at y (0 outside the section; at a step the upper piece's)."""
        y = np.asarray(y, float)
        out = np.zeros_like(y)
        for y0, y1, b0, b1 in self.pieces:
            on = (y >= y0) & (y <= y1)
            out[on] = b0 + (b1 - b0) * (y[on] - y0) / (y1 - y0)
        return out

    def integral(self, k: int, lo=-np.inf, hi=np.inf, about: float = 0.0):
        """∫ b(y) (y - about)^k dy over [lo, hi] (``lo``, ``hi`` may be arrays)."""
        lo, hi = np.broadcast_arrays(np.asarray(lo, float), np.asarray(hi, float))
        total = np.zeros(lo.shape)
        for y0, y1, b0, b1 in self.pieces:
            a, c = np.clip(lo, y0, y1), np.clip(hi, y0, y1)
            slope = (b1 - b0) / (y1 - y0)
            # b = p + slope (y - about), p = b0 + slope (about - y0): ∫ (p t^k + slope t^(k+1)), t = y - about
            p = b0 + slope * (about - y0)
            ta, tc = a - about, c - about
            total += p * (tc ** (k + 1) - ta ** (k + 1)) / (k + 1) + slope * (tc ** (k + 2) - ta ** (k + 2)) / (k + 2)
        return total

    @property
    def bottom(self) -> float:
        return float(self.pieces[0, 0])

    @property
    def top(self) -> float:
        return float(self.pieces[-1, 1])

    @cached_property
    def area(self) -> float:
        return float(self.integral(0))

    @cached_property
    def centroid(self) -> float:
        return float(self.integral(1)) / self.area

    @cached_property
    def inertia(self) -> float:
        """Second moment about the centroid."""
        return float(self.integral(2, about=self.centroid))

    @property
    def height(self) -> float:
        return self.top - self.bottom

    @cached_property
    def extreme_fibre(self) -> float:
        """The largest distance from the centroid to a fibre (c of S = I / c)."""
        return max(self.top - self.centroid, self.centroid - self.bottom)

    @property
    def elastic_modulus(self) -> float:
        """S = I / c: the first-yield moment is sigma_y S."""
        return self.inertia / self.extreme_fibre

    @cached_property
    def plastic_axis(self) -> float:
        """The y that halves the area (the neutral axis of the fully plastic section)."""
        lo, hi = self.bottom, self.top
        for _ in range(200):  # bisection on the monotone area below y: to round-off
            mid = 0.5 * (lo + hi)
            if self.integral(0, -np.inf, mid) < self.area / 2:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    @cached_property
    def plastic_modulus(self) -> float:
        """Z = ∫ b |y - y_p| dy: the fully plastic moment is sigma_y Z."""
        yp = self.plastic_axis
        return float(-self.integral(1, -np.inf, yp, about=yp) + self.integral(1, yp, np.inf, about=yp))

    @property
    def shape_factor(self) -> float:
        """Mp / My = Z / S (1.5 for a rectangle)."""
        return self.plastic_modulus / self.elastic_modulus

    @cached_property
    def shear_coefficient(self) -> float:
        """k = I² / (A ∫ Q(y)² / b(y) dy), Q the first moment of the area above y about the centroid (the energy of
        Jourawski's shear stress; 5/6 for a rectangle)."""
        yc, total = self.centroid, 0.0
        for y0, y1, b0, b1 in self.pieces:
            t = 0.5 * (y1 - y0) * _GL_X + 0.5 * (y1 + y0)
            Q = self.integral(1, t, np.inf, about=yc)
            b = b0 + (b1 - b0) * (t - y0) / (y1 - y0)
            total += 0.5 * (y1 - y0) * np.sum(_GL_W * np.where(b > 0, Q**2 / np.where(b > 0, b, 1.0), 0.0))
        return self.inertia**2 / (self.area * total)

    @cached_property
    def lateral_inertia(self) -> float:
        """Second moment about the vertical axis of symmetry, ∫ b(y)³ / 12 dy (exact on linear pieces:
        ∫ b³ dy = (y1 - y0)(b0 + b1)(b0² + b1²) / 4)."""
        y0, y1, b0, b1 = self.pieces.T
        return float(np.sum((y1 - y0) * (b0 + b1) * (b0**2 + b1**2)) / 48.0)

    @property
    def symmetric(self) -> bool:
        """b(yc + s) = b(yc - s) at every breakpoint (to 1e-12 of the height and widths)."""
        yc = self.centroid
        y = np.asarray(self.y, float)
        s = np.unique(np.abs(y - yc))
        scale = max(self.height, 1e-300)
        tol = 1e-12 * scale
        bw = max(np.max(np.abs(self.b)), 1e-300)
        inside = s[s < 0.5 * self.height - tol] + tol
        up, down = self.width(yc + inside), self.width(yc - inside)
        return abs(self.top - yc - (yc - self.bottom)) <= 1e-12 * scale and bool(
            np.all(np.abs(up - down) <= 1e-12 * bw)
        )

    def fibre_moment(self, kappa, E: float, yield_stress: float):
        """M(kappa) of an elastic-perfectly plastic section bent about its centroid from a stress-free state (a
        symmetric section: the neutral axis stays at the centroid): ∫ b y E clip(kappa y, -eps_y, eps_y) dy, exact."""
        kappa = np.asarray(kappa, float)
        eps_y = yield_stress / E
        yc, c = self.centroid, self.extreme_fibre
        with np.errstate(divide="ignore"):
            ye = np.where(np.abs(kappa) > 0, np.minimum(eps_y / np.abs(kappa), c), c)  # elastic core half-depth
        core = self.integral(2, yc - ye, yc + ye, about=yc)
        outer = self.integral(1, yc + ye, np.inf, about=yc) - self.integral(1, -np.inf, yc - ye, about=yc)
        return E * kappa * core + np.sign(kappa) * yield_stress * outer

    def fibre_stiffness(self, kappa, E: float, yield_stress: float):
        """dM/dkappa of :meth:`fibre_moment` (E times the second moment of the elastic core)."""
        kappa = np.asarray(kappa, float)
        eps_y = yield_stress / E
        yc, c = self.centroid, self.extreme_fibre
        with np.errstate(divide="ignore"):
            ye = np.where(np.abs(kappa) > 0, np.minimum(eps_y / np.abs(kappa), c), c)
        return E * self.integral(2, yc - ye, yc + ye, about=yc)


def profile_of(section) -> Profile | None:
    """The :class:`Profile` of a scene's section (``pdverify.core.scene.Section``): its shape's, or a rectangle's;
    None for a section given by area and inertia only."""
    shape = getattr(section, "shape", None)
    if shape == "I":
        y, b = i_section(section.height, section.flange_width, section.flange_thickness, section.web_thickness)
    elif shape == "profile":
        y, b = np.asarray(section.y, float), np.asarray(section.b, float)
    elif section.width is not None and section.height is not None:
        y, b = rectangle(section.width, section.height)
    else:
        return None
    return _profile(tuple(float(v) for v in y), tuple(float(v) for v in b))


@lru_cache(maxsize=256)
def _profile(y: tuple, b: tuple) -> Profile:
    """One :class:`Profile` per point list (its properties are computed once)."""
    return Profile(y, b)


class Section(BaseModel):
    """Rectangle (``width``, ``height``), given ``area``, ``inertia`` (and ``shear_factor``), or a ``shape``:
    ``"rectangle"`` (width, height), ``"I"`` (``height``, ``flange_width``, ``flange_thickness``, ``web_thickness``) or
    ``"profile"`` (the width ``b`` at heights ``y``, bottom to top, linear between; a repeated y is a step). A shape's
    area, second moment, shear coefficient and section moduli come from its :class:`Profile`."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    shape: Literal["rectangle", "I", "profile"] | None = None
    width: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    height: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    area: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    inertia: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    shear_factor: Real | None = Field(default=None, gt=0, le=1.5, allow_inf_nan=False)
    torsion_constant: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    flange_width: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    flange_thickness: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    web_thickness: Real | None = Field(default=None, gt=0, allow_inf_nan=False)
    y: list[Finite] | None = None
    b: list[Annotated[Real, Field(ge=0, allow_inf_nan=False)]] | None = None

    @model_validator(mode="after")
    def _complete(self):
        if self.shape in ("I", "profile"):
            return self._shaped()
        extra = [
            k for k in ("flange_width", "flange_thickness", "web_thickness", "y", "b") if getattr(self, k) is not None
        ]
        if extra:
            raise ValueError(f'{", ".join(extra)}: keys of shape = "I" or "profile"; give shape or drop them')
        rect = self.width is not None and self.height is not None
        given = self.area is not None and self.inertia is not None
        if self.shape == "rectangle" and not rect:
            raise ValueError('shape = "rectangle" needs width and height')
        if not rect and not given:
            raise ValueError(
                "give width and height (rectangle) or area and inertia; "
                f"got width={self.width}, height={self.height}, area={self.area}, inertia={self.inertia}"
            )
        if (self.width is None) != (self.height is None):
            raise ValueError("width and height go together; give both or neither")
        both = [k for k in ("width", "height", "area", "inertia") if getattr(self, k) is not None]
        if rect and (self.area is not None or self.inertia is not None):
            raise ValueError(
                f"{', '.join(both)} given: a section is a rectangle (width, height) or given by area and "
                "inertia, not both (they would disagree); keep one pair"
            )
        return self

    def _shaped(self):
        """The keys of an I-section or a profile: complete, consistent, nothing else that would disagree."""
        need = {"I": ("height", "flange_width", "flange_thickness", "web_thickness"), "profile": ("y", "b")}[self.shape]
        missing = [k for k in need if getattr(self, k) is None]
        if missing:
            raise ValueError(f'shape = "{self.shape}" needs {", ".join(need)}; missing {", ".join(missing)}')
        other = [
            k
            for k in (
                "width",
                "area",
                "inertia",
                "height",
                "flange_width",
                "flange_thickness",
                "web_thickness",
                "y",
                "b",
            )
            if getattr(self, k) is not None and k not in need
        ]
        if other:
            raise ValueError(f'{", ".join(other)}: not keys of shape = "{self.shape}" (its {", ".join(need)} give it)')
        if self.shape == "I":
            if 2 * self.flange_thickness >= self.height:
                raise ValueError(
                    f"flange_thickness = {self.flange_thickness!r}: two flanges must leave a web inside height = "
                    f"{self.height!r}; give 2 flange_thickness < height"
                )
            if self.web_thickness > self.flange_width:
                raise ValueError(
                    f"web_thickness = {self.web_thickness!r}: wider than flange_width = {self.flange_width!r}"
                )
            return self
        if len(self.y) != len(self.b) or len(self.y) < 2:
            raise ValueError(
                f"y ({len(self.y)} values) and b ({len(self.b)}): give as many widths as heights, two or more"
            )
        if any(y1 < y0 for y0, y1 in zip(self.y, self.y[1:])):
            raise ValueError(f"y = {self.y}: heights go from the bottom up (non-decreasing)")
        if not self.y[-1] > self.y[0] or self.profile.area <= 0:
            raise ValueError(f"y = {self.y}, b = {self.b}: the profile has no area")
        return self

    @property
    def profile(self) -> Profile | None:
        """The width profile b(y) (:class:`Profile`); None for an area/inertia section."""
        return profile_of(self)

    @property
    def A(self) -> float:
        if self.shape in ("I", "profile"):
            return self.profile.area
        return self.area if self.area is not None else self.width * self.height

    @property
    def I(self) -> float:  # noqa: E743 - the field's name
        if self.shape in ("I", "profile"):
            return self.profile.inertia
        return self.inertia if self.inertia is not None else self.width * self.height**3 / 12.0

    @property
    def k(self) -> float:
        if self.shear_factor is not None:
            return self.shear_factor
        if self.shape in ("I", "profile"):
            return self.profile.shear_coefficient
        return 5.0 / 6.0

    @property
    def J(self) -> float | None:
        """Saint-Venant torsion constant: given, or of the rectangle (series-fit formula
        a b³ (1/3 - 0.21 (b/a)(1 - b⁴/(12 a⁴))), a >= b), or of a thin-walled I (Σ b t³ / 3 of its plates); None for
        an area/inertia section or a profile without it."""
        if self.torsion_constant is not None:
            return self.torsion_constant
        if self.shape == "I":
            web = self.height - 2 * self.flange_thickness
            return (2 * self.flange_width * self.flange_thickness**3 + web * self.web_thickness**3) / 3.0
        if self.width is None or self.shape == "profile":
            return None
        a, b = max(self.width, self.height), min(self.width, self.height)
        return a * b**3 * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b**4 / (12.0 * a**4)))

    @property
    def polar(self) -> float | None:
        """Polar moment of area about the axis of twist, I + ∫ b³ / 12 dy (the rotary inertia of Saint-Venant
        torsion, warping's left out): of a rectangle, an I or a doubly symmetric profile, whose centroid is the shear
        centre; None for an area/inertia section or a singly symmetric profile (its twist axis is the shear centre,
        and twist couples with bending there)."""
        if self.shape in ("I", "profile"):
            return self.profile.inertia + self.profile.lateral_inertia if self.profile.symmetric else None
        if self.width is None:
            return None
        return self.width * self.height * (self.width**2 + self.height**2) / 12.0

    @property
    def depth(self) -> float:
        """Height of the section (for a given area/inertia: of the equivalent rectangle)."""
        if self.shape == "profile":
            return self.profile.height
        if self.height is not None:
            return self.height
        return math.sqrt(12.0 * self.I / self.A)

    @property
    def kind(self) -> str:
        """``rectangle``, ``I``, ``profile``, or ``given`` (area and inertia)."""
        if self.shape is not None:
            return self.shape
        return "rectangle" if self.width is not None else "given"
