"""The beam elements of ``fem-eb`` and ``fem-timoshenko``: nodes at every load position and span end, work-
equivalent loads, the cubic Hermite and the interdependent interpolation (IIE) element's stiffness, the two-field
(natural) form of :func:`natural_band`, the linear elements and the supports' constrained DOFs. Arrays in,
arrays out; the models are in :mod:`reference_fem.beam`, the transient in :mod:`reference_fem.beam_transient`."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from pdverify.core.scene import Distributed, PointForce, PointMoment, Scene
from pdverify.numerics.band import Band
from pdverify.numerics.linalg import eliminate

_GX, _GW = np.polynomial.legendre.leggauss(12)


def beam_nodes(scene: Scene, points: int) -> np.ndarray:
    """Uniform nodes plus every load position and span end, every support inside the span and every segment's
    end (one within 1e-12 L of a node is that node)."""
    L = scene.length
    extra = [s.position for s in scene.supports.inner] + [g.end for g in scene.segments[:-1]]
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


def merge_warnings(scene: Scene, nodes: np.ndarray) -> list[str]:
    """A load, span end or inner support within 1e-12 L of a node, and further than its rounding, is taken on that node
    (:func:`beam_nodes`): its distance to the node is lost, and a result that grows with it (a force beside a clamp
    deflects the beam by its arm squared) is lost with it; one warning each."""
    L = scene.length
    marks = [(f"supports.inner[{i}]", s.position) for i, s in enumerate(scene.supports.inner)]
    for i, ld in enumerate(scene.loads):
        for v in scene.span(ld) if isinstance(ld, Distributed) else (ld.position,):
            marks.append((f"loads[{i}]", v))
    out = []
    for name, v in marks:
        d = np.abs(nodes - v).min()
        if 1e-14 * L < d <= 1e-12 * L:  # a distance of more than the positions' rounding (a few eps L)
            out.append(
                f"{name} at {v:g} lies {d:.3g} from the node at {nodes[np.argmin(np.abs(nodes - v))]:g}, within "
                "1e-12 of the length, and is taken on it: a result that depends on that distance is lost; give the "
                "position on the node, or the scene in a shorter length"
            )
    return out


def line_load(scene: Scene, x: np.ndarray, nodes: np.ndarray | None = None) -> np.ndarray:
    """q(x) of all distributed loads (N/m) at points x (span ends are nodes: no straddling). With the ``nodes``: a
    span end taken on a node within 1e-12 L (:func:`beam_nodes`) ends there, and the load keeps its resultant, its
    value times (b - a) / (b' - a') over the nodes' span [a', b'] (one ulp off a 1e-9 L span is 1e-7 of it)."""
    q = np.zeros_like(x)
    for load in scene.loads:
        if isinstance(load, Distributed):
            a, b = scene.span(load)
            scale = 1.0
            if nodes is not None:
                a1, b1 = (nodes[np.argmin(np.abs(nodes - v))] for v in (a, b))
                if b1 > a1:
                    scale, a, b = (b - a) / (b1 - a1), a1, b1
            on = (x >= a) & (x <= b)
            v = load.value if load.shape == "uniform" else load.value * np.sin(np.pi * x / scene.length)
            q += np.where(on, scale * v, 0.0)
    return q


