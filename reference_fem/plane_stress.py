"""``fem-plane-stress``: the 2D continuum of the beam, thickness = section width (scikit-fem; q4 full
integration = ANSYS PLANE182 analogue, q8 serendipity, q9 Lagrange), for straight and curved axes.

Plane stress: scikit-fem's ``lame_parameters`` are the plane-strain constants; plane stress uses
lambda* = 2 lambda mu / (lambda + 2 mu) = E nu / (1 - nu²) (tests/test_plane_stress.py would catch the
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
on the section line through its station (along that station's tangent), so that its deflection converges: the
pair of opposite forces on the neighbouring mid-height nodes used before grew as the mesh was refined, and the
deflection under it with them, like a 2D point force's (log): 1.7e-2, 4.3e-2, 1.1e-1 from exact Timoshenko at
101, 401, 1601 points (pinned-pinned, L/h = 20, couple at L/4; now 3.1e-4, 3.2e-4, 3.2e-4, the theories' gap).
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

from pdverify.core.contract import Model, Option
from pdverify.core.errors import InputError
from pdverify.core.geometry import geometry, mechanism_message
from pdverify.core.result import Result, Timer
from pdverify.core.scene import Distributed, PointForce, Scene
from pdverify.core.stations import STATIONS_HELP, parse_stations
from pdverify.numerics.linalg import solve_linear
from reference_fem import curved_mesh as cm
from reference_fem import q4_variants, vtu
from reference_fem.beam import beam_nodes
from reference_fem.render import render_png
from reference_fem.stresses import through_section

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


def _couple(C: float, te: np.ndarray, I: float, width: float):
    """The line density of a couple C on a section line with tangent te: the bending stress -C t / I along te
    times the thickness (per unit length of the line); its moment about the mid-height is C."""

    def density(sq, tq):
        return te[:, None, None] * (-C * tq / I * width)[None]

    return density


def _local(load, tan: np.ndarray, nor: np.ndarray):
    """(tangential, normal) components of a load's (axial, value) in its frame, at frames (…, 2)."""
    if getattr(load, "frame", "local") == "global":
        g = np.array([load.axial, load.value])
        return tan @ g, nor @ g
    return np.full(tan.shape[:-1], float(load.axial)), np.full(tan.shape[:-1], float(load.value))


def _reactions(r: np.ndarray, basis, geo, length: float) -> dict[str, float]:
    """Support reactions from r = K u - F (the nodal forces the supports put on the strip; round-off elsewhere),
    summed over the nodes nearer each end: force along the end normal (+z for a straight beam), axial along the
    end tangent, moment counter-clockwise about the end of the axis."""
    ends = geo.position(np.array([0.0, length]))
    tan, nor = geo.frame(np.array([0.0, length]))
    xd, yd = _dofs(basis)
    loc = basis.doflocs[:, xd]
    near_left = np.hypot(*(loc - ends[0][:, None])) <= np.hypot(*(loc - ends[1][:, None]))
    out = {}
    for k, side in enumerate(("left", "right")):
        sel = near_left if k == 0 else ~near_left
        fx, fy = r[xd[sel]], r[yd[sel]]
        arm = loc[:, sel] - ends[k][:, None]
        f = np.array([fx.sum(), fy.sum()])
        out[f"force_{side}"] = float(f @ nor[k])
        out[f"axial_{side}"] = float(f @ tan[k])
        out[f"moment_{side}"] = float(np.sum(arm[0] * fy - arm[1] * fx))
    return out


def _dofs(basis) -> tuple[np.ndarray, np.ndarray]:
    """(x-DOFs, y-DOFs) of every node (vertices, and the mid-side / centre nodes of q8 / q9), paired."""
    xs, ys = [basis.nodal_dofs[0]], [basis.nodal_dofs[1]]
    for d in (basis.facet_dofs, basis.interior_dofs):
        if d.shape[0]:
            xs.append(d[0])
            ys.append(d[1])
    return np.concatenate(xs), np.concatenate(ys)


