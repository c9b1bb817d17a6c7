"""Model ``pd-eb``: ordinary state-based PD Euler–Bernoulli beam (Diyaroglu, Oterkus & Oterkus 2019).

One transverse DOF per material point, points x_k = k dx (ends included). The kernels (the curvature, the paper's
fictitious layers, the corrected variant's ghost points and the pieces of its mixed form) are in :mod:`.operator`.

Curvature (Eq. 11a) of point k with family j = 1..J on each side::

    kappa_k = d Σ_j (w_{k+j} + w_{k-j} - 2 w_k) V_j / xi_j²  =  Σ_j c_j (w_{k+j} + w_{k-j} - 2 w_k)

strain energy density W_k = a kappa_k² / 2 (Eq. 10a) with a = EI/A (Eq. 33); the force densities of
Eq. 13–15 are the gradient of U = Σ_k W_k V_k (Eq. 2, 6), so the static equation is
``a D^T D w = b`` (paper, energy form) or ``a D (D w) = b`` (corrected, strong form), with
b = p/A per unit volume (Eq. 25) and point loads as b = P/(A dx) on the loaded point.

Variants
--------
``paper`` (as published): delta = (m + 0.015) dx, full volumes V = A dx, d = 1/(A delta) (Eq. 32);
clamped = support point fixed + mirror image of the real points (w_{-j} = w_j), simply supported =
support point fixed + negative mirror image (w_{-j} = -w_j), both eliminated by the master–slave
transformation U = T Û, K̂ = T^T K T (Eq. 39–42); free end = no fictitious points, the first point
uses the one-sided curvature of Eq. A1 with d1 = 1/(A dx) (A6), the p-th point (p = 1..m-1) the reduced
horizon delta_p = (p + 0.015) dx with d_p = 1/(A delta_p) (A7–A12). Point moments enter as
b = -dm/dx (Eq. 25): a force couple on the two neighbouring points.

The horizon factor: ``--horizon 3`` means the papers' delta = 3.015 dx in ``paper`` (the 0.015 keeps
the third neighbour inside despite round-off, and enters d as published); in ``corrected`` the
horizon is exactly m dx and the last member's partial volume is used.

``corrected``: three changes, each tested in tests/papers/diyaroglu/test_pd_eb.py.
1. d calibrated on the DISCRETE family: c_j = beta_j / (j² dx² Σ beta), so kappa is exact for any
   quadratic (the paper's continuous d makes kappa too small by m / (m + 0.015) and K by its square).
2. partial volume of the last member: beta_j = clip(m - (j - 1/2), 0, 1) (beta_3 = 1/2 for m = 3).
3. boundaries by Taylor ghost points (docs/design/formulas.md §1): a degree-4 polynomial satisfying the support's
   conditions (clamped w = w' = 0; pinned w = 0, EI w'' = M̄; free EI w'' = M̄, EI w''' = -V̄; guided
   w' = 0, EI w''' = -V̄) is fitted to the first four real points and evaluated at 2J ghosts per end;
   end loads enter through M̄, V̄ (not as body forces), the support point's equation is w = 0.
"""

from __future__ import annotations

import numpy as np

from ...core.contract import MAX_POINTS, NONLOCAL, Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer, merge_info
from ...core.scene import Distributed, PointMoment, Scene
from ...numerics.linalg import eliminate
from ...numerics.load_warnings import (
    boundary_layer_warnings,
    cell_average_warnings,
    couple_at_joint_warnings,
    edge_layer_warnings,
    horizon_layer,
    moment_rotation_warnings,
    slope_jump_warnings,
)
from ...numerics.loads import solve_without_support_couples, support_couples
from ...numerics.solvers import SOLVER, solve
from ...numerics.span_warnings import short_span_warnings
from ...theory.model_error import pair_factor
from ...theory.symbols import GRADIENT, Series, beam_series
from . import dynamics, mixed, outputs
from .operator import corrected_system, curvature_weights, paper_system
from .scenes import edge_loads, inner_layer_warnings, spreads


