"""``fem-plane-stress`` on straight beams with supports inside the span, elastic supports and segments
(docs/scenes.md, docs/models/plane-stress.md).

A support inside the span holds the strip on its section line x = a (the mesh has a station there,
:func:`reference_fem.beam_elements.beam_nodes`), as an end support holds its end face:

* ``pinned`` / ``roller``, option ``pin = face`` (default): the parabola-weighted mean vertical displacement of the
  section line is zero, ∫ φ(z) u_z dz = 0 with φ = 3/(2h) (1 - (2z/h)²) (a parabolic shear reaction, as the
  beam's shear flows); pinned also its mean axial displacement. ``pin = node``: the neutral-axis (mid-height) node
  is held (u_z; pinned: and u_x), a 2D point force whose deflection grows like log(1/element size);
* ``clamped``: every node of the section line is held (a rigid wall through the section);
* ``spring`` (and an elastic end on its end face): the energy ½ k (c·u)² + ½ k_r (r·u)², c·u the section's
  parabola-weighted mean vertical displacement and r·u its rotation, the least-squares slope of its axial
  displacement, θ = -(12/h³) ∫ z u_x dz (a counter-clockwise rotation moves the top to -x).

Segments: each element takes its segment's Young's modulus, Poisson's ratio and width (the strip's thickness); the
strip has one height, so a segment may change the width and the material, not the height. The reactions are
K u - F (the elastic stiffness, springs left out: their forces are reactions too) summed over the nodes nearest each
support's station: force along +z, axial along +x, moment counter-clockwise about the station's mid-line point.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from pdverify.core.scene import HELD, Scene, Spring
from reference_fem import curved_mesh as cm
from reference_fem.plane_conditions import node_dofs


def _parabola(h: float):
    return lambda tq: 1.5 / h * (1 - (2 * tq / h) ** 2)


def section_row(bm, basis, i: int, direction: np.ndarray, weight) -> np.ndarray:
    """The row r with r·u = ∫ weight(z) u·direction dz over the section line of station i (consistent line
    integrals)."""
    return cm.line_forces(bm, basis, *cm.face_edges(bm, i), lambda sq, tq: direction[:, None, None] * weight(tq)[None])


def station(bm, position: float) -> int:
    """The station of the section line at ``position``."""
    return int(np.argmin(np.abs(bm.s - position)))


def inner_conditions(scene: Scene, pin: str, bm, basis, mid: int):
    """(fixed, pairs, tangents, crows) of the supports inside the span, in the form of
    :func:`reference_fem.plane_conditions.support_conditions` (straight axis: the x/y DOFs are the frame's)."""
    h = scene.section.depth
    ex, ez = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    fixed, pairs, tangents, crows = [], [], [], []
    for s in scene.supports.inner:
        if s.type == "spring":
            continue
        i = station(bm, s.position)
        if s.type == "clamped":
            face = cm.face_node_pairs(bm, basis, i)
            fixed.append(face.ravel())
        elif pin == "face":
            crows.append(section_row(bm, basis, i, ez, _parabola(h)))
            if s.type == "pinned":
                crows.append(section_row(bm, basis, i, ex, lambda tq: np.full_like(tq, 1.0 / h)))
            continue
        else:
            face = basis.nodal_dofs[:, [bm.vid[i, mid]]]
            fixed.append(face.ravel() if s.type == "pinned" else face[1])
        pairs.append(face)
        tangents.append(np.repeat(ex[:, None], face.shape[1], axis=1))
    return fixed, pairs, tangents, crows


def springs(scene: Scene, bm, basis) -> sp.csr_matrix | None:
    """The springs' stiffness k c cᵀ + k_r r rᵀ (module docstring), elastic ends and springs inside the span; None
    without springs."""
    h = scene.section.depth
    ex, ez = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    found = [(0, scene.supports.left), (len(bm.s) - 1, scene.supports.right)]
    found = [(i, s) for i, s in found if isinstance(s, Spring)]
    found += [(station(bm, s.position), s) for s in scene.supports.inner if s.type == "spring"]
    if not found:
        return None
    K = sp.csr_matrix((basis.N, basis.N))
    for i, s in found:
        for k, direction, weight in (
            (s.stiffness or 0.0, ez, _parabola(h)),
            (s.rotational_stiffness or 0.0, ex, lambda tq: -12.0 / h**3 * tq),
        ):
            if k:
                r = sp.csr_matrix(section_row(bm, basis, i, direction, weight))
                K = K + k * (r.T @ r)
    return K.tocsr()


def element_constants(scene: Scene, mesh, lame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lambda*, mu, width) per element from its segment (its centroid's), each (elements, 1) to broadcast over the
    quadrature points; ``lame(E, nu)`` the plane-stress constants."""
    xc = mesh.p[0, mesh.t].mean(axis=0)
    lam, mu, width = (np.empty(len(xc)) for _ in range(3))
    for a, b, sec, mat in scene.pieces():
        on = (xc >= a) & (xc <= b)
        lam[on], mu[on] = lame(mat.E, mat.poissons_ratio)
        width[on] = sec.width
    return lam[:, None], mu[:, None], width[:, None]


def segment_stiffness(basis, scene: Scene, lame):
    """K of a strip whose elements take their segment's constants (:func:`element_constants`)."""
    from skfem import BilinearForm  # scikit-fem is loaded by the model's solve only
    from skfem.helpers import ddot, eye, sym_grad, trace

    @BilinearForm
    def elasticity(u, v, w):
        e_u, e_v = sym_grad(u), sym_grad(v)
        return w.width * ddot(2 * w.mu * e_u + w.lam * eye(trace(e_u), 2), e_v)

    lam, mu, width = element_constants(scene, basis.mesh, lame)
    nq = basis.X.shape[-1]
    return elasticity.assemble(
        basis, lam=np.repeat(lam, nq, axis=1), mu=np.repeat(mu, nq, axis=1), width=np.repeat(width, nq, axis=1)
    )


def checks(scene: Scene) -> list[str]:
    """What the strip cannot represent among these scenes, one line each."""
    out = []
    h = scene.section.height
    for k, (_, _, sec, _) in enumerate(scene.pieces() if scene.segments else []):
        if sec.height is None or sec.width is None:
            out.append(f"segments[{k}].section: the plane-stress strip needs a rectangle (width and height)")
        elif abs(sec.height - h) > 1e-12 * h:
            out.append(
                f"segments[{k}].section.height = {sec.height:g}: the plane-stress strip has one height ({h:g}); "
                "a segment may change the width and the material"
            )
    sup = scene.supports
    if not sup.simple:
        ends = [s for s in (sup.left, sup.right) if isinstance(s, str)]
        if not any(HELD[s][0] for s in ends) and not any(s.type in ("pinned", "clamped") for s in sup.inner):
            out.append(
                f"supports = {sup.kind('left')}-{sup.kind('right')}: nothing holds the strip along its axis (rollers, "
                "guided and free ends and springs slide), so the axial translation is a mechanism; make one support "
                "pinned or clamped"
            )
    return out


def reactions(r: np.ndarray, basis, scene: Scene) -> dict[str, float]:
    """Every support's force, axial force and moment from r = K u - F (module docstring): each node's to the
    nearest support station."""
    stations = [("left", 0.0)] + [(f"inner_{i}", s.position) for i, s in enumerate(scene.supports.inner)]
    stations.append(("right", scene.length))
    at = np.array([p for _, p in stations])
    xd, yd = node_dofs(basis)
    loc = basis.doflocs[:, xd]
    nearest = np.argmin(np.abs(loc[0][:, None] - at[None, :]), axis=1)
    out = {}
    for k, (label, p) in enumerate(stations):
        sel = nearest == k
        fx, fz = r[xd[sel]], r[yd[sel]]
        out[f"force_{label}"] = float(fz.sum())
        out[f"axial_{label}"] = float(fx.sum())
        out[f"moment_{label}"] = float(np.sum((loc[0, sel] - p) * fz - loc[1, sel] * fx))
    return out
