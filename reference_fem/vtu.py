"""VTU output of a ``fem-plane-stress`` solution: the element's own cells (VTK quad for q4 and its variants,
quad8 for q8 with the mid-side nodes, quad9 for q9 with the centre node too) and, as nodal fields, the
displacement and the stresses sigma_xx, sigma_zz, tau_xz and von Mises (plane stress, global axes; z = the
mesh's y). Nodal stresses: the displacement gradient of each element at its own nodes (a custom quadrature on
the reference nodes), averaged over the elements that share the node (no projection). For q4-qm6 and
q4-reduced they are the compatible part only (the incompatible modes / hourglass terms carry no stress output).

Node numbering: the mesh vertices, then one node per edge (scikit-fem facet order), then one per element
(q9); the cell's edge i joins its corners i and i + 1 (scikit-fem's t2f order, VTK's quad8/quad9 order)."""

from __future__ import annotations

import numpy as np

from reference_fem.stresses import _components

_REF = {  # reference coordinates in scikit-fem's [0, 1]^2: corners, mid-sides (edge i: corners i, i+1), centre
    4: [[0, 1, 1, 0], [0, 0, 1, 1]],
    8: [[0, 1, 1, 0, 0.5, 1, 0.5, 0], [0, 0, 1, 1, 0, 0.5, 1, 0.5]],
    9: [[0, 1, 1, 0, 0.5, 1, 0.5, 0, 0.5], [0, 0, 1, 1, 0, 0.5, 1, 0.5, 0.5]],
}


def cells(basis) -> tuple[str, np.ndarray, np.ndarray, list[np.ndarray]]:
    """(VTK cell type, connectivity (nel x k), node positions (n x 2), [x-DOFs, y-DOFs] per node)."""
    mesh = basis.mesh
    nv, nf = mesh.nvertices, mesh.facets.shape[1]
    conn = [mesh.t[:4]]
    xd, yd = [basis.nodal_dofs[0]], [basis.nodal_dofs[1]]
    if basis.facet_dofs.shape[0]:
        conn.append(nv + mesh.t2f)
        xd.append(basis.facet_dofs[0])
        yd.append(basis.facet_dofs[1])
    if basis.interior_dofs.shape[0]:
        conn.append(nv + nf + np.arange(mesh.t.shape[1])[None, :])
        xd.append(basis.interior_dofs[0])
        yd.append(basis.interior_dofs[1])
    xd, yd = np.concatenate(xd), np.concatenate(yd)
    conn = np.vstack(conn).T
    kind = {4: "quad", 8: "quad8", 9: "quad9"}[conn.shape[1]]
    return kind, conn, basis.doflocs[:, xd].T, [xd, yd]


def nodal_stresses(basis, u: np.ndarray, conn: np.ndarray, lam: float, mu: float) -> dict[str, np.ndarray]:
    """Stresses at the nodes of ``conn``: each element's gradient at its k reference nodes, averaged per node."""
    import skfem as fem

    k = conn.shape[1]
    X = np.array(_REF[k], float)
    bq = fem.Basis(basis.mesh, basis.elem, quadrature=(X, np.ones(k)))
    s = _components(bq.interpolate(u).grad, lam, mu)  # each (nel, k)
    n = int(conn.max()) + 1
    count = np.bincount(conn.ravel(), minlength=n)
    out = {}
    for c in ("sigma_xx", "sigma_zz", "tau_xz"):
        out[c] = np.bincount(conn.ravel(), weights=s[c].ravel(), minlength=n) / count
    out["von_mises"] = np.sqrt(
        out["sigma_xx"] ** 2 - out["sigma_xx"] * out["sigma_zz"] + out["sigma_zz"] ** 2 + 3 * out["tau_xz"] ** 2
    )
    return out


def write(path: str, basis, u: np.ndarray, lam: float, mu: float) -> None:
    import meshio

    kind, conn, pts, (xd, yd) = cells(basis)
    s = nodal_stresses(basis, u, conn, lam, mu)
    disp = np.column_stack([u[xd], u[yd], np.zeros(len(xd))])
    meshio.write(
        path,
        meshio.Mesh(
            np.column_stack([pts, np.zeros(len(pts))]),
            [(kind, conn)],
            point_data={"displacement": disp, **s},
        ),
    )
