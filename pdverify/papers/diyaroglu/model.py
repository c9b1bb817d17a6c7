"""Model ``pd-eb``: ordinary state-based PD Euler–Bernoulli beam (Diyaroglu, Oterkus & Oterkus).

One transverse DOF per material point, points x_k = k dx (ends included).

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

``corrected``: three changes, each measured in tests/test_pd_eb.py.
1. d calibrated on the DISCRETE family: c_j = beta_j / (j² dx² Σ beta), so kappa is exact for any
   quadratic (the paper's continuous d makes kappa too small by m / (m + 0.015) and K by its square).
2. partial volume of the last member: beta_j = clip(m - (j - 1/2), 0, 1) (beta_3 = 1/2 for m = 3).
3. boundaries by Taylor ghost points (design note §1): a degree-4 polynomial satisfying the support's
   conditions (clamped w = w' = 0; pinned w = 0, EI w'' = M̄; free EI w'' = M̄, EI w''' = -V̄; guided
   w' = 0, EI w''' = -V̄) is fitted to the first four real points and evaluated at 2J ghosts per end;
   end loads enter through M̄, V̄ (not as body forces), the support point's equation is w = 0.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.contract import Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer
from ...core.scene import Distributed, PointMoment, Scene
from ...numerics.band import Band
from ...numerics.families import ghost_stencil_system, partial_volumes, stencil_operator
from ...numerics.ghosts import curvature_end_rows, poly_ghosts, taylor_ghosts
from ...numerics.linalg import eliminate, solve_linear
from ...numerics.loads import body_loads, boundary_layer_warnings, end_loads

# -- kernels (arrays in, arrays out) ---------------------------------------------------------


def curvature_weights(m: float, dx: float, variant: str) -> np.ndarray:
    """c_j, j = 1..J, of kappa_k = Σ_j c_j (w_{k+j} + w_{k-j} - 2 w_k) (Eq. 11a with Eq. 32 or discrete)."""
    if variant == "paper":
        delta = (m + 0.015) * dx
        J = int(np.floor(delta / dx + 1e-12))
        j = np.arange(1, J + 1)
        return dx / (delta * j**2 * dx**2)  # d V / xi² with d = 1/(A delta), V = A dx
    j, beta = partial_volumes(m)
    return beta / (j**2 * dx**2 * beta.sum())


def curvature_operator(n_rows: int, row0: int, n_cols: int, c: np.ndarray) -> sp.csr_matrix:
    """Sparse D: rows are points row0 .. row0 + n_rows - 1 of a column grid of n_cols points."""
    J = len(c)
    j = np.arange(1, J + 1)
    offsets = np.concatenate([[0], -j, j])
    return stencil_operator(n_rows, row0, n_cols, offsets, np.concatenate([[-2.0 * c.sum()], c, c]))


def fixed_points(scene: Scene, n: int) -> list[int]:
    """End points held at w = 0 (clamped and pinned supports) of a grid of n points."""
    held = ("clamped", "pinned", "roller")  # no axial unknown: roller = pinned
    return [i for i, sup in ((0, scene.supports.left), (n - 1, scene.supports.right)) if sup in held]


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
    source = "Diyaroglu, Oterkus & Oterkus, PD Euler–Bernoulli beam (seed 000)"
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
        left, right = scene.supports.left, scene.supports.right
        if variant == "paper":
            K, b, fixed, info = self._assemble_paper(scene, x, c, a, A, left, right, params.get("reading", "energy"))
        else:
            K, b, fixed, info = self._assemble_corrected(scene, x, c, a, A, left, right)
        K.fix(fixed, b)  # master–slave elimination of the supported points (Eq. 39–42): w = 0 there
        return K, b, fixed, info

    # paper: energy form with mirror ghosts and Appendix free ends -------------------------
    def _assemble_paper(self, scene, x, c, a, A, left, right, reading="energy"):
        """The paper's boundary treatment in one of three readings (``reading``):

        * ``energy``: U = Σ over the real points of a kappa² V / 2 (Eq. 2, 10a), kappa (Eq. 11a) using the
          fictitious points as mirror images of real ones (w = T w_real, Eq. 39-41), K = a (D T)^T (D T):
          Eq. 42 applied to the real points' energy;
        * ``literal``: Eq. 37 written for every point of the extended grid, fictitious ones included (their
          kappa from the points that exist: the family truncated at the layer's outer edge), then
          K̂ = T^T K T (Eq. 42): the fictitious points' energy counts too;
        * ``layer``: ``literal`` with the fictitious layer of 2.015 dx at simply supported ends (Section
          "Simply supported boundary condition": two mirrored points; the real points whose family
          reaches past them use the horizon 2.015 dx with d = 1 / (A 2.015 dx), as Eq. A10-A12). In the
          energy reading the layer changes nothing: the only real point whose family reaches past it is
          the support point, whose curvature is zero under the negative mirror either way."""
        n, dx, J = len(x), x[1] - x[0], len(c)
        G = J
        D = curvature_operator(n, G, n + 2 * G, c).tocoo()
        keep = np.ones(D.nnz, bool)
        rr, cc, vv = [D.row], [D.col], [D.data]
        for side, sup in ((0, left), (1, right)):
            if sup != "free":
                continue
            o = 1 if side == 0 else -1
            for pnt in range(min(J, n)):
                k = pnt if side == 0 else n - 1 - pnt
                keep &= D.row != k
                e = k + G
                if pnt == 0:  # Eq. A1 with d1 = 1/(A dx): one-sided second difference
                    cols, vals = [e, e + o, e + 2 * o], [1 / dx**2, -2 / dx**2, 1 / dx**2]
                else:  # Eq. A7/A10: reduced horizon (p + 0.015) dx, d_p = 1/(A delta_p)
                    cp = curvature_weights(float(pnt), dx, "paper")
                    cols = [e] + [e + j for j in range(1, len(cp) + 1)] + [e - j for j in range(1, len(cp) + 1)]
                    vals = [-2 * cp.sum()] + list(cp) + list(cp)
                rr.append(np.full(len(cols), k))
                cc.append(np.array(cols))
                vv.append(np.array(vals))
        layer = {
            side: reading == "layer" and sup in ("pinned", "roller") and J > 2 for side, sup in ((0, left), (1, right))
        }
        for side in (0, 1):
            if not layer[side]:
                continue
            c2 = curvature_weights(2.0, dx, "paper")  # delta = 2.015 dx, d = 1 / (A delta)
            for pnt in range(J - 2):  # real points whose family would reach past the two fictitious points
                k = pnt if side == 0 else n - 1 - pnt
                keep &= D.row != k
                e = k + G
                rr.append(np.full(5, k)), cc.append(np.array([e, e + 1, e - 1, e + 2, e - 2]))
                vv.append(np.array([-2 * c2.sum(), c2[0], c2[0], c2[1], c2[1]]))
        rr[0], cc[0], vv[0] = D.row[keep], D.col[keep], D.data[keep]
        D = sp.csr_matrix((np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=D.shape)
        # master–slave map T: extended (ghost + real) <- real (Eq. 39–41)
        tr, tc, tv = [G + np.arange(n)], [np.arange(n)], [np.ones(n)]
        for side, sup in ((0, left), (1, right)):
            sign = {"clamped": 1.0, "guided": 1.0, "pinned": -1.0, "roller": -1.0, "free": 0.0}[sup]
            if sign == 0.0:
                continue
            j = np.arange(1, (2 if layer[side] else G) + 1)
            g = G - j if side == 0 else G + n - 1 + j
            r = j if side == 0 else n - 1 - j
            ok = (r >= 0) & (r < n)
            tr.append(g[ok]), tc.append(r[ok]), tv.append(np.full(ok.sum(), sign))
        T = sp.csr_matrix((np.concatenate(tv), (np.concatenate(tr), np.concatenate(tc))), shape=(n + 2 * G, n))
        if reading in ("literal", "layer"):  # Eq. 37 on the fictitious points of supported ends as well
            alive = np.zeros(n + 2 * G, bool)
            alive[np.unique(T.tocoo().row)] = True  # the real points and the fictitious points that exist
            ghosts = np.flatnonzero(alive & ((np.arange(n + 2 * G) < G) | (np.arange(n + 2 * G) >= G + n)))
            jj = np.arange(1, J + 1)
            cols = np.c_[ghosts, ghosts[:, None] - jj, ghosts[:, None] + jj]
            vals = np.broadcast_to(np.r_[-2 * c.sum(), c, c], cols.shape)
            ok = (cols >= 0) & (cols < n + 2 * G)
            ok[ok] = alive[cols[ok]]  # the family truncated at the layer's outer edge
            Dg = sp.csr_matrix(
                (vals[ok], (np.broadcast_to(np.arange(len(ghosts))[:, None], cols.shape)[ok], cols[ok])),
                shape=(len(ghosts), n + 2 * G),
            )
            D = sp.vstack([D, Dg]).tocsr()
        DT = D @ T
        K = Band.from_sparse(a * (DT.T @ DT))
        b = body_loads(scene, x) / A
        fixed = fixed_points(scene, n)
        return K, b, fixed, {"ghosts_per_end": G, "boundary": "mirror images, Appendix free ends", "reading": reading}

    # corrected: strong form with Taylor ghosts -----------------------------------------------
    def _assemble_corrected(self, scene, x, c, a, A, left, right):
        n, dx, J = len(x), x[1] - x[0], len(c)
        G = 2 * J
        # K_ext = a D2 D1 (D1: kappa on the real points and J ghosts each side; D2: on the real points),
        # a Toeplitz operator whose stencil is the self-convolution of the curvature stencil
        st = np.concatenate([c[::-1], [-2.0 * c.sum()], c])
        g_rows, g_cols, g_vals, e0, skip = self.ghosts(scene, n, dx, G)
        K, r = ghost_stencil_system(np.arange(-G, G + 1), a * np.convolve(st, st), G, n, g_rows, g_cols, g_vals, e0)
        b = body_loads(scene, x, skip_ends=skip) / A - r
        fixed = fixed_points(scene, n)
        return K, b, fixed, {"ghosts_per_end": G, "boundary": "Taylor ghost points (degree 4, 4 real points)"}

    @staticmethod
    def form(params: dict) -> str:
        f = params.get("form", "auto")
        return ("mixed" if params["variant"] == "corrected" else "direct") if f == "auto" else f

    def ghosts(self, scene: Scene, n: int, dx: float, G: int, curvature_ends: bool = False):
        """Taylor ghost points of both ends (design note §1): w_ghost = Gm w_real + g0.
        Returns (rows, cols, values) of the ghost rows of E in extended numbering (G ghosts, n real,
        G ghosts), the constant part e0 (length n + 2G) and the end loads handled by the ghosts.
        ``curvature_ends``: free and guided ends take their moment and shear through conditions on the
        curvature (:func:`curvature_end_rows`); their ghost w only extrapolate (free: cubic through the
        first four points; guided: degree 4 with w' = 0), so no third difference of w carries the shear."""
        P, C = end_loads(scene)
        EI = scene.EI
        p = min(4, n)
        er, ec, ev = [], [], []
        e0 = np.zeros(n + 2 * G)
        skip = {0: set(), n - 1: set()}
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            # internal moment and the third s-derivative coefficient EI d3w/ds3 at the end
            if side == 0:
                M_end, V3 = -C[0], -P[0]  # M(0+) = -C0, EI w'''(0) = P0 -> d3/ds3 = -w'''
            else:
                M_end, V3 = C[1], -P[1]  # M(L-) = C1, EI w'''(L) = -P1
            if curvature_ends and sup in ("free", "guided"):
                Gm, g0 = poly_ghosts((4,) if sup == "free" else (1,), G, p)[0], np.zeros(G)
            else:
                Gm, g0 = taylor_ghosts(sup, G, dx, M_end, V3, EI, p)
            real = np.arange(p) if side == 0 else n - 1 - np.arange(p)
            ghost = G - 1 - np.arange(G) if side == 0 else G + n + np.arange(G)
            er.append(np.repeat(ghost, p)), ec.append(np.tile(real, G)), ev.append(Gm.ravel())
            e0[ghost] = g0
            skip[0 if side == 0 else n - 1] = {"point_force", "point_moment"}  # end loads: in the ghosts or reactions
        return np.concatenate(er), np.concatenate(ec), np.concatenate(ev), e0, skip

    def assemble_mixed(self, scene: Scene, params: dict):
        """The corrected operator split in two second-order equations (``form = mixed``)::

            h² kappa - h² D1 (E w + e0) = 0      (kappa on the real points and J ghosts each side)
            h² D2 (h² kappa)            = h⁴ b / a

        the same discrete solution as a D2 D1 (E w + e0) = b, but the matrix of fourth differences
        (entries ~1/h⁴) is never formed, which lowers the round-off floor (tests/test_hard_cases.py).

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
        # ghost w (outside the beam) = Gm w_real + g0: onto the real columns of the kappa rows that reach them
        g_rows, g_cols, g_vals, e0, skip = self.ghosts(scene, n, dx, G, curvature_ends=True)
        gpos = g_rows - G  # ghost position (extended numbering -> grid position, < 0 or > n - 1)
        p = np.unique(np.clip(np.r_[np.arange(-J, J), np.arange(n - J, n + J)], -J, n - 1 + J))  # rows reaching a ghost
        ge, kp = np.nonzero(np.abs(gpos[:, None] - p[None, :]) <= J)  # (ghost entry, kappa row) within a family
        rows, cols = 2 * (p[kp] + J), 2 * (g_cols[ge] + J) + 1
        q = body_loads(scene, x, skip_ends=skip)
        P, C = end_loads(scene)
        ends = []  # free and guided ends: conditions on k instead of Taylor ghosts of w
        for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
            if sup in ("free", "guided"):
                M_end, V3 = (-C[0], -P[0]) if side == 0 else (C[1], -P[1])
                ends.append(
                    curvature_end_rows(
                        sup,
                        side,
                        n,
                        dx,
                        c,
                        M_end,
                        V3,
                        scene.EI,
                        q[0 if side == 0 else -1],
                        J,
                        lambda p_: 2 * (np.asarray(p_) + J),
                        lambda p_: 2 * (np.asarray(p_) + J) + 1,
                    )
                )
        off = (
            np.r_[cols - rows, -2 * J - 1, 2 * J + 1]
            if not ends
            else np.r_[cols - rows, -2 * J - 1, 2 * J + 1, np.concatenate([e[1] - e[0] for e in ends])]
        )
        M = Band(2 * npos, int(-off.min()), int(off.max()))
        # unknowns k_p = h² kappa_p and w_p (entries of order one): kappa rows (dof 0) k_p - h² Σ_o st_o w_{p+o},
        # w rows (dof 1) h² Σ_o st_o k_{p+o}
        blocks = {o: [[1.0 if o == 0 else 0.0, -h2 * st[o + J]], [h2 * st[o + J], 0.0]] for o in range(-J, J + 1)}
        M.add_block_stencil(2, blocks)
        M.add_entries(rows, cols, -h2 * st[gpos[ge] - p[kp] + J] * g_vals[ge])
        rhs = np.zeros(2 * npos)
        gp = np.unique(gpos)
        gi, kq = np.nonzero(np.abs(gp[:, None] - p[None, :]) <= J)
        np.add.at(rhs, 2 * (p[kq] + J), h2 * st[gp[gi] - p[kq] + J] * e0[gp[gi] + G])
        rhs[2 * J + 1 : 2 * (n + J) : 2] = q / A * h2 * h2 / a
        for e_rows, e_cols, e_vals, r_rows, r_vals in ends:
            M.clear_rows(np.unique(e_rows))
            M.add_entries(e_rows, e_cols, e_vals)
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
            # the banded LU eliminates from the left end: a guided end there amplifies round-off (measured,
            # guided-clamped, mixed loads, 10,001 points: 1.5e-6 in this order, 2.2e-8 reversed; 100,001:
            # 1.6e-3 against 3.0e-7), so such a scene is solved as its mirror image and flipped back
            flip = scene.supports.left == "guided" and scene.supports.right != "guided"
            with timer("assemble"):
                system = self.assemble(mirror_scene(scene) if flip else scene, params)
            with timer("solve"):
                z, info = solve_linear(system.matrix, system.rhs, what="pd-eb (corrected, mixed form)")
                n = params["points"]
                J = (system.matrix.n // 2 - n) // 2  # positions -J .. n-1+J, two unknowns each
                w = z[2 * J + 1 : 2 * (n + J) : 2].copy()
                if flip:
                    w = w[::-1].copy()
        else:
            with timer("assemble"):
                system = self.assemble(scene, params)
            with timer("solve"):
                w, info = solve_linear(system.matrix, system.rhs, what=f"pd-eb ({params['variant']})")
        ndofs, binfo = system.unknowns, system.info  # mixed: kappa on every position, w on the free points
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        rot = np.gradient(w, dx, edge_order=2)
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        info.update(binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        flags = boundary_layer_warnings(
            scene, x, 2 * len(curvature_weights(params["horizon"], dx, params["variant"])) + 4
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
