"""Plane-stress meshes that follow the beam axis, and the line loads and rotated supports on them.

A beam of arc length L and height h is the image of the parameter rectangle (s, t) in [0, L] x [-h/2, h/2]
under (s, t) -> X(s) + t n(s), with X the axis (``pdverify.core.geometry``: straight, circular arc or polynomial
y = f(x)) and n = e_z x tangent its unit normal (+z for a straight beam, towards the centre of curvature
of a counter-clockwise arc). The nodes of a tensor grid (s_i, t_j) are mapped; for q8/q9 on a curved axis
the mesh is a scikit-fem ``MeshQuad2`` whose mid-side and centre nodes are the mapped parameter mid-points,
so every element edge is the quadratic interpolant of the mapped curve (isoparametric geometry); q4 and
every straight beam use ``MeshQuad1`` (straight edges; for a straight axis the map is the identity, bit for
bit, so the straight results are unchanged).

Loads are assembled edge by edge in the parameter (on a straight axis, where parameter = physical coordinates,
by scikit-fem's ``FacetBasis`` + ``LinearForm``): a density f(s, t) (force per unit parameter length, a
global vector) on a row of edges t = t_j (or a column s = s_i) gives work-equivalent nodal forces
∫ f N_k dξ |dp/dξ| with the edge's Lagrange trace functions N_k (2 nodes, or 3 with the mid-side dof of
q8/q9) and 8-point Gauss. Loads per unit length of the axis therefore keep their beam resultants on the
offset top face, whose length differs from the axis by the factor (1 - κ h/2).

Supports in a rotated frame: u = T u' where, at a node with end frame (t_end, n_end), u'_x is the
tangential and u'_y the normal component; constraints then fix single entries of u'.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from pdverify.core.geometry import AxisGeometry, geometry
from pdverify.numerics.factorcache import digest
from pdverify.numerics.kept import Kept

KEPT_DOFS = 200_000  # the bases of larger strips are not kept (a 10,241-station strip's basis takes gigabytes)
_FACETS = Kept(24)  # (mesh, element, facets) digest -> FacetBasis: other loads on the same edges of one strip

_GX, _GW = np.polynomial.legendre.leggauss(8)


def map_points(geo: AxisGeometry, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Physical points (2, n) of parameter points (s, t): X(s) + t n(s) (frames evaluated once per distinct s)."""
    us, inv = np.unique(np.asarray(s, float), return_inverse=True)
    X = geo.position(us)
    _, n = geo.frame(us)
    return np.ascontiguousarray((X[inv] + np.asarray(t, float)[:, None] * n[inv]).T)


