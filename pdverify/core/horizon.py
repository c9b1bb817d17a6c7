"""The horizon of a PD model (a model with a ``horizon`` option) as a length: its spacing, the horizon delta of its
options, the option that gives a horizon length on a grid, and the hooks of its nonlocal continuum
(:mod:`pdverify.theory.continuum`). A mixin of :class:`pdverify.core.contract.Model` (docs/nonlocal.md)."""

from __future__ import annotations

from .errors import InputError
from .scene import Scene
from .text import spacings


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
        if round(m) >= 1 and abs(m - round(m)) <= 1e-9 * max(1.0, m):
            m = float(round(m))  # a whole number of spacings, whatever the rounding of delta / dx
        opt = self.option("horizon")
        least = opt.minimum if opt.minimum is not None else 0.0
        if opt.kind is int or self.whole_horizon:
            least = max(least, 1.0)  # a horizon of whole spacings covers one at least (pd-curved's 0: its default)
        if m < least or m <= 0:
            what = f"{least:g} spacing{'' if least == 1 else 's'}" if least > 0 else "more than 0 spacings"
            raise InputError(
                f"horizon_length = {delta:g}: {spacings(m, '.6g')} of {dx:.6g}, below the least horizon of model "
                f"{self.name} ({what}); give horizon_length >= {max(least, 1.0) * dx:.6g} or more points"
            )
        if (self.whole_horizon or opt.kind is int) and m != round(m):
            near = self.nearest_whole(scene, params, m)
            raise InputError(
                f"horizon_length = {float(delta)!r}: {spacings(m, '.10g')} of {dx:.10g}; model {self.name} needs a "
                f"whole number ({self.whole_horizon or 'its horizon counts whole spacings'}); give horizon_length = "
                f"{near * dx:.12g} or points with (points - 1) delta / length whole"  # digits enough to be whole
            )
        value = m - self.horizon_offset(params)
        return int(round(value)) if opt.kind is int else float(value)

    def nearest_whole(self, scene: Scene, params: dict, m: float) -> int:
        """The whole horizon nearest m whose family fits the grid (:meth:`grid_problems`), the nearer of floor and
        ceil first; round(m) when neither fits (the refusal of a horizon too wide then follows)."""
        lower = max(1, int(m))
        for near in sorted({lower, lower + 1}, key=lambda k: (abs(k - m), k)):
            value = near - self.horizon_offset(params)
            trial = {**params, "horizon": int(round(value)) if self.option("horizon").kind is int else float(value)}
            if not self.grid_problems(scene, trial):
                return near
        return max(1, round(m))

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """What the model's grid refuses in the resolved ``params`` on ``scene``, found without solving (a horizon
        whose family does not fit in the points, a variant defined only up to some horizon): one line each, checked
        by :meth:`~pdverify.core.contract.Model.resolve`, so that a command and a study's up-front check refuse it
        at once (exit 2). None by default; a model that refuses more inside its solve still does."""
        return []

    def family_problems(self, scene: Scene, params: dict, reach, stencil: bool = False) -> list[str]:
        """The refusal of a family that does not fit in the points (:meth:`grid_problems` of a model whose family
        reaches ``reach(m)`` points each side of a point, 2 reach + 1 <= points): none when it fits. ``stencil``:
        the operator is the family applied twice (a stencil of 2 x reach points each side, 2 reach + 1 <= points
        all the same)."""
        n = params["points"]

        def fits(k) -> bool:  # a family reaches at least floor(k) points: no arrays for a horizon past the grid
            return k < n and 2 * reach(k) + 1 <= n

        if fits(params["horizon"]):
            return []
        J = reach(params["horizon"]) if params["horizon"] < n else int(params["horizon"])
        J = J if J < 10**15 else f"{float(J):.3g}"  # (a horizon of 1e308 spacings: not 309 digits)
        shape = f"the stencil (2 x {J} points)" if stencil else f"the family ({J} points each side)"
        return [self.horizon_refusal(scene, params, f"{shape} does not fit in {n} points", fits)]

    def horizon_named(self, scene: Scene, params: dict) -> str:
        """The horizon as the user set it, for a refusal: ``horizon = 250``, or with ``horizon_length`` given
        ``horizon_length = 5 (horizon = 250 spacings of 0.02)``."""
        m = params["horizon"]
        if params.get("horizon_length") is None:
            return f"horizon = {m:g}"
        dx = self.spacing(scene, params)
        return f"horizon_length = {params['horizon_length']:g} (horizon = {spacings(m, 'g')} of {dx:.6g})"

    def horizon_refusal(self, scene: Scene, params: dict, what: str, fits, fix: str = "", more_points=True) -> str:
        """One line refusing the horizon of ``params`` on its grid before any work: the horizon as the user set it
        (:meth:`horizon_named`), ``what`` is wrong, and the fix: with ``horizon`` a smaller horizon (the largest
        whole one that ``fits(m)``, a predicate monotone in m) or more points; with ``horizon_length`` the longest
        horizon_length that fits (more points do not help: the horizon's spacings grow with them). ``fix``: more
        ways out (", or variant corrected"); ``more_points``: whether more points make a given horizon fit."""
        most = 0
        hi = max(1, int(params["horizon"]) + 1)
        if fits(1):
            lo = 1  # fits(lo), not fits(hi): bisect on whole m
            while hi - lo > 1:
                mid = (lo + hi) // 2
                lo, hi = (mid, hi) if fits(mid) else (lo, mid)
            most = lo
        n = params.get("points")
        if params.get("horizon_length") is None:
            way = f"use horizon <= {most}" if most else "use more points"
            if most and n is not None and more_points:
                way = f"use more points or horizon <= {most} at {n} points"
        elif most:
            length = (most + self.horizon_offset(params)) * self.spacing(scene, params)
            way = f"give horizon_length <= {length:.6g} ({spacings(most, 'g')})"
        else:
            way = "give a shorter horizon_length"
        return f"{self.horizon_named(scene, params)}: {what}; {way}{fix}"

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

    def gradient_coefficient(self, scene: Scene, params: dict) -> float | None:
        """g of the model's nonlocal law: on a sine load of wave number k its continuum is softer than the local
        theory by g (k delta)^2 + O((k delta)^4) (docs/nonlocal.md, the symbols' expansions in
        :mod:`pdverify.theory.symbols`); None where it is not derived."""
        return None

    def model_error_ends(self, scene: Scene, params: dict, delta: float) -> tuple[float, str]:
        """(factor, why): how many times the first sine mode's model error g (pi delta / L)^2 the variant's ends may
        make it on ``scene``'s supports at the horizon ``delta`` (a length), measured (docs/nonlocal.md); (1, "")
        where its ends add nothing known."""
        return 1.0, ""

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """(why, largest m) when the variant's discrete rules have no limit at fixed delta on ``scene`` (its
        continuum is then its own finest grid, flagged), else None."""
        return None
