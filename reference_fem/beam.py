"""Beam references: ``fem-eb`` (cubic Hermite, scikit-fem; ANSYS BEAM3 analogue) and
``fem-timoshenko`` (interdependent interpolation element, locking-free; naive variants for contrast).

Both put every load position and every span end on a node, so the nodal values are those of the
exact beam theory for any straight scene (Tong's theorem: the shape functions solve the homogeneous
equations, and the loads are work-equivalent, integrated by 12-point Gauss per element, which is
exact to round-off for the uniform and sine loads of the scene format).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.interpolate import CubicHermiteSpline

from pdverify.band import Band
from pdverify.linalg import eliminate, solve_linear
from pdverify.registry import Model, Option
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
        x0, l = nodes[e0:e1, None], np.diff(nodes[e0:e1 + 1])[:, None]
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
                d[row0:row0 + 2 * n_el:2] += ke[:, a, b]
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


def element_vector(fe: np.ndarray, n_nodes: int) -> np.ndarray:
    """(n_el, 4) element vectors summed into the global vector (DOFs 2e .. 2e + 3)."""
    F = np.zeros(2 * n_nodes)
    for a in range(4):
        F[a: a + 2 * len(fe): 2] += fe[:, a]
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

    def assemble(self, scene: Scene, params: dict, **options):
        """(K_ff, F_f, free, nodes): the sparse system after eliminating the supported DOFs."""
        K, F, nodes = self.assemble_band(scene, params, **options)
        return (*reduce_supports(scene, K.tocsr(), F, len(nodes)), nodes)

    def limit_system(self, scene: Scene, params: dict):
        """(matrix, rhs) that ``solve`` factorises (for ``pdverify bench``'s limit)."""
        K, F, nodes = self.assemble_band(scene, params)
        return hold_supports(scene, K, F, len(nodes))[:2]

    def solve_nodal(self, scene: Scene, params: dict, what: str):
        """(u, info, free DOF count, nodes, timer): nodal DOFs (w_i, w'_i or theta_i) interleaved."""
        timer = Timer()
        with timer("assemble"):
            K, F, nodes = self.assemble_band(scene, params)
            K, F, dofs = hold_supports(scene, K, F, len(nodes))
        with timer("solve"):
            u, info = solve_linear(K, F, what=what)
        return u, info, dofs, nodes, timer


def hermite_shapes(xi, l):
    """Cubic Hermite shape functions (w1, w1', w2, w2') on [0, l], xi = s / l."""
    return np.stack(np.broadcast_arrays(1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3),
                                        3 * xi**2 - 2 * xi**3, l * (-(xi**2) + xi**3)))


class FemEulerBernoulli(_BeamFE):
    name = "fem-eb"
    title = "Euler–Bernoulli beam, cubic Hermite elements (scikit-fem; BEAM3 analogue)"
    source = "scikit-fem ElementLineHermite; nodally exact (loads on nodes)"
    options = (Option("points", int, 101, "nodes along the beam before load positions are added", minimum=2),)

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

    def evaluate(self, scene, params, x):  # noqa: D401 - the FE solution itself between nodes
        r = self.solve(scene, params)
        spline = CubicHermiteSpline(r.x, r.w, r.rotation)
        return {"w": spline(x), "rotation": spline(x, 1)}

    def solve(self, scene: Scene, params: dict) -> Result:
        u, info, dofs, nodes, timer = self.solve_nodal(scene, params, "fem-eb")
        info.update(element="ElementLineHermite", elements=len(nodes) - 1)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=nodes, w=u[0::2],
                      rotation=u[1::2], dofs=dofs, timings=timer.timings, info=info)


def iie_shapes(phi):
    """Interdependent-interpolation Timoshenko element: w shape functions with Phi = 12EI/(kGA l²)."""
    def shapes(xi, l):
        f = phi(l)
        c = 1 / (1 + f)
        return c * np.array([1 - 3 * xi**2 + 2 * xi**3 + f * (1 - xi),
                             l * (xi - 2 * xi**2 + xi**3 + f / 2 * (xi - xi**2)),
                             3 * xi**2 - 2 * xi**3 + f * xi,
                             l * (-(xi**2) + xi**3 + f / 2 * (-xi + xi**2))])
    return shapes


def linear_shapes(xi, l):
    return np.array([1 - xi, 0 * xi, xi, 0 * xi]) * np.ones_like(l)


class FemTimoshenko(_BeamFE):
    theory = "timoshenko"
    name = "fem-timoshenko"
    title = "Timoshenko beam element (interdependent interpolation; locking-free)"
    source = "IIE element (exact homogeneous solutions, nodally exact); 'reduced'/'full' linear for contrast"
    options = (
        Option("points", int, 101, "nodes along the beam before load positions are added", minimum=2),
        Option("variant", str, "iie", "iie | reduced (linear, 1-point shear) | full (linear, locks)",
               choices=("iie", "reduced", "full")),
    )

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
            kb = np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0], [0, -1, 0, 1]], float)
            ke = EI / l[:, None, None] * kb
            pts = np.array([0.5]) if params["variant"] == "reduced" else (np.array([-1, 1]) / np.sqrt(3) + 1) / 2
            wts = np.array([1.0]) if params["variant"] == "reduced" else np.array([0.5, 0.5])
            for xi, wt in zip(pts, wts):
                B = np.stack([-1 / l, -(1 - xi) * np.ones_like(l), 1 / l, -xi * np.ones_like(l)], axis=1)
                ke = ke + kGA * wt * l[:, None, None] * B[:, :, None] * B[:, None, :]
            fe = element_loads(scene, nodes, linear_shapes)
        return element_band(ke, len(nodes)), element_vector(fe, len(nodes)) + nodal_point_loads(scene, nodes, 2), nodes

    def solve(self, scene: Scene, params: dict) -> Result:
        u, info, dofs, nodes, timer = self.solve_nodal(scene, params, f"fem-timoshenko ({params['variant']})")
        info.update(element={"iie": "interdependent interpolation (IIE)", "reduced": "linear, reduced shear",
                             "full": "linear, full integration"}[params["variant"]], elements=len(nodes) - 1)
        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=nodes, w=u[0::2],
                      rotation=u[1::2], dofs=dofs, timings=timer.timings, info=info)


MODELS = [FemEulerBernoulli(), FemTimoshenko()]
