"""``fem-plane-stress``: the 2D continuum of the beam, thickness = section width (scikit-fem; q4 full
integration = ANSYS PLANE182 analogue, q8 serendipity, q9 Lagrange), for straight and curved axes.

Plane stress: scikit-fem's ``lame_parameters`` are the plane-strain constants; plane stress uses
lambda* = 2 lambda mu / (lambda + 2 mu) = E nu / (1 - nu²) (tests/reference_fem/test_plane_stress.py would catch the
mix-up against the exact cantilever).

Geometry (``reference_fem.curved_mesh``): the parameter rectangle (s, t) in [0, L] x [-h/2, h/2] mapped
by X(s) + t n(s); a straight axis gives [0, L] x [-h/2, h/2] exactly; an arc or a polynomial axis y = f(x)
(scene ``[axis]``, beam.length = arc length) gives a curved strip of constant height whose q8/q9 mid-side
nodes lie on the mapped curves. The "top" face is t = +h/2 (the +n side; for a counter-clockwise arc the
inner face), except on a clockwise arc (``direction = "clockwise"``), where it is t = -h/2, again the inner
face: a clockwise arc is then the mirror image of the counter-clockwise one, normal loads on the mirrored face
(the +n face of a clockwise arc is the outer one, and the face a load acts on moves the 2D solution:
docs/models/curved.md). t and n below are the axis tangent and normal at the station concerned.

Supports on the end faces (s = 0, L), the same meaning at both ends and in every model (docs/supports.md):
clamped = whole face fixed; pinned = both displacements (t and n) of the mid-height node held; roller = its
normal (n) displacement only (slides along the end tangent; for a straight beam: vertical only). That point
reaction is a 2D point force: the deflection grows like log(1/element size) (q8, L/h = 5: +1 % of w per mesh
halving, never converging); option ``pin = face`` (default) instead makes the parabola-weighted mean normal
displacement of the end face zero (pinned: and its mean tangential displacement), a parabolic shear
reaction: converges at order ~4 and matches Timoshenko & Goodier's 2D simply supported beam to 4e-4
(L/h = 5). guided = the end face cannot rotate: every face node's tangential displacement equals the
mid-height node's (the face stays straight and normal to the axis, it slides freely along t and n); free =
nothing. A support pair that leaves a rigid-body motion (two rollers on a straight axis or on an arc, a
ring pinned at both ends) is rejected by ``check`` (:func:`pdverify.core.geometry.mechanism_message`).
Loads (value along n, axial along t; ``frame = "global"``: (axial, value) = global (x, y), decomposed into
the local t and n at each point): a distributed load's normal part is a traction on the top face, its
tangential part a line load on the mid-line (no eccentric moment, as in the beam models), both per unit
axis length; a point force at an end is a parabolic shear traction over the end face (the Timoshenko
shear distribution, along n_end) plus a uniform traction for its tangential part; an interior point force
acts at the top node (normal part) and at the mid-height node (tangential part); an end moment is a
linear normal traction (-C t / I, along the end tangent); an interior point moment the same linear traction
on the section line through its station (along that station's tangent), so that its deflection converges (a
pair of opposite forces on the neighbouring mid-height nodes would grow as the mesh is refined, and the
deflection under it with them, like a 2D point force's, logarithmically).
(:mod:`reference_fem.plane_conditions` assembles these loads and supports and sums the reactions.)
Output: at the mid-line vertices (t = 0), x = arc length s, w = u·n, fields u = u·t (tangential),
ux, uy (global), rotation of the section line = (u_t(bottom) - u_t(top)) / h; ``--out result.vtu``
writes the element's own cells (quad / quad8 / quad9) with the displacement and the nodal stresses
(reference_fem/vtu.py), ``--out result.png`` a picture (colour bar and displacement scale stated);
``info.load_resultant`` = (Fx, Fy, Mz about the axis' left end) of the assembled load vector (every
load above is placed so that it equals the beam load's resultant); ``info.reactions`` = K u - F summed over
each end's nodes (force along the end normal, axial, moment ccw about the end of the axis); option
``stations``: ``info.sections``, sigma_xx(z), sigma_zz(z), tau_xz(z) at those x (reference_fem/stresses.py).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from pdverify.core.contract import MAX_POINTS, Model, Option
from pdverify.core.errors import InputError
from pdverify.core.geometry import geometry, mechanism_message
from pdverify.core.result import Result, Timer
from pdverify.core.scene import Scene
from pdverify.core.stations import STATIONS_HELP, parse_stations
from pdverify.numerics.factorcache import digest
from pdverify.numerics.kept import Kept
from pdverify.numerics.linalg import solve_linear
from reference_fem import curved_mesh as cm
from reference_fem import plane_scenes, q4_variants, vtu
from reference_fem.beam import beam_nodes
from reference_fem.plane_conditions import (
    constrained_system,
    full_displacement,
    load_resultant,
    load_vector,
    reactions,
    support_conditions,
)
from reference_fem.render import render_png
from reference_fem.stresses import through_section

MAX_ELEMENTS = 200_000  # elements of a strip mesh (points - 1) x layers; more is refused before the mesh is built

ELEMENTS = {
    "q4": "ElementQuad1",
    "q8": "ElementQuadS2",
    "q9": "ElementQuad2",
    "q4-bbar": "ElementQuad1",
    "q4-qm6": "ElementQuad1",
    "q4-reduced": "ElementQuad1",
}  # q4-*: PLANE182 KEYOPT(1) = 0, 2/3, 1 (q4_variants)
LOCKING_ELEMENTS = ("q4", "q4-bbar")  # full integration: parasitic shear in bending (a warning on every result)


def mesh_lines(scene: Scene, points: int, layers: int):
    """Stations s along the axis (load positions and span ends included) and through-thickness t."""

    h = scene.section.depth
    x = beam_nodes(scene, points)
    y = np.linspace(-h / 2, h / 2, layers + 1)
    return x, y


def strip_mesh(scene: Scene, points: int, layers: int, element: str) -> cm.BeamMesh:
    """The mesh of the strip: the parameter grid of :func:`mesh_lines` mapped onto the axis, with q8/q9 mid-side
    nodes on the mapped curves on a curved axis (straight-edged q4 and straight axes)."""
    s, tt = mesh_lines(scene, points, layers)
    return cm.build_mesh(scene, s, tt, quadratic_geometry=(not scene.is_straight and not element.startswith("q4")))


def plane_stress_lame(E: float, nu: float) -> tuple[float, float]:
    """(lambda*, mu): scikit-fem's plane-strain Lame constants with lambda* = 2 lambda mu / (lambda + 2 mu)
    = E nu / (1 - nu²), the plane-stress constant."""
    from skfem.models.elasticity import lame_parameters  # scikit-fem is loaded by the model's solve only

    lam, mu = lame_parameters(E, nu)
    return 2 * lam * mu / (lam + 2 * mu), mu


_KEPT = Kept(6, budget=cm.KEPT_DOFS, size=lambda kept: kept[0].N)  # mesh digest -> (basis, K): another load on
# the same strip; the grids of a card's scene (641 ... 21 stations: 49,000 unknowns), bases of at most cm.KEPT_DOFS
# unknowns together


def basis_and_stiffness(mesh, scene: Scene, element: str, lam: float, mu: float):
    """(the vector basis, K, the key that determines K) of one material on ``mesh``, kept for the last six meshes of
    up to :data:`reference_fem.curved_mesh.KEPT_DOFS` unknowns together (by their nodes' and elements' bytes, the
    element, the constants and the width): a study solves the same strip under several loads, scene by scene on
    each of its grids, and the assembly is a deterministic function of these."""
    import skfem as fem

    key = digest(
        mesh.p, mesh.t, params=(element, lam, mu, scene.material.E, scene.material.poissons_ratio, scene.section.width)
    )

    def make():
        basis = fem.Basis(mesh, fem.ElementVector(getattr(fem, ELEMENTS[element])()))
        K = stiffness(basis, scene, element, lam, mu)
        K.data.flags.writeable = False  # shared: every use makes new matrices (K + Ks, K @ u, constrained_system)
        return basis, K

    return (*_KEPT.get(key, make), key)


def stiffness(basis, scene: Scene, element: str, lam: float, mu: float):
    """K of the strip (thickness = section width): plane-stress linear elasticity (:func:`elasticity`; q4 with 3x3
    Gauss, q8, q9), or
    the PLANE182 stand-ins q4-bbar, q4-qm6, q4-reduced (:mod:`reference_fem.q4_variants`)."""
    E, nu, width = scene.material.E, scene.material.poissons_ratio, scene.section.width
    if element.startswith("q4-"):
        return width * q4_variants.assemble(basis.mesh, basis, E, nu, element[3:])
    return width * elasticity(basis, lam, mu)


def elasticity(basis, lam: float, mu: float) -> sp.csr_matrix:
    """∫ sigma(u) : eps(v) dx, sigma = lam tr(eps) I + 2 mu eps: the bilinear form of scikit-fem's
    ``linear_elasticity``. With each basis function's strain components (tr, exx, eyy, exy) at the quadrature
    points as the rows of A_e, every element's matrix is A_e W A_eᵀ, W = (lam, 2 mu, 2 mu, 4 mu) times the
    quadrature weights: one batched matrix product over the elements (scikit-fem's assembly calls the form once
    per pair of basis functions)."""
    from skfem.helpers import sym_grad  # scikit-fem is loaded by the model's solve only

    eps = [sym_grad(phi[0]) for phi in basis.basis]  # per function (2, 2, elements, quadrature points)
    nf, (ne, nq) = len(eps), basis.dx.shape
    A = np.empty((ne, nf, 4, nq))
    for i, e in enumerate(eps):  # a loop over the element's basis functions (8 to 18), not over elements
        A[:, i, 0] = e[0, 0] + e[1, 1]
        A[:, i, 1], A[:, i, 2], A[:, i, 3] = e[0, 0], e[1, 1], e[0, 1]
    AW = A * (np.array([lam, 2.0 * mu, 2.0 * mu, 4.0 * mu])[:, None] * basis.dx[:, None, :])[:, None]
    ke = np.matmul(AW.reshape(ne, nf, 4 * nq), A.reshape(ne, nf, 4 * nq).transpose(0, 2, 1))  # (elements, i, j)
    dofs = basis.element_dofs.T  # (elements, functions)
    rows = np.broadcast_to(dofs[:, :, None], ke.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], ke.shape).ravel()
    K = sp.coo_matrix((ke.ravel(), (rows, cols)), shape=(basis.N, basis.N)).tocsr()
    K.eliminate_zeros()  # as scikit-fem's assembly does
    return K


def face_rows(scene: Scene, nt: int) -> tuple[int, int]:
    """(loaded face, mid-line): node rows of the face that carries the normal loads (t = +h/2; on a clockwise arc
    t = -h/2, the inner face as on a counter-clockwise arc) and of the mid-line, of nt rows."""
    top = 0 if scene.axis.type == "arc" and scene.axis.direction == "clockwise" else nt - 1
    return top, nt // 2


def midline_fields(u: np.ndarray, basis, bm: cm.BeamMesh, tan_s: np.ndarray, nor_s: np.ndarray, h: float):
    """(w, rotation, fields) at the mid-line vertices: w = u·n, u = u·t, (ux, uy) global, rotation of the section
    line = (u_t(bottom) - u_t(top)) / h."""
    nt = len(bm.t)
    vx, vy = basis.nodal_dofs[0], basis.nodal_dofs[1]
    mid, topn, botn = bm.vid[:, nt // 2], bm.vid[:, nt - 1], bm.vid[:, 0]
    ux, uy = u[vx[mid]], u[vy[mid]]
    w = ux * nor_s[:, 0] + uy * nor_s[:, 1]
    ut = ux * tan_s[:, 0] + uy * tan_s[:, 1]

    def tangential(nodes):
        return u[vx[nodes]] * tan_s[:, 0] + u[vy[nodes]] * tan_s[:, 1]

    rot = (tangential(botn) - tangential(topn)) / h
    return w, rot, {"u": ut, "ux": ux, "uy": uy}


def locking_warning(element: str, scene: Scene, stations: int, layers: int) -> str | None:
    """The warning of a fully integrated q4 (parasitic shear in bending), with the elements' aspect ratio."""
    if element not in LOCKING_ELEMENTS:
        return None
    aspect = (scene.length / (stations - 1)) / (scene.section.depth / layers)
    return (
        f"element = {element}: full integration locks in bending (parasitic shear), here with elements "
        f"{aspect:.3g} times as long as they are thick; the deflection may be far too small (-27 % on a "
        "100 x 8 cantilever at L/h = 100, docs/models/yang.md): use q8, q4-qm6 or q4-reduced"
    )


