"""Models ``pd-rod``, ``pd-timoshenko``, ``pd-torsion``: micro-elastic PD rod, Timoshenko beam and
torsion (Moyer & Miraglia 2014; torsion: Section 5, Eq. 54–56), static or transient.

The pieces, one direction of imports: :mod:`.kernels` (quadrature weights, ghost polynomials, loads, the
end-patched stencil) -> :mod:`.system` (the discrete system and its direct solve) -> :mod:`.energy` (the beam's
variant energy) and :mod:`.ends` (the ghost points of each support, Eq. 20–21 and the mirror images) ->
:mod:`.operator` (the rod and beam operators, Eq. 19, 45–49) -> :mod:`.spectrum` (eigenvalues of M⁻¹K: stable
step, frequencies) and :mod:`.steps` (step engines) -> :mod:`.transient` (the time integration of Eq. 7–12, its
history and energy ledger) -> this module (the models and :func:`simulate`).

The beam's variants: ``energy`` (the default: the corrected equations as the gradient of a discrete energy,
symmetric, no ghosts), ``corrected`` (collocation with ghost points: exact for cubics), ``paper`` (as published).

Results: x, w, rotation = γ, fields M = EIγ' (energy: M' = V integrated, :func:`.energy.moment_field`),
V = M' = -kGA ψ (the exact models' convention), psi;
rod: u, N = EA u'; torsion: twist, T = GJ θ'. A scene with a ``[dynamics]`` table is run in time by
``solve`` (option ``analysis``: auto | static | dynamic); the time histories are in info["history"]
and ``--out file.csv`` writes them.
"""

from __future__ import annotations

import numpy as np

from ...core.contract import Option, Rule
from ...core.errors import InputError
from ...core.scene import Scene
from ...numerics.loads import support_side
from ...theory.model_error import pair_factor
from ...theory.symbols import GRADIENT, Series, timoshenko_series
from .base import _OPTIONS, _context, _MoyerModel, stabilisation_warning
from .couples import couple_column
from .ends import MIRRORED
from .energy import moment_field, shear_force
from .operator import beam_operator, segments_refusal
from .point_loads import beam_points_loaded
from .rods import PDRod, PDTorsion
from .system import prescribed_motions
from .transient import History, integrate

__all__ = ["MODELS", "PDRod", "PDTimoshenko", "PDTorsion", "simulate", "stabilisation_warning"]


