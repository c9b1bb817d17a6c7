"""Model ``pd-bond-pair``: non-ordinary state-based bond-pair beam (O'Grady & Foster 2014).

Every bond xi from a point is paired with its opposite -xi through a rotational spring with potential
``w(xi) = omega(xi) alpha [1 + cos theta]`` (Eq. 1; theta = deformed angle between the two bonds; the force
state of Eq. 2 is its gradient). For small deflections 1 + cos theta ≈ Δ²/2 with
Δ = (w_{k+j} - 2 w_k + w_{k-j}) / xi_j, so the bending energy per point is
Σ_j ½ alpha omega_j beta_j dx (Δ_j)² dx and its gradient per unit length is (docs/design/formulas.md §1)::

    Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j}) = q_k,   c_j = alpha omega_j beta_j dx / xi_j²

(= EI w'''' + O(delta²) w^(6)). alpha from energy equivalence with Euler–Bernoulli bending under uniform
curvature (Eq. 5 and §3.1; :mod:`.calibration`): ``paper`` the discrete family sum over the whole nodes within
delta (§3.1), ``corrected`` the same sum over the cells' parts inside delta, ``continuous-alpha`` the continuous
integral 3 EI / delta³ (a reconstruction, not the paper).

The stencil reaches 2J points past an end. Ends (``ends`` option):
``mirror`` (the energy form: clamped = reflection of the real points through the normal to the clamp,
pinned = point reflection through the support, guided = reflection through the support's vertical,
free = cubic extrapolation, end points' energy halved; the linear path is the tangent stiffness of that
energy at the undeformed state, the nonlinear path its Newton solution) or ``taylor`` (the degree-4
polynomial ghost points of :func:`pdverify.numerics.ghosts.taylor_ghosts`, end loads through the moment and shear
at the end; solved in the mixed form of :func:`.taylor.assemble_mixed` by default).
"""

# long module: the model class dispatches its five paths (Taylor and mirror ends, pair form, nonlinear, load path)

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.contract import LOAD_TYPES, MAX_POINTS, NONLOCAL, Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer, merge_info
from ...core.scene import Scene
from ...core.text import spacings
from ...numerics.linalg import forward_error_bound, record_bound, solve_linear
from ...numerics.load_warnings import (
    boundary_layer_warnings,
    couple_deflection_warnings,
    edge_layer_warnings,
    horizon_layer,
)
from ...numerics.loads import solve_without_support_couples, support_couples
from ...numerics.solvers import SOLVER, solve
from ...theory.model_error import pair_factor
from ...theory.symbols import GRADIENT, Series, beam_series
from . import dynamics
from .bias import bias_warnings
from .calibration import VARIANTS, alpha, horizon_length, pair_family, spring_constants
from .general import first_order_warnings, linear_system, off_grid_holds, scene_pairs, solve_pairs_linear
from .limit import no_limit_reason
from .nonlinear import NonlinearBondPair
from .path import failure_warnings, follows_path, plastic_warnings, solve_path
from .recovery import (
    inner_forces,
    mirror_pairs,
    mixed_fields,
    pair_fields,
    rotation,
    rotation_warnings,
)
from .taylor import assemble_mixed, assemble_taylor, factored_stencils, operator_stencil
from .weights import WEIGHTS, check_section, moment_curvature_curve, weights

ENDS = ("auto", "taylor", "mirror", "none")

FORM_HELP = "taylor ends: auto (= mixed) | direct (one fourth-order system) | mixed (curvature and deflection)"


# measured on a clamped-free and -guided beam, L/h = 100, 101 points, Taylor ends (docs/models/ogrady.md)
EDGE_ERRORS = (
    "errors of about 1e-2 there (2.7e-2 ... 1.3e-2 at 0.3 ... 1.5 spacings from a free end; w and V 1e-2, 5e-3, 1e-3 "
    "at 3, 4, 5 spacings from a guided end, 1.4e-3 ... 9e-4 at 6 ... 9, at any number of points)"
)
EDGE_LAYER = 10  # spacings: the Taylor ends' fit reaches farther than pd-eb's (9e-4 with the edge 9 spacings in)


def resolved_ends(scene: Scene, params: dict) -> dict:
    """``params`` with ``ends = auto`` made concrete: mirror for the nonlinear path and for scenes that need the pair
    form (supports inside the span, springs, segments), taylor otherwise."""
    if params["ends"] != "auto":
        return params
    return dict(params, ends="mirror" if params["nonlinear"] or needs_pairs(scene) else "taylor")


