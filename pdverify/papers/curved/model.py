"""Model ``pd-curved``: planar curved Timoshenko–Ehrenfest beam by PDDO collocation (Curved PDDO beam 2024).

The paper's printed equations are not available to pdverify; docs/design/formulas.md §2–3 writes them out, and
they are re-derived here from virtual work (the signs below are checked: the virtual-work identity, the
straight-beam limit against ``exact-timoshenko`` and the closed-form semicircle of :mod:`pdverify.exact.curved`).

Axis r(s) (arc length s), tangent t, normal n = e_z × t, curvature κ (t' = κ n, n' = -κ t).
Unknowns per particle: u_t, u_n (u = u_t t + u_n n) and the section rotation φ (counter-clockwise).

* strains (Eq. 3):             ε = u_t' - κ u_n,   γ = u_n' + κ u_t - φ,   χ = φ'
* resultants (Eq. 4):          N = EA ε,   Q = kGA γ,   M = EI χ
* equilibrium (Eq. 8–10):      N' - κ Q + p_t = 0,   Q' + κ N + p_n = 0,   M' + Q + m = 0
* boundary (Eq. 11–13):        at s = L either u_t, u_n, φ given or N = F·t, Q = F·n, M = C̄;
                               at s = 0 the same with a minus sign.

For a straight beam Q = kGA(w' - φ) = -dM/dx: ``exact-timoshenko``'s V is -Q (Result.fields["V"]).

Collocation (Eq. 27–35): three equations per particle, every derivative replaced by PDDO functions of
degree P (:mod:`pdverify.papers.curved.pddo`), families of 2 m + 1 particles (m = ``horizon``, default
⌊P/2⌋ + 1, i.e. P + 3 members for even P, P + 2 for odd P, mixed form at even P >= 6: P + 1; see
:func:`default_horizon`), shifted inward
at the ends. Two forms:

* ``primal`` (the paper, Eq. 14–16): constitutive law substituted, second derivatives by g²:
  ``EA(u_t'' - κ' u_n - κ u_n') - κ kGA(u_n' + κ u_t - φ) + p_t = 0`` etc.;
* ``mixed`` (beyond the paper): first-derivative functions only, applied twice: N = EA(D1 u_t - κ u_n),
  then D1 N - κ Q + p_t = 0, ... With ``unknowns = resultants`` (default) N, Q, M are unknowns of their
  own (six per particle: the constitutive rows ε(u) - N/EA = 0, γ(u) - Q/kGA = 0, χ(u) - M/EI = 0 at every
  particle plus the equilibrium rows). The discrete solution is the same as with them substituted
  (``unknowns = displacements``, three per particle), but the condition number no longer grows like
  (L/h)², which keeps slender beams clear of round-off (docs/models/curved.md, Known limits).

At each end particle the three boundary equations replace the three equilibrium equations (slot t
takes u_t or N, slot n takes u_n or Q, slot φ takes φ or M): clamped u_t = u_n = φ = 0; pinned
u_t = u_n = 0, M = ±C̄; roller u_n = 0, N, M = ±(F·t, C̄); free N, Q, M = ±(F·t, F·n, C̄); guided φ = 0,
N, Q = ±(F·t, F·n) (docs/supports.md).

Particles are uniform by default; ``grading`` (largest / smallest spacing, ``graded_by`` curvature or ends) or
``positions`` (arc lengths) place them non-uniformly (the paper: "not limited to uniform distributions of material
particles"), the families keep 2m + 1 members, so each particle's horizon follows its spacing.

Point loads inside the beam and the ends of a distributed load's span split the axis into segments
(each with its own particles and families; a PDDO function never reaches across a load
discontinuity). At an interface the two coincident particles carry continuity of u_t, u_n, φ and the
jumps N⁺ - N⁻ = -F·t, Q⁺ - Q⁻ = -F·n, M⁺ - M⁻ = -C (a counter-clockwise couple C). Distributed loads are
collocated point-wise (value along n, axial along t; ``frame = global``: (axial, value) = global
(x, y) components per unit arc length; ``sine``: times sin(π s / L)). Every equation row is divided
by its largest coefficient, the non-symmetric system is solved by LU (``solve_linear``; unknowns
interleaved per particle, so it is banded) and its condition number reported. The default form is
written straight into a :class:`~pdverify.numerics.band.Band` (6 x 6 block stencils, one diagonal per family
offset; :meth:`PDCurved.assemble_band`), which ``solve_linear`` factorises in place above 20,000 unknowns;
``assemble`` returns the same band as CSR.

Four modules, one idea each: the particles (axis frame, segments, uniform / graded / given distributions,
family size, loads at the particles: :mod:`pdverify.papers.curved.particles`), the collocation system
(:mod:`pdverify.papers.curved.assembly`), the output map and the round-off of the weights and of superposed solves
(:mod:`pdverify.papers.curved.outputs`), and here the model: its options and the superposed solves. PDDO
functions: :mod:`pdverify.papers.curved.pddo`. Errors, orders, locking and cost: docs/models/curved.md.
"""

