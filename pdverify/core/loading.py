"""A scene's load path and prescribed deflections: ``[loading]`` (the scene's loads times a load factor along
``factors``, ``steps`` increments per segment) and ``[[loads]] type = "displacement"`` (the deflection ``value``
held at ``position``, times the same factor). Models that follow a path (elastic-plastic or brittle material,
``[material] yield_stress`` / ``failure_strain``) read them; the others refuse them in one line.
"""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, Strict, model_validator

Real = Annotated[float, Strict()]  # as pdverify.core.scene's: an int may give it, never a boolean or a string


class Displacement(BaseModel):
    """A prescribed deflection: w(``position``) = ``value`` (times the load factor of ``[loading]``)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    type: Literal["displacement"]
    position: Real = Field(allow_inf_nan=False)
    value: Real = Field(allow_inf_nan=False)


MAX_PATH_STEPS = 10_000  # load steps along a whole path: fem-eb takes about 10 ms a step at 101 points


class Loading(BaseModel):
    """``factors``: the load factor at the path's corners (default [0, 1]: load once); ``steps``: the increments of
    each segment between two corners (a whole number, at least 1)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    factors: list[Annotated[Real, Field(allow_inf_nan=False)]] = Field(default_factory=lambda: [0.0, 1.0])
    steps: Annotated[int, Strict(), Field(ge=1, le=100000)] = 10

    @model_validator(mode="after")
    def _path(self):
        if len(self.factors) < 2:
            raise ValueError(
                f"factors = {self.factors}: a load path needs two factors or more (e.g. [0.0, 1.0, 0.0]: load, unload)"
            )
        if any(b == a for a, b in zip(self.factors, self.factors[1:])):
            raise ValueError(f"factors = {self.factors}: two equal factors in a row make an empty segment; drop one")
        total = self.steps * (len(self.factors) - 1)
        if total > MAX_PATH_STEPS:
            raise ValueError(
                f"steps = {self.steps} on {len(self.factors) - 1} segments asks for {total} load steps, more than the "
                f"limit of {MAX_PATH_STEPS} (each step is a nonlinear solve); give fewer steps or corners"
            )
        return self

    def path(self) -> np.ndarray:
        """The load factor at every step, the first corner included: ``steps`` equal increments per segment."""
        f = np.asarray(self.factors, float)
        t = np.arange(1, self.steps + 1) / self.steps
        inner = (f[:-1, None] + (f[1:] - f[:-1])[:, None] * t[None, :]).ravel()
        return np.r_[f[0], inner]
