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

from pathlib import Path

import numpy as np

from ...core.contract import Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import ROD_HELD, Scene
from ...numerics.loads import boundary_layer_warnings, moment_rotation_warnings
from .ends import FIT_POINTS, MIRRORED
from .energy import moment_field
from .kernels import node_loads
from .operator import beam_operator, rod_operator
from .system import Discrete, prescribed_motions, static_solution, static_system
from .transient import STABILISATION, History, integrate

# -- the models -------------------------------------------------------------------------------

_OPTIONS = (
    Option(
        "points", int, 101, "material points along the beam, ends included (grid = cells: points - 1 cells)", minimum=6
    ),
    Option("horizon", int, 3, "horizon delta = m dx, m an integer (1 = nearest neighbours)", minimum=1),
    Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
    Option(
        "analysis",
        str,
        "auto",
        "auto (dynamic when the scene has [dynamics]) | static | dynamic",
        choices=("auto", "static", "dynamic"),
    ),
    Option(
        "grid",
        str,
        "nodes",
        "nodes (ends included) | cells (Section 4 cell centres; variant paper, static)",
        choices=("nodes", "cells"),
    ),
)


class _MoyerModel(Model):
    source = "Moyer & Miraglia 2014, Peridynamic solutions for Timoshenko beams"
    options = _OPTIONS
    analyses = frozenset({"static", "dynamic"})  # the damped leapfrog-Verlet integrator (Eq. 7-11)
    end_motions = True  # prescribed end motions of [dynamics] (Example 2); the static part: their final value
    assembles = True
    modes = True  # eigenproblem(): the operator of the transient and its lumped mass
    stabilisation = STABILISATION  # κ of the scheme's stiffness-proportional damping (transient.integrate)

    def stabilisation_for(self, scene: Scene, params: dict) -> float:
        """κ of this scene's run (the class's; the beam drops it where its closures are stable)."""
        return self.stabilisation

    variant_rules = (
        Rule(
            (("variant", "corrected"),),
            "grid",
            "the corrections are written for the node grid; grid = cells "
            "is the paper's Section 4 setup (variant = paper)",
            allowed=("nodes",),
        ),
    )

    def operator(self, scene: Scene, params: dict) -> Discrete:  # pragma: no cover - interface
        raise NotImplementedError

    def assemble(self, scene: Scene, params: dict) -> System:
        """The static system ``solve`` factorises (:func:`static_system`): the operator's band with the
        prescribed DOFs held (unit rows; a settled end motion moved to the right-hand side)."""
        disc = self.operator(scene, params)
        B, rhs, _ = static_system(scene, disc)
        return System(B, rhs, np.asarray(disc.free), dict(disc.info))

    def _dynamic(self, scene: Scene, params: dict) -> bool:
        if params["analysis"] == "dynamic" and scene.dynamics is None:
            raise InputError(
                "analysis = 'dynamic': the scene has no [dynamics] table; add one (end_time, ...) "
                "or use analysis = static"
            )
        dyn = params["analysis"] == "dynamic" or (params["analysis"] == "auto" and scene.dynamics is not None)
        moving = scene.dynamics is not None and any(
            getattr(em, k) is not None
            for em in (scene.dynamics.left, scene.dynamics.right)
            if em is not None
            for k in ("displacement", "axial", "rotation", "twist")
        )
        if params.get("grid") == "cells" and (dyn or moving):
            raise InputError(
                "grid = 'cells': the cell-centred grid takes no dynamics or prescribed end motions here "
                "(its end faces carry no points); use grid = nodes"
            )
        return dyn

    def eigenproblem(self, scene: Scene, params: dict) -> tuple:
        """(K, mass) on the free DOFs: K φ = ω² diag(mass) φ, the operator of the transient (``pdverify
        modes``); K is not symmetric in the paper and corrected variants (the boundary closures), so ω² may be
        complex there; variant energy's K times the volumes is symmetric, so its ω² are real."""
        if scene.material.density is None:
            raise InputError("material.density: needed for natural frequencies; add density to the scene")
        disc = self.operator(scene, params)
        if not np.all(np.isfinite(disc.mass)):
            raise InputError("section: pd-torsion needs the polar moment of a rectangle; give width and height")
        free = disc.free
        return disc.K[free][:, free], disc.mass[free]

    def bench_dynamics(self, scene: Scene, params: dict, steps: int = 200) -> float:
        """Point-updates per second of the explicit integration (``pdverify bench``)."""
        import time

        disc = self.operator(scene, params)
        t0 = time.perf_counter()
        h = integrate(disc, {}, t_end=None, steps=steps, record_every=steps)  # dt = 0.9 of the stable limit
        return len(disc.x) * h.steps / (time.perf_counter() - t0)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        if self._dynamic(scene, params) and scene.material.density is None:
            raise InputError("material.density: needed for dynamics; add density to the scene")
        with timer("assemble"):
            disc = self.operator(scene, params)
        m = params["horizon"]
        info = dict(disc.info, horizon_factor=m, variant=params["variant"])
        fields = {}
        writers = {}
        if self._dynamic(scene, params):
            d = scene.dynamics
            with timer("solve"):
                h = integrate(
                    disc,
                    prescribed_motions(scene, disc),
                    d.end_time,
                    dt=d.time_step,
                    damping=d.damping or 0.0,
                    damping_ratio=d.damping_ratio,
                    probes=d.probes,
                    output_interval=d.output_interval,
                    damp_rotations=d.damping_on == "all",
                    stabilisation=self.stabilisation_for(scene, params),
                    context=_context(scene, params),
                )
            u = h.final
            label = "w" if self.bending else ("u" if self.axial else "twist")
            series = {f"{label}(x={p:g})": h.values[:, k] for k, p in enumerate(h.probes)}
            if h.rotations is not None:
                series.update({f"rotation(x={p:g})": h.rotations[:, k] for k, p in enumerate(h.probes)})
            info.update(
                analysis="dynamic",
                dt=h.dt,
                dt_limit=h.dt_limit,
                steps=h.steps,
                damping=h.damping,
                omega1=h.omega1,
                stabilisation=h.stabilisation,
                energy_drift=h.energy_drift,
                scheme_drift=h.scheme_drift,
                history={
                    "t": h.t,
                    "series": series,
                    "energy": h.energy,
                    "ylabel": {"u": "axial displacement", "w": "deflection", "twist": "twist (rad)"}[label],
                },
            )
            writers[".csv"] = lambda path, h=h: Path(path).write_text(h.to_csv())
            flag = stabilisation_warning(h, params)
            if flag:
                info.setdefault("warnings", []).append(flag)
        else:
            with timer("assemble"):  # the band of K and the supports
                system = static_system(scene, disc)
            with timer("solve"):
                u, sinfo = static_solution(scene, disc, f"{self.name} ({params['variant']})", system)
            info.update(sinfo, analysis="static")
            flags = boundary_layer_warnings(scene, disc.x, FIT_POINTS + m) + point_force_order(self, scene, params)
            flags += moment_rotation_warnings(scene) if self.bending else []
            if flags:
                info.setdefault("warnings", []).extend(flags)
        return self.from_solution(scene, params, disc, u, fields, info, timer, writers)


