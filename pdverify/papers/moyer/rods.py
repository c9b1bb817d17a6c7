"""Models ``pd-rod`` and ``pd-torsion`` (Moyer & Miraglia 2014, Sections 2 and 5): the rod kernel's one field and its
resultant (u and N = EA u'; the twist and T = GJ θ'), static or transient (:mod:`.base`)."""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.scene import ROD_HELD, PointForce, PointTorque, Scene
from ...theory.symbols import GRADIENT, Series, rod_series
from .base import _MoyerModel
from .operator import rod_operator
from .pieces import bond_stiffness, holds_somewhere
from .point_loads import rod_points_loaded
from .resultants import interval_averages, shear_at_points, stepped


class _RodModel(_MoyerModel):
    """The rod kernel's models (axial and torsion): one field and its resultant, stiffness x the field's slope."""

    field, resultant = "u", "N"
    dispersion = "rod"  # its waves' frequencies (pdverify.theory.symbols)
    grid_checked = True  # a sine load 0.93 % off at 21 points, below the model-error line's 1 % (docs/nonlocal.md)
    # no stabilisation: with the mirror-image ghosts (ends.rod_mirror_ghosts) M^-1 K has a real spectrum
    # for every support pair and horizon (test_dynamics), so the scheme is stable undamped; damping is only what
    # the scene asks for
    stabilisation = 0.0

    def gradient_coefficient(self, scene: Scene, params: dict) -> float:
        """1/24: the rod kernel's symbol (docs/nonlocal.md)."""
        return GRADIENT["rod"]

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """Variant paper at a spring end: Section 4 gives an end that does not hold the unknown no traction
        condition, so the spring's end was held as if rigid (u there 0: 98 % of max |u| off on a clamped-spring rod
        under a uniform load, at every grid); refused, as a free end is (:meth:`refusals`)."""
        found = super().grid_problems(scene, params)
        if params.get("variant") == "paper":
            found += [
                f"supports.{side} = spring: variant paper sets no traction condition at an end that does not hold the "
                f"{self._unknown()} (Section 4 as published), so a spring end cannot be represented; use variant "
                "corrected"
                for side in ("left", "right")
                if scene.supports.kind(side) == "spring"
            ]
        return found

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """Variant paper at a free, guided or roller end that does not hold the unknown (Moyer & Miraglia,
        Section 4: such an end has no traction condition, only its ghosts' extrapolation): a static solve's system
        is singular (condition estimate ~1e17 at every grid and horizon), and the operator's lowest natural
        frequencies and a transient are wrong (studies/paper_moyer/rod_transient.toml, a clamped-free rod: 21 times
        max |u| off exact-modal-rod at 41, 81 and 161 points)."""
        if params.get("variant") != "paper":
            return []
        held = ROD_HELD["axial" if self.axial else "torsion"] + ("spring",)  # a spring end: grid_problems
        return [
            f"supports.{side} = {kind}: variant paper sets no traction condition at an end that does not hold the "
            f"{self._unknown()} (Section 4 as published), so its system is singular; use variant corrected"
            for side in ("left", "right")
            if (kind := scene.supports.kind(side)) not in held
        ]

    def _unknown(self) -> str:
        return {"u": "axial displacement"}.get(self.measures, self.measures)

    def stiffness(self, scene) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def continuum_series(self, scene: Scene, params: dict) -> Series | None:
        """The corrected variant's mirror ends (odd where the field is held, even where its resultant is given:
        :func:`.ends.rod_mirror_ghosts`): a series of the mirror modes with the rod kernel's symbol."""
        if params["variant"] != "corrected" or params["grid"] != "nodes":
            return None
        kind = "axial" if self.axial else "torsion"
        component = "axial" if self.axial else "torque"
        delta = self.delta(scene, params)
        return rod_series(scene, delta, self.stiffness(scene), tuple(ROD_HELD[kind]), component, self.field)

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """No limit at fixed delta where a single point inside carries a force (:func:`.point_loads.rod_points_loaded`):
        the rod kernel's symbol grows only like (4 E / delta^2) ln(k delta) (Moyer & Miraglia 2014, Eq. 3 and
        13-19, c_j = w_j / j; docs/nonlocal.md), so the response there, ∫ dk / symbol up to k ~ pi / dx, grows
        like m / ln m."""
        inside = rod_points_loaded(self, scene)
        if not inside:
            return None
        why = (
            f"a point {'torque' if self.unknowns == 'torsion' else 'force'}, a support or a spring inside "
            f"(x = {min(inside):g}): a single point carries a force, and the rod kernel's symbol grows like "
            "ln(k delta), so the field there grows without bound as m grows at fixed delta (docs/nonlocal.md): no limit"
        )
        return why, int(params.get("continuum_m") or self.continuum_m)

    @property
    def key(self) -> str:
        return "EA" if self.unknowns == "axial" else "GJ"

    def end_reactions(self, scene, params, disc, u, loads, inner, kinks):
        """-N(0) and N(L) (T for the bar) of the resultant field: the mirror-image ghosts carry the end's force, so
        the held end's row holds no reaction."""
        R = self.from_solution(scene, params, disc, u, {}, {}, None, {}, reactions=inner).fields[self.resultant]
        key = "axial" if self.unknowns == "axial" else "torque"
        return {("left", key): float(-R[0]), ("right", key): float(R[-1])}, "the resultant at the ends"

    def from_solution(self, scene, params, disc, u, fields, info, timer, writers, reactions=(), kinks=()):
        """The result: u (twist) and its resultant N (T) at the points from the flux of the bonds across each cut
        between two points, which every point's equation steps by its load (the cumulative sum of K u, anchored by
        the median of EA Δu/Δ over the intervals; within a horizon of an end, where the ghosts' bonds cross the cuts
        too, EA Δu/Δ itself), to the points by the loads between them (:mod:`.resultants`); ``reactions``: the inner
        supports' and springs' (position, force, 0)."""
        x = disc.x
        dx = x[1] - x[0]
        stiff = self.stiffness(scene) if scene.uniform else bond_stiffness(scene, x[:-1], x[1:], self.key)
        local = stiff * np.diff(u) / dx  # the intervals' averages
        component = "axial" if self.unknowns == "axial" else "torque"
        # the steps give N at the intervals' middles (the points' cell integrals); to their averages by the loads
        to_average = interval_averages(np.zeros(len(local)), x, scene, component, sign=-1.0)
        Nbar = stepped(-(disc.op @ u) * dx, local - to_average) + to_average
        ends = np.minimum(np.arange(len(local)), np.arange(len(local))[::-1]) <= params["horizon"]
        Nbar[ends] = local[ends]  # the ghosts' bonds cross the cuts there: the local strain
        forces = [(ld.position, v) for ld in scene.loads if (v := _point_value(ld, component))]
        forces += [(at, f) for at, f, _ in reactions if f]
        N = shear_at_points(Nbar, x, scene, forces, component, sign=-1.0)
        fields = dict(fields, **{self.field: u, self.resultant: N})
        return self.new_result(
            scene,
            params,
            x,
            np.zeros_like(x),
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings if timer is not None else {},
            info=info,
            writers=writers,
        )


