"""Model ``pd-bond-pair``: non-ordinary state-based bond-pair beam (O'Grady & Foster 2014), linear path.

Every bond xi from a point is paired with its opposite -xi through a rotational spring with potential
``w(xi) = omega(xi) alpha [1 + cos theta]`` (theta = deformed angle between the two bonds; the force
state of Eq. 2 is its gradient). For small deflections 1 + cos theta ≈ Δ²/2 with
Δ = (w_{k+j} - 2 w_k + w_{k-j}) / xi_j, so the bending energy per point is
Σ_j ½ alpha omega_j beta_j dx (Δ_j)² dx and its gradient per unit length is (docs/design/formulas.md §1)::

    Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j}) = q_k,   c_j = alpha omega_j beta_j dx / xi_j²

(= EI w'''' + O(delta²) w^(6)). omega = 1. alpha from energy equivalence with Euler–Bernoulli bending
under uniform curvature (docs/design/formulas.md §1; the paper's extracted text ends after Eq. 2):

* ``paper``: the continuous horizon integral, alpha = EI / ∫_0^delta xi² dxi = 3 EI / delta³ with the
  full family volumes (delta = (m + 0.015) dx as in the other papers);
* ``corrected``: the discrete family sum with the last member's partial volume,
  alpha = EI / Σ_j xi_j² beta_j dx, so a uniform curvature field gives exactly EI kappa² / 2.

The stencil reaches 2J points past an end. Ends (``ends`` option):
``mirror`` (the energy form: clamped = reflection of the real points through the normal to the clamp,
pinned = point reflection through the support, guided = reflection through the support's vertical,
free = cubic extrapolation, end points' energy halved; the linear path is the tangent stiffness of that
energy at the undeformed state, the nonlinear path its Newton solution) or ``taylor`` (the degree-4
polynomial ghost points of :func:`pdverify.numerics.ghosts.taylor_ghosts`, end loads through the moment and shear
at the end; solved in the mixed form of :meth:`PDBondPair.assemble_mixed` by default).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.contract import Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import Scene
from ...numerics.band import Band
from ...numerics.families import family, ghost_stencil_system, stencil_operator
from ...numerics.ghosts import curvature_end_rows, taylor_ghosts
from ...numerics.loads import body_loads, boundary_layer_warnings, end_loads, moment_rotation_warnings
from ...numerics.solvers import SOLVER, solve
from .bias import paper_bias
from .nonlinear import NonlinearBondPair


def spring_constants(EI: float, m: float, dx: float, variant: str) -> np.ndarray:
    """c_j of the linear operator (alpha calibrated continuous or discrete)."""
    j, beta = family(m, dx, variant)
    xi = j * dx
    if variant == "paper":
        delta = (m + 0.015) * dx
        alpha = 3.0 * EI / delta**3
    else:
        alpha = EI / np.sum(xi**2 * beta * dx)
    return alpha * beta * dx / xi**2


def operator_stencil(j: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Offsets and coefficients of Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j})."""
    offs = np.array([-2, -1, 0, 1, 2])
    coef = np.array([1.0, -4.0, 6.0, -4.0, 1.0])
    return (np.asarray(j)[:, None] * offs[None, :]).ravel(), (np.asarray(c)[:, None] * coef[None, :]).ravel()


def operator(n_rows: int, row0: int, n_cols: int, j: np.ndarray, c: np.ndarray) -> sp.csr_matrix:
    """The operator of :func:`operator_stencil` for rows k = row0 .. row0 + n_rows - 1 of a grid of
    n_cols points (families truncated at the grid's ends)."""
    return stencil_operator(n_rows, row0, n_cols, *operator_stencil(j, c), truncate=True)


