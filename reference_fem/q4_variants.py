"""Four-node quadrilateral stiffness variants standing in for ANSYS PLANE182's KEYOPT(1), the element Yang et al.
2020 compare with.

All are bilinear isoparametric quads (nodes of ``mesh.t`` taken in their cyclic order as the reference corners
(-1,-1), (1,-1), (1,1), (-1,1)), plane stress D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]], 2x2
Gauss points, element matrices computed for all elements at once (arrays, no loop over elements):

- ``full``: plain 2x2 integration (the same matrix as scikit-fem's ElementQuad1; locks in bending);
- ``bbar`` (KEYOPT(1) = 0, "full integration with B-bar"): the volumetric part of B replaced by its element
  mean (Hughes 1980); in plane stress it does not touch shear locking;
- ``qm6`` (KEYOPT(1) = 2/3, "enhanced strain"): Wilson's incompatible modes 1 - xi^2, 1 - eta^2 per direction
  with Taylor's correction (their derivatives through the centre Jacobian J0, weighted det J0 / det J, so the
  patch test passes on distorted quads), condensed element by element (Taylor, Beresford & Wilson 1976);
- ``reduced`` (KEYOPT(1) = 1, "uniform reduced integration with hourglass control"): one Gauss point at the
  centre, K_1 = A B0^T D B0, plus a stiffness for the two hourglass modes. The modes are Flanagan &
  Belytschko's (1981) orthogonal hourglass vectors gamma = (h - (h.x) b_x - (h.y) b_y) / 4, h = (1, -1, 1, -1),
  b = dN/dx at the centre (gamma is orthogonal to every linear field, so the patch test holds on any quad);
  the hourglass amplitudes q_i = gamma . u_i carry K_hg = (4/3) E A gamma gamma^T (x) (b b^T): the energy of
  the mode's pure-bending strain with Young's modulus and without its parasitic shear, the "quintessential
  bending" stabilisation of Belytschko & Bindeman (1993, plane stress: nu-bar = nu). For a rectangle
  2a x 2b (b b^T = diag(1/4a^2, 1/4b^2), A = 4ab) the x mode u = q xi eta has e_xx = q eta / a and
  K_hg = E (4ab/3) / a^2, which is also what Wilson's incompatible modes leave after condensation (they cancel
  the parasitic shear and give the anticlastic e_yy = -nu e_xx), so on rectangles ``reduced`` is QM6's
  matrix (tests/reference_fem/test_q4_variants.py); on distorted quads the two differ.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

XI = np.array([-1.0, 1.0, 1.0, -1.0])
ETA = np.array([-1.0, -1.0, 1.0, 1.0])
GAUSS = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) / np.sqrt(3.0)
VARIANTS = ("full", "bbar", "qm6", "reduced")


def _plane_stress(E: float, nu: float) -> np.ndarray:
    return E / (1 - nu * nu) * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])


def _jacobian(X: np.ndarray, xi: float, eta: float):
    """(J (ne x 2 x 2), dN/dxi (2 x 4)) at (xi, eta); X: ne x 4 x 2 corner coordinates."""
    dN = 0.25 * np.array([XI * (1 + ETA * eta), ETA * (1 + XI * xi)])
    return np.einsum("ak,ekb->eab", dN, X), dN


def _strain_matrix(dNx: np.ndarray) -> np.ndarray:
    """B (ne x 3 x 2k) from physical derivatives dNx (ne x 2 x k), DOFs (u_x, u_y) node by node."""
    ne, _, k = dNx.shape
    B = np.zeros((ne, 3, 2 * k))
    B[:, 0, 0::2] = dNx[:, 0]
    B[:, 1, 1::2] = dNx[:, 1]
    B[:, 2, 0::2] = dNx[:, 1]
    B[:, 2, 1::2] = dNx[:, 0]
    return B


def _reduced(X: np.ndarray, D: np.ndarray, E: float) -> np.ndarray:
    """One-point quadrature + Flanagan-Belytschko hourglass vectors with the bending stiffness (module doc)."""
    J0, dN = _jacobian(X, 0.0, 0.0)
    b = np.einsum("eab,bk->eak", np.linalg.inv(J0), dN)  # ne x 2 x 4: dN/dx, dN/dy at the centre
    area = 4.0 * np.linalg.det(J0)  # exact for a bilinear quad (det J is linear in xi, eta)
    B0 = _strain_matrix(b)
    K = np.einsum("eia,ij,ejb->eab", B0, D, B0) * np.abs(area)[:, None, None]
    h = XI * ETA  # (1, -1, 1, -1) at the corners
    hx = np.einsum("k,ekd->ed", h, X)  # (h.x, h.y) per element
    gamma = 0.25 * (h[None, :] - np.einsum("ed,edk->ek", hx, b))
    H = 4.0 / 3.0 * E * np.abs(area)[:, None, None] * np.einsum("eik,ejk->eij", b, b)  # 2 x 2 per element
    Khg = np.einsum("ek,el,eij->ekilj", gamma, gamma, H).reshape(len(X), 8, 8)  # DOFs (x, y) node by node
    return K + Khg


def element_matrices(X: np.ndarray, E: float, nu: float, variant: str) -> np.ndarray:
    """K_e (ne x 8 x 8) per unit thickness; X: ne x 4 x 2 corner coordinates in cyclic order."""
    D = _plane_stress(E, nu)
    if variant == "reduced":
        return _reduced(X, D, E)
    J0, _ = _jacobian(X, 0.0, 0.0)
    det0 = np.linalg.det(J0)
    inv0 = np.linalg.inv(J0)
    Bs, dets = [], []
    for xi, eta in GAUSS:
        J, dN = _jacobian(X, xi, eta)
        dNx = np.einsum("eab,bk->eak", np.linalg.inv(J), dN)
        Bs.append(_strain_matrix(dNx))
        dets.append(np.linalg.det(J))
    if variant == "bbar":
        vol = sum(np.abs(d) for d in dets)
        mean = sum(B[:, :2] * np.abs(d)[:, None, None] for B, d in zip(Bs, dets)) / vol[:, None, None]
        for B in Bs:  # B = B_dev + (1/2) m m^T B_mean: the dilatation (exx + eyy) replaced by its element mean
            dil = 0.5 * (mean[:, 0] + mean[:, 1] - B[:, 0] - B[:, 1])
            B[:, 0] += dil
            B[:, 1] += dil
    K = sum(np.einsum("eia,ij,ejb->eab", B, D, B) * np.abs(d)[:, None, None] for B, d in zip(Bs, dets))
    if variant != "qm6":
        return K
    Kua = np.zeros((len(X), 8, 4))
    Kaa = np.zeros((len(X), 4, 4))
    for (xi, eta), B, d in zip(GAUSS, Bs, dets):
        dP = np.array([[-2 * xi, 0.0], [0.0, -2 * eta]])  # d(1 - xi^2, 1 - eta^2)/d(xi, eta)
        dPx = np.einsum("eab,bk->eak", inv0, dP) * (det0 / d)[:, None, None]  # Taylor: centre Jacobian
        G = _strain_matrix(dPx)
        w = np.abs(d)[:, None, None]
        Kua += np.einsum("eia,ij,ejb->eab", B, D, G) * w
        Kaa += np.einsum("eia,ij,ejb->eab", G, D, G) * w
    return K - Kua @ np.linalg.solve(Kaa, np.swapaxes(Kua, 1, 2))


def assemble(mesh, basis, E: float, nu: float, variant: str) -> sp.csr_matrix:
    """Global K (per unit thickness) of a scikit-fem MeshQuad with an ElementVector(ElementQuad1) basis."""
    X = np.transpose(mesh.p[:, mesh.t], (2, 1, 0))
    Ke = element_matrices(X, E, nu, variant)
    dofs = np.stack([basis.nodal_dofs[0][mesh.t], basis.nodal_dofs[1][mesh.t]], axis=1)  # 4 x 2 x ne
    dofs = dofs.reshape(8, -1).T  # ne x 8: (x, y) node by node
    rows = np.repeat(dofs[:, :, None], 8, axis=2)
    cols = np.repeat(dofs[:, None, :], 8, axis=1)
    return sp.csr_matrix((Ke.ravel(), (rows.ravel(), cols.ravel())), shape=(basis.N, basis.N))
