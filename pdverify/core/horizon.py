"""The horizon of a PD model (a model with a ``horizon`` option) as a length: its spacing, the horizon delta of its
options, the option that gives a horizon length on a grid, and the hooks of its nonlocal continuum
(:mod:`pdverify.theory.continuum`). A mixin of :class:`pdverify.core.contract.Model` (docs/nonlocal.md)."""

from __future__ import annotations

from .errors import InputError
from .scene import Scene


class Horizon:
    """The horizon methods of every model (they apply to those with a ``horizon`` option)."""

    whole_horizon: str = ""  # why its equations need m = delta / dx whole (the equation), "" when any m is defined
    full_volumes: str = ""  # the variant whose sums take full volumes up to delta (none: "")
    continuum_m: int = 128  # the finest m of the extrapolation to its continuum (its cost grows like N m^2)
    dispersion: str = ""  # the kernel of pdverify.theory.symbols.FACTORS its waves follow ("" none known)

    def spacing(self, scene: Scene, params: dict) -> float:
        """The grid spacing dx of ``params`` (points x_k = k dx, ends included, by default)."""
        return scene.length / (params["points"] - 1)

    def horizon_offset(self, params: dict) -> float:
        """delta / dx minus the ``horizon`` option (the papers' delta = (m + 0.015) dx: 0.015); 0 by default."""
        return 0.0

    def delta(self, scene: Scene, params: dict) -> float:
        """The horizon delta of ``params`` in the scene's length unit (given, or m dx with the variant's offset)."""
        if params.get("horizon_length") is not None:
            return float(params["horizon_length"])
        return (params["horizon"] + self.horizon_offset(params)) * self.spacing(scene, params)

    def horizon_from_length(self, scene: Scene, params: dict):
        """The ``horizon`` option that gives the horizon ``params["horizon_length"]`` on this grid: m = delta / dx
        less :meth:`horizon_offset`, refused (one line naming the equation, :attr:`whole_horizon`) when the model's
        equations need a whole m and delta / dx is not one."""
        delta, dx = params["horizon_length"], self.spacing(scene, params)
        m = delta / dx
        if abs(m - round(m)) <= 1e-9 * max(1.0, m):
            m = float(round(m))  # a whole number of spacings, whatever the rounding of delta / dx
        opt = self.option("horizon")
        if (self.whole_horizon or opt.kind is int) and m != round(m):
            near = max(1, round(m))
            raise InputError(
                f"horizon_length = {delta:g}: {m:.6g} spacings of {dx:.6g}; model {self.name} needs a whole "
                f"number ({self.whole_horizon or 'its horizon counts whole spacings'}); give horizon_length = "
                f"{near * dx:.6g} or points with (points - 1) delta / length whole"
            )
        least = opt.minimum if opt.minimum is not None else 0.0
        if m < least or m <= 0:
            raise InputError(
                f"horizon_length = {delta:g}: {m:.6g} spacings of {dx:.6g}, below the least horizon of model "
                f"{self.name} ({least:g} spacing{'' if least == 1 else 's'}); give a longer horizon or more points"
            )
        value = m - self.horizon_offset(params)
        return int(round(value)) if opt.kind is int else float(value)

    def continuum_series(self, scene: Scene, params: dict):
        """The closed form of the model's continuum on ``scene`` (:class:`pdverify.theory.nonlocal.Series`: the
        modes and the continuous symbol's compliance), or None where none is known: a model whose ends are odd or
        even mirror images has sin / cos modes as eigenfunctions of its operator (docs/design/nonlocal.md)."""
        return None

    def continuum_whole(self, params: dict) -> str:
        """Why the variant's sums reach a smooth limit in m only through whole m = delta / dx (the variant
        :attr:`full_volumes`: their error depends on the fraction of m), "" when any m is smooth."""
        if self.full_volumes and params.get("variant") == self.full_volumes:
            return f"variant {self.full_volumes}'s sums take full volumes up to delta and depend on its fraction"
        return ""

    def fixed_horizon_order(self, params: dict) -> tuple[float, str]:
        """(order, why) of the discretisation error in dx at a fixed horizon delta (m-convergence to the model's
        continuum, ``params`` the user's options over the defaults): the model's :attr:`order`, or 1 for the variant
        :attr:`full_volumes`, whose sums give each of the m bonds in a horizon a whole volume dx: a one-sided rule of
        the horizon's integral, exact only as dx -> 0 (docs/nonlocal.md)."""
        if self.full_volumes and self.with_defaults(params).get("variant") == self.full_volumes:
            return 1.0, f"variant {self.full_volumes}'s sums give each bond a whole volume up to delta: first order"
        return float(self.order), ""

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """(why, largest m) when the variant's discrete rules have no limit at fixed delta on ``scene`` (its
        continuum is then its own finest grid, flagged), else None."""
        return None