class PDTimoshenko(_MoyerModel):
    name = "pd-timoshenko"
    jump_rotation = (0.65, 0.65)  # inside, at an end: above the ratios of benchmarks/jump_rotation.py (docs/trust.md)
    # above the values of benchmarks/end_loads.py (docs/trust.md); a spring end takes the pin's, with a rotational
    # stiffness the clamp's (registry/end_loads.py: end_kind); the rotation's up to 2.53 times the estimate ("rotation")
    end_load_error = {"clamped": 0.65, "pinned": 0.15, "spring": 0.15, "rotational spring": 0.65, "rotation": 3.0}
    title = "micro-elastic PD Timoshenko beam (w, rotation)"
    theory = "timoshenko"
    options = tuple(
        Option(
            "variant",
            str,
            "energy",
            "energy (the corrected beam from a discrete energy: symmetric, stable undamped; horizons 1-12) | "
            "corrected (collocation: exact for cubics) | paper",
            choices=("paper", "corrected", "energy"),
        )
        if o.name == "variant"
        else o
        for o in _OPTIONS
    )
    variant_rules = (
        *_MoyerModel.variant_rules,
        Rule(
            (("variant", "energy"),),
            "grid",
            "the energy form is written for the node grid; grid = cells is the paper's Section 4 setup "
            "(variant = paper)",
            allowed=("nodes",),
        ),
    )

    def gradient_coefficient(self, scene: Scene, params: dict) -> float:
        """7/72: the bending part of w's symbol, the larger of its two (the shear part's 1/18; docs/nonlocal.md)."""
        return GRADIENT["timoshenko-bending"]

    def model_error_ends(self, scene: Scene, params: dict, delta: float) -> tuple[float, str]:
        """Measured per variant and support pair (:mod:`pdverify.theory.model_error`)."""
        return pair_factor(scene, f"pd-timoshenko {self.with_defaults(params)['variant']}", delta)

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """Segments in the paper and corrected variants (:func:`.operator.segments_refusal`)."""
        why = segments_refusal(scene, params["variant"])
        return [why] if why else []

    def operator(self, scene, params):
        return beam_operator(scene, params["points"], params["horizon"], params["variant"], grid=params["grid"])

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """Variant energy's fitted end bonds exist for horizons 1-12 only (:mod:`.energy`): no limit at fixed delta.
        Under a transverse point force inside the beam the deflection at the load grows like ln m at fixed delta
        (measured, docs/nonlocal.md: the shear kernel's response to a point force): no limit there either; nor beside a
        support inside the beam, whose reaction is such a force (and a spring's couple, a point couple)."""
        if params["variant"] == "energy":
            return (
                "variant energy's fitted end bonds exist for horizons 1-12 only, so it has no limit at fixed delta",
                12,
            )
        m = int(params.get("continuum_m") or self.continuum_m)
        inside = beam_points_loaded(scene)
        if inside:
            return (
                f"a point force inside the beam (x = {min(inside):g}): the deflection at the load grows like ln m at "
                "fixed delta (docs/nonlocal.md), so there is no limit",
                m,
            )
        if scene.supports.inner:
            at = min(s.position for s in scene.supports.inner)
            return (
                f"a support inside the beam (x = {at:g}): its reaction is a point force (a couple too where it holds "
                "the rotation) on the points around it, under which the deflection grows like ln m at fixed delta "
                "(docs/nonlocal.md), so there is no limit",
                m,
            )
        return None

    def continuum_series(self, scene: Scene, params: dict) -> Series | None:
        """The corrected variant's pinned (roller) and guided ends are mirror images (:func:`.ends.mirror_ghosts`):
        under sine loads a series of the mirror modes with the continuous symbols of Eq. 47-49."""
        if params["variant"] == "corrected" and params["grid"] == "nodes":
            return timoshenko_series(scene, self.delta(scene, params))
        return None

    def stabilisation_for(self, scene: Scene, params: dict) -> float:
        """0 between two mirrored ends (pinned, roller, guided) of the corrected variant: their spectrum is
        real (ends.mirror_ghosts), so damping is only what the scene asks for."""
        if params["variant"] == "energy":  # symmetric in the volumes: a real spectrum at every end (.energy)
            return 0.0
        ends = (scene.supports.left, scene.supports.right)
        if params["variant"] == "corrected" and params["grid"] == "nodes" and all(e in MIRRORED for e in ends):
            return 0.0
        return self.stabilisation

    def couples(self, scene, params, disc):
        if params["variant"] != "energy":
            return None
        return lambda a: couple_column(disc.op, scene, disc.x, params["horizon"], disc.weights, a)

    def end_reactions(self, scene, params, disc, u, loads, inner, kinks):
        """Variant energy: the held rows' residual K u - b (its rows are ∂U/∂u - b) times the points' volumes; the
        others: V(0), -M(0), -V(L), M(L) of the fields (their ghost closures carry the end's force)."""
        x = disc.x
        dx = x[1] - x[0]
        out = {}
        if params["variant"] == "energy":
            r = (disc.op @ u - disc.b - loads) * disc.weights * dx
            for dof, (field, side) in disc.prescribed.items():
                out[("left" if side == 0 else "right", "force" if field == "w" else "moment")] = float(r[dof])
            return out, "the held rows' residual times the points' volumes"
        fields = self.from_solution(scene, params, disc, u, {}, {}, None, {}, reactions=inner, kinks=kinks).fields
        V, M = fields["V"], fields["M"]
        out = {
            ("left", "force"): V[0],
            ("left", "moment"): -M[0],
            ("right", "force"): -V[-1],
            ("right", "moment"): M[-1],
        }
        return {k: float(v) for k, v in out.items()}, "the shear force and moment fields at the ends"

    def from_solution(self, scene, params, disc, u, fields, info, timer, writers, reactions=(), kinks=()):
        """The result; ``reactions``: the inner supports' and springs' (position, force, couple), loads on the beam
        for the resultants of variant energy (:mod:`.resultants`), ``kinks`` those of their couples applied on their
        kink (:mod:`.couples`)."""
        x = disc.x
        dx = x[1] - x[0]
        w, g = u[0::2], u[1::2]
        psi = disc.psi[0] @ u + disc.psi[1]
        if params["variant"] == "energy":  # M' = V integrated (energy.moment_field), V from the intervals
            kinks = list(disc.kinks) + list(kinks)
            M = moment_field(u, scene, params["horizon"], dx, reactions, kinks)
            V = shear_force(u, scene, dx, reactions, kinks)
        else:
            # their end closures carry the end loads as conditions (EI gamma' = M, kGA psi = P): the beam's side
            M = support_side(scene, scene.EI * np.gradient(g, dx, edge_order=2), "moment")
            V = support_side(scene, -scene.kGA * psi, "shear")
            M, V = spring_end_values(scene, M, V, info.get("reactions") or {})
        fields = dict(fields, M=M, V=V, psi=psi)
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=g,
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings if timer is not None else {},
            info=info,
            writers=writers,
        )