def writers(scene: Scene, basis, u: np.ndarray, lam: float, mu: float) -> dict:
    """The result's writers: ``.vtu`` the element's own cells with the displacement and the nodal stresses
    (:mod:`reference_fem.vtu`), ``.png`` a picture of it (deformation drawn at 10 % of L)."""

    def write_vtu(path, u=u, basis=basis, lam=lam, mu=mu):
        vtu.write(path, basis, u, lam, mu)

    def write_png(path):
        import os
        import tempfile

        fd, tmp = tempfile.mkstemp(suffix=".vtu")
        os.close(fd)
        try:
            write_vtu(tmp)
            amp = max(np.abs(u).max(), 1e-300)
            render_png(tmp, path, scale=0.1 * scene.length / amp)  # deformation drawn at 10 % of L
        finally:
            os.unlink(tmp)

    return {".vtu": write_vtu, ".png": write_png}


class FemPlaneStress(Model):
    name = "fem-plane-stress"
    shapes = frozenset({"rectangle", "given"})  # its equations use the depth of a rectangle
    title = "2D plane-stress continuum (scikit-fem; q8 by default, PLANE182 stand-ins q4-*), straight or curved axis"
    source = "scikit-fem linear elasticity, plane-stress Lame constants; mesh mapped onto the axis"
    theory = "continuum"
    reference = True
    curved = True
    axial = True
    springs = True  # straight axes (the scene's rule): reference_fem.plane_scenes
    inner_supports = True
    segments = True
    options = (
        Option(
            "points",
            int,
            101,
            "nodes along the beam (elements + 1), load positions added",
            minimum=2,
            maximum=MAX_POINTS,
        ),
        Option("layers", int, 8, "elements through the thickness (even: the mid-line is a node row)", minimum=2),
        Option(
            "element",
            str,
            "q8",
            "q8 (default: no locking in bending) | q9 | q4 (full integration, 3x3 Gauss; locks in bending) | "
            "q4-bbar (2x2 with B-bar: PLANE182 KEYOPT(1)=0; locks in bending) | "
            "q4-qm6 (incompatible modes, Taylor's QM6: as PLANE182's enhanced strain, KEYOPT(1)=2/3) | "
            "q4-reduced (1-point quadrature + Flanagan-Belytschko hourglass vectors with bending stiffness: "
            "PLANE182 KEYOPT(1)=1)",
            choices=tuple(ELEMENTS),
        ),
        Option(
            "pin",
            str,
            "face",
            "pinned support: node = the mid-height node (PLANE182 practice; its point "
            "reaction makes the 2D deflection grow like log(1/element size)) | face = parabola-weighted mean "
            "normal (and, at the left, mean tangential) displacement of the end face zero (converges)",
            choices=("node", "face"),
        ),
        Option("stations", str, "", STATIONS_HELP + " (straight axes)"),
    )

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """A mesh of more than :data:`MAX_ELEMENTS` elements, refused before it is built."""
        elements = (params["points"] - 1) * params["layers"]
        if elements <= MAX_ELEMENTS:
            return []
        return [
            f"points = {params['points']}, layers = {params['layers']}: {elements:,} elements, more than the "
            f"{MAX_ELEMENTS:,} a reference mesh may have (its sparse LU holds about 50 kB an element: 80,000 q8 "
            "elements took 4 GB and 19 s); use fewer points or layers"
        ]

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if scene.section.height is None:  # one line: the declared shapes' own where it names the shape
            said = any(line.startswith("section.shape") for line in out)
            return out if said else [*out, "section: the plane-stress reference needs a rectangle (width and height)"]

        if not scene.is_straight:
            h = scene.section.height
            kmax = float(np.max(np.abs(geometry(scene).curvature(np.linspace(0, scene.length, 401)))))
            if kmax * h / 2 >= 1:
                out.append(
                    f"section.height = {h!r}: the face on the concave side would cross the centre of "
                    f"curvature (smallest radius {1 / kmax:.6g} <= h/2); give height < {2 / kmax:.6g}"
                )
        if not scene.supports.simple or scene.segments:
            return out + plane_scenes.checks(scene)
        why = mechanism_message(scene)  # also the axial slide of two rollers on a straight axis
        return out + ([why] if why is not None else [])

    def solve(self, scene: Scene, params: dict) -> Result:
        import skfem as fem

        if params["layers"] % 2:
            raise InputError(f"layers = {params['layers']}: give an even number so the mid-line is a row of nodes")
        stations = parse_stations(params.get("stations", ""), scene.length)
        if len(stations) and not scene.is_straight:
            raise InputError("stations: through-section stresses are given for straight axes only")
        el, h = params["element"], scene.section.depth
        timer = Timer()
        with timer("assemble"):
            bm = strip_mesh(scene, params["points"], params["layers"], el)
            lam, mu = plane_stress_lame(scene.material.E, scene.material.poissons_ratio)
            if scene.segments:  # each element its segment's constants (reference_fem.plane_scenes)
                if el.startswith("q4-"):
                    raise InputError(f"segments: element = {el} takes one material; use element q8, q9 or q4")
                basis = fem.Basis(bm.mesh, fem.ElementVector(getattr(fem, ELEMENTS[el])()))
                K, key = plane_scenes.segment_stiffness(basis, scene, plane_stress_lame), None
            else:
                basis, K, key = basis_and_stiffness(bm.mesh, scene, el, lam, mu)
            top, mid = face_rows(scene, len(bm.t))
            tan_s, nor_s = bm.geo.frame(bm.s)
            F = load_vector(scene, bm, basis, tan_s, nor_s, top, mid)
            conditions = support_conditions(scene, params["pin"], bm, basis, tan_s, nor_s, mid)
            inner = plane_scenes.inner_conditions(scene, params["pin"], bm, basis, mid)
            conditions = tuple(a + b for a, b in zip(conditions, inner, strict=True))
            Ks = plane_scenes.springs(scene, bm, basis)
            elastic, key = (K, key) if Ks is None else (K + Ks, None)  # a spring's stiffness: K's key no longer
            Kf, Ff, free, T, S, key = constrained_system(elastic, F, basis.N, *conditions, key=key)
        with timer("solve"):
            uf, info = solve_linear(Kf, Ff, what="fem-plane-stress", condition=el.startswith("q4-"), key=key)
            u = full_displacement(uf, free, basis.N, T, S)
        w, rot, fields = midline_fields(u, basis, bm, tan_s, nor_s, h)
        ns = len(bm.s)
        flag = locking_warning(el, scene, ns, params["layers"])
        if flag:
            info.setdefault("warnings", []).append(flag)
        info.update(
            element=el,
            mesh=f"{ns - 1} x {params['layers']} {el}",
            nodes=bm.mesh.p.shape[1],
            plane_stress_lambda=lam,
            load_resultant=load_resultant(F, basis, bm.geo),
        )
        if scene.supports.simple:  # K u - F: the supports' forces on the strip (springs' included: K is elastic)
            info["reactions"] = reactions(K @ u - F, basis, bm.geo, scene.length)
        else:
            info["reactions"] = plane_scenes.reactions(K @ u - F, basis, scene)
        if len(stations):
            info["sections"] = through_section(basis, u, stations, h, 4 * params["layers"] + 1, lam, mu)
        if not scene.is_straight:
            info.update(
                axis=scene.axis.type,
                geometry=("quadratic edges on the mapped curves" if not el.startswith("q4") else "straight-edged q4"),
            )
        return self.new_result(
            scene,
            params,
            bm.s,
            w,
            rotation=rot,
            fields=fields,
            dofs=len(free),
            timings=timer.timings,
            info=info,
            writers=writers(scene, basis, u, lam, mu),
        )


MODELS = [FemPlaneStress()]


def write_pvd(path: str, series: list[tuple[float, str]]) -> None:
    """A ParaView collection (.pvd) of VTU files for a series: [(time or load factor, vtu file), ...];
    file names are written relative to the .pvd's folder when they are inside it."""
    import os
    from xml.sax.saxutils import quoteattr

    base = os.path.dirname(os.path.abspath(path))
    rows = []
    for t, f in series:
        rel = os.path.relpath(os.path.abspath(f), base)
        rows.append(f'    <DataSet timestep="{float(t)!r}" group="" part="0" file={quoteattr(rel)}/>')
    with open(path, "w", encoding="utf-8") as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n')
        fh.write("\n".join(rows) + "\n  </Collection>\n</VTKFile>\n")