def mirror_scene(scene: Scene) -> Scene:
    """The mirror image x -> L - x of a straight scene: supports swapped, positions, spans, inner supports and
    segments reflected, couples and axial components reversed (a sine load sin(pi x / L) is its own image)."""
    L = scene.length
    loads = []
    for load in scene.loads:
        up = {}
        if hasattr(load, "position"):
            up["position"] = L - load.position
        if isinstance(load, PointMoment):
            up["value"] = -load.value
        if getattr(load, "axial", 0.0):
            up["axial"] = -load.axial
        if isinstance(load, Distributed):
            a, b = scene.span(load)
            up["start"], up["end"] = L - b, L - a
        loads.append(load.model_copy(update=up))
    inner = [s.model_copy(update={"position": L - s.position}) for s in scene.supports.inner]
    sup = scene.supports.model_copy(update={"left": scene.supports.right, "right": scene.supports.left, "inner": inner})
    segs = [g.model_copy(update={"start": L - g.end, "end": L - g.start}) for g in scene.segments[::-1]]
    return scene.model_copy(update={"supports": sup, "loads": loads, "segments": segs})


def paper_bias(m: float) -> str:
    """The warning of the paper variant ("" when its bonds fill the horizon): with d = 1/(A delta), delta =
    (m + 0.015) dx (Eq. 32), and J whole bonds of volume A dx in the family (the points within delta), the curvature
    of a quadratic is J dx / delta of its own, so the refined beam is too flexible by (delta / (J dx))^2 - 1:
    (1 + 0.015/m)^2 - 1 for a whole m, more where a ``horizon_length`` gives a fractional one (m = 15.99: J = 15
    bonds, 13.6 %)."""
    ratio = m + 0.015
    J = int(np.floor(ratio + 1e-12))
    bias = (ratio / J) ** 2 - 1.0
    if bias <= 1e-9:  # a horizon_length of whole spacings: the family's bonds fill it
        return ""
    return (
        f"variant = paper does not converge to the Euler-Bernoulli beam: d = 1/(A delta) with delta = "
        f"({m:g} + 0.015) dx (Eq. 32) over {J} whole bonds leaves the refined beam too flexible by "
        f"(delta / ({J} dx))^2 - 1 = {bias:.2%} (refined grids give deflections that much too large; the moment and "
        "shear do not converge either: on a uniformly loaded cantilever at horizon 3, M 1.5e-2, 7.5e-3, 5.6e-3 and V "
        "beside the clamp 3.3e-2, 3.7e-2, 3.8e-2 of their largest values off at 101, 401, 1601 points); use variant = "
        "corrected"
    )


# -- the model -------------------------------------------------------------------------------


# pd-eb (corrected), clamped-pinned 2 m beam, aluminium and steel segments joined at 0.8 m, a couple there: the
# deflection's largest error against exact-eb at 101, 201, 401 points (docs/models/diyaroglu.md)
COUPLE_AT_JOINT = "measured 3.0e-3, 1.5e-3, 7.7e-4 of max |w| at 101, 201, 401 points on a two-material beam"
# the moment and shear of a short span between two supports that hold w: c (h / a)² of their largest in the span,
# measured up to 1.31 (V) and 1.17 (M) where a support inside at the span's ends holds the rotation, 0.43 and 0.36
# where none does (a clamped end beside a pin inside among them; spans of 0.02 ... 0.08 L, on and off the grid, 101 ...
# 801 points: benchmarks/short_spans.py); spans inside an end's layer (2 J + 4 spacings) or under 4 spacings between
# two supports take the layer and straddle lines instead (up to 76 times this estimate there); load edges' shear:
# benchmarks/load_edges.py and slope_jumps.py
SHORT_SPAN = {"held": {"V": 1.5, "M": 1.2}, "pinned": {"V": 0.5, "M": 0.4}}
CELL_SHEAR, SLOPE_SHEAR = 1.2, 1.0  # the c of cell_average_warnings and of slope_jump_warnings
EDGE_ERRORS = (
    "errors of about 1e-2 there (w 1.1e-2 ... 5.8e-3 with the edge 0.3 ... 1.5 spacings from a free end; V 3.2e-2, "
    "1.9e-2, 9.9e-3, 7.8e-3 at 2.5, 3, 4, 5 spacings from a guided or free end, at any number of points)"
)


