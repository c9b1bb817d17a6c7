"""Model ``pd-bond-pair``: non-ordinary state-based bond-pair beam (O'Grady & Foster 2014), linear path.

Every bond xi from a point is paired with its opposite -xi through a rotational spring with potential
``w(xi) = omega(xi) alpha [1 + cos theta]`` (theta = deformed angle between the two bonds; the force
state of Eq. 2 is its gradient). For small deflections 1 + cos theta ≈ Δ²/2 with
Δ = (w_{k+j} - 2 w_k + w_{k-j}) / xi_j, so the bending energy per point is
Σ_j ½ alpha omega_j beta_j dx (Δ_j)² dx and its gradient per unit length is (design note §1)::

    Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k - 4 w_{k-j} + w_{k-2j}) = q_k,   c_j = alpha omega_j beta_j dx / xi_j²

(= EI w'''' + O(delta²) w^(6)). omega = 1. alpha from energy equivalence with Euler–Bernoulli bending
under uniform curvature (reconstructed in the design note, the seed is truncated there):

* ``paper``: the continuous horizon integral, alpha = EI / ∫_0^delta xi² dxi = 3 EI / delta³ with the
  full family volumes (delta = (m + 0.015) dx as in the other papers);
* ``corrected``: the discrete family sum with the last member's partial volume,
  alpha = EI / Σ_j xi_j² beta_j dx, so a uniform curvature field gives exactly EI kappa² / 2.

The stencil reaches 2J points past an end. Ends (``ends`` option):
``mirror`` (the energy form: clamped = reflection of the real points through the normal to the clamp,
pinned = point reflection through the support, guided = reflection through the support's vertical,
free = no ghosts, truncated families; the linear path is the tangent stiffness of that energy at the
undeformed state, the nonlinear path its Newton solution) or ``taylor`` (the degree-4 polynomial ghost points of
``pd_eb.taylor_ghosts``: end loads enter through the moment and shear at the end).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..errors import InputError
from ..linalg import eliminate, solve_linear
from ..registry import Model, Option
from ..result import Result, Timer
from ..scene import Scene
from .pd_eb import (body_loads, boundary_layer_warnings, end_loads, ghost_stencil_system, partial_volumes,
                    stencil_operator, taylor_ghosts)


def family(m: float, dx: float, variant: str) -> tuple[np.ndarray, np.ndarray]:
    """Offsets j = 1..J and volume factors beta_j (paper: full volumes within (m + 0.015) dx)."""
    if variant == "paper":
        J = int(np.floor(m + 0.015 + 1e-12))
        j = np.arange(1, J + 1)
        return j, np.ones(J)
    return partial_volumes(m)


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


class PDBondPair(Model):
    name = "pd-bond-pair"
    title = "non-ordinary state-based bond-pair PD beam (linear path)"
    source = "O'Grady & Foster 2014 (seed 003) + design note §1 (alpha calibration, ghost rules)"
    options = (
        Option("points", int, 201, "material points along the beam, ends included", minimum=5),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing", minimum=1.0),
        Option("variant", str, "corrected", "paper (continuous alpha) | corrected (discrete alpha)",
               choices=("paper", "corrected")),
        Option("ends", str, "taylor", "boundary ghost rule: mirror | taylor", choices=("mirror", "taylor")),
        Option("nonlinear", bool, False, "geometrically nonlinear path (Newton, load steps, mirror ghosts)"),
        Option("steps", int, 10, "load steps of the nonlinear path", minimum=1),
    )
    axial = True

    def energy_model(self, scene: Scene, params: dict):
        from ._bond_pair_nonlinear import NonlinearBondPair

        n = params["points"]
        dx = scene.length / (n - 1)
        j, beta = family(params["horizon"], dx, params["variant"])
        return NonlinearBondPair(scene, n, j, beta, self.alpha(scene.EI, params["horizon"], dx, params["variant"]))

    def assemble(self, scene: Scene, params: dict):
        """(K, b, free, info) after the supports, K sparse.

        ``ends = taylor``: the strong-form operator on w (one DOF per point, per unit length).
        ``ends = mirror``: the tangent stiffness of the full energy at the undeformed state (u and w per
        point, forces), i.e. exactly the linearisation of the nonlinear path."""
        if params["ends"] == "mirror":
            model = self.energy_model(scene, params)
            K = model.tangent(np.zeros(2 * model.n), 0.0)
            free = model.free
            b = -model.gradient(np.zeros(2 * model.n), 1.0)  # dead loads and the couples' forces at rest
            return K[free][:, free].tocsr(), b[free], free, {"ghosts_per_end": model.G, "form": "energy tangent"}
        K, b, fixed, info = self.assemble_taylor(scene, params)
        Kf, bf, free = eliminate(K.tocsr(), b, fixed)
        return Kf, bf, free, info

    def limit_system(self, scene: Scene, params: dict):
        """(matrix, rhs) of the linear system ``solve`` factorises (for ``pdverify bench``'s limit)."""
        if params["ends"] == "mirror":
            return self.assemble(scene, params)[:2]
        K, b, *_ = self.assemble_taylor(scene, params)
        return K, b

    def assemble_taylor(self, scene: Scene, params: dict):
        """(K, b, fixed, info): the strong-form operator on all real points as a
        :class:`~pdverify.band.Band` (Toeplitz by diagonals + the ghost entries), the supported points
        ``fixed`` held at w = 0 (unit rows, ``Band.fix``)."""
        n = params["points"]
        x = np.linspace(0.0, scene.length, n)
        dx = x[1] - x[0]
        j, _ = family(params["horizon"], dx, params["variant"])
        c = spring_constants(scene.EI, params["horizon"], dx, params["variant"])
        G = 2 * int(j.max())
        if G + 1 > n:
            raise InputError(f"horizon = {params['horizon']:g}: the stencil (2 x {j.max()} points) does not fit in "
                             f"{n} points; use more points or a smaller horizon")
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

    def alpha(self, EI: float, m: float, dx: float, variant: str) -> float:
        j, beta = family(m, dx, variant)
        if variant == "paper":
            return 3.0 * EI / ((m + 0.015) * dx) ** 3
        return EI / np.sum((j * dx) ** 2 * beta * dx)

    def solve_nonlinear(self, scene: Scene, params: dict) -> Result:
        if params["ends"] != "mirror":
            raise InputError("ends = taylor: the nonlinear path uses the reflection (mirror) ghosts of the energy "
                             "form; give -o ends=mirror with -o nonlinear=true")
        timer = Timer()
        dx = scene.length / (params["points"] - 1)
        with timer("assemble"):
            model = self.energy_model(scene, params)
        with timer("solve"):
            P, shots, iters = model.solve(steps=params["steps"])
        X0 = model.X0
        moments = [l for l in scene.loads if l.type == "point_moment"]
        if (scene.supports.left, scene.supports.right) == ("clamped", "free") and len(moments) == len(scene.loads) == 1 \
                and abs(moments[0].position - scene.length) < 1e-12 * scene.length:
            s_ = np.linspace(0, scene.length, 201)  # exact elastica: circles of radius EI / (factor M)
            for shot in shots:
                k = shot["factor"] * moments[0].value / scene.EI
                xs = np.sin(k * s_) / k if k else s_
                zs = (1 - np.cos(k * s_)) / k if k else 0 * s_
                shot["exact_x"], shot["exact_z"] = xs.tolist(), zs.tolist()
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=X0[:, 0], w=P[:, 1],
                      fields={"u": P[:, 0]}, dofs=len(model.free), timings=timer.timings,
                      info={"load_steps": shots, "newton_iterations": iters, "ends": "mirror (nonlinear reflections)",
                            "spacing": dx, "horizon_factor": params["horizon"]})

    def solve(self, scene: Scene, params: dict) -> Result:
        if params["nonlinear"]:
            return self.solve_nonlinear(scene, params)
        timer = Timer()
        what = f"pd-bond-pair ({params['variant']}, {params['ends']} ends)"
        x = np.linspace(0.0, scene.length, params["points"])
        fields = {}
        if params["ends"] == "mirror":
            with timer("assemble"):
                K, b, free, binfo = self.assemble(scene, params)
            model = self.energy_model(scene, params)
            with timer("solve"):
                u, info = solve_linear(K, b, what=what)
                full = refine(model, K, b, free, u)
            w, fields["u"] = full[1::2], full[0::2]
        else:
            with timer("assemble"):
                K, b, fixed, binfo = self.assemble_taylor(scene, params)
                free = np.delete(np.arange(len(x)), fixed)
            with timer("solve"):
                w, info = solve_linear(K, b, what=what)
        dx = x[1] - x[0]
        flags = boundary_layer_warnings(scene, x, 4 * int(family(params["horizon"], dx, params["variant"])[0].max()) + 4)
        if flags:
            info.setdefault("warnings", []).extend(flags)
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"],
                    horizon=(params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=x, w=w, fields=fields,
                      rotation=np.gradient(w, dx, edge_order=2), dofs=len(free), timings=timer.timings, info=info)


MODELS = [PDBondPair()]