def spring_end_values(scene: Scene, M: np.ndarray, V: np.ndarray, reactions: dict) -> tuple[np.ndarray, np.ndarray]:
    """M and V at a spring end's point from its reactions (the support's side: V(0) = force_left, M(0) =
    -moment_left, V(L) = -force_right, M(L) = moment_right): the corrected and paper closures see a spring end as
    a free one, so their end values leave the spring's force out (V there 66 % and 73 % of max |V| off at 81 and 321
    points on a clamped-spring beam), while the reactions carry it."""
    M, V = np.array(M, float), np.array(V, float)
    for side, i, sign in (("left", 0, 1.0), ("right", -1, -1.0)):
        if scene.supports.kind(side) == "spring" and f"force_{side}" in reactions:
            V[i] = sign * reactions[f"force_{side}"]
            M[i] = -sign * reactions.get(f"moment_{side}", 0.0)
    return M, V


def simulate(
    scene: Scene,
    params: dict | None = None,
    t_end: float | None = None,
    dt: float | None = None,
    damping: float | None = None,
    damping_ratio: float | None = None,
    safety: float = 0.9,
    probes=None,
    record_every: int | None = None,
    model: str = "pd-timoshenko",
    damp_rotations: bool | None = None,
    stabilisation: float | None = None,
) -> History:
    """Transient run of ``pd-timoshenko`` (or ``model = "pd-rod"`` / ``"pd-torsion"``) on ``scene``: the scene's
    [dynamics] table gives the defaults (end time, damping, probes, prescribed end motions); the
    arguments override them (``record_every`` overrides the table's output_interval; ``stabilisation`` the
    model's own, none for the rod kernel's models; ``damp_rotations`` the table's damping_on, default all).
    Returns a :class:`History`."""
    m = {"pd-timoshenko": PDTimoshenko(), "pd-rod": PDRod(), "pd-torsion": PDTorsion()}[model]
    params = m.resolve(scene, params or {})
    if scene.material.density is None:
        raise InputError("material.density: needed for dynamics; add density to the scene")
    d = scene.dynamics
    if t_end is None:
        if d is None:
            raise InputError("t_end: give the end time (the scene has no [dynamics] table)")
        t_end = d.end_time
    if d is not None:
        dt = d.time_step if dt is None else dt
        if damping is None and damping_ratio is None:
            damping, damping_ratio = d.damping, d.damping_ratio
        probes = d.probes if probes is None else probes
    if damp_rotations is None:
        damp_rotations = d is None or d.damping_on == "all"
    output_interval = d.output_interval if (d is not None and record_every is None) else None
    disc = m.operator(scene, params)
    return integrate(
        disc,
        prescribed_motions(scene, disc),
        t_end,
        dt=dt,
        damping=damping or 0.0,
        damping_ratio=damping_ratio,
        safety=safety,
        probes=probes,
        record_every=record_every,
        output_interval=output_interval,
        damp_rotations=damp_rotations,
        stabilisation=m.stabilisation_for(scene, params) if stabilisation is None else stabilisation,
        context=_context(scene, params),
    )


MODELS = [PDRod(), PDTimoshenko(), PDTorsion()]