from __future__ import annotations

import numpy as np

from ...core.contract import MAX_POINTS, NONLOCAL, Model, Option, System
from ...core.errors import InputError
from ...core.geometry import geometry, mechanism_message
from ...core.result import Result, Timer, merge_info
from ...core.scene import Scene
from ...numerics.band import Band
from ...numerics.linalg import BOUND_LIMIT, bound_warning, solve_linear
from ...numerics.loads import axis_support_side, force_components
from ...theory.curved_beam import coupling_warning, thick_ring_warning
from .assembly import assemble_displacements, assemble_resultants
from .outputs import output_map, superposed_bound, weight_rounding
from .particles import (
    axis_frame,
    breakpoints,
    default_horizon,
    distributed_loads,
    given_grids,
    graded_families_warning,
    grading_density,
    merged_break_warnings,
    parse_positions,
    segment_grids,
)
from .resolution import (
    amplification,
    frame_defect,
    near_mechanism_warning,
    pinned_note,
    pinned_segments,
    resolution_warning,
)
from .supports import BREAK, axial_mechanism, particle_stiffness, reactions

PRIMAL_LOCKS = (  # docs/models/curved.md, "Locking": studies/paper_curved_quintic_bending.toml, 201 particles, P = 2
    "form = primal (the paper's second-derivative collocation) locks: at a fixed grid and degree its error grows like "
    "(L/h)^2 (P = 2, 201 particles on the quintic arch: 2.5e-3 at L/h = 10, 0.20 at 100, 0.96 at 1000) and can be of "
    "order 1 on coarse grids; form = mixed, the default, does not lock"
)


