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
from scipy.interpolate import CubicHermiteSpline

from pdverify.core.contract import LOAD_TYPES, MAX_POINTS, Model, Option, System
from pdverify.core.result import Result, Timer
from pdverify.core.scene import Scene
from pdverify.numerics.band import Band
from pdverify.numerics.linalg import solve_linear

from .beam_elements import (
    add_springs,
    beam_nodes,
    constrained_dofs,
    element_band,
    element_loads,
    element_properties,
    element_vector,
    held_rows,
    hermite_shapes,
    hermite_stiffness,
    hold_supports,
    iie_shapes,
    line_load,
    linear_shapes,
    linear_timoshenko,
    merge_warnings,
    natural_band,
    nodal_point_loads,
    reactions,
)
from .beam_plastic import solve_path
from .beam_resultants import end_forces, nodal, statics
from .beam_transient import free_system, transient


class _BeamFE(Model):
    """Shared by the two beam elements: ``assemble_band`` gives (K, F, nodes) before the supports. Every support
    inside the span and every segment end is a node; springs add their stiffness to their node's DOF."""

    springs = True
    inner_supports = True
    segments = True

    def assemble_band(self, scene: Scene, params: dict):  # pragma: no cover - interface
        raise NotImplementedError

    assembles = True

    def assemble(self, scene: Scene, params: dict) -> System:
        """The system ``solve`` factorises: the two-field band of :meth:`assemble_mixed` (``form = mixed``), or
        the band of :meth:`assemble_band` with the supported DOFs held (unit rows, cleared columns); free: the
        unknowns not held (two-field: w_i, w'_i or theta_i and the element end moments)."""
        if self.mixed(params):
            K, b, nodes, s, (rows, loads) = self.assemble_mixed(scene, params)
            fixed = constrained_dofs(scene, nodes)
            held = 4 * (fixed // 2) + fixed % 2
            info = {"nodes": nodes, "scaling": s, "held_rows": rows, "loads": loads}
            return System(K, b, np.delete(np.arange(K.n), held), info)
        K, F, nodes = self.assemble_band(scene, params)
        add_springs(scene, K, nodes)
        fixed = constrained_dofs(scene, nodes)
        rows, loads = held_rows(K, fixed), F.copy()
        K, F, _ = hold_supports(scene, K, F, nodes)
        return System(
            K, F, np.delete(np.arange(2 * len(nodes)), fixed), {"nodes": nodes, "held_rows": rows, "loads": loads}
        )

    def mixed(self, params: dict) -> bool:
        """True when the two-field form (:func:`natural_band`) is solved; the elements' own stiffness K
        (``form = direct``) otherwise and for the linear contrast variants, which have no such form."""
        return params.get("form", "mixed") == "mixed" and params.get("variant", "iie") == "iie"

    def nodal_loads(self, scene: Scene, params: dict, nodes: np.ndarray) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError

    def shear_stiffness(self, scene: Scene) -> float | None:
        return None

    def assemble_mixed(self, scene: Scene, params: dict):
        """(band, rhs, nodes, scaling, (held rows, loads)) of the two-field system with the springs added
        and the supports held (:func:`natural_band`); the held rows and the loads as they were before."""
        nodes = beam_nodes(scene, params["points"])
        EI, kGA = element_properties(scene, nodes)
        kGA = kGA if self.shear_stiffness(scene) is not None else None
        K, s = natural_band(np.diff(nodes), EI, kGA)
        F = self.nodal_loads(scene, params, nodes)
        b = np.zeros(K.n)
        b[0::4], b[1::4] = F[0::2], F[1::2]
        add_springs(scene, K, nodes, stride=4)
        fixed = constrained_dofs(scene, nodes)
        held = 4 * (fixed // 2) + fixed % 2
        rows = held_rows(K, held), b.copy()  # the held rows and loads before K.fix: the reactions
        K.fix(held, b)
        s[held] = 1.0
        return K, b, nodes, s, rows

    def element(self, params: dict) -> str:  # pragma: no cover - interface
        """The element's name, in info["element"]."""
        raise NotImplementedError

    def what(self, params: dict) -> str:
        """The solve's name in its messages."""
        return self.name

    def routed(self, scene: Scene, params: dict) -> Result | None:
        """The result of a scene another solve takes (a transient, a load path), else None."""
        return None

    def solve(self, scene: Scene, params: dict) -> Result:
        return self.routed(scene, params) or self.static(scene, params)[0]

    def static(self, scene: Scene, params: dict) -> tuple[Result, np.ndarray | None]:
        """(the static solution, its elements' end forces: :func:`~reference_fem.beam_resultants.end_forces`, None for
        elements that report no moment)."""
        u, info, dofs, nodes, timer, moments = self.solve_nodal(scene, params, self.what(params))
        info.update(element=self.element(params), elements=len(nodes) - 1)
        if merged := merge_warnings(scene, nodes):
            info.setdefault("warnings", []).extend(merged)
        matrices = self.element_matrices(scene, params, nodes)
        end = None if matrices is None else end_forces(*matrices, nodes, u, moments)
        result = self.new_result(
            scene,
            params,
            nodes,
            u[0::2],
            rotation=u[1::2],
            fields={} if end is None else nodal(scene, nodes, end),
            dofs=dofs,
            timings=timer.timings,
            info=info,
        )
        return result, end

    def element_matrices(self, scene: Scene, params: dict, nodes: np.ndarray):
        """(ke, fe): each element's stiffness (n_el, 4, 4) and work-equivalent loads (n_el, 4), or None."""
        return None

    def evaluator(self, scene, params):
        """Solve once; x -> the FE solution between the nodes (:meth:`interpolant`) and its moment and shear
        (:func:`~reference_fem.beam_resultants.statics`: exact where the nodal values are; none from elements that
        report none). The function carries the solve's round-off bound as ``error_bound`` (a study row measured
        against it is suspect when the bound passes 1e-6, pdverify.measure.status)."""
        r, end = (routed, None) if (routed := self.routed(scene, params)) is not None else self.static(scene, params)
        between = self.interpolant(r)
        shear = self.theory != "euler-bernoulli"
        resultants = None if end is None else statics(scene, r.x, end, r.w, r.rotation, shear)

        def fields(x):
            x = np.asarray(x, float)
            if resultants is not None:
                return resultants(x)
            w, rotation = between(x)
            return {"w": w, "rotation": rotation}

        fields.error_bound = r.info.get("error_bound")
        return fields

    def interpolant(self, r: Result):
        """x -> (w, rotation) between the nodes: cubic splines through the nodal values."""
        from scipy.interpolate import CubicSpline

        w, rotation = CubicSpline(r.x, r.w), CubicSpline(r.x, r.rotation)
        return lambda x: (w(x), rotation(x))

    def solve_nodal(self, scene: Scene, params: dict, what: str):
        """(u, info, free DOF count, nodes, timer, moments): nodal DOFs (w_i, w'_i or theta_i) interleaved; the
        two-field form's element moments (p, q) (:func:`natural_band`), None for the direct form."""
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
                    refine_in_place=True,
                )
            u = np.empty(2 * len(nodes))
            u[0::2], u[1::2] = z[0::4], z[1::4]
            info["form"] = "two-field (displacements and element end moments, K = T^T F^-1 T)"
            info["reactions"] = reactions(scene, nodes, system.info["held_rows"], z, system.info["loads"], stride=4)
            return u, info, system.unknowns, nodes, timer, (z[2::4], z[3::4])
        with timer("assemble"):
            system = self.assemble(scene, params)
        with timer("solve"):
            u, info = solve_linear(system.matrix, system.rhs, what=what, watch=np.arange(0, system.matrix.n, 2))
        info["form"] = "direct (the assembled stiffness K)"
        nodes = system.info["nodes"]
        info["reactions"] = reactions(scene, nodes, system.info["held_rows"], u, system.info["loads"])
        return u, info, system.unknowns, nodes, timer, None


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
    options = (
        Option(
            "points", int, 101, "nodes along the beam before load positions are added", minimum=2, maximum=MAX_POINTS
        ),
        FORM,
        Option("fibres", int, 400, "layers of each section along a load path (two fibres each)", minimum=1),
    )
    materials = frozenset({"yield_stress"})  # fibre sections along a load path (beam_plastic.py)
    load_path = True
    load_types = LOAD_TYPES | {"displacement"}  # held nodes, solved on the load path's fibre beam

    SKFEM_MAX_NODES = 20_001  # ElementLineHermite inverts a global-coordinate Vandermonde per element:
    # singular in float64 for elements below ~1e-4 of the coordinates; the closed form takes over there, and wherever
    # an element is shorter than the uniform elements of this many nodes (a load beside a node)

    def assemble_band(self, scene: Scene, params: dict, use_skfem: bool | None = None):
        """(K, F, nodes) before the supports, K a :class:`Band`."""
        nodes = beam_nodes(scene, params["points"])
        if use_skfem is None:
            shortest = scene.length / (self.SKFEM_MAX_NODES - 1)
            use_skfem = len(nodes) <= self.SKFEM_MAX_NODES and np.diff(nodes).min() >= shortest
        EI, _ = element_properties(scene, nodes)
        if not use_skfem:
            l = np.diff(nodes)
            ke = hermite_stiffness(l, EI / l**3)
            F = element_vector(element_loads(scene, nodes, hermite_shapes), len(nodes))
            return element_band(ke, len(nodes)), F + nodal_point_loads(scene, nodes, 2), nodes
        import skfem as fem
        from skfem.helpers import dd, ddot

        mesh = fem.MeshLine(nodes)
        basis = fem.Basis(mesh, fem.ElementLineHermite(), intorder=12)

        at = scene.stiffness_at  # EI of the segment a quadrature point lies in (segment ends are nodes)

        @fem.BilinearForm
        def bending(u, v, w):
            return (scene.EI if scene.uniform else at(w.x[0])["EI"]) * ddot(dd(u), dd(v))

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

    def element_matrices(self, scene: Scene, params: dict, nodes: np.ndarray):
        l = np.diff(nodes)
        EI, _ = element_properties(scene, nodes)
        return hermite_stiffness(l, EI / l**3), element_loads(scene, nodes, hermite_shapes)

    def evaluate(self, scene, params, x):  # noqa: D401 - the FE solution itself between nodes
        return self.evaluator(scene, params)(x)

    def routed(self, scene: Scene, params: dict) -> Result | None:
        shown = any(ld.type == "displacement" for ld in scene.loads)
        if scene.loading is not None or scene.material.yield_stress is not None or shown:
            return self.solve_load_path(scene, params)
        return None

    def solve_load_path(self, scene: Scene, params: dict) -> Result:
        """Fibre sections along the scene's load path (:mod:`.beam_plastic`): the last step's fields, every step in
        ``Result.path``."""
        timer = Timer()
        with timer("solve"):
            nodes, u, path, info = solve_path(scene, params["points"], params["fibres"])
        info.update(element="cubic Hermite, fibre sections", elements=len(nodes) - 1)
        return self.new_result(
            scene,
            params,
            nodes,
            u[0::2],
            rotation=u[1::2],
            fields={"health": path[-1]["health"]},
            dofs=len(u),
            timings=timer.timings,
            info=info,
            path=path,
        )

    def interpolant(self, r: Result):
        """x -> (w, w') between the nodes: the Hermite interpolant of w and w' (the element's own shape)."""
        spline = CubicHermiteSpline(r.x, r.w, r.rotation)
        return lambda x: (spline(x), spline(x, 1))

    def element(self, params: dict) -> str:
        return "ElementLineHermite"


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
        Option(
            "points", int, 101, "nodes along the beam before load positions are added", minimum=2, maximum=MAX_POINTS
        ),
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
        K, M, _, _, _ = free_system(self, scene, params, probes=())
        return K, M

    def check(self, scene: Scene) -> list[str]:
        out = super().check(scene)
        d = scene.dynamics  # prescribed end motions: the contract's check says it (Model.end_motions)
        if d is not None and scene.segments:
            out.append("segments: fem-timoshenko's transient takes one section and material (its mass is uniform)")
        return out

    def routed(self, scene: Scene, params: dict) -> Result | None:
        return transient(self, scene, params) if scene.dynamics is not None else None

    def nodal_loads(self, scene: Scene, params: dict, nodes: np.ndarray) -> np.ndarray:
        EI, kGA = element_properties(scene, nodes)
        phi = 12 * EI / (kGA * np.diff(nodes) ** 2)
        shapes = iie_shapes(phi) if params["variant"] == "iie" else linear_shapes
        return element_vector(element_loads(scene, nodes, shapes), len(nodes)) + nodal_point_loads(scene, nodes, 2)

    def element_matrices(self, scene: Scene, params: dict, nodes: np.ndarray):
        if params["variant"] != "iie":
            return None  # the linear elements' moments are constant per element: not reported
        l = np.diff(nodes)
        EI, kGA = element_properties(scene, nodes)
        f = 12 * EI / (kGA * l**2)
        return hermite_stiffness(l, EI / ((1 + f) * l**3), f), element_loads(scene, nodes, iie_shapes(f))

    def assemble_band(self, scene: Scene, params: dict):
        """(K, F, nodes) before the supports, K a :class:`Band`."""
        nodes = beam_nodes(scene, params["points"])
        l = np.diff(nodes)
        EI, kGA = element_properties(scene, nodes)
        if params["variant"] == "iie":
            f = 12 * EI / (kGA * l**2)
            ke = hermite_stiffness(l, EI / ((1 + f) * l**3), f)
            fe = element_loads(scene, nodes, iie_shapes(f))
        else:
            at = scene.stiffness_at
            ei, ga = (scene.EI, scene.kGA) if scene.uniform else (lambda x: at(x)["EI"], lambda x: at(x)["kGA"])
            return linear_timoshenko(nodes, ei, ga, params["variant"]), self.nodal_loads(scene, params, nodes), nodes
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