def needs_pairs(scene: Scene) -> bool:
    """True when only the pair form represents ``scene``: supports inside the span, springs, segments, prescribed
    deflections, a load path or a material that yields or breaks."""
    displaced = any(ld.type == "displacement" for ld in scene.loads)
    return not scene.supports.simple or bool(scene.segments) or displaced or follows_path(scene)


PAIR_FORM_M = 32  # the finest m of a continuum on the pair form (continuum_limit)


def pair_form(scene: Scene, params: dict) -> bool:
    """True when ``scene`` is solved on the pair form (:mod:`.general`): ``ends = none``, or a scene with supports
    inside the span, springs or segments (refused with Taylor ends, in one line)."""
    general = needs_pairs(scene)
    if general and params["ends"] == "taylor":
        what = (
            "supports inside the span"
            if scene.supports.inner
            else "springs"
            if not scene.supports.simple
            else "segments"
            if scene.segments
            else "a load path or prescribed deflections"
        )
        raise InputError(
            f"{what}: ends = taylor solves one elastic section between end supports under loads only; give "
            "-o ends=mirror (or auto, or none)"
        )
    if params["ends"] == "none":
        for side in ("left", "right"):
            end = getattr(scene.supports, side)
            if getattr(end, "rotational_stiffness", None):  # an elastic end that holds a rotation: as a clamp
                raise InputError(
                    f"supports.{side}.rotational_stiffness = {end.rotational_stiffness:g}: ends = none has no points "
                    "outside the beam to hold a rotation (O'Grady & Foster 2014, §3.2), so a rotational spring acts "
                    "on a one-sided slope only (two such ends under a uniform load: w 62 % off at 81 points, 20 % at "
                    "321); give -o ends=mirror"
                )
            if scene.supports.kind(side) in ("clamped", "guided"):
                raise InputError(
                    f"supports.{side} = {scene.supports.kind(side)}: ends = none has no points outside the beam to "
                    "hold a rotation (O'Grady & Foster 2014, §3.2: clamps 'require careful treatment'); give "
                    "-o ends=mirror"
                )
    if (general or params["ends"] == "none") and scene.has_axial_loads:
        i = next(i for i, ld in enumerate(scene.loads) if getattr(ld, "axial", 0.0))
        raise InputError(
            f"loads[{i}].axial = {scene.loads[i].axial!r}: the pair form (supports inside the span, springs, "
            "segments, ends = none) carries the deflection only; drop the axial component"
        )
    return general or params["ends"] == "none" or (params["weight"] != "uniform" and params["ends"] == "mirror")


def check_weight(scene: Scene, params: dict) -> None:
    """InputError when ``params["weight"]`` cannot be made on ``scene``: segments (one section along the beam) or a
    section :func:`.weights.check_section` refuses."""
    if params["weight"] != "uniform" and scene.segments:
        raise InputError(
            f"weight = {params['weight']}: a section weight takes one section along the beam; use weight = uniform "
            "with segments"
        )
    check_section(scene.section.profile, params["weight"])


def omega(scene: Scene, params: dict):
    """The members' weights of ``params["weight"]`` (None for uniform; :mod:`.weights`)."""
    if params["weight"] == "uniform":
        return None
    check_weight(scene, params)
    dx = scene.length / (params["points"] - 1)
    return weights(scene.section.profile, params["weight"], params["horizon"], dx, params["variant"])


__all__ = ["MODELS", "PDBondPair", "factored_stencils", "operator_stencil", "pair_family", "spring_constants"]


def end_layer_warnings(scene: Scene, params: dict, x: np.ndarray) -> list[str]:
    """:func:`~pdverify.numerics.load_warnings.boundary_layer_warnings` over the ends' layer of 4 J + 4 spacings (J the
    longest pair's offset in spacings: the pairs' reach past an end and the points a ghost rule is fitted on)."""
    dx = x[1] - x[0]
    reach = 4 * int(pair_family(params["horizon"], dx, params["variant"])[0].max()) + 4
    return boundary_layer_warnings(scene, x, reach, horizon_layer(params, dx, reach, 4))


