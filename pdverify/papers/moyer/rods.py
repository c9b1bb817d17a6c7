"""Models ``pd-rod`` and ``pd-torsion`` (Moyer & Miraglia 2014, Sections 2 and 5): the rod kernel's one field and its
resultant (u and N = EA u'; the twist and T = GJ θ'), static or transient (:mod:`.base`)."""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ...core.scene import ROD_HELD, Scene
from .base import _MoyerModel
from .operator import rod_operator
from .pieces import holds_somewhere, piece_stiffness


class _RodModel(_MoyerModel):
    """The rod kernel's models (axial and torsion): one field and its resultant, stiffness x the field's slope."""

    field, resultant = "u", "N"
    # no stabilisation: with the mirror-image ghosts (ends.rod_mirror_ghosts) M^-1 K has a real spectrum
    # for every support pair and horizon (test_dynamics), so the scheme is stable undamped; damping is only what
    # the scene asks for
    stabilisation = 0.0

    def stiffness(self, scene) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def stiffness_at(self, scene, x) -> np.ndarray | float:
        """The stiffness (EA, GJ) at the points x (segments: each point's segment, an interface's right one)."""
        if scene.uniform:
            return self.stiffness(scene)
        out = np.empty(len(x))
        for a, _, S in piece_stiffness(scene, "EA" if self.unknowns == "axial" else "GJ"):
            out[x >= a] = S
        return out

    def end_reactions(self, scene, params, disc, u, loads, inner, kinks):
        """-N(0) and N(L) (T for the bar): the mirror-image ghosts carry the end's force, so the held end's row
        holds no reaction."""
        x = disc.x
        R = self.stiffness_at(scene, x) * np.gradient(u, x[1] - x[0], edge_order=2)
        R = np.broadcast_to(R, x.shape)
        key = "axial" if self.unknowns == "axial" else "torque"
        return {("left", key): float(-R[0]), ("right", key): float(R[-1])}, "the resultant at the ends"

    def from_solution(self, scene, params, disc, u, fields, info, timer, writers, reactions=(), kinks=()):
        x = disc.x
        slope = np.gradient(u, x[1] - x[0], edge_order=2)
        fields = dict(fields, **{self.field: u, self.resultant: self.stiffness_at(scene, x) * slope})
        return self.new_result(
            scene,
            params,
            x,
            np.zeros_like(x),
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings,
            info=info,
            writers=writers,
        )


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
                "section: pd-torsion dynamics needs the polar moment of a rectangle; give width and height"
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