def element_properties(scene: Scene, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(EI, kGA) of each element: those of the segment it lies in (segment ends are nodes)."""
    if scene.uniform:
        n = len(nodes) - 1
        return np.full(n, scene.EI), np.full(n, scene.kGA)
    at = scene.stiffness_at(0.5 * (nodes[1:] + nodes[:-1]))
    return at["EI"], at["kGA"]


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
        q = line_load(scene, x0 + l * xi[None, :], nodes)
        N = shape_fns(xi[None, :], l, slice(e0, e1))  # (4, n_el, nq)
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


def element_vector(fe: np.ndarray, n_nodes: int) -> np.ndarray:
    """(n_el, 4) element vectors summed into the global vector (DOFs 2e .. 2e + 3)."""
    F = np.zeros(2 * n_nodes)
    for a in range(4):
        F[a : a + 2 * len(fe) : 2] += fe[:, a]
    return F


def assemble_elements(ke: np.ndarray, fe: np.ndarray, n_nodes: int):
    """(K, F): the global sparse K (CSR, from :func:`element_band`) and load vector."""
    return element_band(ke, n_nodes).tocsr(), element_vector(fe, n_nodes)


# the nodal DOFs (0: w, 1: w' or theta) each support holds; roller = pinned in w, a spring holds none rigidly
_FIX = {"clamped": (0, 1), "pinned": (0,), "roller": (0,), "guided": (1,), "free": (), "spring": ()}


def support_nodes(scene: Scene, nodes: np.ndarray) -> list[tuple[str, int, object]]:
    """(reaction label, node, support) of every support: the ends ("left", "right", a name or a Spring) and those
    inside the span ("inner_<i>", an InnerSupport; each on its own node: beam_nodes puts it there)."""
    out = [("left", 0, scene.supports.left), ("right", len(nodes) - 1, scene.supports.right)]
    for i, s in enumerate(scene.supports.inner):
        out.append((f"inner_{i}", int(np.argmin(np.abs(nodes - s.position))), s))
    return out


def _held(support) -> tuple[int, ...]:
    kind = support if isinstance(support, str) else support.type
    return _FIX[kind]


def constrained_dofs(scene: Scene, nodes: np.ndarray | int) -> np.ndarray:
    """The nodal DOFs (2 node + 0 for w, + 1 for the rotation) the supports hold rigidly."""
    nodes = np.linspace(0.0, scene.length, nodes) if isinstance(nodes, (int, np.integer)) else nodes
    out = [2 * k + d for _, k, sup in support_nodes(scene, nodes) for d in _held(sup)]
    return np.array(sorted(out), dtype=int)


def spring_dofs(scene: Scene, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(DOFs, stiffnesses) of the elastic supports: a spring's stiffness on its node's w, its rotational stiffness
    on the rotation."""
    dofs, ks = [], []
    for _, k, sup in support_nodes(scene, nodes):
        if isinstance(sup, str) or sup.type != "spring":
            continue
        for d, stiff in ((0, sup.stiffness), (1, sup.rotational_stiffness)):
            if stiff:
                dofs.append(2 * k + d)
                ks.append(stiff)
    return np.array(dofs, dtype=int), np.array(ks, float)


def add_springs(scene: Scene, K: Band, nodes: np.ndarray, stride: int = 2) -> Band:
    """The springs on the diagonal of K (nodal DOFs numbered ``stride`` per node: 2, or 4 in the two-field form)."""
    dofs, ks = spring_dofs(scene, nodes)
    if len(dofs):
        K.add_entries(stride * (dofs // 2) + dofs % 2, stride * (dofs // 2) + dofs % 2, ks)
    return K


def held_rows(K: Band, dofs: np.ndarray) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """(dof, columns, values) of the rows ``dofs`` of K, read before the supports are held (for the reactions)."""
    out = []
    for i in np.asarray(dofs, int):
        cols = np.arange(max(0, i - K.lower), min(K.n, i + K.upper + 1))
        out.append((int(i), cols, K.values(np.full(len(cols), i), cols)))
    return out


def reactions(scene: Scene, nodes: np.ndarray, rows, u: np.ndarray, F: np.ndarray, stride: int = 2) -> dict:
    """The support reactions on the beam (force +z, moment counter-clockwise), keyed as exact-eb keys them:
    K u - F on each held DOF (``rows`` from :func:`held_rows`, DOFs ``stride`` per node) and -k u of each
    spring; zero where a support holds nothing."""
    R = {int(i): float(vals @ u[cols] - F[i]) for i, cols, vals in rows}
    dofs, ks = spring_dofs(scene, nodes)
    for d, k in zip(dofs, ks):
        j = stride * (d // 2) + d % 2
        R[j] = R.get(j, 0.0) - k * float(u[j])
    out = {}
    for label, k, sup in support_nodes(scene, nodes):
        force, moment = R.get(stride * k, 0.0), R.get(stride * k + 1, 0.0)
        if label.startswith("inner"):
            if sup.holds_deflection:
                out[f"force_{label}"] = force
            if sup.holds_rotation:
                out[f"moment_{label}"] = moment
        else:
            out[f"force_{label}"], out[f"moment_{label}"] = force, moment
    out["method"] = "K u - F on the held DOFs, -k u of each spring"
    return out


def reduce_supports(scene: Scene, K, F, n_nodes: int):
    """Eliminate the supported DOFs: (K_ff, F_f, free)."""
    return eliminate(K, F, constrained_dofs(scene, n_nodes))


def hold_supports(scene: Scene, K: Band, F: np.ndarray, nodes: np.ndarray | int) -> tuple[Band, np.ndarray, int]:
    """The supported DOFs held at zero in place (unit rows, cleared columns): (K, F, free DOF count)."""
    fixed = constrained_dofs(scene, nodes)
    K.fix(fixed, F)
    n_nodes = nodes if isinstance(nodes, (int, np.integer)) else len(nodes)
    return K, F, 2 * n_nodes - len(fixed)


def hermite_shapes(xi, l, elements=None):
    """Cubic Hermite shape functions (w1, w1', w2, w2') on [0, l], xi = s / l."""
    return np.stack(
        np.broadcast_arrays(
            1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-(xi**2) + xi**3)
        )
    )


def iie_shapes(phi: np.ndarray):
    """Interdependent-interpolation Timoshenko element: w shape functions with each element's Phi = 12EI/(kGA l²)."""

    def shapes(xi, l, elements=slice(None)):
        f = np.asarray(phi)[elements].reshape(l.shape)
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


def linear_shapes(xi, l, elements=None):
    return np.array([1 - xi, 0 * xi, xi, 0 * xi]) * np.ones_like(l)


def two_fields(form, nodes: np.ndarray, **quadrature) -> sp.csr_matrix:
    """A bilinear form on w and theta, both scikit-fem ElementLineP1 on the nodes, assembled with the DOFs
    (w_i, theta_i) interleaved per node (this module's order); ``quadrature``: scikit-fem Basis keywords."""
    import skfem as fem

    basis = fem.Basis(fem.MeshLine(nodes), fem.ElementLineP1() * fem.ElementLineP1(), **quadrature)
    order = basis.nodal_dofs.T.ravel()
    return fem.BilinearForm(form).assemble(basis).tocsr()[order][:, order]


def linear_timoshenko(nodes: np.ndarray, EI, kGA, variant: str) -> Band:
    """The linear Timoshenko element in scikit-fem (:func:`two_fields`): the energy
    EI theta' phi' + kGA (w' - theta)(v' - phi) integrated with one Gauss point (``reduced``: the shear term
    underintegrated, no locking) or two (``full``: exact, locks when slender). scikit-fem's line rules have at
    least two points, so the one-point rule is given explicitly."""

    def energy(w, theta, v, phi, at):  # EI, kGA: numbers, or functions of x (segments)
        ei = EI(at.x[0]) if callable(EI) else EI
        ga = kGA(at.x[0]) if callable(kGA) else kGA
        return ei * theta.grad[0] * phi.grad[0] + ga * (w.grad[0] - theta) * (v.grad[0] - phi)

    one_point = {"quadrature": (np.array([[0.5]]), np.array([1.0]))}
    return Band.from_sparse(two_fields(energy, nodes, **(one_point if variant == "reduced" else {"intorder": 2})))