def refine(model, K, b, free, u, sweeps: int = 3) -> tuple[np.ndarray, float]:
    """Iterative refinement of K u = b with the residual from the element forces
    (:meth:`NonlinearBondPair.apply_linear`): the assembled K's round-off grows like N^4 eps, the element
    residual's like N^2 eps, so two or three sweeps give the discrete solution the nonlinear path
    converges to (its first Newton iterate is this solve). Returns all 2n displacements and the round-off bound
    of :func:`element_bound`."""
    import scipy.sparse.linalg as spla

    lu = spla.splu(sp.csc_matrix(K))
    full = np.zeros(2 * model.n)
    full[free] = u
    for _ in range(sweeps):
        r = b - model.apply_linear(full)[free]
        du = lu.solve(r)
        full[free] += du
        if np.abs(du).max() <= 1e-14 * np.abs(full).max():
            break
    return full, element_bound(model, lu, b, free, full)


def element_bound(model, lu, b, free, full) -> float:
    """The round-off bound of a solution refined against the element residual (:func:`refine`), relative to the
    largest deflection (and, with axial loads, to the largest axial displacement, each field its own): Skeel's
    componentwise bound || |K^-1| (c eps g) ||, g the magnitude of the element forces meeting at each unknown
    (:meth:`NonlinearBondPair.linear_force_scale`, the terms the residual sums), plus the next correction K^-1 r
    (:func:`pdverify.numerics.linalg.forward_error_bound`). The fixed point of the refinement is the element
    residual's, so the assembled K's rounding (its fourth differences) is not part of it."""
    correction = lu.solve(b - model.apply_linear(full)[free])
    w = np.flatnonzero(free % 2 == 1)  # the deflections' places among the free unknowns (u, w per point, in order)
    fields = (w, np.flatnonzero(free % 2 == 0)) if model.scene.has_axial_loads else (w,)
    return forward_error_bound(
        lu.solve,
        lambda z: lu.solve(z, trans="T"),
        correction,
        model.linear_force_scale(full)[free],
        full[free],
        fields,
    )


# (jump_rotation, end_load_error) per variant and resolved ends, each above the ratios of benchmarks/jump_rotation.py
# and benchmarks/end_loads.py run with those options (docs/trust.md); mirror ends carry a larger error in the rotation
# at a clamped end, the paper variant beside a support inside and at a clamp; the rotation's end error up to 1.58 times
# the estimate for the defaults ("rotation"; the others' not measured)
ESTIMATES = {
    ("corrected", "taylor"): (
        (2.3, 0.62),
        {"clamped": 2.3, "pinned": 0.8, "spring": 0.8, "rotation": 2.0, "free": 0.35, "guided": 0.35},
    ),
    ("corrected", "mirror"): ((2.3, 3.9), {"clamped": 2.3, "pinned": 0.8, "spring": 0.8}),
    ("paper", "taylor"): ((3.3, 0.66), {"clamped": 2.5, "pinned": 0.8, "spring": 0.8}),
    ("paper", "mirror"): ((3.3, 5.0), {"clamped": 2.3, "pinned": 0.8, "spring": 0.8}),
}


# a point moment C inside the span: the pair form takes it as a force pair on the points around it, and w beside it is
# off by about c |C| h² / EI: measured c = 0.64 (a couple at mid-span, pinned-pinned or clamped-clamped) to 1.1 (a
# cantilever), up to 2.4 just outside an end's layer (20 spacings from a free end), over every variant, end treatment
# and horizons 3 and 5 (docs/models/ogrady.md; tests/verification/test_couple_deflection.py)
COUPLE_DEFLECTION = 2.5