class _RodModel(_MoyerModel):
    """The rod kernel's models (axial and torsion): one field and its resultant, stiffness x the field's slope."""

    field, resultant = "u", "N"
    # no stabilisation: with the mirror-image ghosts (ends.rod_mirror_ghosts) M^-1 K has a real spectrum
    # for every support pair and horizon (test_dynamics), so the scheme is stable undamped; damping is only what
    # the scene asks for
    stabilisation = 0.0

    def stiffness(self, scene) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def from_solution(self, scene, params, disc, u, fields, info, timer, writers):
        x = disc.x
        slope = np.gradient(u, x[1] - x[0], edge_order=2)
        fields = dict(fields, **{self.field: u, self.resultant: self.stiffness(scene) * slope})
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
    axial = True
    bending = False
    theory = "axial"
    measures = "u"
    load_types = frozenset({"point_force", "distributed"})  # their axial components

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        sup = (scene.supports.left, scene.supports.right)
        if not set(sup) & set(ROD_HELD["axial"]):
            out.append(
                f"supports = {sup[0]}-{sup[1]}: neither end holds the axial displacement (a roller or guided "
                "end slides along the axis), so the rod is a mechanism; make one end clamped or pinned"
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

    def stiffness(self, scene) -> float:
        """GJ: the torque T = GJ twist'."""
        return scene.material.G * scene.section.J


class PDTimoshenko(_MoyerModel):
    name = "pd-timoshenko"
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

    def operator(self, scene, params):
        return beam_operator(scene, params["points"], params["horizon"], params["variant"], grid=params["grid"])

    def stabilisation_for(self, scene: Scene, params: dict) -> float:
        """0 between two mirrored ends (pinned, roller, guided) of the corrected variant: their spectrum is
        real (ends.mirror_ghosts), so damping is only what the scene asks for."""
        if params["variant"] == "energy":  # symmetric in the volumes: a real spectrum at every end (.energy)
            return 0.0
        ends = (scene.supports.left, scene.supports.right)
        if params["variant"] == "corrected" and params["grid"] == "nodes" and all(e in MIRRORED for e in ends):
            return 0.0
        return self.stabilisation

    def from_solution(self, scene, params, disc, u, fields, info, timer, writers):
        x = disc.x
        dx = x[1] - x[0]
        w, g = u[0::2], u[1::2]
        if params["variant"] == "energy":  # M' = V integrated (energy.moment_field)
            _, mu, _ = node_loads(scene, x, "transverse", ends_apart=True)
            M = moment_field(u, scene, params["horizon"], dx, mu * dx)
        else:
            M = scene.EI * np.gradient(g, dx, edge_order=2)
        # ψ as the operator sees it (interval averages at the point; paper: central differences):
        # np.gradient(w) - γ would carry the O(Δ²) error of w' multiplied by kGA
        psi = disc.psi[0] @ u + disc.psi[1]
        fields = dict(fields, M=M, V=-scene.kGA * psi, psi=psi)
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=g,
            fields=fields,
            dofs=disc.n_free,
            timings=timer.timings,
            info=info,
            writers=writers,
        )


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


