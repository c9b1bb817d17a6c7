"""Model ``pd-eb``: ordinary state-based PD Euler–Bernoulli beam (Diyaroglu, Oterkus & Oterkus 2019).

One transverse DOF per material point, points x_k = k dx (ends included).
The kernels (the curvature, the paper's fictitious layers, the corrected variant's ghost points and the
pieces of its mixed form) are in :mod:`.operator`; this module holds the model.

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

from ...core.contract import Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import Distributed, PointMoment, Scene
from ...numerics.linalg import eliminate
from ...numerics.loads import body_loads, boundary_layer_warnings, moment_rotation_warnings
from ...numerics.solvers import SOLVER, solve
from .operator import (
    corrected_system,
    curvature_weights,
    fixed_points,
    ghost_map,
    mixed_end_rows,
    mixed_ghost_coupling,
    mixed_matrix,
    paper_system,
)


def mirror_scene(scene: Scene) -> Scene:
    """The mirror image x -> L - x of a straight scene: supports swapped, positions and spans reflected,
    couples and axial components reversed (a sine load sin(pi x / L) is its own image)."""
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
    sup = scene.supports.model_copy(update={"left": scene.supports.right, "right": scene.supports.left})
    return scene.model_copy(update={"supports": sup, "loads": loads})


# -- the model -------------------------------------------------------------------------------


class PDEulerBernoulli(Model):
    name = "pd-eb"
    title = "ordinary state-based PD Euler–Bernoulli beam"
    source = "Diyaroglu et al. 2019, An Euler–Bernoulli beam formulation in an ordinary state-based PD framework"
    options = (
        Option("points", int, 101, "material points along the beam, ends included", minimum=5),
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
        SOLVER,
    )
    assembles = True
    variant_rules = (
        Rule(
            (("variant", "paper"),),
            "horizon",
            "Eq. 32: delta = (m + 0.015) dx, d = 1/(A delta) over whole "
            "families of m points; use variant = corrected for a fractional horizon",
            whole=True,
        ),
        Rule(
            (("variant", "paper"),),
            "form",
            "Eq. 13-15, 39-42: one fourth-order system; only the corrected variant has the two-equation (mixed) form",
            allowed=("auto", "direct"),
        ),
    )

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        return np.linspace(0.0, scene.length, params["points"])

    def assemble(self, scene: Scene, params: dict) -> System:
        """The system ``solve`` factorises: ``form = mixed`` the band of :meth:`assemble_mixed` (free: its
        unknowns not held), else the band of :meth:`assemble_full` with the supported points held at
        w = 0 (unit rows; free: the unknown points). ``System.reduced()`` gives the master–slave
        eliminated system of Eq. 39–42."""
        if self.form(params) == "mixed":
            return self.assemble_mixed(scene, params)
        K, b, fixed, info = self.assemble_full(scene, params)
        return System(K, b, np.delete(np.arange(params["points"]), fixed), info)

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
            K, b, fixed, info = corrected_system(scene, x, c, a, A)
        K.fix(fixed, b)  # master–slave elimination of the supported points (Eq. 39–42): w = 0 there
        return K, b, fixed, info

    @staticmethod
    def form(params: dict) -> str:
        f = params.get("form", "auto")
        return ("mixed" if params["variant"] == "corrected" else "direct") if f == "auto" else f

    def assemble_mixed(self, scene: Scene, params: dict):
        """The corrected operator split in two second-order equations (``form = mixed``)::

            h² kappa - h² D1 (E w + e0) = 0      (kappa on the real points and J ghosts each side)
            h² D2 (h² kappa)            = h⁴ b / a

        the same discrete solution as a D2 D1 (E w + e0) = b, but the matrix of fourth differences
        (entries ~1/h⁴) is never formed, which lowers the round-off floor (tests/verification/test_hard_cases.py).

        Assembled straight into LAPACK's band layout (:class:`~pdverify.numerics.band.Band`): positions
        p = -J .. n-1+J, two unknowns each (kappa_p, w_p), interleaved; both equations are Toeplitz block
        stencils, the ghost map adds a few entries at each end, and the w of positions outside the beam
        and of the supported points are held at zero (unit rows). Returns the :class:`~pdverify.registry.System`
        (free: the unknowns not held): w of real point i is unknown 2 (i + J) + 1."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        c = curvature_weights(params["horizon"], dx, "corrected")
        J = len(c)
        G = 2 * J
        if 2 * J + 1 > n:
            raise InputError(
                f"horizon = {params['horizon']:g}: the family ({J} points each side) does not fit in "
                f"{n} points; use more points or a smaller horizon"
            )
        A = scene.section.A
        a = scene.EI / A
        h2 = dx * dx
        st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])  # D1 = D2 stencil, offsets -J..J
        npos = n + 2 * J
        g_rows, g_cols, g_vals, e0, skip = ghost_map(scene, n, dx, G, curvature_ends=True)
        rows, cols, vals, rhs = mixed_ghost_coupling(g_rows - G, g_cols, g_vals, e0, n, J, st, h2)
        q = body_loads(scene, x, skip_ends=skip)
        ends = mixed_end_rows(scene, n, dx, c, q)  # free and guided ends: conditions on k
        M = mixed_matrix(npos, J, st, h2, (rows, cols, vals), ends)
        rhs[2 * J + 1 : 2 * (n + J) : 2] = q / A * h2 * h2 / a
        for _, _, _, r_rows, r_vals in ends:
            rhs[r_rows] = r_vals
        fixed = fixed_points(scene, n)
        held = np.r_[2 * np.arange(J) + 1, 2 * (n + J + np.arange(J)) + 1, 2 * (np.asarray(fixed, np.int64) + J) + 1]
        M.fix(held, rhs)
        return System(
            M,
            rhs,
            np.delete(np.arange(2 * npos), held),
            {
                "ghosts_per_end": G,
                "form": "mixed (two second-order equations)",
                "boundary": "Taylor ghost points (degree 4, 4 real points)",
            },
        )

    def reduced(self, K, b, fixed):
        """Master–slave elimination of the fixed points (w = 0): the rows/columns of the free points."""
        return eliminate(K, b, fixed)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        if params.get("reading", "energy") != "energy" and params["variant"] != "paper":
            raise InputError(
                f"reading = {params['reading']!r}: a reading of the paper's boundary treatment "
                "(Eq. 37-42); use variant = paper or reading = energy"
            )
        if self.form(params) == "mixed":
            if params["variant"] != "corrected":
                raise InputError(
                    "form = 'mixed': only the corrected variant has the two-equation form; "
                    "use variant = corrected or form = direct"
                )
            # the banded LU eliminates from the left end: a guided end there amplifies round-off by orders of
            # magnitude on fine grids, so such a scene is solved as its mirror image and flipped back
            flip = scene.supports.left == "guided" and scene.supports.right != "guided"
            with timer("assemble"):
                system = self.assemble(mirror_scene(scene) if flip else scene, params)
            with timer("solve"):
                z, info = solve(system.matrix, system.rhs, "pd-eb (corrected, mixed form)", params["solver"])
                n = params["points"]
                J = (system.matrix.n // 2 - n) // 2  # positions -J .. n-1+J, two unknowns each
                w = z[2 * J + 1 : 2 * (n + J) : 2].copy()
                if flip:
                    w = w[::-1].copy()
        else:
            with timer("assemble"):
                system = self.assemble(scene, params)
            with timer("solve"):
                w, info = solve(system.matrix, system.rhs, f"pd-eb ({params['variant']})", params["solver"])
        ndofs, binfo = system.unknowns, system.info  # mixed: kappa on every position, w on the free points
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        rot = np.gradient(w, dx, edge_order=2)
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        flags = boundary_layer_warnings(
            scene, x, 2 * len(curvature_weights(params["horizon"], dx, params["variant"])) + 4
        )
        flags += moment_rotation_warnings(scene)
        if params["variant"] == "paper":  # d = 1 / (A delta) with delta = (m + 0.015) dx: kappa too small by m / delta
            flags.append(
                f"variant = paper does not converge to the beam: its curvature is too small by m/(m + 0.015), so the "
                f"beam is {(1 + 0.015 / params['horizon']) ** 2 - 1:.2%} too flexible at horizon {params['horizon']:g} "
                "on fine grids; variant = corrected converges"
            )
        if flags:
            info.setdefault("warnings", []).extend(flags)
        return self.new_result(
            scene,
            params,
            x,
            w,
            rotation=rot,
            dofs=ndofs,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDEulerBernoulli()]