class PDBondPair(Model):
    name = "pd-bond-pair"
    jump_rotation, end_load_error = ESTIMATES[("corrected", "taylor")]  # the defaults' (variant, ends = auto)
    dispersion = "bond-pair"  # its waves' frequencies (pdverify.theory.symbols)
    grid_checked = True  # its suite's sine loads 1.5e-3 off at 81 points with no other line (docs/trust.md)
    title = "non-ordinary state-based bond-pair PD beam (linear path)"
    source = (
        "O'Grady & Foster 2014, Peridynamic beams: a non-ordinary, state-based model (alpha calibration and ghost "
        "rules: docs/design/formulas.md §1)"
    )
    options = (
        Option("points", int, 201, "material points along the beam, ends included", minimum=5, maximum=MAX_POINTS),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing", minimum=1.0),
        Option(
            "variant",
            str,
            "corrected",
            "corrected (discrete alpha, the cells' parts inside delta) | paper (§3.1: discrete alpha over the whole "
            "nodes within delta) | continuous-alpha (3 EI / delta^3, a reconstruction, not the paper)",
            choices=VARIANTS,
        ),
        Option(
            "ends",
            str,
            "auto",
            "auto (taylor for end supports only, else mirror) | taylor (Taylor ghost points, strong form) | mirror "
            "(reflected ghosts, energy form) | none (no points outside the beam: the paper's §3.1)",
            choices=ENDS,
        ),
        Option(
            "form",
            str,
            "auto",
            "taylor ends: auto (= mixed) | direct (one fourth-order system) | mixed (curvature "
            "and deflection, two second-order equations: round-off ~N^2 eps instead of ~N^4 eps)",
            choices=("auto", "direct", "mixed"),
        ),
        Option(
            "weight",
            str,
            "uniform",
            "the pairs' weight omega: uniform (1) | paper (Eq. 6, |xi| b(y) at y = (xi / delta) t / 2) | fibre (b(y): "
            "the fibre theory's moment-curvature curve)",
            choices=WEIGHTS,
        ),
        Option("nonlinear", bool, False, "geometrically nonlinear path (Newton, load steps, mirror ghosts)"),
        Option("steps", int, 10, "load steps of the nonlinear path", minimum=1, maximum=100_000),
        *NONLOCAL,
        SOLVER,
        dynamics.ANALYSIS,
    )
    axial = True
    load_types = LOAD_TYPES | {"displacement"}
    materials = frozenset({"yield_stress", "failure_strain"})
    load_path = True
    springs = True
    inner_supports = True
    segments = True
    assembles = True
    analyses = frozenset({"static", "dynamic"})  # the PD equation of motion with rho A w_tt (dynamics.py)
    modes = True

    def gradient_coefficient(self, scene: Scene, params: dict) -> float:
        """1/10: the bond-pair symbol with omega = 1 (docs/nonlocal.md; O'Grady & Foster 2014, Appendix B)."""
        return GRADIENT["bond-pair"]

    def model_error_ends(self, scene: Scene, params: dict, delta: float) -> tuple[float, str]:
        """Measured per ends and support pair (:mod:`pdverify.theory.model_error`)."""
        ends = resolved_ends(scene, self.with_defaults(params))["ends"]
        return pair_factor(scene, f"pd-bond-pair {ends}", delta)

    def eigenproblem(self, scene: Scene, params: dict):
        return dynamics.eigenproblem(self, scene, resolved_ends(scene, params))

    def bench_dynamics(self, scene: Scene, params: dict, steps: int = 200) -> float:
        return dynamics.bench(self, scene, resolved_ends(scene, params), steps)

    full_volumes = "paper"  # its sums take full volumes up to delta
    nonlinear_when = (("nonlinear", True),)
    variant_rules = (
        Rule(
            (("variant", "continuous-alpha"),),
            "horizon",
            "a reconstruction, not O'Grady & Foster's calibration (docs/design/formulas.md §1): alpha = 3 EI / "
            "delta^3 with delta = (m + 0.015) dx over whole families of m points; use variant = paper or corrected "
            "for a fractional horizon",
            whole=True,
            unless="horizon_length",  # a given delta: the points within it, alpha = 3 EI / delta^3
        ),
        Rule(
            (("variant", "continuous-alpha"),),
            "ends",
            "the continuous alpha goes with the mirror (reflection) ghosts of Diyaroglu et al. 2019; Taylor ghosts "
            "carry the true EI (docs/design/formulas.md §1); use ends = mirror",
            allowed=("mirror",),
        ),
        Rule(
            (("variant", "continuous-alpha"),),
            "weight",
            "Eq. 5's continuous integral alpha = 3 EI / delta^3 is the one of omega = 1; use variant = paper or "
            "corrected for a section weight",
            allowed=("uniform",),
        ),
    )

    def estimate_constants(self, scene: Scene, params: dict) -> tuple[dict, tuple[float, float]]:
        """The constants of :data:`ESTIMATES` for the variant and the ends these options resolve to (none for
        continuous-alpha and for ends = none, not measured)."""
        p = resolved_ends(scene, self.with_defaults(params))
        jump, end_load = ESTIMATES.get((p["variant"], p["ends"]), ((0.0, 0.0), {}))
        return end_load, jump

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """The ends and loads the chosen ends do not take (:func:`pair_form`'s line) and a section weight the scene's
        sections do not define (:func:`check_weight`)."""
        try:
            pair_form(scene, params)
            check_weight(scene, params)
        except InputError as exc:
            return list(exc.lines)
        return []

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """A stencil that does not fit in the points (:func:`.taylor.assemble_taylor`, :func:`.taylor.assemble_mixed`:
        the linear path with Taylor ends), before any work. Mirror ends (the nonlinear path, the pair form's default)
        reflect the beam's own points, so a pair reaches at most points - 1 spacings past an end
        (:func:`.pairs.ghost_rows`); ``ends = none`` takes any horizon (the pairs past the ends are absent, §3.1)."""
        dx, n = self.spacing(scene, params), params["points"]

        def reach(k) -> int:  # the longest pair's offset in spacings at horizon k
            return int(pair_family(k, dx, params["variant"])[0].max(initial=0))

        def fits(k) -> bool:
            return reach(k) <= n - 1

        ends = resolved_ends(scene, params)["ends"]
        if ends == "mirror":
            what = f"its mirror ghosts reflect the beam's {n} points, so a pair reaches at most {spacings(n - 1, 'g')}"
            return [] if fits(params["horizon"]) else [self.horizon_refusal(scene, params, what, fits)]
        if ends != "taylor" or params["nonlinear"] or needs_pairs(scene):
            return []
        return self.family_problems(scene, params, reach, stencil=True)

    def horizon_offset(self, params: dict) -> float:
        """delta = (m + 0.015) dx with the continuous alpha (as in the other papers)."""
        return 0.015 if params["variant"] == "continuous-alpha" else 0.0

    def fixed_horizon_order(self, params: dict) -> tuple[float, str]:
        """First order in dx at a fixed delta for ``paper`` (§3.1's family sum gives each node within delta a whole
        volume) and for ``continuous-alpha``, whose alpha = 3 EI / delta^3 (Eq. 5) is the integral its family sum
        reaches only as dx -> 0: stiffer by (m + 1)(2m + 1) / (2 m^2) = 1 + 3 / (2m) + ... (docs/nonlocal.md); else
        the model's."""
        params = self.with_defaults(params)
        if params["variant"] == "continuous-alpha":
            return 1.0, "alpha = 3 EI / delta^3 over a family sum stiffer by (m + 1)(2m + 1) / (2 m^2): first order"
        return super().fixed_horizon_order(params)

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """No limit at fixed delta where a single point carries a force, or at free and guided Taylor ends
        (:func:`.limit.no_limit_reason`); the continuum is then the grid at ``continuum_m``, at most
        :data:`PAIR_FORM_M` on the pair form (supports inside, springs, segments, prescribed deflections), whose
        unknowns and bandwidth both grow with m (m = 16, 32, 48 on 81 points at delta = 0.1 L: 1 s, 3 s and 30 s
        with 1.7 GB; 128 did not end)."""
        params = resolved_ends(scene, params)
        why = no_limit_reason(scene, params["ends"])
        if not why:
            return None
        top = int(params.get("continuum_m") or self.continuum_m)
        if pair_form(scene, params):
            if params.get("continuum_m") and top > PAIR_FORM_M:
                raise InputError(
                    f"continuum_m = {top}: pd-bond-pair's continuum on the pair form (supports inside, springs, "
                    f"segments, prescribed deflections) costs too much past m = {PAIR_FORM_M} (its unknowns and "
                    f"bandwidth both grow with m); give continuum_m <= {PAIR_FORM_M}"
                )
            top = min(top, PAIR_FORM_M)
        return why, top

    def continuum_series(self, scene: Scene, params: dict) -> Series | None:
        """Mirror ends (linear path): a series of the mirror modes with the continuous bond-pair symbol (omega = 1)."""
        if params["ends"] == "mirror" and not params["nonlinear"]:
            return beam_series(scene, self.delta(scene, params), "bond-pair")
        return None

    def energy_model(self, scene: Scene, params: dict):
        n = params["points"]
        dx = scene.length / (n - 1)
        j, beta = pair_family(params["horizon"], dx, params["variant"])
        return NonlinearBondPair(scene, n, j, beta, alpha(scene.EI, params["horizon"], dx, params["variant"]))

    def mirror_system(self, scene: Scene, params: dict):
        """(System, energy model) of mirror ends: the energy's tangent at rest reduced to the free DOFs, and the
        :class:`NonlinearBondPair` it comes from (whose element residual refines the solve)."""
        model = self.energy_model(scene, params)
        K = model.tangent(np.zeros(2 * model.n), 0.0)
        free = model.free
        b = -model.gradient(np.zeros(2 * model.n), 1.0)  # dead loads and the couples' forces at rest
        info = {"ghosts_per_end": model.G, "form": "energy tangent"}
        return System(K[free][:, free].tocsr(), b[free], free, info), model

    def assemble(self, scene: Scene, params: dict) -> System:
        """The linear system ``solve`` factorises.

        ``ends = mirror``: the tangent stiffness of the full energy at the undeformed state (u and w per
        point, forces), i.e. exactly the linearisation of the nonlinear path, reduced to the free DOFs (CSR).
        ``ends = taylor``: ``form = mixed`` (default) the two second-order equations of
        :func:`.taylor.assemble_mixed`; ``form = direct`` the strong-form operator on w of
        :func:`.taylor.assemble_taylor`, supported points held."""
        if not self.linear(params):
            raise InputError("nonlinear = true: the nonlinear path solves no single linear system")
        params = resolved_ends(scene, params)
        if pair_form(scene, params):
            K, rhs, elim, _ = linear_system(scene, params, omega(scene, params))
            free = np.setdiff1d(np.arange(params["points"]), elim.dep)
            return System(K, rhs, free, {"form": "pair form (supports, springs, segments)", "ends": params["ends"]})
        if params["ends"] == "mirror":
            return self.mirror_system(scene, params)[0]
        dx = scene.length / (params["points"] - 1)
        j, _ = pair_family(params["horizon"], dx, params["variant"])
        c = spring_constants(scene.EI, params["horizon"], dx, params["variant"], omega(scene, params))
        if params.get("form", "auto") in ("auto", "mixed"):
            return assemble_mixed(scene, params, c, j)
        K, b, fixed, info = assemble_taylor(scene, params, c, j)
        return System(K, b, np.delete(np.arange(params["points"]), fixed), info)

    def solve_pairs(self, scene: Scene, params: dict) -> Result:
        """The linear pair form (:mod:`.general`)."""
        timer = Timer()
        with timer("solve"):
            x, w, pairs, f, info = solve_pairs_linear(scene, params, omega(scene, params))
        dx = x[1] - x[0]
        if off := off_grid_holds(scene, dx):  # the error does not fall regularly: no Richardson estimate from it
            info["irregular"] = off[0]
        flags = self.discretisation_warnings(scene, params, x)  # mirror ends: no Taylor edge layer
        flags += self.couple_lines(scene, params, x, w)
        if flags:
            info.setdefault("warnings", []).extend(flags)
        info.update(
            form="pair form (supports, springs, segments)",
            ends=params["ends"],
            spacing=dx,
            horizon_factor=params["horizon"],
            horizon=horizon_length(params["horizon"], dx, params["variant"]),
        )
        mirror = params["ends"] == "mirror"
        fields = pair_fields(
            scene,
            pairs,
            f,
            mirror,
            g=info.pop("nodal_forces"),
            extra_couples=info.pop("reaction_couples"),
            reactions=inner_forces(scene, info["reactions"]),
        )
        if mirror:  # a clamped or guided end's couple is its mirror ghosts': the section moment there (statics)
            for side, M_end in (("left", -fields["moment"][0]), ("right", fields["moment"][-1])):
                if scene.supports.kind(side) in ("clamped", "guided"):
                    info["reactions"].setdefault(f"moment_{side}", float(M_end))
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=rotation(w, dx),
            fields=fields,
            dofs=len(x),
            timings=timer.timings,
            info=info,
        )

    def solve_load_path(self, scene: Scene, params: dict) -> Result:
        """A load path with pairs that yield or break (:mod:`.path`, Eq. 7 and 8): the last step's fields, every
        step in ``Result.path``."""
        pair_form(scene, params)  # the ends and loads the pair form takes (one line otherwise)
        timer = Timer()
        what = f"pd-bond-pair ({params['variant']}, {params['ends']} ends, load path)"
        with timer("solve"):
            pairs = scene_pairs(scene, params, omega(scene, params))
            w, f, path, info, _ = solve_path(scene, params, pairs, what)
        dx = pairs.dx
        x = np.arange(pairs.n) * dx
        info.setdefault("warnings", []).extend(
            first_order_warnings(scene, dx)
            + end_layer_warnings(scene, params, x)
            + plastic_warnings(scene, params, dx)
            + failure_warnings(scene, params, x, info, path[-1]["health"])
            + rotation_warnings(scene)
        )
        info.update(ends=params["ends"], spacing=dx, horizon_factor=params["horizon"])
        if scene.material.yield_stress:  # the section law the pairs carry (Eq. 7), beside the fibre theory's
            mat, m = scene.material, params["horizon"]
            info["moment_curvature"] = moment_curvature_curve(
                scene.section.profile, mat.E, mat.yield_stress, params["weight"], m, dx, params["variant"]
            )
        mirror = params["ends"] == "mirror"
        inner = inner_forces(scene, info["reactions"])
        fields = dict(pair_fields(scene, pairs, f, mirror, reactions=inner), health=path[-1]["health"])
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=rotation(w, dx),
            fields=fields,
            dofs=len(x),
            timings=timer.timings,
            info=info,
            path=path,
        )

    def axial_displacement(self, scene: Scene, params: dict) -> np.ndarray:
        """u of the axial bonds at rest (Taylor ends carry w only; at rest in a straight beam u and w decouple, so
        the axial block of the energy form's tangent gives u): the same axial discretisation as ``ends = mirror``."""
        model = self.energy_model(scene, params)
        zero = np.zeros(2 * model.n)
        K, b = model.tangent(zero, 0.0), -model.gradient(zero, 1.0)
        f = model.free[model.free % 2 == 0]
        u = np.zeros(2 * model.n)
        u[f], _ = solve_linear(K[f][:, f].tocsr(), b[f], what="pd-bond-pair axial bonds")
        return u[0::2]

    def solve_nonlinear(self, scene: Scene, params: dict) -> Result:
        if follows_path(scene) or any(ld.type == "displacement" for ld in scene.loads):
            raise InputError(
                "nonlinear = true: the large-rotation path takes elastic pairs under loads; drop nonlinear for "
                "[loading], yield_stress, failure_strain or displacement loads"
            )
        if params["weight"] != "uniform":
            raise InputError(
                f"weight = {params['weight']}: the large-rotation path weighs every pair alike; give -o weight=uniform "
                "with -o nonlinear=true"
            )
        if params["ends"] != "mirror":
            raise InputError(
                f"ends = {params['ends']}: the nonlinear path uses the reflection (mirror) ghosts of the energy "
                "form; give -o ends=mirror (or auto) with -o nonlinear=true"
            )
        if pair_form(scene, params):
            raise InputError(
                "nonlinear = true: the large-rotation path takes supports at the ends only, one section and one "
                "material; drop nonlinear for supports inside the span, springs or segments"
            )
        timer = Timer()
        dx = scene.length / (params["points"] - 1)
        with timer("assemble"):
            model = self.energy_model(scene, params)
        with timer("solve"):
            P, shots, iters = model.solve(steps=params["steps"])
        X0 = model.X0
        return self.new_result(
            scene,
            params,
            X0[:, 0],
            P[:, 1],
            fields={"u": P[:, 0]},
            dofs=len(model.free),
            timings=timer.timings,
            info={
                "load_steps": shots,
                "newton_iterations": iters,
                "ends": "mirror (nonlinear reflections)",
                "spacing": dx,
                "horizon_factor": params["horizon"],
            },
        )

    @staticmethod
    def couple_lines(scene: Scene, params: dict, x: np.ndarray, w: np.ndarray) -> list[str]:
        """The deflection beside the point moments inside the span (a static solution ``w``): COUPLE_DEFLECTION."""
        delta = horizon_length(params["horizon"], x[1] - x[0], params["variant"])
        return couple_deflection_warnings(scene, x, w, delta, COUPLE_DEFLECTION)

    def discretisation_warnings(self, scene: Scene, params: dict, x: np.ndarray) -> list[str]:
        """The warnings of the linear operator's space discretisation on the points ``x`` (ends resolved): supports
        held at first order, point loads inside the ends' layer, the rotation near a point moment or a free end, the
        variant's and the Taylor ends' biases, load edges in the fitted ghosts' reach. A static solve and a transient
        share them (:mod:`.dynamics` integrates the same operator and loads)."""
        flags = first_order_warnings(scene, x[1] - x[0]) + end_layer_warnings(scene, params, x)
        flags += rotation_warnings(scene) + bias_warnings(scene, params)
        if params["ends"] == "taylor":  # its Taylor ghosts at free and guided ends (docs/models/ogrady.md)
            flags += edge_layer_warnings(scene, x, EDGE_ERRORS, layer=EDGE_LAYER)
        return flags

    def solve(self, scene: Scene, params: dict) -> Result:
        params = resolved_ends(scene, params)
        if dynamics.dynamic(scene, params):
            return dynamics.transient(self, scene, params)
        if params["ends"] != "taylor" and support_couples(scene)[0]:  # force pairs would bend the first spacing
            return solve_without_support_couples(self.solve, scene, params, "moment")
        if params["nonlinear"]:
            return self.solve_nonlinear(scene, params)
        if follows_path(scene):
            return self.solve_load_path(scene, params)
        if pair_form(scene, params):
            return self.solve_pairs(scene, params)
        timer = Timer()
        what = f"pd-bond-pair ({params['variant']}, {params['ends']} ends)"
        x = np.linspace(0.0, scene.length, params["points"])
        fields = {}
        with timer("assemble"):
            mirror = params["ends"] == "mirror"
            system, model = self.mirror_system(scene, params) if mirror else (self.assemble(scene, params), None)
        binfo = dict(system.info)
        if params["ends"] == "mirror":
            with timer("solve"):
                # no bound of the assembled system (its fourth differences round like N^4 eps): the bound is the
                # element residual's, to which the refinement converges
                u, info = solve(system.matrix, system.rhs, what, params["solver"], bound=False)
                full, bound = refine(model, system.matrix, system.rhs, system.free, u)
                record_bound(info, bound)
            w, fields["u"] = full[1::2], full[0::2]
            dx = x[1] - x[0]
            pairs = mirror_pairs(scene.EI, params, len(x), dx, (scene.supports.left, scene.supports.right))
            fields.update(pair_fields(scene, pairs, pairs.moments(w), mirror=True))
        elif binfo.get("Jk") is not None:
            Jk = binfo.pop("Jk")
            with timer("solve"):
                # the condition number of the two-equation matrix grows like N^4 but is no bound on its
                # round-off (which stays far below cond eps), so it is not estimated; the round-off estimate
                # 0.1 eps N^2 holds the errors at 10^5-10^6 points, every support pair, mixed loads
                # (tests/papers/ogrady/test_bond_pair_large.py; docs/models/ogrady.md)
                z, info = solve(system.matrix, system.rhs, what + ", mixed form", params["solver"], condition=False)
                w = z[2 * Jk + 1 : 2 * (len(x) + Jk) : 2].copy()
            dx = x[1] - x[0]
            j, _ = pair_family(params["horizon"], dx, params["variant"])
            c = spring_constants(scene.EI, params["horizon"], dx, params["variant"], omega(scene, params))
            r, _ = factored_stencils(j, c, scene.EI, dx)
            fields.update(mixed_fields(scene, r, z[0::2], len(x), Jk, dx))
            info["roundoff_estimate"] = roundoff = 0.1 * np.finfo(float).eps * len(x) ** 2
            if roundoff > 1e-6:
                info.setdefault("warnings", []).append(
                    f"round-off estimate {roundoff:.1g} relative (0.1 eps N^2, N = {len(x)} points; measured 0.01-1 "
                    "of it): past 1e-6; use fewer points"
                )
        else:
            with timer("solve"):
                w, info = solve(system.matrix, system.rhs, what, params["solver"])
        if params["ends"] == "taylor" and scene.has_axial_loads:
            with timer("solve"):
                fields["u"] = self.axial_displacement(scene, params)
        dx = x[1] - x[0]
        flags = self.discretisation_warnings(scene, params, x)
        flags += self.couple_lines(scene, params, x, w)
        if flags:
            info.setdefault("warnings", []).extend(flags)
        merge_info(
            info,
            binfo,
            spacing=dx,
            horizon_factor=params["horizon"],
            horizon=horizon_length(params["horizon"], dx, params["variant"]),
        )
        return self.new_result(
            scene,
            params,
            x,
            w,
            fields=fields,
            rotation=rotation(w, dx),
            dofs=system.unknowns,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDBondPair()]
