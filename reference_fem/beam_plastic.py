"""``fem-eb`` along a load path: cubic Hermite Euler-Bernoulli elements whose sections are integrated over fibres of
an elastic-perfectly plastic material, for any supports (the reference of indeterminate plastic beams).

Each element has ``GAUSS`` Gauss-Legendre points along its length; at each, the section is ``fibres`` layers of the
width profile b(y) (two Gauss points per layer: the elastic section's area and second moment exactly) with the
plastic strain of each fibre as its history. A fibre's strain is eps = kappa y (y from the centroid, kappa = w'' =
B u_e); its stress the return mapping sigma = E (eps - eps_p) capped at +-sigma_y (the cap moves eps_p), its tangent
E or 0. The section's M = Σ sigma y dA and tangent Σ E_t y² dA are the consistent ones, so Newton on
K_t du = lambda F - f_int(u) is exact once the set of yielded fibres repeats (the law is piecewise linear).

Supports hold their DOFs, springs add their stiffness, a prescribed deflection holds its node at lambda times its value;
a step's increment of it enters the first Newton iteration, linearised at the converged state (K_ff du_f = r_f - K_fh
du_h), not as a kink imposed on that state. A step whose Newton does not settle is halved up to ``CUTS`` times; then the
path stops with one line and keeps the steps so far (collapse: a hinge, no equilibrium past it). The discrete beam's
hinge is not a perfect mechanism (a Gauss point's section yields whole while its element's others keep an elastic core),
so past collapse Newton can settle on deflections hundreds of lengths large: a step whose stiffness, dλ over the largest
change of w, is below ``COLLAPSE`` times the first loading step's stops the path the same way (Bergan's current
stiffness parameter; Bergan et al. 1978, Comput. Methods Appl. Mech. Eng. 14). Arrays in, arrays out: no loops over
elements or fibres (the loop is over Newton iterations and steps).

The fibres' quadrature of a yielded section is second order in the layer thickness (the elastic core's edge is a
kink of sigma(y) inside one layer), and the elements' of the curvature field at the plastic zone's edge likewise.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from pdverify.core.errors import InputError, SolveError
from pdverify.core.loading import Displacement, Loading
from pdverify.core.scene import Scene

from .beam_elements import (
    beam_nodes,
    constrained_dofs,
    element_loads,
    hermite_shapes,
    nodal_point_loads,
    spring_dofs,
    support_nodes,
)

GAUSS = 4  # Gauss points per element (the curvature is linear in each element; its M(kappa) is not)
CUTS = 8  # halvings of a step before the path stops
NEWTON = 60  # Newton iterations per step at most
TOL = 1e-13  # the residual relative to the element forces' scale (or: the yielded set repeats)
COLLAPSE = 1e-4  # a step whose stiffness dλ / max|dw| falls below this share of the first step's is past collapse
# the last converged factor over the beam's collapse factor, less 1, per element length over the beam's: 1.25 h / L at
# a clamped-clamped beam (uniform load or centre force), 0.82 propped cantilever, 0.62 simply supported centre force;
# 40, 80, 160 elements (docs/exact.md, "fem-eb" limits)
COLLAPSE_OVERSHOOT = 1.3


def fibre_rule(prof, count: int) -> tuple[np.ndarray, np.ndarray]:
    """(y, dA): the fibres of the profile, y from the centroid: about ``count`` layers spread over the pieces by
    their height, two Gauss-Legendre points each (b linear on a piece: the area and second moment exact)."""
    gx, gw = np.polynomial.legendre.leggauss(2)
    pieces = prof.pieces
    layers = np.maximum(1, np.round(count * (pieces[:, 1] - pieces[:, 0]) / prof.height)).astype(int)
    y0 = np.repeat(pieces[:, 0], layers)
    span = np.repeat((pieces[:, 1] - pieces[:, 0]) / layers, layers)
    k = np.concatenate([np.arange(n) for n in layers])
    a = y0 + k * span
    y = (a[:, None] + 0.5 * span[:, None] * (gx[None, :] + 1)).ravel()
    dA = (0.5 * span[:, None] * gw[None, :]).ravel() * prof.width(y)
    return y - prof.centroid, dA


def curvature_matrix(l: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """(n_el, n_gauss, 4): w'' at xi (in [0, 1]) of the Hermite shape functions (w_i, w'_i, w_j, w'_j)."""
    L = l[:, None]
    return np.stack(
        [(12 * xi - 6) / L**2, (6 * xi - 4) / L + 0 * xi, (6 - 12 * xi) / L**2, (6 * xi - 2) / L + 0 * xi], axis=-1
    )


class FibreBeam:
    """The discrete problem of one scene: nodes, elements, fibres, loads, held DOFs."""

    def __init__(self, scene: Scene, points: int, fibres: int):
        if scene.segments:
            raise InputError("segments: fem-eb's load path takes one section and material; drop [[segments]]")
        prof, mat = scene.section.profile, scene.material
        if prof is None:
            raise InputError(
                "section: fem-eb's fibres need the section's shape; give width and height or a shape (I, profile)"
            )
        if mat.failure_strain is not None:
            raise InputError(
                "material.failure_strain: fem-eb's fibres yield but do not break; use exact-eb (first failure) or "
                "pd-bond-pair"
            )
        self.scene, self.E = scene, mat.E
        self.sy = mat.yield_stress if mat.yield_stress is not None else np.inf
        self.nodes = beam_nodes(scene, points)
        self.l = np.diff(self.nodes)
        gx, gw = np.polynomial.legendre.leggauss(GAUSS)
        self.xi, self.gw = 0.5 * (gx + 1), 0.5 * gw
        self.B = curvature_matrix(self.l, self.xi)
        self.y, self.dA = fibre_rule(prof, fibres)
        self.area = prof.area
        n_el = len(self.l)
        self.dofs = 2 * np.arange(n_el)[:, None] + np.arange(4)[None, :]
        self.rows = np.broadcast_to(self.dofs[:, :, None], (n_el, 4, 4)).ravel()
        self.cols = np.broadcast_to(self.dofs[:, None, :], (n_el, 4, 4)).ravel()
        N = 2 * len(self.nodes)
        fe = element_loads(scene, self.nodes, hermite_shapes)
        self.F1 = np.bincount(self.dofs.ravel(), fe.ravel(), minlength=N) + nodal_point_loads(scene, self.nodes, 2)
        self.springs = spring_dofs(scene, self.nodes)
        held = list(constrained_dofs(scene, self.nodes))
        self.shown = [ld for ld in scene.loads if isinstance(ld, Displacement)]
        self.shown_dofs = [2 * int(np.argmin(np.abs(self.nodes - ld.position))) for ld in self.shown]
        self.held = np.array(sorted(set(held) | set(self.shown_dofs)), int)
        self.free = np.setdiff1d(np.arange(N), self.held)
        self.iterations = 0  # Newton iterations (tangent solves) over the path, cut steps included

    def held_values(self, factor: float) -> np.ndarray:
        u = np.zeros(2 * len(self.nodes))
        for ld, d in zip(self.shown, self.shown_dofs):
            u[d] = factor * ld.value
        return u

    def section(self, u: np.ndarray, eps_p: np.ndarray):
        """(kappa, M, k_t, trial yield mask, eps_p') at every Gauss point from the nodal u and the fibres' history."""
        kappa = np.einsum("egk,ek->eg", self.B, u[self.dofs])
        strain = kappa[..., None] * self.y
        trial = self.E * (strain - eps_p)
        over = np.abs(trial) > self.sy
        sigma = np.where(over, np.sign(trial) * self.sy, trial)
        M = sigma @ (self.dA * self.y)
        kt = (~over * self.E) @ (self.dA * self.y**2)
        return kappa, M, kt, over, np.where(over, strain - sigma / self.E, eps_p)

    def forces(self, u, eps_p):
        """(f_int + springs, K_t, state, magnitude): the internal force vector, the consistent tangent (CSR), the
        new fibre state and the size of the element forces summed into each row (the residual's round-off scale)."""
        kappa, M, kt, over, ep = self.section(u, eps_p)
        w = self.l[:, None] * self.gw[None, :]
        fe = np.einsum("egk,eg->ek", self.B, M * w)
        Ke = np.einsum("egk,eg,egm->ekm", self.B, kt * w, self.B)
        N = 2 * len(self.nodes)
        f = np.bincount(self.dofs.ravel(), fe.ravel(), minlength=N)
        mag = np.bincount(self.dofs.ravel(), np.abs(fe).ravel(), minlength=N)
        K = sp.coo_matrix((Ke.ravel(), (self.rows, self.cols)), shape=(N, N)).tocsr()
        d, k = self.springs
        if len(d):
            f[d] += k * u[d]
            K = K + sp.csr_matrix((k, (d, d)), shape=(N, N))
            mag[d] += np.abs(k * u[d])
        return f, K, (over, ep), mag

    def equilibrium(self, factor: float, u0: np.ndarray, eps_p: np.ndarray):
        """(u, f_int, over, eps_p'): Newton from u0 at ``factor``; SolveError when it does not settle."""
        u = u0.copy()
        dh = self.held_values(factor)[self.held] - u0[self.held]  # the prescribed deflections' increment
        dh = dh if np.any(dh) else None
        F = factor * self.F1
        fr = self.free
        last, before = None, np.inf
        for _ in range(NEWTON):
            f, K, (over, ep), mag = self.forces(u, eps_p)
            r = (F - f)[fr]
            if dh is not None:
                # the first iteration is linearised at u0 with the held DOFs' increment inside it: K_ff du_f =
                # r_f - K_fh du_h (Newton on the constrained system). Setting u_h first instead puts the increment
                # as a kink in one element at the converged state (curvature ~ 6 du_h / l^2, growing with the grid),
                # whose fibres yield before the step's load does
                r = r - K[fr][:, self.held] @ dh
                u[self.held] += dh
                size, dh = np.inf, None
            else:
                size = np.abs(r).max()
            # the law is piecewise linear: once the yielded set at u is the one whose tangent gave u, the corrections
            # are iterative refinement of that linear system (the direct K rounds like N^4 eps); they stop when the
            # residual, computed from the element forces, no longer halves
            if size <= TOL * max(np.abs(F).max(), mag.max(), 1e-300) or (
                np.array_equal(over, last) and size > 0.5 * before
            ):
                return u, f, over, ep
            before = size if np.array_equal(over, last) else np.inf
            self.iterations += 1
            try:
                du = spla.splu(K[fr][:, fr].tocsc()).solve(r)
            except RuntimeError:
                raise SolveError("fem-eb: the tangent stiffness is singular (a hinge: a mechanism)") from None
            if not np.all(np.isfinite(du)):
                raise SolveError("fem-eb: the tangent stiffness is singular (a hinge: a mechanism)")
            u[fr] += du
            last = over
        raise SolveError(f"fem-eb: Newton did not settle in {NEWTON} iterations (no equilibrium: past collapse)")

    def reactions(self, f: np.ndarray, factor: float) -> dict:
        R = f - factor * self.F1
        out = {}
        for label, k, sup in support_nodes(self.scene, self.nodes):
            force, moment = float(R[2 * k]), float(R[2 * k + 1])
            if label.startswith("inner"):
                if sup.holds_deflection:
                    out[f"force_{label}"] = force
                if sup.holds_rotation:
                    out[f"moment_{label}"] = moment
            else:
                out[f"force_{label}"], out[f"moment_{label}"] = force, moment
        for i, d in enumerate(self.shown_dofs):
            out[f"force_displacement_{i}"] = float(R[d])
        return out

    def health(self, ever: np.ndarray) -> tuple[np.ndarray, float]:
        """(health at the nodes, plastic zone): the area fraction of the section never yielded, at the Gauss points
        interpolated to the nodes, and the length of beam whose Gauss points yielded (weights of the rule)."""
        h = 1.0 - (ever * self.dA).sum(-1) / self.area
        xg = (self.nodes[:-1, None] + self.l[:, None] * self.xi[None, :]).ravel()
        zone = float(np.sum((self.l[:, None] * self.gw[None, :])[h < 1.0]))
        return np.interp(self.nodes, xg, h.ravel()), zone


def solve_path(scene: Scene, points: int, fibres: int):
    """(nodes, u, path, info): the scene's ``[loading]`` (default [0, 1] in 10 steps) on the fibre beam."""
    beam = FibreBeam(scene, points, fibres)
    factors = (scene.loading or Loading()).path()
    N, shape = 2 * len(beam.nodes), (len(beam.l), GAUSS, len(beam.y))
    u, ep, ever = np.zeros(N), np.zeros(shape), np.zeros(shape, bool)
    steps, stop, lam, first = [], None, 0.0, None  # first: the first loading step's stiffness d factor / max |dw|
    targets = list(factors)
    for target in targets:
        cut, t = 0, target
        while True:
            try:
                un, f, over, epn = beam.equilibrium(t, u, ep)
            except SolveError as exc:
                if cut >= CUTS:
                    stop = (
                        f"the path stops at load factor {lam:.6g} (the step to {t:.6g}: {exc}); the steps so far "
                        "are kept"
                    )
                    break
                cut, t = cut + 1, lam + 0.5 * (t - lam)
                continue
            dw = float(np.abs(un[0::2] - u[0::2]).max())
            stiff = abs(t - lam) / dw if dw > 0 else np.inf
            if first is None and np.isfinite(stiff) and stiff > 0:
                first = stiff
            elif first is not None and stiff < COLLAPSE * first:
                over = COLLAPSE_OVERSHOOT * float(beam.l.max()) / scene.length
                stop = (
                    f"the path stops at load factor {lam:.6g}: the step to {t:.6g} has {stiff / first:.1e} of the "
                    "first step's stiffness (a hinge: the beam collapses); the steps so far are kept. Displacement "
                    "elements find the collapse above the beam's (their Gauss points miss the hinge's peak moment, "
                    f"first order in the element length): this factor may exceed the beam's collapse by up to about "
                    f"{over:.1%} ({COLLAPSE_OVERSHOOT:g} h / L), and the steps past that carry loads no real beam can"
                )
                break
            u, ep, lam = un, epn, t
            ever |= over
            health, zone = beam.health(ever)
            steps.append(
                {
                    "factor": float(t),
                    "w": u[0::2].copy(),
                    "reactions": beam.reactions(f, t),
                    "plastic_zone": zone,
                    "health": health,
                    "cut_back": int(cut),
                }
            )
            if t == target:
                break
            cut, t = 0, target
        if stop is not None:
            break
    if len(steps) < 2 and stop is not None:  # no step past the first corner: a failure, as in the other path models
        raise SolveError(f"fem-eb: {stop.replace('; the steps so far are kept', '')}")
    info = {
        "load_path": {
            "factors": [float(v) for v in (scene.loading or Loading()).factors],
            "steps": len(steps),
            "completed": stop is None,
            "last_factor": steps[-1]["factor"],
            "fibres": int(len(beam.y)),
            "gauss_points": GAUSS,
            "elements": int(len(beam.l)),
            "newton_iterations": beam.iterations,
        },
        "reactions": steps[-1]["reactions"],
    }
    if stop is not None:
        info.setdefault("warnings", []).append(stop)
    return beam.nodes, u, steps, info