def stabilisation_warning(h: History, params: dict) -> str | None:
    """The warning of a run that had the scheme's stiffness-proportional damping (not asked for by the scene, not in
    the paper): how much of the work put in it took (the ledger's ``stabilisation`` column) and the variant that needs
    none."""
    if not h.stabilisation:
        return None
    e = h.energy
    put_in = max(np.nanmax(np.abs(e["load_work"])), np.nanmax(np.abs(e["support_work"])), 0.0) if e else 0.0
    took = float(e["stabilisation"][-1]) / put_in if put_in > 0 else float("nan")
    return (
        f"the scheme's stabilising damping (kappa = {h.stabilisation:g}, not in the scene or the paper) took "
        f"{took:.2g} of the work put in: the closures of variant {params['variant']} at these supports have growing "
        "modes; variant = energy runs without it"
    )


def _context(scene: Scene, params: dict) -> str:
    """Where a growing mode comes from, for the blow-up message."""
    return (
        f"supports {scene.supports.left}-{scene.supports.right}, horizon = {params['horizon']}, "
        f"points = {params['points']}, variant {params['variant']}"
    )


MODELS = [PDRod(), PDTimoshenko(), PDTorsion()]


def point_force_order(model, scene: Scene, params: dict) -> list[str]:
    """The corrected beam's known loss of order: a transverse point force inside the beam is first order there (its
    jump in shear falls between the collocation points' PD sums; docs/models/moyer.md, "Known limits")."""
    inside = [
        ld for ld in scene.loads if ld.type == "point_force" and ld.value != 0.0 and 0.0 < ld.position < scene.length
    ]
    if not (model.bending and params["variant"] == "corrected" and inside):
        return []
    return [
        "variant = corrected converges at first order near a point force inside the beam "
        f"(x = {inside[0].position:g}): the error halves, not quarters, per halving of the spacing (1.0e-3, 5.0e-4, "
        "2.5e-4 at 321, 641, 1281 points on a centre force, L/h = 5); variant = energy is second order there"
    ]