def refine(model, K, b, free, u, sweeps: int = 3) -> np.ndarray:
    """Iterative refinement of K u = b with the residual from the element forces
    (:meth:`NonlinearBondPair.apply_linear`): the assembled K's round-off grows like N^4 eps, the element
    residual's like N^2 eps, so two or three sweeps give the discrete solution the nonlinear path
    converges to (its first Newton iterate is this solve). Returns all 2n displacements."""
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
    return full


def factored_stencils(j: np.ndarray, c: np.ndarray, EI: float, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """(r, s): the operator of :func:`operator_stencil` written as (EI / dx⁴) D1 r D1, D1 = (1, -2, 1).

    w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j} = D_j² w and D_j = D1 T_j with T_j the triangle
    stencil (1, 2, .., j, .., 2, 1) (offsets 1-j .. j-1), so Σ_j c_j D_j² = D1 (Σ_j c_j T_j²) D1. r =
    Σ_j c_j T_j² dx⁴ / EI (offsets -2(J-1) .. 2(J-1); its sum is Σ_j c_j j⁴ dx⁴ / EI, 1 for the discrete
    calibration), s = D1 * r (offsets -(2J-1) .. 2J-1)."""
    J = int(np.max(j))
    r = np.zeros(4 * J - 3)
    for jj, cj in zip(j, c):
        tri = np.r_[np.arange(1, jj + 1), np.arange(jj - 1, 0, -1)].astype(float)
        t2 = np.convolve(tri, tri)
        mid = 2 * (J - 1)
        r[mid - 2 * (jj - 1) : mid + 2 * (jj - 1) + 1] += cj * t2 * dx**4 / EI
    return r, np.convolve([1.0, -2.0, 1.0], r)


HELD_W = ("clamped", "pinned", "roller")  # supports that hold w (roller: pinned's transverse conditions)
D1 = {-1: 1.0, 0: -2.0, 1: 1.0}  # the second difference of the mixed form's first equation


def mixed_ends(scene: Scene, n: int, dx: float, G: int, Jk: int, q: np.ndarray):
    """The ends of the mixed form (:meth:`PDBondPair.assemble_mixed`): (ghosts, conditions). At clamped, pinned and
    roller ends the G ghost w outside the beam by the degree-4 Taylor polynomial of ``taylor_ghosts`` (end loads
    through the moment and shear at the end), ghosts = (positions, real points, weights, (position, constant)
    rows); at free and guided ends the end conditions on k = D1 w (the curvature stencil c = 1/dx²;
    :func:`~pdverify.numerics.ghosts.curvature_end_rows`): conditions = (rows, cols, vals, (row, rhs) rows) lists,
    round-off ~N eps instead of ~N³ eps through Taylor ghosts of w."""
    P, C = end_loads(scene)
    g_pos, g_real, g_val, g_const = [], [], [], []
    k_rows, k_cols, k_vals, k_rhs = [], [], [], []  # the end rows of free and guided ends (on k)
    kidx = lambda p: 2 * (np.asarray(p) + Jk)  # noqa: E731  (unknown k_p)
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
        if sup in ("free", "guided"):
            q_end = q[0 if side == 0 else n - 1]
            er_, ec_, ev_, rr_, rv_ = curvature_end_rows(
                sup, side, n, dx, np.array([1 / dx**2]), M_end, V3, scene.EI, q_end, Jk, kidx, lambda p_: kidx(p_) + 1
            )
            k_rows.append(er_), k_cols.append(ec_), k_vals.append(ev_), k_rhs.append(np.c_[rr_, rv_])
            continue
        Gm, g0 = taylor_ghosts("pinned" if sup == "roller" else sup, G, dx, M_end, V3, scene.EI, min(4, n))
        real = np.arange(4) if side == 0 else n - 1 - np.arange(4)
        pos = -1 - np.arange(G) if side == 0 else n + np.arange(G)
        g_pos.append(np.repeat(pos, 4)), g_real.append(np.tile(real, G)), g_val.append(Gm.ravel())
        g_const.append(np.stack([pos, g0], axis=1))
    g_pos, g_real = (np.concatenate(v) if v else np.zeros(0, np.int64) for v in (g_pos, g_real))
    g_val = np.concatenate(g_val) if g_val else np.zeros(0)
    g_const = np.concatenate(g_const) if g_const else np.zeros((0, 2))
    return (g_pos, g_real, g_val, g_const), (k_rows, k_cols, k_vals, k_rhs)


def ghost_rows(g_pos, g_real, g_val, g_const, n: int, Jk: int):
    """The ghost w in the first equation k_p - (w_{p+1} - 2 w_p + w_{p-1}) = 0 of the rows p within the grid
    whose second difference reaches a ghost position (|g - p| <= 1): (rows, cols, vals) lists onto the real w
    columns and the constant part (rhs, length 2 (n + 2 Jk))."""
    rows, cols, vals = [], [], []
    rhs = np.zeros(2 * (n + 2 * Jk))
    for o, w_o in D1.items():
        p = g_pos - o
        ok = (p >= -Jk) & (p <= n - 1 + Jk)
        rows.append(2 * (p[ok] + Jk)), cols.append(2 * (g_real[ok] + Jk) + 1), vals.append(-w_o * g_val[ok])
        pc = g_const[:, 0].astype(np.int64) - o
        okc = (pc >= -Jk) & (pc <= n - 1 + Jk)
        np.add.at(rhs, 2 * (pc[okc] + Jk), w_o * g_const[okc, 1])
    return rows, cols, vals, rhs


def mixed_band(npos: int, Jk: int, st: np.ndarray, rows, cols, vals, cleared) -> Band:
    """The band of the mixed form, unknowns (k_p, w_p) interleaved at the positions p = -Jk .. n-1+Jk: the block
    stencil of k_p - D1 w and Σ_o s_o k_{p+o}, the rows ``cleared`` (free and guided end conditions) emptied, then
    the entries (rows, cols, vals) of the ghosts and end conditions added."""
    off = np.r_[cols - rows, -2 * Jk - 1, 2 * Jk + 1]
    M = Band(2 * npos, int(-off.min()), int(off.max()))
    blocks = {o: [[1.0 if o == 0 else 0.0, -D1.get(o, 0.0)], [st[o + Jk], 0.0]] for o in range(-Jk, Jk + 1)}
    M.add_block_stencil(2, blocks)
    if cleared is not None:
        M.clear_rows(np.unique(cleared))
    M.add_entries(rows, cols, vals)
    return M


class PDBondPair(Model):
    name = "pd-bond-pair"
    title = "non-ordinary state-based bond-pair PD beam (linear path)"
    source = (
        "O'Grady & Foster 2014, Peridynamic beams: a non-ordinary, state-based model (alpha calibration and ghost "
        "rules: docs/design/formulas.md §1)"
    )
    options = (
        Option("points", int, 201, "material points along the beam, ends included", minimum=5),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing", minimum=1.0),
        Option(
            "variant",
            str,
            "corrected",
            "paper (continuous alpha) | corrected (discrete alpha)",
            choices=("paper", "corrected"),
        ),
        Option("ends", str, "taylor", "boundary ghost rule: mirror | taylor", choices=("mirror", "taylor")),
        Option(
            "form",
            str,
            "auto",
            "taylor ends: auto (= mixed) | direct (one fourth-order system) | mixed (curvature "
            "and deflection, two second-order equations: round-off ~N^2 eps instead of ~N^4 eps)",
            choices=("auto", "direct", "mixed"),
        ),
        Option("nonlinear", bool, False, "geometrically nonlinear path (Newton, load steps, mirror ghosts)"),
        Option("steps", int, 10, "load steps of the nonlinear path", minimum=1, maximum=100_000),
        SOLVER,
    )
    axial = True
    assembles = True
    nonlinear_when = (("nonlinear", True),)
    variant_rules = (
        Rule(
            (("variant", "paper"),),
            "horizon",
            "O'Grady & Foster 2014 as reconstructed in docs/design/formulas.md §1: alpha = 3 EI / delta^3 with "
            "delta = (m + 0.015) dx over whole families of m points; use variant = corrected for a fractional "
            "horizon",
            whole=True,
        ),
        Rule(
            (("variant", "paper"),),
            "ends",
            "the paper's continuous alpha goes with the mirror (reflection) ghosts of Diyaroglu et al. 2019; "
            "Taylor ghosts carry the true EI (docs/design/formulas.md §1); use ends = mirror",
            allowed=("mirror",),
        ),
    )

    def energy_model(self, scene: Scene, params: dict):
        n = params["points"]
        dx = scene.length / (n - 1)
        j, beta = family(params["horizon"], dx, params["variant"])
        return NonlinearBondPair(scene, n, j, beta, self.alpha(scene.EI, params["horizon"], dx, params["variant"]))

    def assemble(self, scene: Scene, params: dict) -> System:
        """The linear system ``solve`` factorises.

        ``ends = mirror``: the tangent stiffness of the full energy at the undeformed state (u and w per
        point, forces), i.e. exactly the linearisation of the nonlinear path, reduced to the free DOFs (CSR).
        ``ends = taylor``: ``form = mixed`` (default) the two second-order equations of :meth:`assemble_mixed`;
        ``form = direct`` the strong-form operator on w of :meth:`assemble_taylor`, supported points held."""
        if not self.linear(params):
            raise InputError("nonlinear = true: the nonlinear path solves no single linear system")
        if params["ends"] == "mirror":
            model = self.energy_model(scene, params)
            K = model.tangent(np.zeros(2 * model.n), 0.0)
            free = model.free
            b = -model.gradient(np.zeros(2 * model.n), 1.0)  # dead loads and the couples' forces at rest
            return System(
                K[free][:, free].tocsr(), b[free], free, {"ghosts_per_end": model.G, "form": "energy tangent"}
            )
        if params.get("form", "auto") in ("auto", "mixed"):
            return self.assemble_mixed(scene, params)
        K, b, fixed, info = self.assemble_taylor(scene, params)
        return System(K, b, np.delete(np.arange(params["points"]), fixed), info)

    def assemble_taylor(self, scene: Scene, params: dict):
        """(K, b, fixed, info): the strong-form operator on all real points as a
        :class:`~pdverify.numerics.band.Band` (Toeplitz by diagonals + the ghost entries), the supported points
        ``fixed`` held at w = 0 (unit rows, ``Band.fix``)."""
        n = params["points"]
        x = np.linspace(0.0, scene.length, n)
        dx = x[1] - x[0]
        j, _ = family(params["horizon"], dx, params["variant"])
        c = spring_constants(scene.EI, params["horizon"], dx, params["variant"])
        G = 2 * int(j.max())
        if G + 1 > n:
            raise InputError(
                f"horizon = {params['horizon']:g}: the stencil (2 x {j.max()} points) does not fit in "
                f"{n} points; use more points or a smaller horizon"
            )
        N = n + 2 * G
        left, right = scene.supports.left, scene.supports.right
        er, ec, ev = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
        e0 = np.zeros(N)
        skip = {}
        # Taylor ghosts (the mirror ends go through the energy form, :meth:`energy_model`)
        P, C = end_loads(scene)
        for side, sup in ((0, left), (1, right)):
            M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
            # roller: the transverse conditions of pinned (the axial one does not enter this path)
            Gm, g0 = taylor_ghosts("pinned" if sup == "roller" else sup, G, dx, M_end, V3, scene.EI, min(4, n))
            real = np.arange(4) if side == 0 else n - 1 - np.arange(4)
            ghost = G - 1 - np.arange(G) if side == 0 else G + n + np.arange(G)
            er.append(np.repeat(ghost, 4)), ec.append(np.tile(real, G)), ev.append(Gm.ravel())
            e0[ghost] = g0
            skip[0 if side == 0 else n - 1] = {"point_force", "point_moment"}
        cat = lambda v, dt: np.concatenate(v[1:]) if len(v) > 1 else np.zeros(0, dt)  # noqa: E731
        K, r = ghost_stencil_system(*operator_stencil(j, c), G, n, cat(er, int), cat(ec, int), cat(ev, float), e0)
        b = body_loads(scene, x, skip_ends=skip) - r
        fixed = [i for i, sup in ((0, left), (n - 1, right)) if sup in ("clamped", "pinned", "roller")]
        K.fix(fixed, b)
        info = {"ghosts_per_end": G, "alpha_calibration": "continuous" if params["variant"] == "paper" else "discrete"}
        return K, b, fixed, info

    def assemble_mixed(self, scene: Scene, params: dict):
        """The Taylor-ghost operator split in two second-order equations (``form = mixed``)::

            k_p - (w_{p+1} - 2 w_p + w_{p-1}) = 0          p = -(2J-1) .. n-1+2J-1
            Σ_o s_o k_{i+o}                  = dx⁴ q_i / EI  (real points i)

        (:func:`factored_stencils`): the same discrete solution as the fourth-order system, but no matrix
        of fourth differences is formed, so the round-off floor falls from ~N⁴ eps to ~N² eps (as pd-eb's
        mixed form). At clamped, pinned and roller ends ghost w (outside the beam, up to 2J spacings) enter
        the first equation through the Taylor map w_g = Gm w_real + g0; at free and guided ends the first
        equation of the end point and of the positions outside is replaced by the end conditions on k
        (:func:`~pdverify.numerics.ghosts.curvature_end_rows`, :func:`mixed_ends`). Unknowns interleaved (k_p,
        w_p) in LAPACK's band layout; the w of positions outside the beam and of supported points are held at zero.
        Returns the :class:`~pdverify.registry.System` (free: the unknowns not held; ``info["Jk"]``): w of real
        point i is unknown 2 (i + Jk) + 1."""
        n = params["points"]
        x = np.linspace(0.0, scene.length, n)
        dx = x[1] - x[0]
        j, _ = family(params["horizon"], dx, params["variant"])
        c = spring_constants(scene.EI, params["horizon"], dx, params["variant"])
        J = int(j.max())
        G, Jk = 2 * J, 2 * J - 1
        if G + 1 > n:
            raise InputError(
                f"horizon = {params['horizon']:g}: the stencil (2 x {J} points) does not fit in "
                f"{n} points; use more points or a smaller horizon"
            )
        _, st = factored_stencils(j, c, scene.EI, dx)
        skip = {0: {"point_force", "point_moment"}, n - 1: {"point_force", "point_moment"}}
        q = body_loads(scene, x, skip_ends=skip)
        ghosts, (k_rows, k_cols, k_vals, k_rhs) = mixed_ends(scene, n, dx, G, Jk, q)
        rows, cols, vals, rhs = ghost_rows(*ghosts, n, Jk)
        cat = lambda a, dt: np.concatenate([np.asarray(v, dt).ravel() for v in a])  # noqa: E731
        rows, cols, vals = cat(rows + k_rows, np.int64), cat(cols + k_cols, np.int64), cat(vals + k_vals, float)
        npos = n + 2 * Jk
        M = mixed_band(npos, Jk, st, rows, cols, vals, cat(k_rows, np.int64) if k_rows else None)
        if k_rows:  # free/guided end rows: the conditions on k instead
            kr = np.concatenate([np.asarray(v, float).reshape(-1, 2) for v in k_rhs])
            rhs[kr[:, 0].astype(np.int64)] = kr[:, 1]
        rhs[2 * Jk + 1 : 2 * (n + Jk) : 2] = q * dx**4 / scene.EI
        fixed = [i for i, sup in ((0, scene.supports.left), (n - 1, scene.supports.right)) if sup in HELD_W]
        held = np.r_[
            2 * np.arange(Jk) + 1, 2 * (n + Jk + np.arange(Jk)) + 1, 2 * (np.asarray(fixed, np.int64) + Jk) + 1
        ]
        M.fix(held, rhs)
        return System(
            M,
            rhs,
            np.delete(np.arange(2 * npos), held),
            {
                "ghosts_per_end": G,
                "form": "mixed (curvature and deflection)",
                "Jk": Jk,
                "alpha_calibration": "continuous" if params["variant"] == "paper" else "discrete",
            },
        )

    def alpha(self, EI: float, m: float, dx: float, variant: str) -> float:
        j, beta = family(m, dx, variant)
        if variant == "paper":
            return 3.0 * EI / ((m + 0.015) * dx) ** 3
        return EI / np.sum((j * dx) ** 2 * beta * dx)

    def solve_nonlinear(self, scene: Scene, params: dict) -> Result:
        if params["ends"] != "mirror":
            raise InputError(
                "ends = taylor: the nonlinear path uses the reflection (mirror) ghosts of the energy "
                "form; give -o ends=mirror with -o nonlinear=true"
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

    def solve(self, scene: Scene, params: dict) -> Result:
        if params["nonlinear"]:
            return self.solve_nonlinear(scene, params)
        timer = Timer()
        what = f"pd-bond-pair ({params['variant']}, {params['ends']} ends)"
        x = np.linspace(0.0, scene.length, params["points"])
        fields = {}
        with timer("assemble"):
            system = self.assemble(scene, params)
        binfo = dict(system.info)
        if params["ends"] == "mirror":
            model = self.energy_model(scene, params)
            with timer("solve"):
                u, info = solve(system.matrix, system.rhs, what, params["solver"])
                full = refine(model, system.matrix, system.rhs, system.free, u)
            w, fields["u"] = full[1::2], full[0::2]
        elif binfo.get("Jk") is not None:
            Jk = binfo.pop("Jk")
            with timer("solve"):
                # the condition number of the two-equation matrix grows like N^4 but is no bound on its
                # round-off (which stays far below cond eps), so it is not estimated; the round-off estimate
                # 0.1 eps N^2 holds the errors at 10^5-10^6 points, every support pair, mixed loads
                # (tests/papers/ogrady/test_bond_pair_large.py; docs/models/ogrady.md)
                z, info = solve(system.matrix, system.rhs, what + ", mixed form", params["solver"], condition=False)
                w = z[2 * Jk + 1 : 2 * (len(x) + Jk) : 2].copy()
            info["roundoff_estimate"] = roundoff = 0.1 * np.finfo(float).eps * len(x) ** 2
            if roundoff > 1e-6:
                info.setdefault("warnings", []).append(
                    f"round-off estimate {roundoff:.1g} relative (0.1 eps N^2, N = {len(x)} points; measured 0.01-1 "
                    "of it): past 1e-6; use fewer points"
                )
        else:
            with timer("solve"):
                w, info = solve(system.matrix, system.rhs, what, params["solver"])
        dx = x[1] - x[0]
        flags = boundary_layer_warnings(
            scene, x, 4 * int(family(params["horizon"], dx, params["variant"])[0].max()) + 4
        )
        flags += moment_rotation_warnings(scene) + (
            [paper_bias(params["horizon"])] if params["variant"] == "paper" else []
        )
        if flags:
            info.setdefault("warnings", []).extend(flags)
        info.update(
            binfo,
            spacing=dx,
            horizon_factor=params["horizon"],
            horizon=(params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx,
        )
        return self.new_result(
            scene,
            params,
            x,
            w,
            fields=fields,
            rotation=np.gradient(w, dx, edge_order=2),
            dofs=system.unknowns,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDBondPair()]