def _point_value(load, component: str) -> float:
    """A point load's axial force (``component`` axial) or torque (torque); 0 for other loads."""
    if component == "axial":
        return load.axial if isinstance(load, PointForce) else 0.0
    return load.value if isinstance(load, PointTorque) else 0.0


class PDRod(_RodModel):
    name = "pd-rod"
    title = "micro-elastic PD rod (axial), trapezoidal kernel"
    unknowns = "axial"
    axial = True
    bending = False
    theory = "axial"
    measures = "u"
    load_types = frozenset({"point_force", "distributed"})  # their axial components

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if not holds_somewhere(scene, "axial", ROD_HELD["axial"]):
            sup = scene.supports
            out.append(
                f"supports = {sup.kind('left')}-{sup.kind('right')}: neither end holds the axial displacement (a "
                "roller or guided end slides along the axis), nor does a support inside the span or a spring, so the "
                "rod is a mechanism; make one end clamped or pinned"
            )
        return out

    def operator(self, scene, params):
        return rod_operator(
            scene, params["points"], params["horizon"], params["variant"], kind="axial", grid=params["grid"]
        )

    def stiffness(self, scene) -> float:
        """EA: the resultant N = EA u' of the solved field u."""
        return scene.EA


class PDTorsion(_RodModel):
    name = "pd-torsion"
    title = "micro-elastic PD torsion (twist), the rod kernel with GJ (Section 5)"
    unknowns = "torsion"
    bending = False
    torsion = True
    theory = "torsion"
    measures = "twist"
    load_types = frozenset({"point_torque", "distributed"})  # distributed: its torque component

    def operator(self, scene, params):
        disc = rod_operator(
            scene, params["points"], params["horizon"], params["variant"], kind="torsion", grid=params["grid"]
        )
        if self._dynamic(scene, params) and not np.all(np.isfinite(disc.mass)):
            raise InputError(
                "section: pd-torsion dynamics needs the polar moment of the section: "
                "give a rectangle (width and height), an I or a doubly symmetric profile"
            )
        return disc

    field, resultant = "twist", "T"

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if not holds_somewhere(scene, "torsion", ROD_HELD["torsion"]):
            sup = scene.supports
            out.append(
                f"supports = {sup.kind('left')}-{sup.kind('right')}: neither end holds the twist, nor does a support "
                "inside the span or a spring (its rotational_stiffness), so the bar is a mechanism; make one end "
                "clamped, pinned or roller"
            )
        return out

    def stiffness(self, scene) -> float:
        """GJ: the torque T = GJ twist'."""
        return scene.material.G * scene.section.J