@dataclass
class BeamMesh:
    mesh: object  # skfem MeshQuad1 | MeshQuad2 (physical coordinates)
    s: np.ndarray  # stations along the axis (arc length), ns
    t: np.ndarray  # through-thickness coordinates, nt, from -h/2 (bottom) to +h/2 (top, the +n side)
    vid: np.ndarray  # (ns, nt) vertex index of node (s_i, t_j)
    geo: AxisGeometry

    def facet_ids(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """scikit-fem facet index of the edges between vertices a and b."""
        f = np.sort(self.mesh.facets, axis=0)
        nv = self.mesh.nvertices
        keys = f[0].astype(np.int64) * nv + f[1]
        order = np.argsort(keys)
        q = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
        pos = np.searchsorted(keys[order], q)
        found = order[np.clip(pos, 0, len(order) - 1)]
        assert np.all(keys[found] == q), "edge not in the mesh"
        return found


def build_mesh(scene, s: np.ndarray, t: np.ndarray, quadratic_geometry: bool) -> BeamMesh:
    import skfem as fem

    geo = geometry(scene)
    m1 = fem.MeshQuad1.init_tensor(s, t)
    i = np.searchsorted(s, m1.p[0])
    j = np.searchsorted(t, m1.p[1])
    vid = np.empty((len(s), len(t)), dtype=np.int64)
    vid[i, j] = np.arange(m1.p.shape[1])
    if quadratic_geometry:
        m2 = fem.MeshQuad2.from_mesh(m1)
        mesh = fem.MeshQuad2(map_points(geo, m2.doflocs[0], m2.doflocs[1]), m2.t)
    else:
        mesh = fem.MeshQuad1(map_points(geo, m1.p[0], m1.p[1]), m1.t)
    return BeamMesh(mesh, s, t, vid, geo)


def edge_dofs(bm: BeamMesh, basis, a: np.ndarray, b: np.ndarray) -> list[np.ndarray]:
    """Dofs (2, ne) of the edge nodes in the order a, [mid-side], b."""
    out = [basis.nodal_dofs[:, a]]
    if basis.facet_dofs.shape[0]:
        out.append(basis.facet_dofs[:, bm.facet_ids(a, b)])
    out.append(basis.nodal_dofs[:, b])
    return out


def line_forces(
    bm: BeamMesh, basis, a: np.ndarray, b: np.ndarray, pa: np.ndarray, pb: np.ndarray, density
) -> np.ndarray:
    """Work-equivalent nodal forces of a line density on the edges (a[k], b[k]) with parameter end points
    pa, pb (2, ne) = (s, t). ``density(s, t)`` -> (2, ne, nq): global force per unit parameter length."""
    F = np.zeros(basis.N)
    if len(a) == 0:
        return F
    if bm.geo.axis.type == "straight":  # parameter (s, t) = physical (x, y): scikit-fem's facet integration
        return _facet_forces(bm, basis, a, b, density)
    xi = (_GX + 1) / 2
    sq = pa[0][:, None] + (pb[0] - pa[0])[:, None] * xi[None, :]
    tq = pa[1][:, None] + (pb[1] - pa[1])[:, None] * xi[None, :]
    jac = np.hypot(pb[0] - pa[0], pb[1] - pa[1]) / 2  # d(parameter length)/dξ
    f = density(sq, tq) * (jac[:, None] * _GW[None, :])[None]  # (2, ne, nq)
    dofs = edge_dofs(bm, basis, a, b)
    if len(dofs) == 2:
        shapes = [(1 - _GX) / 2, (1 + _GX) / 2]
    else:
        shapes = [_GX * (_GX - 1) / 2, (1 - _GX) * (1 + _GX), _GX * (_GX + 1) / 2]
    for d, N in zip(dofs, shapes):
        contrib = f @ N  # (2, ne)
        np.add.at(F, d[0], contrib[0])
        np.add.at(F, d[1], contrib[1])
    return F


def _facet_mapping(mesh):
    """scikit-fem's isoparametric mapping of ``mesh``, its inverse (with which a ``FacetBasis`` locates its
    quadrature points in the elements) stopping at the round-off of the mapped coordinates. scikit-fem stops Newton
    at 1e-12 in reference coordinates summed over an element's points, below what float64 reaches once an element
    is ~1e-4 of the coordinates (a beam of ~5000 points and more: "Newton iteration didn't converge"). Here the
    elements are rectangles, whose bilinear map Newton inverts in one step."""
    import skfem as fem

    extent = np.abs(mesh.p).max()
    edge = np.min(np.linalg.norm(mesh.p[:, mesh.facets[0]] - mesh.p[:, mesh.facets[1]], axis=0))
    tol = max(1e-12, 1e-12 * extent / edge)

    class RoundOff(fem.MappingIsoparametric):
        def invF(self, x, tind=None, newton_max_iters=50, newton_tol=tol):
            return super().invF(x, tind, newton_max_iters, newton_tol)

    return RoundOff(mesh, mesh.elem(), mesh.bndelem)


def _facet_forces(bm: BeamMesh, basis, a: np.ndarray, b: np.ndarray, density) -> np.ndarray:
    """:func:`line_forces` on a straight axis with scikit-fem's idiom: a ``FacetBasis`` on the edges and a
    ``LinearForm`` of the density (per unit physical length there), the same 8-point Gauss rule (intorder 15)."""
    import skfem as fem
    from skfem.helpers import dot

    facets = bm.facet_ids(a, b)
    key = digest(bm.mesh.p, bm.mesh.t, np.asarray(facets), params=_element_name(basis.elem) + (basis.N,))
    fb = _FACETS.get(
        key,
        lambda: fem.FacetBasis(bm.mesh, basis.elem, facets=facets, intorder=15, mapping=_facet_mapping(bm.mesh)),
        keep=lambda _: basis.N <= KEPT_DOFS,
    )

    @fem.LinearForm
    def work(v, w):
        return dot(density(w.x[0], w.x[1]), v)

    return work.assemble(fb)


def _element_name(elem) -> tuple[str, str]:
    """The element's class and, for a vector element, its scalar element's class: what its basis is made of."""
    return type(elem).__name__, type(getattr(elem, "elem", None)).__name__


def row_edges(bm: BeamMesh, j: int, lo: float = -np.inf, hi: float = np.inf):
    """Edges of node row t_j between stations lo <= s <= hi: (a, b, pa, pb)."""
    s = bm.s
    keep = (s[:-1] >= lo - 1e-12 * s[-1]) & (s[1:] <= hi + 1e-12 * s[-1])
    i = np.nonzero(keep)[0]
    a, b = bm.vid[i, j], bm.vid[i + 1, j]
    tj = np.full(len(i), bm.t[j])
    return a, b, np.vstack([s[i], tj]), np.vstack([s[i + 1], tj])


def face_edges(bm: BeamMesh, i: int):
    """Edges of the section line s = s_i (an end face for i = 0 or -1), bottom to top: (a, b, pa, pb)."""
    j = np.arange(len(bm.t) - 1)
    si = np.full(len(j), bm.s[i])
    return bm.vid[i, j], bm.vid[i, j + 1], np.vstack([si, bm.t[j]]), np.vstack([si, bm.t[j + 1]])


def face_node_pairs(bm: BeamMesh, basis, i: int) -> np.ndarray:
    """(2, n) x/y dofs of every node (vertices and mid-side dofs) on the end face s = s_i."""
    a, b, _, _ = face_edges(bm, i)
    d = edge_dofs(bm, basis, a, b)
    return np.unique(np.hstack(d), axis=1)


def rotation_matrix(N: int, pairs: np.ndarray, tangents: np.ndarray) -> sp.csr_matrix:
    """T (N x N) with u = T u': at each pair (ix, iy) with unit tangent t (2, n), u'[ix] = u·t and u'[iy] = u·n."""
    ix, iy = pairs
    tx, ty = tangents
    nx, ny = -ty, tx
    rest = np.setdiff1d(np.arange(N), np.concatenate([ix, iy]))
    rows = np.concatenate([rest, ix, ix, iy, iy])
    cols = np.concatenate([rest, ix, iy, ix, iy])
    vals = np.concatenate([np.ones(len(rest)), tx, nx, ty, ny])
    return sp.csr_matrix((vals, (rows, cols)), shape=(N, N))


def constraint_basis(C: np.ndarray) -> sp.csr_matrix:
    """S (n x (n - m)) with C S = 0 for m independent constraint rows C (m, n) u = 0: one master dof per
    row (the largest remaining weight) is eliminated, u_M = -C_MM^-1 C_MS u_S; the others stay."""
    m, n = C.shape
    masters = []
    R = C.copy()
    for r in range(m):  # greedy pivoting: a well-conditioned C_MM
        k = int(np.argmax(np.abs(R[r])))
        masters.append(k)
        if r + 1 < m:
            R[r + 1 :] -= np.outer(R[r + 1 :, k] / R[r, k], R[r])
    masters = np.array(masters)
    slaves = np.setdiff1d(np.arange(n), masters)
    G = -np.linalg.solve(C[:, masters], C[:, slaves])  # (m, n - m), nonzero only on the constrained faces
    G[np.abs(G) < 1e-300] = 0.0
    Gs = sp.coo_matrix(G)
    rows = np.concatenate([slaves, masters[Gs.row]])
    cols = np.concatenate([np.arange(len(slaves)), Gs.col])
    vals = np.concatenate([np.ones(len(slaves)), Gs.data])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n - m))
