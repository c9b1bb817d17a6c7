"""``fem-plane-stress``: the 2D continuum on [0, L] x [-h/2, h/2], thickness = section width
(scikit-fem; q4 full integration = ANSYS PLANE182 analogue, q8 serendipity, q9 Lagrange).

Plane stress: scikit-fem's ``lame_parameters`` are the plane-strain constants; plane stress uses
lambda* = 2 lambda mu / (lambda + 2 mu) = E nu / (1 - nu²) (tests/test_plane_stress.py would catch the
mix-up against the exact cantilever).

Supports on the end faces: clamped = whole face fixed; pinned = the mid-height node (both directions
at the left, vertical only at the right); guided = the face's horizontal displacement fixed (a symmetry
plane: zero rotation, free to deflect); free = nothing. Loads: distributed loads as a traction on the top
face; a point force at an end as a parabolic shear traction over the end face (the Timoshenko shear
distribution); an interior point force at the top node; an end moment as a linear normal traction
(-C y / I); an interior point moment as two opposite vertical forces on the neighbouring mid-height nodes.
Output: the mid-line (y = 0) deflection and section rotation at the vertices; ``--out result.vtu`` writes
the 2D displacement and cell von Mises stress (meshio).
"""

from __future__ import annotations

import numpy as np

from pdverify.errors import InputError
from pdverify.linalg import solve_linear
from pdverify.registry import Model, Option
from pdverify.result import Result, Timer
from pdverify.scene import Distributed, PointForce, PointMoment, Scene

ELEMENTS = {"q4": "ElementQuad1", "q8": "ElementQuadS2", "q9": "ElementQuad2"}


def mesh_lines(scene: Scene, points: int, layers: int):
    from reference_fem.beam import beam_nodes

    h = scene.section.depth
    x = beam_nodes(scene, points)
    y = np.linspace(-h / 2, h / 2, layers + 1)
    return x, y