class PDCurved(Model):
    breaks = True  # a segment of particles between each two features (a short one: info["irregular"], resolution.py)
    name = "pd-curved"
    title = "PDDO curved Timoshenko–Ehrenfest beam (u_t, u_n, φ), any degree"
    source = (
        "Curved PDDO beam 2024, A peridynamic formulation for planar arbitrarily curved Timoshenko–Ehrenfest beams "
        "(equations: docs/design/formulas.md §2–3)"
    )
    options = (
        Option("points", int, 101, "particles along the axis, ends included", minimum=5, maximum=MAX_POINTS),
        Option("degree", int, 4, "polynomial degree P of the PDDO functions", minimum=2, maximum=10),
        Option(
            "horizon",
            int,
            0,
            "family half-width m in particles (family 2m + 1); 0 = floor(P/2) + 1 (mixed form, even P >= 6: P/2)",
            minimum=0,
        ),
        Option(
            "grading",
            float,
            1.0,
            "largest / smallest particle spacing (1 = uniform particles; see graded_by)",
            minimum=1.0,
            maximum=1e3,
        ),
        Option(
            "graded_by",
            str,
            "curvature",
            "where particles gather when grading > 1: curvature (where the axis "
            "bends) | ends (at the supports and at point loads)",
            choices=("curvature", "ends"),
        ),
        Option(
            "positions",
            str,
            "",
            "particle arc lengths in m, comma-separated (0 and L added; breaks at point "
            "loads and load ends added): overrides the particles of points and grading (points still sets the "
            "output grid)",
        ),
        Option(
            "form",
            str,
            "mixed",
            "primal (the paper: second-derivative functions) | mixed (first-derivative functions applied twice)",
            choices=("primal", "mixed"),
        ),
        Option(
            "unknowns",
            str,
            "resultants",
            "mixed form only: resultants (u_t, u_n, φ, N, Q, M per particle: "
            "condition number free of the slenderness) | displacements (N, Q, M substituted: 3 per particle, "
            "the same discrete solution, condition ~ (L/h)^2)",
            choices=("resultants", "displacements"),
        ),
        *NONLOCAL,
    )
    curved = True
    axial = True
    theory = "timoshenko"
    assembles = True
    springs = True  # straight axes (the scene's rule): breaks with their own conditions (.supports)
    inner_supports = True
    segments = True
    whole_horizon = "Eq. 27-35: PDDO families of 2m + 1 particles"

    def check(self, scene: Scene) -> list[str]:
        """The scene checks plus the axial rigid-body test on straight axes (e.g. two rollers slide along x)."""

        out = super().check(scene)
        why = mechanism_message(scene) if scene.supports.simple else axial_mechanism(scene)
        return out + ([why] if why is not None else [])

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """The PDDO families (Eq. 27-35) are fitted to degree P on 2m + 1 particles: at fixed delta, larger m leaves
        the modes near the sawtooth held by ever smaller stencil symbols (:func:`.particles.default_horizon`), so the
        discrete solutions have no limit in m; the largest m is the model's own family."""
        P = params["degree"]
        return (
            f"its PDDO families of degree {P} hold the high-frequency modes only for small families, so it has no "
            "limit at fixed delta",
            self.family_half_width({**params, "horizon": 0}),  # the default family of these particles
        )

    @staticmethod
    def family_half_width(params: dict) -> int:
        """m of the 2m + 1-member families: ``horizon``, else :func:`~.particles.default_horizon` of the degree, the
        form and the particles (graded by ends or not)."""
        graded_ends = params.get("grading", 1.0) > 1.0 and params.get("graded_by") == "ends"
        return params["horizon"] or default_horizon(params["degree"], params["form"], graded_ends)

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """The family :meth:`discretise` refuses (too small for the degree, larger than the grid), before any work:
        naming the horizon as the user set it (``horizon`` or ``horizon_length``)."""
        P, n, given = params["degree"], params["points"], params.get("horizon_length") is not None
        m = self.family_half_width(params)
        if 2 * m + 1 < P + 1:
            low = int(np.ceil(P / 2))
            fix = f"horizon_length >= {low * self.spacing(scene, params):.6g}" if given else f"horizon >= {low}"
            what = f"a family of {2 * m + 1} particles cannot carry degree {P}"
            return [
                f"{self.horizon_named(scene, params)}: {what}; {'give' if given else 'use'} {fix} or a lower degree"
            ]
        size = 2 * m + 1 if m < 10**15 else f"2 x {float(m):.3g} + 1"  # (not 309 digits)
        if 2 * m + 1 > n and not given:
            family = f"{size} particles for degree {P}, horizon {m if m < 10**15 else format(float(m), '.3g')}"
            return [f"points = {n}: fewer than one family ({family}); use more points"]
        if 2 * m + 1 > n:
            what = f"a family ({size} particles for degree {P}) is larger than the {n} points"
            return [self.horizon_refusal(scene, params, what, lambda k: 2 * k + 1 <= n)]
        return []

    # ---------------------------------------------------------------------------------------
    def discretise(self, scene: Scene, params: dict):
        m = self.family_half_width(params)
        size = 2 * m + 1
        if found := self.grid_problems(scene, params):  # resolve checked it; params built by hand (rules off)
            raise InputError(found)
        bps, inner, ends = breakpoints(scene)
        if params.get("positions"):
            segs = given_grids(scene.length, bps, parse_positions(params["positions"], scene.length), size)
            return segs, inner, ends, m, size
        ratio = params.get("grading", 1.0)
        density = None if ratio == 1.0 else grading_density(scene, ratio, params.get("graded_by", "curvature"))
        segs = segment_grids(scene.length, bps, params["points"], size, density)
        return segs, inner, ends, m, size

    def promised_order(self, params: dict) -> float:
        """The mixed form converges at order 2 ceil(P / 2), the primal form at 2 floor(P / 2) (docs/models/curved.md,
        the table of observed orders at L/h = 10)."""
        p = self.with_defaults(params)
        P = int(p["degree"])
        return float(2 * ((P + 1) // 2) if p["form"] == "mixed" else 2 * (P // 2))

    def checks_own_grid(self, scene: Scene, params: dict) -> bool:
        """On a curved axis, on a grid of ``points`` (not given particle positions): its error on coarse grids
        outruns the frame-defect warning (docs/models/curved.md, "Coarse grids on a curved axis")."""
        return not scene.is_straight and not params.get("positions")

    def assemble(self, scene: Scene, params: dict, body=None) -> System:
        """The collocation system of all the scene's loads as one :class:`~pdverify.numerics.band.Band`
        (:meth:`assemble_band`), z = (u_t, u_n, φ[, N, Q, M]) interleaved per particle; every unknown is
        free (the end conditions are rows of the system). ``solve`` factorises one such system per group of
        loads with the same breaks."""
        B, b, data = self.assemble_band(scene, params, body)
        return System(B, b, np.arange(B.n), data)

    def assemble_band(self, scene: Scene, params: dict, body=None):
        """(B, b, data): the collocation system (Eq. 27–35, boundary and interface rows replacing
        equilibrium or constitutive rows, rows then columns equilibrated) as a :class:`~pdverify.numerics.band.Band`
        with the unknowns of a particle interleaved. ``body(s, x)`` optionally adds distributed (p_t, p_n, m)
        at the arc lengths s (x: their axis abscissae on a polynomial axis, else None; the manufactured loads).

        The default form (mixed, resultants) is written straight into the band: the 6 x 6 block stencils of
        the constitutive and equilibrium rows (PDDO weights per particle, one band diagonal per family offset)
        and the boundary entries; the row and column scales are read and applied on the diagonals that were
        written, over the stretch that was written. The other forms (three unknowns per particle, stencils
        of D1 D1 and D2) are assembled as sparse products and copied into a band."""
        segs, inner, ends, m, size = self.discretise(scene, params)
        P = params["degree"]
        s = np.concatenate(segs)
        N = len(s)
        t, nv, kap, dkap, xa = axis_frame(scene, s)
        offs = np.cumsum([0] + [len(g) for g in segs])
        six = params["form"] == "mixed" and params.get("unknowns", "resultants") == "resultants"
        pt, pn, mm = np.zeros(N), np.zeros(N), np.zeros(N)
        for i, g in enumerate(segs):
            sl = slice(offs[i], offs[i + 1])
            pt[sl], pn[sl] = distributed_loads(scene, g, t[sl], nv[sl], 0.5 * (g[0] + g[-1]))
        if body is not None:
            bt, bn, bm = body(s, xa)
            pt, pn, mm = pt + bt, pn + bn, mm + bm
        data = dict(s=s, segs=segs, offs=offs, N=N, t=t, n=nv, kappa=kap, horizon=m, family=size)
        if six:
            B, b, cs = assemble_resultants(scene, segs, offs, inner, ends, size, P, kap, t, nv, (pt, pn, mm))
            nf = 6
            data.update(Eps=None, Gam=None, Chi=None)
        else:
            K, b, cs, ops = assemble_displacements(
                scene, params, segs, offs, inner, ends, size, P, kap, dkap, t, nv, (pt, pn, mm)
            )
            B = Band.from_sparse(K)
            nf = 3
            data.update(ops)
        # perm: interleaved index i -> component-major index perm[i]; cscale (component-major) and cscale_i
        # (interleaved): the column scales, z = cscale_i * (solution of B)
        data.update(
            nf=nf, perm=np.arange(nf * N).reshape(nf, N).T.ravel(), cscale=cs.reshape(N, nf).T.ravel(), cscale_i=cs
        )
        return B, b, data

    def solve(self, scene: Scene, params: dict, body=None) -> Result:
        """Superposition of single-load solutions: the loads are grouped by the breaks they need (a point
        load inside the beam: its position; a distributed load: its span ends inside the beam; end loads,
        full-span loads and ``body``: none), each group solved on particles that respect its own breaks,
        and the fields summed on the uniform output grid. So the result is exactly linear in the loads
        (a discretisation that depended on all loads together would not be), and each discontinuity is
        still resolved by its own segments."""
        timer = Timer()
        groups: dict[tuple, list] = {}
        for load in scene.loads:
            bps, _, _ = breakpoints(scene.model_copy(update={"loads": [load]}))
            groups.setdefault(tuple(np.round(bps / scene.length, 12)), []).append(load)
        if body is not None or not groups:
            groups.setdefault((), [])
        total, infos, dofs = None, [], 0
        for key, loads in sorted(groups.items()):
            sub = scene.model_copy(update={"loads": loads})
            out, info, n_dofs = self._solve_once(sub, params, body if key == () else None, timer)
            total = out if total is None else {k: total[k] + out[k] for k in total}
            infos.append(info)
            dofs += n_dofs
        total = axis_support_side(scene, total["x"] / len(infos), total)  # the end points: their supports' side
        worst = infos[int(np.argmax([i.get("cond", 0.0) for i in infos]))]
        info = {k: v for k, v in worst.items() if k not in ("bound_scale", "warnings")}  # warnings: every solve's
        if "reactions" in info:  # each solve's supports carry its loads: the sum
            info["reactions"] = {k: sum(i["reactions"][k] for i in infos) for k in info["reactions"]}
        merge_info(info, superposed_bound(infos, total))
        warnings = {w for i in infos for w in i.get("warnings", []) if not w.startswith("round-off bound")}
        if not info.get("error_bound", 0.0) <= BOUND_LIMIT:
            warnings.add(bound_warning(info["error_bound"]))
        if params["form"] == "primal":
            warnings.add(PRIMAL_LOCKS)
        defect = max(i.get("frame_defect", 0.0) for i in infos)
        pinned = sorted({p for i in infos for p in i.get("pinned_segments", [])})
        info.pop("pinned_segments", None)
        if note := pinned_note(pinned, infos[0].get("family", 0)):
            info["irregular"] = note
        if params["form"] == "mixed":
            info["frame_defect"] = defect
        amplified = 1.0
        if not scene.is_straight and body is None:  # near a mechanism (on a curved axis: a rigid motion strains)
            amplified = info["amplification"] = amplification(float(np.hypot(total["ux"], total["uy"]).max()), scene)
        for flag in (
            thick_ring_warning(scene),
            coupling_warning(scene, total["x"] / len(infos), total["N"], total["M"]),
            resolution_warning(defect, params["degree"], amplified) if params["form"] == "mixed" else "",
            near_mechanism_warning(amplified, pinned),
            *merged_break_warnings(scene),
            graded_families_warning(params, infos[0]["horizon_factor"]),
        ):
            if flag:
                warnings.add(flag)
        if warnings:
            info.setdefault("warnings", []).extend(sorted(warnings))
        info.update(solves=len(infos), segments=max(i["segments"] for i in infos))
        w, rot = total.pop("w"), total.pop("rotation")
        x = total.pop("x") / len(infos)
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=rot,
            fields=total,
            dofs=dofs,
            timings=timer.timings,
            info=info,
        )

    def _solve_once(self, scene: Scene, params: dict, body, timer: Timer):
        """Fields on the uniform output grid, solver info and unknowns of one discretisation."""
        with timer("assemble"):
            B, b, d = self.assemble_band(scene, params, body)
        with timer("solve"):  # factorises B in place above 20,000 unknowns (solve_band), else as CSR
            N, nf = d["N"], d["nf"]
            zi, info = solve_linear(
                B,
                b,
                what=f"pd-curved (degree {params['degree']}, {params['form']})",
                watch=np.flatnonzero(np.arange(nf * N) % nf < 2),  # the displacements u_t, u_n
                # the mixed band's entries are the PDDO weights themselves (times section constants): a weight's
                # rounding from the rounded positions; the primal band's are their compositions, whose entry-wise
                # bound already exceeds that rounding (the entries' cancellation: docs/trust.md)
                entry_rounding=weight_rounding(d["s"]) if nf == 6 else None,
            )
        del B
        Z = (zi * d["cscale_i"]).reshape(N, nf)  # row k: the unknowns of particle k
        ut, un, phi = Z[:, 0], Z[:, 1], Z[:, 2]
        if nf == 6:
            Nf, Qf, Mf = Z[:, 3], Z[:, 4], Z[:, 5]
        else:
            z = Z.T.ravel()
            EA, kGA, EI = particle_stiffness(scene, d["segs"])
            Nf, Qf, Mf = EA * (d["Eps"] @ z), kGA * (d["Gam"] @ z), EI * (d["Chi"] @ z)
        # the supports' forces and moments, from the resultants at the particles
        info["reactions"] = reactions(
            scene, d["segs"], d["offs"], np.array([Nf, Qf, Mf]), lambda at: _point_loads(scene, at)
        )
        # output on the uniform grid of ``points`` positions (independent of the loads): the particle value
        # where a particle sits there, else the degree-P PDDO interpolant g^0 of its segment; at a break
        # the left segment's (left limit of the resultants)
        T = output_map(d, scene.length, params["points"], params["degree"])
        t, nv = d["t"], d["n"]
        ux = ut * t[:, 0] + un * nv[:, 0]
        uy = ut * t[:, 1] + un * nv[:, 1]
        info["bound_scale"] = float(max(np.abs(ux).max(), np.abs(uy).max()))  # the bound's 1 (superposed_bound)
        # a segment of one family on a curved axis: its error does not fall with the grid (on a straight axis its
        # families carry the fields' polynomials; measured: docs/models/curved.md); uniform particles only
        if not scene.is_straight and not params.get("positions") and params.get("grading", 1.0) == 1.0:
            info["pinned_segments"] = pinned_segments(d["segs"], params["points"], d["family"], scene.length)
        if params["form"] == "mixed":  # the primal form warns of its locking whatever the grid
            frames = [(t[a:b], nv[a:b], d["kappa"][a:b]) for a, b in zip(d["offs"][:-1], d["offs"][1:])]
            info["frame_defect"] = frame_defect(d["segs"], frames, params["degree"], d["family"], scene.length)
        fields = {
            "x": d["x"],
            "w": T @ un,
            "rotation": T @ phi,
            "u": T @ ut,
            "N": T @ Nf,
            "Q": T @ Qf,
            "M": T @ Mf,
            "ux": T @ ux,
            "uy": T @ uy,
        }
        if scene.is_straight:
            fields["V"] = -fields["Q"]
        info.update(
            degree=params["degree"],
            horizon_factor=d["horizon"],
            horizon=d["horizon"] * scene.length / (params["points"] - 1),  # m nominal spacings (uniform particles)
            family=d["family"],
            form=params["form"],
            unknowns_per_particle=d["nf"],
            segments=len(d["segs"]),
            particles=N,
        )
        return fields, info, d["nf"] * N


MODELS = [PDCurved()]


def _point_loads(scene: Scene, at: float) -> np.ndarray:
    """(F_t, F_n, C) of the scene's point loads at arc length ``at``, in the axis' frame there (a straight axis:
    t = +x, n = +z)."""
    t, n = geometry(scene).frame(np.array(at))
    F = np.zeros(3)
    for load in scene.loads:
        if getattr(load, "position", None) is not None and abs(load.position - at) <= BREAK * scene.length:
            F += force_components(load, t, n)
    return F
