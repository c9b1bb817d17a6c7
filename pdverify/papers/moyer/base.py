"""The shared part of the Moyer & Miraglia 2014 models (:mod:`.model`, :mod:`.rods`): their options, the static and
transient solve of the operator (:mod:`.operator`), with supports inside the span and springs (:mod:`.constraints`),
and the stabilisation's warning."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.contract import NONLOCAL, Model, Option, Rule, System
from ...core.errors import InputError, SolveError
from ...core.result import Result, Timer, merge_info
from ...core.scene import Scene
from ...numerics.explicit import step_warnings
from ...numerics.load_warnings import (
    boundary_layer_warnings,
    couple_at_joint_warnings,
    couple_deflection_warnings,
    edge_layer_warnings,
    held_rotation_warnings,
    horizon_layer,
    moment_rotation_warnings,
)
from ...numerics.span_warnings import short_span_warnings
from .constraints import reactions, solve_with_holds
from .couples import couple_warnings
from .ends import FIT_POINTS
from .energy import ENERGY_HORIZONS, zone
from .load_edges import member_edge_warnings
from .pieces import piece_stiffness, plain_ends
from .point_loads import point_force_order
from .published import paper_warnings
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
    *NONLOCAL,
)


# pd-timoshenko (energy), clamped-pinned 2 m beam, aluminium and steel segments joined at 0.8 m, a couple there:
# the rotation's largest error against exact-timoshenko at 101, 201, 401 points (docs/models/moyer.md)
COUPLE_AT_JOINT = "measured 5.5e-2, 2.8e-2, 1.4e-2 of max |rotation| at 101, 201, 401 points on a two-material beam"
# pd-rod and pd-torsion: a distributed load's edge inside an end's fitted layer (FIT_POINTS + m spacings) spoils the
# resultant there, first order (a 1 m bar, the load's edge 0.4 ... 5.4 spacings from a free or clamped end, the other
# end clamped or free: docs/models/moyer.md); the displacement (twist) stays second order
MEMBER_EDGE = 0.6  # c of member_edge_warnings (measured up to 0.56: benchmarks/member_edges.py)
ROD_EDGE = (
    "N (T) off by 1.2e-2, 4.8e-3, 9.6e-4, 6.0e-4 of its largest at 0.4, 3.2, 4.2, 5.0 spacings from the end at 101 "
    "points, first order (half at twice the points); u (the twist) second order"
)
# w beside a couple inside the span is off by about c |C| h² / EI (second order; h = max(spacing, horizon / 3)):
# variants corrected and paper put the couple on the two points around it, measured c up to 0.57 at horizon 3 and 2.75
# at 5 (a couple 10 spacings from a free end; paper 3.25 on a clamped-clamped beam, L/h = 100); energy takes it by its
# kink, c up to 0.12 over five end pairs, couples at 0.1 ... 0.9 L, L/h = 20 and 100, horizons 3 and 5, 101 and 401
# points, and 0.3 with two pins inside and a free overhang (docs/models/moyer.md)
COUPLE_DEFLECTION = {"energy": 0.35, "corrected": 3.5, "paper": 3.5}
# the moment and shear of a short span between two supports that hold w (energy): c (h / a)² of their largest in the
# span, measured c up to 1.85 (V: a stiff spring with a partial rotational stiffness beside a clamped end; 1.09 at a
# clamp) and 1.12 (M) where a support of the span holds the rotation, 0.40 and 0.24 where neither does (spans of 0.02
# ... 0.08 L, on and off the grid, beside an end or between two supports inside, 101 ... 801 points:
# benchmarks/short_spans.py); corrected and paper say their own first order beside a support inside
SHORT_SPAN = {"held": {"V": 2.0, "M": 1.2}, "pinned": {"V": 0.45, "M": 0.3}}


class _MoyerModel(Model):
    source = "Moyer & Miraglia 2014, Peridynamic solutions for Timoshenko beams"
    options = _OPTIONS
    whole_horizon = "Eq. 13-19: the trapezoidal rule over the nodes 0..m of the horizon delta = m dx"
    springs = True  # statics: elastic ends and supports inside the span (.constraints), segments (.pieces)
    inner_supports = True
    segments = True
    unknowns = "beam"  # what the supports hold (.pieces.holds): beam, axial or torsion
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

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """The horizon the grid refuses, before any work (the operator's own checks: :func:`.operator._check_grid`,
        variant energy's :func:`.energy.energy_beam_operator`, whose fit of m = 250 alone takes seconds)."""
        m, n = params["horizon"], params["points"] - (1 if params.get("grid") == "cells" else 0)
        if self.name == "pd-timoshenko" and params.get("variant") == "energy":

            def need(k):
                return max(2 * zone(k), 5)

            if m > ENERGY_HORIZONS:
                what = (
                    f"variant energy's fitted end bonds have an end mode of negative bending energy past horizon "
                    f"{ENERGY_HORIZONS} (horizons 1-{ENERGY_HORIZONS} are positive definite)"
                )
                return [
                    self.horizon_refusal(
                        scene,
                        params,
                        what,
                        lambda k: k <= ENERGY_HORIZONS and n >= need(k),
                        " or variant corrected",
                        more_points=False,
                    )
                ]
            what = "its two ends' fitted bonds must not overlap"
        else:

            def need(k):
                return max(2 * k + 2, FIT_POINTS + 1)

            what = "the horizon and the end fits must fit in the grid"
        if n < need(m):
            if params.get("horizon_length") is None:  # the points are short (advise refines on this "points = n:")
                energy = (
                    " (variant energy)" if params.get("variant") == "energy" and self.name == "pd-timoshenko" else ""
                )
                return [
                    f"points = {n}: model {self.name}{energy} with horizon = {m} needs at least {need(m)} points "
                    f"({what}); use more points or a smaller horizon"
                ]
            what = f"model {self.name} needs at least {need(m)} points at this horizon, {n} given ({what})"
            return [self.horizon_refusal(scene, params, what, lambda k: n >= need(k))]
        return []

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
        _statics_only(scene, self.name, "natural frequencies")
        disc = self.operator(scene, params)
        if not np.all(np.isfinite(disc.mass)):
            raise InputError(
                "section: pd-torsion needs the polar moment of the section: "
                "give a rectangle (width and height), an I or a doubly symmetric profile"
            )
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
        if self._dynamic(scene, params):
            _statics_only(scene, self.name, "transient runs")
        with timer("assemble"):
            disc = self.operator(plain_ends(scene), params)
        m = params["horizon"]
        info = dict(disc.info, horizon_factor=m, variant=params["variant"])
        fields = {}
        writers = {}
        extra = {}
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
            writers[".csv"] = lambda path, h=h, series=series: Path(path).write_text(h.to_csv(series))
            flag = stabilisation_warning(h, params)
            if flag:
                info.setdefault("warnings", []).append(flag)
            if fast := step_warnings(h.dt, h.dt_limit):
                info.setdefault("warnings", []).extend(fast)
        elif not scene.supports.simple:  # springs, supports inside the span (.constraints)
            with timer("solve"):
                u, sinfo, R, loads, kinks = self._held(scene, params, disc)
            merge_info(info, sinfo, analysis="static")
            inner = [h for h in R if h.label.startswith("inner")]  # (ends' reactions are in the end rows' values)
            extra["reactions"] = [
                (h.position, R[h] if h.slot == 0 else 0.0, R[h] if h.slot == 1 else 0.0) for h in inner
            ]
            extra["kinks"] = kinks
            ends, method = self.end_reactions(scene, params, disc, u, loads, extra["reactions"], kinks)
            info["reactions"] = reactions(scene, self.unknowns, R, ends, method)
        else:
            with timer("assemble"):  # the band of K and the supports
                system = static_system(scene, disc)
            with timer("solve"):
                u, sinfo = static_solution(scene, disc, f"{self.name} ({params['variant']})", system)
            merge_info(info, sinfo, analysis="static")
        if flags := self.discretisation_warnings(scene, params, disc.x):  # a transient's too: the same operator
            info.setdefault("warnings", []).extend(flags)
        result = self.from_solution(scene, params, disc, u, fields, info, timer, writers, **extra)
        if self.bending and info.get("analysis") == "static":
            delta = params["horizon"] * (disc.x[1] - disc.x[0])
            shear = result.fields["V"] if params["variant"] == "energy" else None  # exact where V is zero
            near = couple_deflection_warnings(
                scene, disc.x, result.w, delta, COUPLE_DEFLECTION[params["variant"]], shear
            )
            if params["variant"] == "energy":
                fixed = params.get("horizon_length") is not None
                near += short_span_warnings(scene, disc.x, result.fields, delta, SHORT_SPAN, fixed_horizon=fixed)
            result.info.setdefault("warnings", []).extend(near)
        elif info.get("analysis") == "static":  # a rod's or a bar's distributed load ending inside it
            key, dx = ("EA", "axial") if self.axial else ("GJ", "torque"), disc.x[1] - disc.x[0]
            pieces = piece_stiffness(scene, key[0])
            S = lambda e: next((s for a, b, s in pieces if e <= b * (1 + 1e-12)), pieces[-1][2])  # noqa: E731
            edges = member_edge_warnings(
                scene, disc.x, np.asarray(result.fields[self.measures]), S, key[1], MEMBER_EDGE,
                params["horizon"] * dx, params.get("horizon_length") is not None,
            )  # fmt: skip
            result.info.setdefault("warnings", []).extend(edges)
        return result

    def discretisation_warnings(self, scene: Scene, params: dict, x: np.ndarray) -> list[str]:
        """The warnings of the space discretisation (the operator and the load vector on the points ``x``) for this
        scene: loads inside the ends' fitted layer, the orders lost under point loads (:func:`point_force_order`),
        point forces beside an inner support that holds the rotation, the rotation near a point moment. A static
        solve and a transient share them: the transient integrates the same operator and the same loads (steps at
        t = 0), so its histories converge in space no faster than the static solution."""
        m, dx = params["horizon"], x[1] - x[0]
        layer = horizon_layer(params, dx, FIT_POINTS + m, 1)
        flags = boundary_layer_warnings(scene, x, FIT_POINTS + m, layer) + point_force_order(self, scene, params)
        flags += held_rotation_warnings(scene, dx, nearest=0.0, delta=m * dx) if self.bending else []
        ends = ("free", "guided", "spring", "clamped", "pinned", "roller")
        flags += [] if self.bending else edge_layer_warnings(scene, x, ROD_EDGE, kinds=ends, layer=FIT_POINTS + m)
        # variant energy applies a couple as the operator's action on its kink: second order there
        flags += moment_rotation_warnings(scene) if self.bending and params["variant"] != "energy" else []
        if self.bending and params["variant"] == "energy":
            flags += couple_at_joint_warnings(scene, "rotation", COUPLE_AT_JOINT)
            flags += couple_warnings(scene, m, dx, horizon_layer(params, dx, m + 3, 1))
        if self.bending and params["variant"] == "paper":
            flags += paper_warnings(scene)
        return flags

    def _held(self, scene, params, disc):
        """:func:`.constraints.solve_with_holds` with the variant's couples on their kinks; where those leave the
        system singular to working precision (the kink's shear terms grow like (L/h)^2: a support that holds the
        rotation inside a slender beam), again with each support's couple on the two points around it, warned."""
        args = (scene, disc, lambda s: self.operator(plain_ends(s), params), self.unknowns)
        what = f"{self.name} ({params['variant']})"
        couples = self.couples(scene, params, disc)
        try:
            out = solve_with_holds(*args, what, couples)
        except SolveError as exc:
            if couples is None or "singular" not in str(exc):
                raise
        else:
            plain = [f"supports.{h.replace('inner_', 'inner[')}]" for h in out[1].pop("couples_on_two_points", [])]
            if plain:
                out[1].setdefault("warnings", []).append(
                    f"{', '.join(plain)}: its couple could not be applied on its kink (no ramp fits in the beam, or "
                    "the kink's rows do not carry it to within their rounding at this slenderness), so it is on the "
                    "two points around the support: first order near it, as variant corrected"
                )
            return out
        held = [f"supports.inner[{i}]" for i, sup in enumerate(scene.supports.inner) if sup.type == "clamped"]
        out = solve_with_holds(*args, what, None)
        out[1].setdefault("warnings", []).append(
            f"{', '.join(held) or 'a support inside the span'}: its couple applied on its kink left the system "
            f"singular to working precision (slender beam: L/h = {scene.slenderness:.3g}), so it is applied "
            "on the two points around the support: first order near it, as variant corrected (2.9e-2, 1.5e-2, "
            "7.4e-3, 3.7e-3 at 101 ... 801 points, clamped-clamped with a clamp at 0.71 L under a uniform load)"
        )
        return out

    def couples(self, scene, params, disc):
        """a -> (rows, u_s) of a unit couple applied on its kink, or None (:mod:`.couples`; variant energy only)."""
        return None

    def end_reactions(self, scene, params, disc, u, loads, inner, kinks) -> tuple[dict, str]:  # pragma: no cover
        """{(side, key): value} of the rigid ends' reactions and where they come from (.constraints.reactions)."""
        raise NotImplementedError


def _statics_only(scene: Scene, model: str, what: str) -> None:
    """Supports inside the span, springs and segments are solved statically (one line otherwise)."""
    found = [k for k, on in (("supports.inner", scene.supports.inner), ("segments", scene.segments)) if on]
    if any(not isinstance(getattr(scene.supports, side), str) for side in ("left", "right")):
        found.append("an elastic end (spring)")
    if found:
        raise InputError(
            f"{', '.join(found)}: model {model} solves these statically only, not {what}; "
            + (
                "drop them for its frequencies (pdverify solve takes the scene statically)"
                if what == "natural frequencies"
                else "use -o analysis=static (or drop the [dynamics] table)"
            )
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