class FemPlaneStress(Model):
    name = "fem-plane-stress"
    title = "2D plane-stress continuum (scikit-fem; PLANE182 analogue with q4)"
    source = "scikit-fem linear elasticity, plane-stress Lame constants"
    theory = "continuum"
    reference = True
    options = (
        Option("points", int, 101, "nodes along the beam (elements + 1), load positions added", minimum=2),
        Option("layers", int, 8, "elements through the thickness (even: the mid-line is a node row)", minimum=2),
        Option("element", str, "q4", "q4 (full integration) | q8 | q9", choices=tuple(ELEMENTS)),
    )

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        if scene.section.height is None:
            out.append("section: the plane-stress reference needs a rectangle (width and height)")
        return out

    def solve(self, scene: Scene, params: dict) -> Result:
        import skfem as fem
        from skfem.helpers import dot
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        if params["layers"] % 2:
            raise InputError(f"layers = {params['layers']}: give an even number so the mid-line is a row of nodes")
        timer = Timer()
        with timer("assemble"):
            x, y = mesh_lines(scene, params["points"], params["layers"])
            mesh = fem.MeshQuad.init_tensor(x, y)
            elem = fem.ElementVector(getattr(fem, ELEMENTS[params["element"]])())
            basis = fem.Basis(mesh, elem)
            E, nu, t = scene.material.E, scene.material.poissons_ratio, scene.section.width
            lam, mu = lame_parameters(E, nu)
            lam = 2 * lam * mu / (lam + 2 * mu)  # plane stress
            K = t * linear_elasticity(lam, mu).assemble(basis)
            F = np.zeros(basis.N)
            L, h, I = scene.length, scene.section.depth, scene.section.I
            top = mesh.facets_satisfying(lambda p: np.isclose(p[1], h / 2))
            ftop = fem.FacetBasis(mesh, elem, facets=top, intorder=8)
            for load in scene.loads:
                if isinstance(load, Distributed):
                    a, b = scene.span(load)

                    @fem.LinearForm
                    def q_top(v, w, load=load, a=a, b=b):
                        xx = w.x[0]
                        val = load.value if load.shape == "uniform" else load.value * np.sin(np.pi * xx / L)
                        on = (xx >= a - 1e-12) & (xx <= b + 1e-12)
                        return np.where(on, val, 0.0) * v[1]  # force per length on the top edge

                    F += q_top.assemble(ftop)
            vx = basis.nodal_dofs[0]
            vy = basis.nodal_dofs[1]
            P = mesh.p
            for load in scene.loads:
                at_end = min(abs(load.position - 0.0), abs(load.position - L)) < 1e-12 * L if not isinstance(load, Distributed) else False
                if isinstance(load, PointForce) and at_end:
                    xe = 0.0 if load.position < L / 2 else L
                    face = mesh.facets_satisfying(lambda p, xe=xe: np.isclose(p[0], xe))
                    fb = fem.FacetBasis(mesh, elem, facets=face, intorder=6)

                    @fem.LinearForm
                    def shear(v, w, P_=load.value):
                        tau = 1.5 * P_ / (h) * (1 - (2 * w.x[1] / h) ** 2)  # per length of the face
                        return tau * v[1]

                    F += shear.assemble(fb)
                elif isinstance(load, PointForce):
                    i = np.argmin(np.hypot(P[0] - load.position, P[1] - h / 2))
                    F[vy[i]] += load.value
                elif isinstance(load, PointMoment) and at_end:
                    xe = 0.0 if load.position < L / 2 else L
                    face = mesh.facets_satisfying(lambda p, xe=xe: np.isclose(p[0], xe))
                    fb = fem.FacetBasis(mesh, elem, facets=face, intorder=6)

                    @fem.LinearForm
                    def bending(v, w, C=load.value):
                        return -C * w.x[1] / I * t * v[0]  # traction (per area) times thickness

                    F += bending.assemble(fb)
                elif isinstance(load, PointMoment):
                    mid = np.where(np.isclose(P[1], 0.0))[0]
                    order = mid[np.argsort(P[0, mid])]
                    k = int(np.argmin(np.abs(P[0, order] - load.position)))
                    lo, hi = order[max(k - 1, 0)], order[min(k + 1, len(order) - 1)]
                    arm = P[0, hi] - P[0, lo]
                    F[vy[lo]] -= load.value / arm
                    F[vy[hi]] += load.value / arm
            fixed = []
            mid = np.where(np.isclose(P[1], 0.0))[0]
            for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
                xe = 0.0 if side == 0 else L
                face_dofs = basis.get_dofs(lambda p, xe=xe: np.isclose(p[0], xe))
                if sup == "clamped":
                    fixed.append(face_dofs.all())
                elif sup == "guided":
                    fixed.append(face_dofs.all("u^1"))
                elif sup == "pinned":
                    node = mid[np.isclose(P[0, mid], xe)][0]
                    fixed.append(np.array([vy[node]] + ([vx[node]] if side == 0 else [])))
            fixed = np.unique(np.concatenate(fixed))
            free = np.setdiff1d(np.arange(basis.N), fixed)
            Kf = K[free][:, free]
        with timer("solve"):
            uf, info = solve_linear(Kf, F[free], what="fem-plane-stress", condition=False)
            u = np.zeros(basis.N)
            u[free] = uf
        order = mid[np.argsort(P[0, mid])]
        xs = P[0, order]
        w = u[vy[order]]
        topn = np.where(np.isclose(P[1], h / 2))[0]
        botn = np.where(np.isclose(P[1], -h / 2))[0]
        topn, botn = topn[np.argsort(P[0, topn])], botn[np.argsort(P[0, botn])]
        rot = (u[vx[botn]] - u[vx[topn]]) / h
        info.update(element=params["element"], mesh=f"{len(x) - 1} x {params['layers']} {params['element']}",
                    nodes=mesh.p.shape[1], plane_stress_lambda=lam)

        def write_vtu(path, mesh=mesh, u=u, basis=basis, E=E, nu=nu, lam=lam, mu=mu):
            import meshio

            ux, uy = u[vx], u[vy]
            ip = basis.interpolate(u)
            g = ip.grad  # (2, 2, nelems, nqp)
            exx, eyy, exy = g[0, 0], g[1, 1], 0.5 * (g[0, 1] + g[1, 0])
            sxx = lam * (exx + eyy) + 2 * mu * exx
            syy = lam * (exx + eyy) + 2 * mu * eyy
            sxy = 2 * mu * exy
            vm = np.sqrt(sxx**2 - sxx * syy + syy**2 + 3 * sxy**2).mean(axis=1)
            pts = np.column_stack([mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])])
            meshio.write(path, meshio.Mesh(pts, [("quad", mesh.t.T)],
                                           point_data={"displacement": np.column_stack([ux, uy, 0 * ux])},
                                           cell_data={"von_mises": [vm]}))

        def write_png(path):
            import os
            import tempfile

            from reference_fem.render import render_png

            fd, tmp = tempfile.mkstemp(suffix=".vtu")
            os.close(fd)
            try:
                write_vtu(tmp)
                amp = max(np.abs(u).max(), 1e-300)
                render_png(tmp, path, scale=0.1 * scene.length / amp)  # deformation drawn at 10 % of L
            finally:
                os.unlink(tmp)

        return Result(scene=scene.name, model=self.name, parameters=dict(params), x=xs, w=w, rotation=rot,
                      dofs=len(free), timings=timer.timings, info=info, writers={".vtu": write_vtu, ".png": write_png})


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