class PDEulerBernoulli(Model):
    name = "pd-eb"
    jump_rotation = (0.65, 0.45)  # inside, at an end: above the ratios of benchmarks/jump_rotation.py (docs/trust.md)
    # above benchmarks/end_loads.py's values (docs/trust.md): the moment's error near a point force sets it at every
    # held end (the deflection's alone: 1.3 at a clamp, 0.3 at a pin); the rotation's within it (at most 0.71)
    end_load_error = {"clamped": 1.8, "pinned": 1.8, "spring": 1.8, "rotational spring": 1.8, "rotation": 1.0}
    end_load_error |= {"free": 0.25, "guided": 0.25}  # the line of a load nearer than 2.5 h (the ghosts' fit)
    dispersion = "curvature"  # its waves' frequencies (pdverify.theory.symbols)
    grid_checked = True  # its suite's sine loads 2.4e-3 off at 41 points with no other line (docs/trust.md)
    title = "ordinary state-based PD Euler–Bernoulli beam"
    source = "Diyaroglu et al. 2019, An Euler–Bernoulli beam formulation in an ordinary state-based PD framework"
    options = (
        Option("points", int, 101, "material points along the beam, ends included", minimum=5, maximum=MAX_POINTS),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing (3 = the paper's 3.015 dx)", minimum=1.0),
        Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
        Option(
            "form",
            str,
            "auto",
            "auto (mixed for corrected, direct for paper) | direct (one fourth-order system) | "
            "mixed (two second-order equations: round-off floor ~N^2 eps instead of ~N^4 eps; corrected only)",
            choices=("auto", "direct", "mixed"),
        ),
        Option(
            "reading",
            str,
            "energy",
            "paper variant's boundary reading: energy (the real points' energy with the "
            "mirror ghosts, Eq. 39-42 on it) | literal (Eq. 37 on the fictitious points too, then Eq. 42) | "
            "layer (literal, with the 2.015 dx fictitious layer and horizon at simply supported ends)",
            choices=("energy", "literal", "layer"),
        ),
        Option(
            "interface",
            str,
            "calibrated",
            "material interfaces ([[segments]]): calibrated (the points within a horizon of one take the flexibility "
            "that carries a uniform moment across it exactly: Diyaroglu et al.'s correction of d there) | point "
            "(each point its own segment's EI)",
            choices=("calibrated", "point"),
        ),
        *NONLOCAL,
        SOLVER,
        dynamics.ANALYSIS,
    )
    assembles = True
    analyses = frozenset({"static", "dynamic"})  # Eq. 3-7, 15 with the inertia rho w_tt (dynamics.py)
    modes = True
    eigenproblem, bench_dynamics = dynamics.eigenproblem, dynamics.bench  # (self, scene, params)
    springs = True
    inner_supports = True
    segments = True
    full_volumes = "paper"  # its sums take full volumes up to delta
    variant_rules = (
        Rule(
            (("variant", "paper"),),
            "horizon",
            "Eq. 32: delta = (m + 0.015) dx, d = 1/(A delta) over whole "
            "families of m points; use variant = corrected for a fractional horizon",
            whole=True,
            unless="horizon_length",  # Eq. 11a with a given delta: the points within it, d = 1/(A delta)
        ),
        Rule(
            (("variant", "paper"),),
            "form",
            "Eq. 13-15, 39-42: one fourth-order system; only the corrected variant has the two-equation (mixed) form",
            allowed=("auto", "direct"),
        ),
    )

    def gradient_coefficient(self, scene: Scene, params: dict) -> float:
        """1/18: the curvature's symbol s(z)^2 = 1 - z^2/18 + ... (docs/nonlocal.md)."""
        return GRADIENT["curvature"]

    def model_error_ends(self, scene: Scene, params: dict, delta: float) -> tuple[float, str]:
        """Measured per variant and support pair (:mod:`pdverify.theory.model_error`): the paper variant's clamped
        ends (the Appendix's mirror images about the clamped point) add a model error of the same order in delta."""
        return pair_factor(scene, f"pd-eb {self.with_defaults(params)['variant']}", delta)

    def horizon_offset(self, params: dict) -> float:
        """Eq. 32: delta = (m + 0.015) dx in the paper variant."""
        return 0.015 if params["variant"] == "paper" else 0.0

    def fixed_horizon_order(self, params: dict) -> tuple[float, str]:
        """First order in dx at a fixed delta, both variants: ``paper``'s sums give each bond a whole volume
        (Eq. 11a, 32); ``corrected`` normalises its weights c_j = beta_j / (j^2 dx^2 sum beta) by sum beta dx =
        (m - 1/2) dx, the trapezoidal rule of the horizon's integral without its node at xi = 0 (where the kernel's
        1/xi^2 has no value), so its nonlocal term is about 1 + 1/(2m) times the continuum's (docs/nonlocal.md)."""
        params = self.with_defaults(params)
        if params["variant"] == "paper":
            return super().fixed_horizon_order(params)
        return 1.0, "its weights are normalised by sum beta dx = (m - 1/2) dx (the horizon without xi = 0): first order"

    def continuum_series(self, scene: Scene, params: dict) -> Series | None:
        """The paper variant's energy reading closes pinned (roller) ends by negative and guided ends by positive
        mirror images (Eq. 39-41): a series of the mirror modes with the continuous curvature symbol."""
        if params["variant"] == "paper" and params.get("reading", "energy") == "energy":
            return beam_series(scene, self.delta(scene, params), "curvature")
        return None

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        return np.linspace(0.0, scene.length, params["points"])

    def assemble_full(self, scene: Scene, params: dict):
        """(K, b, fixed, info): K w = b on all real points (per unit volume), K a
        :class:`~pdverify.numerics.band.Band`; the points ``fixed`` are held at w = 0 (unit rows, ``Band.fix``)."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        m, variant = params["horizon"], params["variant"]
        c = curvature_weights(m, dx, variant)
        J = len(c)
        if 2 * J + 1 > n:
            raise InputError(
                f"horizon = {m:g}: the family ({J} points each side) does not fit in {n} points; "
                "use more points or a smaller horizon"
            )
        a = scene.EI / scene.section.A
        A = scene.section.A
        if variant == "paper":
            K, b, fixed, info = paper_system(scene, x, c, a, A, params.get("reading", "energy"))
        else:
            st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])
            K, b, fixed, info = corrected_system(
                scene, x, c, a, A, lambda skip: mixed.point_load_terms(scene, n, dx, st, skip)
            )
        K.fix(fixed, b)  # master–slave elimination of the supported points (Eq. 39–42): w = 0 there
        return K, b, fixed, info

    @staticmethod
    def form(params: dict) -> str:
        f = params.get("form", "auto")
        return ("mixed" if params["variant"] == "corrected" else "direct") if f == "auto" else f

    def assemble_mixed(self, scene: Scene, params: dict) -> System:
        """The corrected operator split in two second-order equations (``form = mixed``, :mod:`.mixed`)::

            EI0 f k - h² D1 (E w + e0) = (couples' curvature)    (on the real points and J ghosts each side)
            h² D2 k                   = h⁴ q / EI0               (k = h² M / EI0, the moment)

        the same discrete solution as a D2 D1 (E w + e0) = b on a uniform beam, but the matrix of fourth differences
        (entries ~1/h⁴) is never formed, which lowers the round-off floor (tests/verification/test_hard_cases.py).

        Assembled straight into LAPACK's band layout (:class:`~pdverify.numerics.band.Band`): positions
        p = -J .. n-1+J, two unknowns each (k_p, w_p), interleaved; both equations are Toeplitz block stencils
        (f: the flexibility, 1 on a uniform beam), the ghost map adds a few entries at each end, and the w of
        positions outside the beam and of the supported points are held at zero (unit rows): w of real point i is
        unknown 2 (i + J) + 1. With springs or supports inside the span their reactions are further unknowns after
        the band's (:func:`.mixed.system`: a sparse matrix)."""
        lay = self.layout(scene, params)
        aug = mixed.system(lay)
        held = lay.held
        free = np.r_[np.delete(np.arange(aug.n_band), held), aug.n_band + np.arange(len(aug.unknowns))]
        return System(
            aug.matrix,
            aug.rhs,
            free,
            {
                "ghosts_per_end": 2 * lay.J,
                "form": "mixed (two second-order equations)",
                "boundary": "Taylor ghost points (degree 4, 4 real points)",
            },
        )

    def layout(self, scene: Scene, params: dict) -> mixed.Layout:
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        c = curvature_weights(params["horizon"], dx, "corrected")
        if 2 * len(c) + 1 > n:
            raise InputError(
                f"horizon = {params['horizon']:g}: the family ({len(c)} points each side) does not fit in "
                f"{n} points; use more points or a smaller horizon"
            )
        return mixed.layout(scene, n, dx, c, params.get("interface", "calibrated") == "calibrated")

    def reduced(self, K, b, fixed):
        """Master–slave elimination of the fixed points (w = 0): the rows/columns of the free points."""
        return eliminate(K, b, fixed)

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """A family that does not fit in the points (:meth:`assemble_full`, :meth:`layout`), before any work."""
        dx = self.spacing(scene, params)
        variant = "corrected" if self.form(params) == "mixed" else params["variant"]
        return self.family_problems(scene, params, lambda k: len(curvature_weights(k, dx, variant)))

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """:meth:`refuse`'s line, as a list."""
        try:
            self.refuse(scene, params)
        except InputError as exc:
            return list(exc.lines)
        return []

    def refuse(self, scene: Scene, params: dict) -> None:
        """InputError (one line) for what the chosen variant and form do not define."""
        if params.get("reading", "energy") != "energy" and params["variant"] != "paper":
            raise InputError(
                f"reading = {params['reading']!r}: a reading of the paper's boundary treatment "
                "(Eq. 37-42); use variant = paper or reading = energy"
            )
        if self.form(params) == "mixed" and params["variant"] != "corrected":
            raise InputError(
                "form = 'mixed': only the corrected variant has the two-equation form; "
                "use variant = corrected or form = direct"
            )
        extra = [k for k, on in (("springs", not scene.supports.simple), ("segments", bool(scene.segments))) if on]
        if extra and (params["variant"] == "paper" or self.form(params) == "direct"):
            what = "variant = paper (the paper's equations hold a beam at its ends only, one section)"
            if params["variant"] != "paper":
                what = "form = direct"
            raise InputError(
                f"{what}: pd-eb takes supports inside the span, springs and segments in the corrected variant's "
                "mixed form only; use variant = corrected, form = auto"
            )

    def assemble(self, scene: Scene, params: dict) -> System:
        """The system ``solve`` factorises: ``form = mixed`` the system of :meth:`assemble_mixed` (free: its
        unknowns not held), else the band of :meth:`assemble_full` with the supported points held at
        w = 0 (unit rows; free: the unknown points). ``System.reduced()`` gives the master–slave
        eliminated system of Eq. 39–42."""
        self.refuse(scene, params)
        if self.form(params) == "mixed":
            return self.assemble_mixed(scene, params)
        K, b, fixed, info = self.assemble_full(scene, params)
        return System(K, b, np.delete(np.arange(params["points"]), fixed), info)

    def discretisation_warnings(self, scene: Scene, params: dict, x: np.ndarray) -> list[str]:
        """The warnings of the space discretisation (the operator and the load vector on the points ``x``): loads and
        supports inside the ends' layer, point forces near a support that holds the rotation, load edges in the
        fitted ghosts' reach, the paper variant's rotation near a point moment and its bias. A static solve and a
        transient share them (:mod:`.dynamics` integrates the same operator and loads); the recovered moment and
        shear's own warnings are the static solve's (:func:`.outputs.recovery_warnings`)."""
        dx = x[1] - x[0]
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        J = len(curvature_weights(params["horizon"], dx, params["variant"]))
        reach = 2 * J + 4
        exact = [f"loads[{i}] from" for i, ld in enumerate(scene.loads) if spreads(ld, scene, len(x), dx, J)]
        if params["variant"] == "paper":
            exact = []  # Eq. 25: the paper's loads are not spread by their kinks
        layer = boundary_layer_warnings(scene, x, reach, horizon_layer(params, dx, reach, 2))
        flags = [f for f in layer if not any(f.startswith(e) for e in exact)]
        flags += inner_layer_warnings(scene, x, reach, delta)
        if params["variant"] != "paper":  # its Taylor ghosts at free, guided and spring ends (docs/models/diyaroglu.md)
            flags += edge_layer_warnings(scene, x, EDGE_ERRORS)
        if params["variant"] == "paper":  # the corrected variant takes a couple by its kink: second order there
            flags += moment_rotation_warnings(scene) + [b for b in [paper_bias(params["horizon"])] if b]
        else:  # but not on a segment joint
            flags += couple_at_joint_warnings(scene, "deflection", COUPLE_AT_JOINT)
        if params.get("interface") == "point" and len(scene.segments) > 1:
            flags.append(
                "interface = point: each point takes its own segment's EI, so a segment joint is seen from one side: "
                "first order there (the interface on a grid point of docs/models/diyaroglu.md's cantilever: w "
                "2.2e-4, 1.1e-4, 5.4e-5 off exact-eb at 81, 161, 321 points, where calibrated is second order), and "
                "the scene's mirror image differs by as much; use interface = calibrated"
            )
        return flags

    def solve(self, scene: Scene, params: dict) -> Result:
        if dynamics.dynamic(scene, params):
            return dynamics.transient(self, scene, params)
        if params["variant"] == "paper" and support_couples(scene)[0]:  # Eq. 25's split couple bends the first spacing
            return solve_without_support_couples(self.solve, scene, params, "M")
        timer = Timer()
        self.refuse(scene, params)
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        if self.form(params) == "mixed":
            # the banded LU eliminates from the left end: a guided end there amplifies round-off by orders of
            # magnitude on fine grids, so such a scene is solved as its mirror image and flipped back
            flip = scene.supports.left == "guided" and scene.supports.right != "guided"
            with timer("assemble"):
                sc = mirror_scene(scene) if flip else scene
                lay = self.layout(sc, params)
                aug = mixed.system(lay)
            with timer("solve"):
                z, info = solve(aug.matrix, aug.rhs, "pd-eb (corrected, mixed form)", params["solver"])
                w, M, multipliers = mixed.unpack(lay, aug, z)
            if flip:
                w, M, multipliers = w[::-1].copy(), M[::-1].copy(), outputs.mirror_reactions(multipliers)
            ndofs = aug.matrix.shape[0] - len(lay.held)
            binfo = {
                "ghosts_per_end": 2 * lay.J,
                "form": "mixed (two second-order equations)",
                "boundary": "Taylor ghost points (degree 4, 4 real points)",
            }
        else:
            with timer("assemble"):
                system = self.assemble(scene, params)
            with timer("solve"):
                w, info = solve(system.matrix, system.rhs, f"pd-eb ({params['variant']})", params["solver"])
            ndofs, binfo, multipliers = system.unknowns, system.info, None
            c = curvature_weights(params["horizon"], dx, params["variant"])
            M = outputs.direct_moment(scene, w, dx, c, params["variant"], params.get("reading", "energy"))
        out = outputs.fields(scene, x, w, M, ends_inside=params["variant"] != "paper")
        if multipliers is not None:
            info["reactions"] = outputs.reactions(scene, x, out["M"], out["V"], multipliers)
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        merge_info(info, binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        flags = self.discretisation_warnings(scene, params, x) + outputs.recovery_warnings(scene, params)
        if params["variant"] != "paper":  # the paper's equations take no supports inside
            J = len(curvature_weights(params["horizon"], dx, params["variant"]))  # the ends' layer: 2 J + 4
            fixed, (cells, layer) = params.get("horizon_length") is not None, edge_loads(scene, len(x), dx, J)
            flags += short_span_warnings(scene, x, out, delta, SHORT_SPAN, (2 * J + 4, 4), fixed, inside_only=True)
            flags += cell_average_warnings(scene, x, out["V"], cells, CELL_SHEAR, layer, params)
            flags += slope_jump_warnings(scene, x, out["V"], cells, SLOPE_SHEAR)
        if flags:
            info.setdefault("warnings", []).extend(flags)
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=out.pop("rotation"),
            fields=out,
            dofs=ndofs,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDEulerBernoulli()]
