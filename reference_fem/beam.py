"""Beam references: ``fem-eb`` (cubic Hermite, scikit-fem; ANSYS BEAM3 analogue) and
``fem-timoshenko`` (interdependent interpolation element, locking-free; naive variants for contrast).

Both put every load position and every span end on a node, so the nodal values are those of the
exact beam theory for any straight scene (Tong's theorem: the shape functions solve the homogeneous
equations, and the loads are work-equivalent, integrated by 12-point Gauss per element, which is
exact to round-off for the uniform and sine loads of the scene format).

By default (``form = mixed``) both solve their elements' stiffness as the two-field system of
:func:`natural_band` (the same K = T^T F^-1 T, round-off ~N^2 eps at most instead of the direct K's
~N^4 eps: within 1e-13 of the exact solution up to 10^6 nodes); ``form = direct`` solves K itself.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.interpolate import CubicHermiteSpline

from pdverify.band import Band
from pdverify.linalg import eliminate, solve_linear
from pdverify.registry import Model, Option, System
from pdverify.result import Result, Timer
from pdverify.scene import Distributed, PointForce, PointMoment, Scene

_GX, _GW = np.polynomial.legendre.leggauss(12)


def beam_nodes(scene: Scene, points: int) -> np.ndarray:
    """Uniform nodes plus every load position and span end (one within 1e-12 L of a node is that node)."""
    L = scene.length
    extra = []
    for load in scene.loads:
        if isinstance(load, Distributed):
            extra.extend(scene.span(load))
        else:
            extra.append(load.position)
    x = np.linspace(0, L, points)
    e = np.unique(np.asarray(extra, float))
    e = e[np.concatenate([[True], np.diff(e) > 1e-12 * L])] if len(e) else e
    i = np.searchsorted(x, e)  # x[i - 1] < e <= x[i]: the nearest nodes are i - 1 and i
    near = np.minimum(np.abs(x[np.minimum(i, points - 1)] - e), np.abs(x[np.maximum(i - 1, 0)] - e))
    new = near > 1e-12 * L
    return np.insert(x, i[new], e[new])  # sorted, no O(n log n) sort of the whole grid


def line_load(scene: Scene, x: np.ndarray) -> np.ndarray:
    """q(x) of all distributed loads (N/m) at points x (span ends are nodes: no straddling)."""
    q = np.zeros_like(x)
    for load in scene.loads:
        if isinstance(load, Distributed):
            a, b = scene.span(load)
            on = (x >= a) & (x <= b)
            v = load.value if load.shape == "uniform" else load.value * np.sin(np.pi * x / scene.length)
            q += np.where(on, v, 0.0)
    return q


def element_loads(scene: Scene, nodes: np.ndarray, shape_fns, chunk: int = 1 << 16) -> np.ndarray:
    """Work-equivalent element load vectors ∫ q N_i dx, (n_el, 4), by Gauss quadrature (in blocks of
    ``chunk`` elements: the (4, n_el, 12) shape-function array of 10^6 elements is 400 MB)."""
    fe = np.zeros((len(nodes) - 1, 4))
    if not any(isinstance(load, Distributed) for load in scene.loads):
        return fe
    xi = (_GX + 1) / 2
    for e0 in range(0, len(fe), chunk):  # blocks of elements, not a loop over elements
        e1 = min(e0 + chunk, len(fe))
        x0, l = nodes[e0:e1, None], np.diff(nodes[e0 : e1 + 1])[:, None]
        q = line_load(scene, x0 + l * xi[None, :])
        N = shape_fns(xi[None, :], l)  # (4, n_el, nq)
        fe[e0:e1] = np.einsum("ieq,eq,q->ei", N, q * l, _GW / 2)
    return fe


def nodal_point_loads(scene: Scene, nodes: np.ndarray, ndof: int) -> np.ndarray:
    F = np.zeros(2 * len(nodes))
    for load in scene.loads:
        if isinstance(load, (PointForce, PointMoment)):
            i = int(np.argmin(np.abs(nodes - load.position)))
            F[2 * i + (0 if isinstance(load, PointForce) else 1)] += load.value
    return F


def element_band(ke: np.ndarray, n_nodes: int) -> Band:
    """(n_el, 4, 4) element matrices with DOFs (w_i, r_i, w_j, r_j) scattered into a :class:`Band`.

    Element e's DOFs are 2e .. 2e + 3, so K is banded (offsets -3..3): each diagonal is accumulated by
    strided slice additions (no COO triplets to sort and sum: ~10x faster at 10^6 elements). ``ke`` may
    be a view of a (4, 4, n_el) array (:func:`hermite_stiffness`): then each ke[:, a, b] is contiguous."""
    n_el = ke.shape[0]
    K = Band(2 * n_nodes, 3, 3)
    for k in range(-3, 4):
        d = K.diag(k)
        for a in range(4):
            b = a + k
            if 0 <= b <= 3:
                row0 = a if k >= 0 else b  # index along the diagonal = min(row, col)
                d[row0 : row0 + 2 * n_el : 2] += ke[:, a, b]
    return K


def hermite_stiffness(l: np.ndarray, coef: np.ndarray, f: np.ndarray | float = 0.0) -> np.ndarray:
    """(n_el, 4, 4) view of the cubic element matrices coef [[12, 6l, -12, 6l], [6l, (4+f)l², -6l, (2-f)l²],
    ...] (f = 0: Euler–Bernoulli Hermite, coef = EI/l³; f = Phi: the IIE Timoshenko element,
    coef = EI/((1+f) l³)), stored entry-major so each entry over the elements is contiguous."""
    kt = np.empty((4, 4, len(l)))
    kt[0, 0] = kt[2, 2] = 12 * coef
    kt[0, 2] = kt[2, 0] = -12 * coef
    kt[0, 1] = kt[1, 0] = kt[0, 3] = kt[3, 0] = 6 * l * coef
    kt[1, 2] = kt[2, 1] = kt[2, 3] = kt[3, 2] = -6 * l * coef
    kt[1, 1] = kt[3, 3] = (4 + f) * l**2 * coef
    kt[1, 3] = kt[3, 1] = (2 - f) * l**2 * coef
    return kt.transpose(2, 0, 1)


def natural_band(l: np.ndarray, EI: float, kGA: float | None = None) -> tuple[Band, np.ndarray]:
    """The same elements' stiffness K_e = T_e^T F_e^-1 T_e as a two-field (displacement + end moment) system.

    T_e maps the element DOFs (w_i, r_i, w_j, r_j) to its natural deformations, the end rotations
    relative to the chord, d_a = r_i - (w_j - w_i)/l and d_b = r_j - (w_j - w_i)/l; F_e is the element
    flexibility that returns them from its end moments m = (m_a, m_b) (Argyris' natural modes;
    Przemieniecki, Theory of Matrix Structural Analysis, ch. 6):
        F_e = l/(6 EI) [[2, -1], [-1, 2]] + 1/(kGA l) [[1, 1], [1, 1]]   (the second term Timoshenko's),
    and T^T F^-1 T is exactly the cubic Hermite matrix (Phi = 0) or the IIE matrix (:func:`hermite_stiffness`).
    Written in the element's symmetric and antisymmetric end moments, m_a = p + q, m_b = p - q, F_e is
    diagonal, diag(l/(3 EI) + 4/(kGA l), l/EI), and the deformations are d_a + d_b = r_i + r_j - 2 (w_j - w_i)/l
    and d_a - d_b = r_i - r_j: the bending flexibility l/EI is then never the small difference of two
    shear-dominated entries (a thick element at 10^6 nodes has Phi ~ 1e8).
    The system  [[0, T^T], [T, -F]] [u; (p, q)] = [f; 0]  has the same u as K u = f, but first differences
    (entries 1 and 2/l) instead of K's third: its round-off grows like N^2 eps at most, not N^4 eps (the
    second-order conditioning of pd-eb's mixed form). Unknowns per node i: (w_i, r_i, p, q of element i);
    the last node has no element: 4 n - 2 unknowns, bandwidths (3, 3).
    Returns (band, s): s, powers of two, the symmetric scaling whose largest entry per row and column is ~1."""
    ne = len(l)
    K = Band(4 * ne + 2, 3, 3)
    fp, fq = flexibility(l, EI, kGA)

    def put(ra, ca, v):  # entry (4e + ra, 4e + ca) of every element e
        o = ca - ra
        k0 = ra - max(0, -o)
        K.diag(o)[k0 : k0 + 4 * ne : 4] += v

    put(2, 2, -fp)
    put(3, 3, -fq)
    for ra, ca, v in ((2, 0, 2 / l), (2, 1, 1.0), (2, 4, -2 / l), (2, 5, 1.0), (3, 1, 1.0), (3, 5, -1.0)):
        put(ra, ca, v)
        put(ca, ra, v)  # T^T
    sp_, sq = 1 / np.sqrt(fp), 1 / np.sqrt(fq)
    s = np.empty(4 * ne + 2)
    s[2::4], s[3::4] = sp_, sq

    def largest_adjacent(v):  # per node, max of v over the elements left and right of it
        return np.maximum(np.concatenate([[0.0], v]), np.concatenate([v, [0.0]]))

    s[1::4] = 1 / largest_adjacent(np.maximum(sp_, sq))  # entries 1 of T
    s[0::4] = 1 / largest_adjacent(2 * sp_ / l)  # entries 2/l of T
    return K, 2.0 ** np.round(np.log2(s))  # powers of two: the scaling rounds no entry


def flexibility(l: np.ndarray, EI: float, kGA: float | None) -> tuple[np.ndarray, np.ndarray]:
    """(F_p, F_q): each element's flexibility for its symmetric and antisymmetric end moments (:func:`natural_band`)."""
    return l / (3 * EI) + (0.0 if kGA is None else 4 / (kGA * l)), l / EI


def natural_magnitude(l: np.ndarray, EI: float, kGA: float | None, b: np.ndarray):
    """u -> the size of each row's independently rounded terms in the system of :func:`natural_band`
    (for :func:`pdverify.linalg.forward_error_bound`): a row of T holds one rounded 2/l for both w's, so
    its term is 2 |w_i - w_j| / l, not 2 |w_i| / l + 2 |w_j| / l; the entries 1 are exact; F's entries and
    the loads are rounded once each."""
    fp, fq = flexibility(l, EI, kGA)

    def magnitude(z):
        w, p, q = z[0::4], z[2::4], z[3::4]
        m = np.abs(b).copy()
        m[2::4] += 2 * np.abs(np.diff(w)) / l + np.abs(fp * p)
        m[3::4] += np.abs(fq * q)
        pair = 2 * np.abs(p) / l
        m[0:-2:4] += pair
        m[4::4] += pair
        return m

    return magnitude


def element_vector(fe: np.ndarray, n_nodes: int) -> np.ndarray:
    """(n_el, 4) element vectors summed into the global vector (DOFs 2e .. 2e + 3)."""
    F = np.zeros(2 * n_nodes)
    for a in range(4):
        F[a : a + 2 * len(fe) : 2] += fe[:, a]
    return F


def assemble_elements(ke: np.ndarray, fe: np.ndarray, n_nodes: int):
    """(K, F): the global sparse K (CSR, from :func:`element_band`) and load vector."""
    return element_band(ke, n_nodes).tocsr(), element_vector(fe, n_nodes)


def constrained_dofs(scene: Scene, n_nodes: int) -> np.ndarray:
    fix = {"clamped": (0, 1), "pinned": (0,), "roller": (0,), "guided": (1,), "free": ()}  # roller = pinned in w
    out = [2 * 0 + d for d in fix[scene.supports.left]]
    out += [2 * (n_nodes - 1) + d for d in fix[scene.supports.right]]
    return np.array(out, dtype=int)


def reduce_supports(scene: Scene, K, F, n_nodes: int):
    """Eliminate the supported DOFs: (K_ff, F_f, free)."""
    return eliminate(K, F, constrained_dofs(scene, n_nodes))


def hold_supports(scene: Scene, K: Band, F: np.ndarray, n_nodes: int) -> tuple[Band, np.ndarray, int]:
    """The supported DOFs held at zero in place (unit rows, cleared columns): (K, F, free DOF count)."""
    fixed = constrained_dofs(scene, n_nodes)
    K.fix(fixed, F)
    return K, F, 2 * n_nodes - len(fixed)


class _BeamFE(Model):
    """Shared by the two beam elements: ``assemble_band`` gives (K, F, nodes) before the supports."""

    def assemble_band(self, scene: Scene, params: dict):  # pragma: no cover - interface
        raise NotImplementedError

    assembles = True

    def assemble(self, scene: Scene, params: dict) -> System:
        """The system ``solve`` factorises: the two-field band of :meth:`assemble_mixed` (``form = mixed``), or
        the band of :meth:`assemble_band` with the supported DOFs held (unit rows, cleared columns); free: the
        unknowns not held (two-field: w_i, w'_i or theta_i and the element end moments)."""
        if self.mixed(params):
            K, b, nodes, s, magnitude = self.assemble_mixed(scene, params)
            held = 4 * (constrained_dofs(scene, len(nodes)) // 2) + constrained_dofs(scene, len(nodes)) % 2
            return System(K, b, np.delete(np.arange(K.n), held), {"nodes": nodes, "scaling": s, "magnitude": magnitude})
        K, F, nodes = self.assemble_band(scene, params)
        fixed = constrained_dofs(scene, len(nodes))
        K, F, _ = hold_supports(scene, K, F, len(nodes))
        return System(K, F, np.delete(np.arange(2 * len(nodes)), fixed), {"nodes": nodes})

    def mixed(self, params: dict) -> bool:
        """True when the two-field form (:func:`natural_band`) is solved; the elements' own stiffness K
        (``form = direct``) otherwise and for the linear contrast variants, which have no such form."""
        return params.get("form", "mixed") == "mixed" and params.get("variant", "iie") == "iie"

    def nodal_loads(self, scene: Scene, params: dict, nodes: np.ndarray) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError

    def shear_stiffness(self, scene: Scene) -> float | None:
        return None

    def assemble_mixed(self, scene: Scene, params: dict):
        """(band, rhs, nodes, scaling) of the two-field system with the supports held (:func:`natural_band`)."""
        nodes = beam_nodes(scene, params["points"])
        K, s = natural_band(np.diff(nodes), scene.EI, self.shear_stiffness(scene))
        F = self.nodal_loads(scene, params, nodes)
        b = np.zeros(K.n)
        b[0::4], b[1::4] = F[0::2], F[1::2]
        fixed = constrained_dofs(scene, len(nodes))
        held = 4 * (fixed // 2) + fixed % 2
        K.fix(held, b)
        s[held] = 1.0
        return K, b, nodes, s, natural_magnitude(np.diff(nodes), scene.EI, self.shear_stiffness(scene), b)

    def element(self, params: dict) -> str:  # pragma: no cover - interface
        """The element's name, in info["element"]."""
        raise NotImplementedError

    def what(self, params: dict) -> str:
        """The solve's name in its messages."""
        return self.name

    def solve(self, scene: Scene, params: dict) -> Result:
        u, info, dofs, nodes, timer = self.solve_nodal(scene, params, self.what(params))
        info.update(element=self.element(params), elements=len(nodes) - 1)
        return self.new_result(
            scene,
            params,
            nodes,
            u[0::2],
            rotation=u[1::2],
            dofs=dofs,
            timings=timer.timings,
            info=info,
        )

    def solve_nodal(self, scene: Scene, params: dict, what: str):
        """(u, info, free DOF count, nodes, timer): nodal DOFs (w_i, w'_i or theta_i) interleaved."""
        timer = Timer()
        if self.mixed(params):
            with timer("assemble"):
                system = self.assemble(scene, params)
            K, b, nodes = system.matrix, system.rhs, system.info["nodes"]
            with timer("solve"):
                z, info = solve_linear(
                    K,
                    b,
                    what=what,
                    scaling=system.info["scaling"],
                    watch=np.arange(0, K.n, 4),
                    magnitude=system.info["magnitude"],
                    refine_in_place=True,
                )
            u = np.empty(2 * len(nodes))
            u[0::2], u[1::2] = z[0::4], z[1::4]
            info["form"] = "two-field (displacements and element end moments, K = T^T F^-1 T)"
            return u, info, system.unknowns, nodes, timer
        with timer("assemble"):
            system = self.assemble(scene, params)
        with timer("solve"):
            u, info = solve_linear(system.matrix, system.rhs, what=what, watch=np.arange(0, system.matrix.n, 2))
        info["form"] = "direct (the assembled stiffness K)"
        return u, info, system.unknowns, system.info["nodes"], timer


def hermite_shapes(xi, l):
    """Cubic Hermite shape functions (w1, w1', w2, w2') on [0, l], xi = s / l."""
    return np.stack(
        np.broadcast_arrays(
            1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-(xi**2) + xi**3)
        )
    )


FORM = Option(
    "form",
    str,
    "mixed",
    "mixed (two-field: displacements and element end moments, the same element's "
    "K = T^T F^-1 T; round-off ~N^2 eps at most) | direct (K itself; ~N^4 eps)",
    choices=("mixed", "direct"),
)


class FemEulerBernoulli(_BeamFE):
    name = "fem-eb"
    title = "Euler–Bernoulli beam, cubic Hermite elements (scikit-fem; BEAM3 analogue)"
    source = (
        "cubic Hermite element, two-field K = T^T F^-1 T (form=direct: scikit-fem ElementLineHermite up to "
        "20,001 nodes); nodally exact (loads on nodes)"
    )
    options = (Option("points", int, 101, "nodes along the beam before load positions are added", minimum=2), FORM)

    SKFEM_MAX_NODES = 20_001  # ElementLineHermite inverts a global-coordinate Vandermonde per element:
    # singular in float64 for elements below ~1e-4 of the coordinates; the closed form takes over there

    def assemble_band(self, scene: Scene, params: dict, use_skfem: bool | None = None):
        """(K, F, nodes) before the supports, K a :class:`Band`."""
        nodes = beam_nodes(scene, params["points"])
        if use_skfem is None:
            use_skfem = len(nodes) <= self.SKFEM_MAX_NODES
        if not use_skfem:
            l = np.diff(nodes)
            ke = hermite_stiffness(l, scene.EI / l**3)
            F = element_vector(element_loads(scene, nodes, hermite_shapes), len(nodes))
            return element_band(ke, len(nodes)), F + nodal_point_loads(scene, nodes, 2), nodes
        import skfem as fem
        from skfem.helpers import dd, ddot

        mesh = fem.MeshLine(nodes)
        basis = fem.Basis(mesh, fem.ElementLineHermite(), intorder=12)

        @fem.BilinearForm
        def bending(u, v, w):
            return scene.EI * ddot(dd(u), dd(v))

        @fem.LinearForm
        def load(v, w):
            return line_load(scene, w.x[0]) * v

        K = bending.assemble(basis).tocsr()
        F = load.assemble(basis)
        # scikit-fem orders DOFs as basis.nodal_dofs; for ElementLineHermite that is (w_i, w'_i) interleaved
        assert np.array_equal(basis.nodal_dofs[0], 2 * np.arange(len(nodes)))
        F = F + nodal_point_loads(scene, nodes, 2)
        return Band.from_sparse(K), F, nodes

    def nodal_loads(self, scene: Scene, params: dict, nodes: np.ndarray) -> np.ndarray:
        F = element_vector(element_loads(scene, nodes, hermite_shapes), len(nodes))
        return F + nodal_point_loads(scene, nodes, 2)

    def evaluate(self, scene, params, x):  # noqa: D401 - the FE solution itself between nodes
        return self.evaluator(scene, params)(x)

    def evaluator(self, scene, params):
        """Solve once; x -> the FE solution between the nodes (the Hermite interpolant of w and w'). The function
        carries the solve's round-off bound as ``error_bound`` (a study row measured against it is suspect when the
        bound passes 1e-6, pdverify.study.status)."""
        r = self.solve(scene, params)
        spline = CubicHermiteSpline(r.x, r.w, r.rotation)

        def fields(x):
            return {"w": spline(x), "rotation": spline(x, 1)}

        fields.error_bound = r.info.get("error_bound")
        return fields

    def element(self, params: dict) -> str:
        return "ElementLineHermite"


def iie_shapes(phi):
    """Interdependent-interpolation Timoshenko element: w shape functions with Phi = 12EI/(kGA l²)."""

    def shapes(xi, l):
        f = phi(l)
        c = 1 / (1 + f)
        return c * np.array(
            [
                1 - 3 * xi**2 + 2 * xi**3 + f * (1 - xi),
                l * (xi - 2 * xi**2 + xi**3 + f / 2 * (xi - xi**2)),
                3 * xi**2 - 2 * xi**3 + f * xi,
                l * (-(xi**2) + xi**3 + f / 2 * (-xi + xi**2)),
            ]
        )

    return shapes


def linear_shapes(xi, l):
    return np.array([1 - xi, 0 * xi, xi, 0 * xi]) * np.ones_like(l)


def two_fields(form, nodes: np.ndarray, **quadrature) -> sp.csr_matrix:
    """A bilinear form on w and theta, both scikit-fem ElementLineP1 on the nodes, assembled with the DOFs
    (w_i, theta_i) interleaved per node (this module's order); ``quadrature``: scikit-fem Basis keywords."""
    import skfem as fem

    basis = fem.Basis(fem.MeshLine(nodes), fem.ElementLineP1() * fem.ElementLineP1(), **quadrature)
    order = basis.nodal_dofs.T.ravel()
    return fem.BilinearForm(form).assemble(basis).tocsr()[order][:, order]


def linear_timoshenko(nodes: np.ndarray, EI: float, kGA: float, variant: str) -> Band:
    """The linear Timoshenko element in scikit-fem (:func:`two_fields`): the energy
    EI theta' phi' + kGA (w' - theta)(v' - phi) integrated with one Gauss point (``reduced``: the shear term
    underintegrated, no locking) or two (``full``: exact, locks when slender). scikit-fem's line rules have at
    least two points, so the one-point rule is given explicitly."""

    def energy(w, theta, v, phi, _):
        return EI * theta.grad[0] * phi.grad[0] + kGA * (w.grad[0] - theta) * (v.grad[0] - phi)

    one_point = {"quadrature": (np.array([[0.5]]), np.array([1.0]))}
    return Band.from_sparse(two_fields(energy, nodes, **(one_point if variant == "reduced" else {"intorder": 2})))


class FemTimoshenko(_BeamFE):
    theory = "timoshenko"
    name = "fem-timoshenko"
    title = "Timoshenko beam element (interdependent interpolation; locking-free)"
    source = (
        "IIE element (exact homogeneous solutions, nodally exact; closed form: its shape functions depend on "
        "12EI/(kGA l^2), which no scikit-fem element has); 'reduced'/'full': scikit-fem ElementLineP1 x "
        "ElementLineP1, one / two Gauss points, for contrast"
    )
    options = (
        Option("points", int, 101, "nodes along the beam before load positions are added", minimum=2),
        Option(
            "variant",
            str,
            "iie",
            "iie | reduced (linear, 1-point shear) | full (linear, locks)",
            choices=("iie", "reduced", "full"),
        ),
        FORM,
    )

    analyses = frozenset({"static", "dynamic"})
    modes = True  # eigenproblem(): the stiffness and consistent mass of its transient

    def shear_stiffness(self, scene: Scene) -> float | None:
        return scene.kGA

    def eigenproblem(self, scene: Scene, params: dict) -> tuple:
        """(K, M) on the free DOFs, M the consistent mass (sparse) its transient integrates with."""
        from .beam_transient import free_system

        K, M, _, _, _ = free_system(self, scene, params, probes=())
        return K, M

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        d = scene.dynamics
        if d is not None and any(em is not None for em in (d.left, d.right)):
            out.append("dynamics.left/right: fem-timoshenko's transient takes step loads, not prescribed end motions")
        return out

    def solve(self, scene: Scene, params: dict) -> Result:
        if scene.dynamics is not None:
            from .beam_transient import transient

            return transient(self, scene, params)
        return super().solve(scene, params)

    def nodal_loads(self, scene: Scene, params: dict, nodes: np.ndarray) -> np.ndarray:
        EI, kGA = scene.EI, scene.kGA
        shapes = iie_shapes(lambda ll: 12 * EI / (kGA * ll**2)) if params["variant"] == "iie" else linear_shapes
        return element_vector(element_loads(scene, nodes, shapes), len(nodes)) + nodal_point_loads(scene, nodes, 2)

    def assemble_band(self, scene: Scene, params: dict):
        """(K, F, nodes) before the supports, K a :class:`Band`."""
        nodes = beam_nodes(scene, params["points"])
        l = np.diff(nodes)
        EI, kGA = scene.EI, scene.kGA
        if params["variant"] == "iie":
            f = 12 * EI / (kGA * l**2)
            ke = hermite_stiffness(l, EI / ((1 + f) * l**3), f)
            fe = element_loads(scene, nodes, iie_shapes(lambda ll: 12 * EI / (kGA * ll**2)))
        else:
            return linear_timoshenko(nodes, EI, kGA, params["variant"]), self.nodal_loads(scene, params, nodes), nodes
        return element_band(ke, len(nodes)), element_vector(fe, len(nodes)) + nodal_point_loads(scene, nodes, 2), nodes

    def element(self, params: dict) -> str:
        return {
            "iie": "interdependent interpolation (IIE)",
            "reduced": "ElementLineP1 x ElementLineP1, one Gauss point (reduced shear)",
            "full": "ElementLineP1 x ElementLineP1, two Gauss points (full integration)",
        }[params["variant"]]

    def what(self, params: dict) -> str:
        return f"fem-timoshenko ({params['variant']})"


MODELS = [FemEulerBernoulli(), FemTimoshenko()]