class FemPlaneStress(Model):
    name = "fem-plane-stress"
    title = "2D plane-stress continuum (scikit-fem; q8 by default, PLANE182 stand-ins q4-*), straight or curved axis"
    source = "scikit-fem linear elasticity, plane-stress Lame constants; mesh mapped onto the axis"
    theory = "continuum"
    reference = True
    curved = True
    axial = True
    options = (
        Option("points", int, 101, "nodes along the beam (elements + 1), load positions added", minimum=2),
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

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if scene.section.height is None:
            out.append("section: the plane-stress reference needs a rectangle (width and height)")
            return out

        if not scene.is_straight:
            h = scene.section.height
            kmax = float(np.max(np.abs(geometry(scene).curvature(np.linspace(0, scene.length, 401)))))
            if kmax * h / 2 >= 1:
                out.append(
                    f"section.height = {h!r}: the face on the concave side would cross the centre of "
                    f"curvature (smallest radius {1 / kmax:.6g} <= h/2); give height < {2 / kmax:.6g}"
                )
        why = mechanism_message(scene)  # also the axial slide of two rollers on a straight axis
        return out + ([why] if why is not None else [])

    def solve(self, scene: Scene, params: dict) -> Result:
        import skfem as fem
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        if params["layers"] % 2:
            raise InputError(f"layers = {params['layers']}: give an even number so the mid-line is a row of nodes")
        stations = parse_stations(params.get("stations", ""), scene.length)
        if len(stations) and not scene.is_straight:
            raise InputError("stations: through-section stresses are given for straight axes only")
        timer = Timer()
        with timer("assemble"):
            el = params["element"]
            s, tt = mesh_lines(scene, params["points"], params["layers"])
            bm = cm.build_mesh(scene, s, tt, quadratic_geometry=(not scene.is_straight and not el.startswith("q4")))
            mesh, geo = bm.mesh, bm.geo
            elem = fem.ElementVector(getattr(fem, ELEMENTS[el])())
            basis = fem.Basis(mesh, elem)
            E, nu, width = scene.material.E, scene.material.poissons_ratio, scene.section.width
            lam, mu = lame_parameters(E, nu)
            lam = 2 * lam * mu / (lam + 2 * mu)  # plane stress
            if el.startswith("q4-"):
                K = width * q4_variants.assemble(mesh, basis, E, nu, el[3:])
            else:
                K = width * linear_elasticity(lam, mu).assemble(basis)
            L, h, I = scene.length, scene.section.depth, scene.section.I
            ns, nt = len(s), len(tt)
            jm = nt // 2  # mid-line row
            top = 0 if scene.axis.type == "arc" and scene.axis.direction == "clockwise" else nt - 1  # loaded face
            F = np.zeros(basis.N)
            tan_s, nor_s = geo.frame(s)
            for load in scene.loads:
                if isinstance(load, Distributed):
                    a, b = scene.span(load)

                    def profile(sq, load=load):
                        return np.ones_like(sq) if load.shape == "uniform" else np.sin(np.pi * sq / L)

                    def normal_part(sq, tq, load=load):
                        tq_, nq_ = geo.frame(sq)
                        _, qn = _local(load, tq_, nq_)
                        return np.moveaxis(nq_ * (qn * profile(sq))[..., None], -1, 0)

                    def tangential_part(sq, tq, load=load):
                        tq_, nq_ = geo.frame(sq)
                        qt, _ = _local(load, tq_, nq_)
                        return np.moveaxis(tq_ * (qt * profile(sq))[..., None], -1, 0)

                    F += cm.line_forces(bm, basis, *cm.row_edges(bm, top, a, b), normal_part)
                    if load.axial != 0.0 or load.frame == "global":
                        F += cm.line_forces(bm, basis, *cm.row_edges(bm, jm, a, b), tangential_part)
                    continue
                at_end = min(abs(load.position - 0.0), abs(load.position - L)) < 1e-12 * L
                i = 0 if load.position < L / 2 else ns - 1
                if at_end:
                    te, ne = tan_s[i], nor_s[i]
                    if isinstance(load, PointForce):
                        ft, fn = _local(load, te, ne)

                        def end_force(sq, tq, ft=float(ft), fn=float(fn), te=te, ne=ne):
                            tau = 1.5 * fn / h * (1 - (2 * tq / h) ** 2)  # parabolic shear, per face length
                            return ne[:, None, None] * tau[None] + te[:, None, None] * (ft / h)

                        F += cm.line_forces(bm, basis, *cm.face_edges(bm, i), end_force)
                    else:
                        F += cm.line_forces(bm, basis, *cm.face_edges(bm, i), _couple(load.value, te, I, width))
                    continue
                k = int(np.argmin(np.abs(s - load.position)))
                if isinstance(load, PointForce):
                    ft, fn = _local(load, tan_s[k], nor_s[k])
                    topk, midn = bm.vid[k, top], bm.vid[k, jm]
                    F[basis.nodal_dofs[:, topk]] += fn * nor_s[k]
                    if ft != 0.0:
                        F[basis.nodal_dofs[:, midn]] += ft * tan_s[k]
                else:  # the end moment's traction on the section line s = s_k (a force pair would be singular)
                    F += cm.line_forces(bm, basis, *cm.face_edges(bm, k), _couple(load.value, tan_s[k], I, width))
            # resultant of the assembled loads (force, moment about the left end of the axis): a check of
            # the load assembly against the scene's beam loads
            xd = (
                np.concatenate([basis.nodal_dofs[0], basis.facet_dofs[0]])
                if basis.facet_dofs.shape[0]
                else basis.nodal_dofs[0]
            )
            yd = (
                np.concatenate([basis.nodal_dofs[1], basis.facet_dofs[1]])
                if basis.facet_dofs.shape[0]
                else basis.nodal_dofs[1]
            )
            rel = basis.doflocs[:, xd] - geo.position(np.array([0.0]))[0][:, None]
            resultant = [float(F[xd].sum()), float(F[yd].sum()), float(np.sum(rel[0] * F[yd] - rel[1] * F[xd]))]
            # supports: constraints on tangential / normal components of the end-face nodes
            fixed, pairs, tangents, crows = [], [], [], []
            for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
                i = 0 if side == 0 else ns - 1
                if sup == "free":
                    continue
                if sup in ("pinned", "roller") and params["pin"] == "face":
                    # weighted means of the face displacement: ∫ φ u·d dt = 0 (consistent line integrals)
                    dirs = [(nor_s[i], lambda tq: 1.5 / h * (1 - (2 * tq / h) ** 2))]
                    if sup == "pinned":
                        dirs.append((tan_s[i], lambda tq: np.full_like(tq, 1.0 / h)))
                    for d, phi in dirs:
                        crows.append(
                            cm.line_forces(
                                bm,
                                basis,
                                *cm.face_edges(bm, i),
                                lambda sq, tq, d=d, phi=phi: d[:, None, None] * phi(tq)[None],
                            )
                        )
                    continue
                if sup in ("pinned", "roller"):
                    face = basis.nodal_dofs[:, [bm.vid[i, jm]]]
                else:
                    face = cm.face_node_pairs(bm, basis, i)
                pairs.append(face)
                tangents.append(np.repeat(tan_s[i][:, None], face.shape[1], axis=1))
                if sup in ("clamped", "pinned"):
                    fixed.append(face.ravel())
                elif sup == "roller":
                    fixed.append(face[1])  # u' y-slot = normal component
                else:  # guided: every face node's tangential component equals the first one's (no rotation)
                    for k in range(1, face.shape[1]):
                        row = np.zeros(basis.N)
                        row[face[:, k]] += tan_s[i]
                        row[face[:, 0]] -= tan_s[i]
                        crows.append(row)
            K0, F0 = K, F.copy()  # before the supports' rotation: the reactions are K0 u - F0
            T = None
            if pairs:
                pr, tg = np.hstack(pairs), np.hstack(tangents)
                if not (np.all(tg[0] == 1.0) and np.all(tg[1] == 0.0)):
                    T = cm.rotation_matrix(basis.N, pr, tg)
                    K = (T.T @ K @ T).tocsr()
                    F = T.T @ F
            fixed = np.unique(np.concatenate(fixed)) if fixed else np.zeros(0, dtype=np.int64)
            Kf, Ff, _, free = fem.condense(K, F, D=fixed)  # the held DOFs (zero) eliminated
            S = None
            if crows:  # eliminate one master dof per face-mean constraint: u_f = S v
                C = np.vstack(crows)
                if T is not None:
                    C = np.asarray((T.T @ C.T).T)
                S = cm.constraint_basis(C[:, free])
                Kf, Ff = (S.T @ Kf @ S).tocsr(), S.T @ Ff
        with timer("solve"):
            uf, info = solve_linear(Kf, Ff, what="fem-plane-stress", condition=el.startswith("q4-"))
            if S is not None:
                uf = S @ uf
            u = np.zeros(basis.N)
            u[free] = uf
            if T is not None:
                u = T @ u
        vx, vy = basis.nodal_dofs[0], basis.nodal_dofs[1]
        mid, topn, botn = bm.vid[:, jm], bm.vid[:, nt - 1], bm.vid[:, 0]
        ux, uy = u[vx[mid]], u[vy[mid]]
        w = ux * nor_s[:, 0] + uy * nor_s[:, 1]
        ut = ux * tan_s[:, 0] + uy * tan_s[:, 1]

        def tangential(nodes):
            return u[vx[nodes]] * tan_s[:, 0] + u[vy[nodes]] * tan_s[:, 1]

        rot = (tangential(botn) - tangential(topn)) / h
        if el in LOCKING_ELEMENTS:
            aspect = (scene.length / (ns - 1)) / (h / params["layers"])
            info.setdefault("warnings", []).append(
                f"element = {el}: full integration locks in bending (parasitic shear), here with elements "
                f"{aspect:.3g} times as long as they are thick; the deflection may be far too small (-27 % on a "
                "100 x 8 cantilever at L/h = 100, docs/models/yang.md): use q8, q4-qm6 or q4-reduced"
            )
        info.update(
            element=el,
            mesh=f"{ns - 1} x {params['layers']} {el}",
            nodes=mesh.p.shape[1],
            plane_stress_lambda=lam,
            load_resultant=resultant,
        )
        info["reactions"] = _reactions(K0 @ u - F0, basis, geo, scene.length)
        if len(stations):
            info["sections"] = through_section(basis, u, stations, h, 4 * params["layers"] + 1, lam, mu)
        if not scene.is_straight:
            info.update(
                axis=scene.axis.type,
                geometry=("quadratic edges on the mapped curves" if not el.startswith("q4") else "straight-edged q4"),
            )

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

        return self.new_result(
            scene,
            params,
            s,
            w,
            rotation=rot,
            fields={"u": ut, "ux": ux, "uy": uy},
            dofs=len(free),
            timings=timer.timings,
            info=info,
            writers={".vtu": write_vtu, ".png": write_png},
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
