"""Model ``pd-higher-order``: PD higher-order beam (Yang, Oterkus & Oterkus 2020).

Kinematics (Eq. 2–3): u(x, z) = z theta + z^3 theta*, w(x, z) = w + z^2 w*; four DOFs per material
point, ordered (theta, theta*, w, w*) as in Eq. 16a. Node grid x_k = k dx, k = 0..n-1 (ends included).
A section given by area/inertia is treated as the equivalent rectangle of height ``Section.depth``
(h = sqrt(12 I / A)); all energies are per unit cross-section area (V_k = A dx cancels A).

Strain energy (Eq. 9 made peridynamic by the transformations Eq. 14a–f / A38a–f, assembled in Eq. 15).
Per bond k -> j, xi = x_j - x_k, five bond measures, each ~ (a derivative) * xi for smooth fields::

    a = theta_j - theta_k          s = 2 xi w*_k          c = theta*_j - theta*_k
    g = w_j - w_k + xi theta_k     e = w*_j - w*_k + 3 xi theta*_k

    W_k = 1/(2h) Σ_j omega_kj Q(a, s, c, g, e),   Q = m^T C m   (C: ``coefficients``)
    Q = E/(1-nu^2) [h^3/12 (a^2 + 2 nu a s + s^2) + h^5/40 c (a + nu s) + h^7/448 c^2]
        + G [h g^2 + h^5/80 e^2 + h^3/6 g e]

with omega_kj = V_j / (delta^2 A |xi|) in the paper (Eq. 14: (1/delta^2 A) Σ ... / |xi| V_j).
The static equations are the Euler–Lagrange equations of Eq. 20–21 without inertia:
dU/du_k = b_k V_k, i.e. K u = F with K = Σ_k V_k d^2 W_k / du^2 (``bond_block`` per bond). Eq. 22c–d
(legible) are rows of this K (checked symbolically in tests/papers/yang/test_pd_higher_order.py); Eq. 22a–b are
damaged in the source and are taken from the energy instead. Loads (Eq. 16b): b_z on w, b_theta on
theta; a point force P gives F_w = P, a ccw point moment C gives F_theta = -C (the paper's theta is
minus the counter-clockwise rotation: gamma = theta + w' vanishes for w' = ccw rotation).

Variants
--------
``paper`` (faithful): delta = (m + 0.015) dx, omega = 1/(delta^2 A |xi|) V_j (Eq. 14) for the members
j = 1..J each side. Family volumes (option ``volumes``): ``partial`` (default) is the authors' convention
(Oterkus/Madenci, reference [17] and the sister paper Diyaroglu et al. 2019's "volume correction"): a member with
delta - dx/2 < xi < delta + dx/2 gets the volume fraction beta = (delta + dx/2 - xi)/dx, so at 3.015 dx the
third neighbour carries 0.515 and Σ_j omega xi^2 = 2 Σ beta_d d / (delta/dx)^2 = 9.09/9.090225, i.e. the
continuous integral of Eq. A30 (δ^2) to 2.5e-5; ``full`` gives every member inside delta a whole cell,
2 (1 + 2 + 3) / 3.015^2 = 12/9.090225 = 1.320: a uniformly 32 % stiffer operator (not the paper's).
Boundaries (Appendix B) by fictitious layers of J points mirrored (option ``mirror``): ``point`` (default)
about the end point, which is a material point and is held (clamped: w, w* symmetric and theta, theta*
antisymmetric, w = w* = 0 at the end point, Eq. B39–B40; simply supported: the opposite, Eq. B41, w and w*
held); read from the text: the conditions are "for the material point adjacent to the clamped end" (zero
w and rotation there; zero w and curvature for the simple support), which an image about that point gives,
and the sister paper mirrors "with respect to the first adjacent material point which is fixed".
``boundary``: cell-centred points x = (k + 1/2) dx, dx = L / points, images i' of the real points i = 1..J
about the boundary between 1 and 1' (Eq. B39–B41 with 1' a point of the fictitious layer), clamped
w(1) = w*(1) = 0 (theta(1) then not zero), pinned and guided nothing held. Guided, not in the paper: the
clamped mirror without w = 0. A free end has no fictitious layer (truncated families). The equations are
those of Eq. 22 at the real points, the fictitious DOFs substituted by their images (a non-symmetric
system). Loads on the mid-surface (Eq. 16b) while the plane-stress reference loads the top face: the
simply supported benchmarks differ from it by that, not by the operator (option ``loads = faces``).

``corrected`` (default), each change tested in tests/papers/yang/test_pd_higher_order.py:
1. micro-modulus calibrated on the discrete family of each point: omega_kj = beta_j / (|xi| S_k),
   S_k = Σ_j beta_j |xi_j| over the actual family (partial volume beta = 1/2 for the member at
   delta = m dx), so every W_k is exact for linear fields, also on truncated families near the ends
   (the same operator as the paper's partial volumes in the interior, exact also on truncated families);
2. shear measures along the bond (option ``shear = path``, :func:`path_measures`): g = w_j - w_k + the
   trapezoid of theta over the bond's nearest-neighbour segments, e likewise with 3 theta*. With theta_k
   alone (Eq. 14d-f, ``shear = point``) a pure bending field leaves g = -theta' xi^2 / 2, a spurious shear
   energy G h theta'^2 delta^2 / 8 next to E h^3 theta'^2 / 12, a stiffening of ~ (G/E) 1.5 (delta/h)^2;
   with the bond-mean rotations (theta_k + theta_j)/2 (``shear = centred``) that is gone, but the J bonds'
   measures cannot all vanish for a cubic w (trapezoid errors ~ xi^3 w'''/12 that differ bond by bond), a
   penalty ~ (G/E) xi^4 / (h L)^2 times the bending energy: shear locking once dx is many depths. Summed over
   the segments every bond's g is a sum of nearest-neighbour measures, which can all vanish together
   (no locking); for smooth fields g = xi (w' + theta) + O(xi dx^2) as with theta_k alone;
3. no fictitious points (option ``ends = truncated``): the discrete energy U = Σ_k V_k W_k with
   trapezoidal volumes (dx/2 at the ends) is minimised with the essential conditions on the end point
   (clamped theta = theta* = w = w* = 0: the whole end face fixed; guided theta = theta* = 0; pinned
   w + h^2/20 w* = 0, option ``pin = face``); natural conditions (free faces, moment-free pins) come out of
   the minimisation as in a finite-element model. The paper's mirror ghosts force w' = 0 at a clamped
   end (zero shear strain where the shear force is largest);
4. loads where the plane-stress reference applies them (option ``loads = faces``): distributed loads and
   interior forces on the top face (work on w + h^2/4 w*), end forces as a parabolic shear traction
   (w + h^2/20 w*), end moments as a linear normal traction (theta + 3 h^2/20 theta*);
5. end layers that pass the patch test (option ``end_layer = patch``,
   :func:`~pdverify.papers.yang.bonds.end_layer_weights`): the per-point
   calibration alone (``end_layer = point``) leaves a uniform state out of equilibrium in the end layers (ghost
   forces, as in quasicontinuum coupling; ``ends = taylor`` does the same): first order at m >= 2. The bonds of
   the 2J + 1 points at each end get the least change of the per-point weights for which every point stays
   calibrated and every nearest-neighbour segment carries the same total weight (the patch test of the segment
   form of the energy with the along-the-bond measures); m = 1 is unchanged;
6. bonds cut at interior point loads (option ``cuts = loads``, :meth:`PDHigherOrder.cut_points`): the beam is
   the sum of sub-beams sharing each loaded point, each with its own patch-test end layers, so no bond averages
   the kink of w* (and of the shear) under a concentrated load; loads exactly on a point, at least 4J + 1
   spacings from the ends and from each other;
7. the clamp's w* condition through its boundary layer (option ``clamp = layer``, :mod:`.layer`):
   w* = 0 on the clamped face makes a layer ~0.1 h wide; held on the end point it acts over dx/2 instead (first
   order once dx is many layer widths: every slender beam). w* of the end point is free, tied to zero by the
   spring whose series with the grid's own layer has the continuous layer's stiffness; the face condition where
   the grid resolves the layer.
Orders: docs/models/yang.md. Band assembly: :mod:`.operator`. Dynamics (Eq. 17-22): :mod:`.dynamics`.
"""

# long module: the model class and its option rules (operator, supports, outputs, dynamics: own modules)

from __future__ import annotations

import numpy as np

from ...core.contract import NONLOCAL, Model, Option, Rule, System
from ...core.errors import InputError
from ...core.result import Result, Timer, merge_info
from ...core.scene import Scene
from ...core.stations import STATIONS_HELP, parse_stations
from ...numerics.families import family
from ...numerics.linalg import solve_linear
from ...numerics.load_warnings import (
    HIGHER_ORDER_LOADS_NEAR_HELD_ROTATION,
    boundary_layer_warnings,
    held_rotation_warnings,
    horizon_layer,
)
from ...numerics.statics import closed_reactions
from ...theory.higher_order import NF, TH, TS, WS, W, coefficients
from ...theory.symbols import higher_order_gradient, higher_order_series
from . import dynamics
from .bonds import end_layer_ratios
from .ends import end_conditions, load_vector
from .layer import clamp_springs
from .operator import Layout, band_operator, ghost_layers, held_system, load_cuts, stiffness_factor
from .outputs import (
    clamp_layer_warning,
    interior_point_loads,
    not_cut,
    point_load_warnings,
    reactions,
    recovery_warnings,
    section_fields_warning,
    section_stresses,
    shear_stiff_warning,
    spurious_shear_warning,
)
from .supports import paper_supports_refusal, section_forces, with_supports

# the ends' layers of the recovered M and V, in horizons (J points each): their error falls about tenfold every three
# points inward; at 3 J, 2e-6 to 7.6e-4 of the largest value on six scenes (docs/models/yang.md, "Scenes: ...")
LAYER_HORIZONS = 3


class PDHigherOrder(Model):
    name = "pd-higher-order"
    shapes = frozenset({"rectangle", "given"})  # its equations use the depth of a rectangle
    title = "PD higher-order beam (theta, theta*, w, w* per point)"
    source = "Yang et al. 2020, Peridynamic higher-order beam formulation"
    theory = "higher-order"
    options = (
        Option(
            "points", int, 201, "material points along the beam, ends included (paper: 1001 for dx = 1 mm)", minimum=5
        ),
        Option("horizon", float, 3.0, "horizon as a multiple of the spacing (3 = the paper's 3.015 dx)", minimum=1.0),
        Option("variant", str, "corrected", "paper | corrected", choices=("paper", "corrected")),
        Option(
            "ends",
            str,
            "auto",
            "auto (mirror for paper, truncated for corrected) | mirror (Appendix B fictitious "
            "layers) | truncated (no ghosts, per-point calibration) | taylor (ghosts extrapolated by a polynomial "
            "of the real points, energy of the real points only)",
            choices=("auto", "mirror", "truncated", "taylor"),
        ),
        Option("ghost_degree", int, 3, "degree of the ghost extrapolation (ends = taylor)", minimum=1, maximum=6),
        Option(
            "pin",
            str,
            "auto",
            "pinned end: auto (mid for paper, face for corrected) | mid (w = 0 on the axis) | "
            "face (parabola-weighted mean of "
            "w + z^2 w* over the end face = 0: w + h^2/20 w* = 0, as fem-plane-stress pin = face)",
            choices=("auto", "mid", "face"),
        ),
        Option(
            "shear",
            str,
            "auto",
            "auto (point for paper, path for corrected) | point (Eq. 14d-f: theta_k xi) | "
            "centred (bond-mean rotations (theta_k + theta_j)/2 xi: no spurious G h theta'^2 delta^2 energy) | path "
            "(the rotations' trapezoid along the bond's segments: no shear locking of slender beams)",
            choices=("auto", "point", "centred", "path"),
        ),
        Option(
            "stretch",
            str,
            "point",
            "the stretch measure s: point (Eq. 14b: 2 xi w*_k) | path (2 xi times the trapezoid mean of w* along the "
            "bond, with shear = path: every measure along the bond; with truncated ends and end_layer = patch, a limit "
            "at a fixed horizon: docs/nonlocal.md)",
            choices=("point", "path"),
        ),
        Option(
            "loads",
            str,
            "auto",
            "auto (mid for paper, faces for corrected) | mid (Eq. 16b: b_z on w, b_theta on theta) | "
            "faces (where the plane-stress "
            "reference puts them: top face, parabolic end shear, linear end traction)",
            choices=("auto", "mid", "faces"),
        ),
        Option(
            "volumes",
            str,
            "partial",
            "paper variant's family volumes: partial (the authors' convention: the "
            "member at 3 dx inside delta = 3.015 dx gets (delta + dx/2 - xi)/dx = 0.515) | full (whole cells "
            "inside delta)",
            choices=("partial", "full"),
        ),
        Option(
            "mirror",
            str,
            "point",
            "paper variant's fictitious layers (ends = mirror): point (points at the ends, "
            "images about the end point, which is held: the material point at the support, as in Appendix B's text "
            "and Diyaroglu et al. 2019) | boundary (cell-centred points, images about the boundary half a spacing "
            "beyond point 1, clamped w(1) = w*(1) = 0, Eq. B39-B41 read with 1' distinct from 1)",
            choices=("boundary", "point"),
        ),
        Option(
            "end_layer",
            str,
            "patch",
            "bond weights of the points within 2J of an end (ends = truncated): patch (each point calibrated and "
            "every segment carrying the same total, so a uniform state is in equilibrium: second order at any m) | "
            "point (per-point calibration only: ghost forces, first order at m >= 2)",
            choices=("patch", "point"),
        ),
        Option(
            "cuts",
            str,
            "loads",
            "with end_layer = patch: loads (no bond crosses a point that carries an interior point force or moment; "
            "each side gets its own patch-test layer: second order under point loads) | none",
            choices=("loads", "none"),
        ),
        Option(
            "clamp",
            str,
            "auto",
            "clamped end: auto (face for paper, layer for corrected) | face (w* = 0 held on the end point) | layer "
            "(w* = 0 through the spring of the face's boundary layer, ~0.1 h wide: second order also when the "
            "spacing is many depths; ends = truncated or taylor)",
            choices=("auto", "face", "layer"),
        ),
        Option("stations", str, "", STATIONS_HELP + " (Eq. 6a-c)"),
        dynamics.ANALYSIS,
        *NONLOCAL,
    )

    assembles = True
    analyses = frozenset({"static", "dynamic"})  # Eq. 17-22 with the inertia of Eq. 19 (dynamics.py)
    modes = True
    eigenproblem, bench_dynamics = dynamics.eigenproblem, dynamics.bench  # (self, scene, params): K and M of Eq. 22
    springs = True
    inner_supports = True
    continuum_m = 32  # the finest level of a continuum (delta = 0.05 m on a 1 m beam: 641 points, about a second)
    _PAPER = (("variant", "paper"),)
    variant_rules = (
        Rule(
            _PAPER,
            "horizon",
            "Eq. 14: delta = (m + 0.015) dx over families of m points (option volumes: partial, the default, or "
            "full); use variant = corrected for a fractional horizon",
            whole=True,
            unless="horizon_length",  # Eq. 14 with a given delta: the members within it, partial volumes
        ),
        Rule(
            _PAPER,
            "ends",
            "Appendix B: fictitious mirror layers (Eq. B39-B41), free ends truncated",
            allowed=("auto", "mirror"),
        ),
        Rule(
            _PAPER,
            "pin",
            "Eq. B41: a simply supported end holds w = w* = 0 at the end point (mid)",
            allowed=("auto", "mid"),
        ),
        Rule(_PAPER, "shear", "Eq. 14d-f: the shear measures use theta_k xi (point)", allowed=("auto", "point")),
        Rule(_PAPER, "stretch", "Eq. 14b: s = 2 xi w*_k (point)", allowed=("point",)),
        Rule(_PAPER, "loads", "Eq. 16b: b_z on w, b_theta on theta (mid)", allowed=("auto", "mid")),
        Rule(_PAPER, "clamp", "Eq. B39: w = w* = 0 at the clamped end point (face)", allowed=("auto", "face")),
    )

    def gradient_coefficient(self, scene: Scene, params: dict) -> float:
        """(1 - 4 nu^2) / (24 (1 - nu^2)): the slender beam's symbol (docs/nonlocal.md)."""
        return higher_order_gradient(scene.material.poissons_ratio)

    def continuum_limit(self, scene: Scene, params: dict) -> tuple[str, int] | None:
        """Bonds measured along their path (``shear = path``, the corrected variant's default) at truncated or Taylor
        ends have no limit at fixed delta at a pinned, roller or guided end, or at a clamped end held through its
        layer spring (``clamp = layer``, the default there). Measured and explained in part (docs/nonlocal.md, a
        limit at fixed delta): on slender beams the changes per doubling of m fall at first order to m = 32-64 and
        then grow (to m = 256 at L/h = 100); a thick one (L/h = 10) converges, so the flag is conservative there. What
        grows is an end mode of theta* and w* near a pin (w held) or a guide (theta held); the patch-test weights of
        the bonds at the end point grow like m, and per-point weights do not converge either. ``stretch = path`` (s
        along the bond too) with truncated ends and the patch-test end layer, ``clamp = face`` (w* held), ``shear =
        centred`` and mirror ends converge; ``stretch = path`` with per-point end weights or Taylor ends does not."""
        if params["variant"] == "paper" or self.ends(params) == "mirror":
            return None
        if params.get("shear", "auto") not in ("auto", "path"):
            return None
        stretch = params.get("stretch", "point") == "path"
        if stretch and self.ends(params) == "truncated" and params.get("end_layer", "patch") == "patch":
            return None
        held = {scene.supports.left, scene.supports.right}
        grows = sorted(held & {"pinned", "roller", "guided"})
        if "clamped" in held and self.clamp(params) == "layer":
            grows.append("clamped (clamp = layer)")
        if not grows:
            return None
        if stretch:
            return (
                f"stretch = path at a {' and a '.join(grows)} end has a limit at fixed delta with truncated ends and "
                "end_layer = patch only: with per-point end weights or taylor ends the changes per doubling of m fall "
                "and then grow (pinned-pinned sine, delta = 0.2 m: 3.2e-4 from m = 32 to 64, then 5.7e-4 from 64 to "
                "128 with per-point weights; 1.2e-4, then 3.7e-4 with taylor ends), so there is no limit to "
                "extrapolate (docs/nonlocal.md)",
                int(params.get("continuum_m") or self.continuum_m),
            )
        return (
            f"shear = path at a {' and a '.join(grows)} end (truncated or taylor ends): the changes per doubling of m "
            "at fixed delta fall to m = 32-64 and then grow on slender beams (measured to m = 256 at L/h = 100; at "
            "L/h = 10 they fall), so there is no limit to extrapolate (stretch = path, shear = centred, clamp = face "
            "and ends = mirror have one: docs/nonlocal.md)",
            int(params.get("continuum_m") or self.continuum_m),
        )

    def continuum_series(self, scene: Scene, params: dict):
        """The corrected variant with mirror layers (``ends = mirror``), pinned ends held on the mid-line, loads on
        it and bonds measured along their path (``pin = mid``, ``loads = mid``, ``shear = path``): its continuum is a
        series of the mirror modes with the continuous symbol (:func:`pdverify.theory.symbols.higher_order_series`)."""
        if (
            params["variant"] != "corrected"
            or self.ends(params) != "mirror"
            or self.choice(params, "pin") != "mid"
            or self.choice(params, "loads") != "mid"
            or params.get("shear", "auto") not in ("auto", "path")
            or params.get("stretch", "point") != "point"  # the series' symbol is Eq. 14b's
        ):
            return None
        return higher_order_series(scene, self.delta(scene, params), self.constants(scene)[0])

    def about(self, params: dict) -> str:
        """The mirror of the paper's fictitious layers: "boundary" or "point" (every other variant/end: "point")."""
        if params["variant"] == "paper" and self.ends(params) == "mirror":
            return params.get("mirror", "point")
        return "point"

    def horizon_offset(self, params: dict) -> float:
        """Eq. 14: delta = (m + 0.015) dx in the paper variant."""
        return 0.015 if params["variant"] == "paper" else 0.0

    def spacing(self, scene: Scene, params: dict) -> float:
        """dx of :meth:`grid` (L / points for cell-centred points)."""
        n = params["points"]
        return scene.length / (n if self.about(params) == "boundary" else n - 1)

    def grid(self, scene: Scene, params: dict) -> np.ndarray:
        """x_k = k dx, ends included; mirrored about the boundary: cell centres (k + 1/2) dx, dx = L / points."""
        n = params["points"]
        if self.about(params) == "boundary":
            return (np.arange(n) + 0.5) * (scene.length / n)
        return np.linspace(0.0, scene.length, n)

    def constants(self, scene: Scene):
        mat = scene.material
        h = scene.section.depth
        return coefficients(mat.E, mat.poissons_ratio, mat.G, h), h

    @staticmethod
    def choice(params: dict, key: str) -> str:
        """An option's value with ``auto`` resolved (paper: Appendix B and Eq. 16b; corrected: see the docstring)."""
        auto = {
            "ends": ("mirror", "truncated"),
            "pin": ("mid", "face"),
            "loads": ("mid", "faces"),
            "clamp": ("face", "layer"),
        }[key]
        v = params.get(key, "auto")
        return auto[params["variant"] != "paper"] if v == "auto" else v

    def ends(self, params: dict) -> str:
        return self.choice(params, "ends")

    def clamp(self, params: dict) -> str:
        """The clamped end's w* condition: ``face`` or ``layer`` (auto: layer for the corrected variant's
        essential end conditions, face for the paper and for mirror layers, whose images hold w*)."""
        clamp = self.choice(params, "clamp")
        if self.ends(params) != "mirror":
            return clamp
        if params.get("clamp", "auto") == "layer":
            raise InputError("clamp = layer needs ends = truncated or taylor (mirror layers hold w* by their images)")
        return "face"

    def reference_options(self, params: dict) -> dict | None:
        """exact-higher-order with the same loads and pin (its options of those names). None for the paper variant
        and mirror ends: their fictitious layers hold w' (symmetric images), not the theory's natural conditions."""
        params = self.with_defaults(params)
        if params["variant"] == "paper" or self.ends(params) == "mirror":
            return None
        return {"loads": self.choice(params, "loads"), "pin": self.choice(params, "pin")}

    def assemble_band(self, scene: Scene, params: dict):
        """(B, b, (drop, tie), info): B u = b on the real points' interleaved DOFs u = (theta, theta*, w, w*)
        per point, assembled straight into a :class:`~pdverify.numerics.band.Band` (the matrix ``solve`` factorises).

        Every row whose point, bonds and partners' bonds lie away from the ends is the same 4x4 block
        stencil (Eq. 15's Hessian with the interior weights, :func:`uniform_blocks`), written diagonal by
        diagonal. The rows of the few points near each end (truncated families and their calibration,
        end volumes, ghost layers folded onto their images, the end conditions) are computed exactly on a
        small window of the extended grid, by the sparse route of Eq. 15 + Appendix B
        (:func:`assemble_blocks`, :func:`mirror_map` / :func:`taylor_map`, :func:`constraint_map`), and
        overwrite those rows. The ties of ``pin = face`` are folded in (u_slave = c u_master) and the held
        DOFs (``drop``, and the slaves) are unit rows with cleared columns (``Band.fix``): the numbering of
        u is kept, u_slave is restored after the solve."""
        lay, J, info = self.layout(scene, params)
        B, end_rows, span = band_operator(lay, J)
        drop, tie = end_conditions(lay.n, lay.left, lay.right, lay.variant, lay.pin, lay.h, lay.about, lay.clamp)
        if lay.clamp == "layer":
            info["clamp_layer"] = clamp_springs(B, scene, lay.n, lay.dx, span, drop)
        F = load_vector(scene, lay.x, self.choice(params, "loads") == "faces").ravel()
        info["end_rows"] = [(k, c0, D, F[NF * k : NF * k + NF].copy()) for k, c0, D in end_rows]
        b = held_system(B, F, drop, tie, lay.symmetric)
        info["stiffness_factor"] = stiffness_factor(J, lay.m, lay.dx, lay.variant, lay.fractions)
        info.update(pin=lay.pin, loads=self.choice(params, "loads"), clamp=lay.clamp)
        if lay.variant == "paper":
            info.update(volumes=lay.fractions, mirror=lay.about)
        return B, b, (drop, tie), info

    def refusals(self, scene: Scene, params: dict) -> list[str]:
        """Springs and supports inside the span in variant paper (:func:`.supports.paper_supports_refusal`)."""
        why = paper_supports_refusal(scene, params)
        return [why] if why else []

    def grid_problems(self, scene: Scene, params: dict) -> list[str]:
        """A family that does not fit in the points (:meth:`layout`), before any work."""
        dx, fractions = self.spacing(scene, params), params.get("volumes", "partial")
        return self.family_problems(scene, params, lambda k: int(family(k, dx, params["variant"], fractions)[0].max()))

    def layout(self, scene: Scene, params: dict) -> tuple[Layout, int, dict]:
        """(layout, J, info): the :class:`~.operator.Layout` of the options on ``scene`` (the variant's choices
        resolved), the family's reach J in points and the result's info so far (depth, ends, section, shear,
        boundary, cuts). Raises InputError when the family does not fit in the grid."""
        x = self.grid(scene, params)
        n, dx = len(x), x[1] - x[0]
        m, variant, ends = params["horizon"], params["variant"], self.ends(params)
        fractions, about = params.get("volumes", "partial"), self.about(params)
        d, _ = family(m, dx, variant, fractions)
        J = int(d.max())
        p = params["ghost_degree"]
        if 2 * J + 1 > n or (ends == "taylor" and p + 1 > n):
            raise InputError(
                f"horizon = {m:g}: the family ({J} points each side) does not fit in {n} points; "
                "use more points or a smaller horizon"
            )
        C, h = self.constants(scene)
        left, right = (scene.supports.kind(s).replace("spring", "free") for s in ("left", "right"))
        pin = self.choice(params, "pin")
        clamp = self.clamp(params)
        info = {
            "depth": h,
            "ends": ends,
            "section": "rectangle"
            if scene.section.height is not None
            else f"equivalent rectangle h = sqrt(12 I / A) = {h:.6g} m",
        }
        shear = params.get("shear", "auto")
        path = shear == "path" or (shear == "auto" and variant != "paper")
        centred = shear == "centred"
        info["shear"] = "path" if path else "centred" if centred else "point"
        stretch = params.get("stretch", "point") == "path"
        if stretch and not path:
            raise InputError(f"stretch = path measures s along the bond's path: it needs shear = path (not {shear})")
        info["stretch"] = "path" if stretch else "point"
        G, calibrate, reach, described = ghost_layers(ends, J, p, left, right, about, params.get("end_layer", "patch"))
        merge_info(info, described)
        cuts = self.cut_points(scene, params, x, J) if calibrate == "patch" and variant != "paper" else ()
        if cuts:
            info["cuts"] = [float(x[c]) for c in cuts]
        if calibrate == "patch" and variant != "paper":
            bounds = [0, *cuts, n + G[0] + G[1] - 1]  # the sub-beams whose end layers are calibrated
            least = min(float(end_layer_ratios(b - a + 1, m, dx, fractions).min()) for a, b in zip(bounds, bounds[1:]))
            if least < 0:  # from m of about 8.5 (docs/nonlocal.md)
                info["end_layer_negative_weight"] = least
        lay = Layout(
            x=x,
            m=m,
            variant=variant,
            fractions=fractions,
            ends=ends,
            G=G,
            calibrate=calibrate,
            reach=reach,
            p=p,
            C=C,
            h=h,
            centred=centred,
            path=path,
            left=left,
            right=right,
            pin=pin,
            about=about,
            clamp=clamp,
            cuts=cuts,
            stretch=stretch,
        )
        return lay, J, info

    @staticmethod
    def cut_points(scene: Scene, params: dict, x: np.ndarray, J: int) -> tuple[int, ...]:
        """The interior points where the corrected variant cuts the bonds (option ``cuts = loads``; ends =
        truncated, end_layer = patch): :func:`.operator.load_cuts`."""
        return load_cuts(scene, x, J) if params.get("cuts", "loads") == "loads" else ()

    def assemble(self, scene: Scene, params: dict) -> System:
        """The band of :meth:`assemble_band` (the system ``solve`` factorises): u interleaved (theta, theta*,
        w, w*) per real point, free = the DOFs not held; ``info["ties"]``: the (slave, master, c) of
        ``pin = face`` (u_slave = c u_master, restored after the solve). With springs or supports inside the span
        their reactions follow u as unknowns (:func:`.supports.augmented`: a sparse matrix; ``info["unknowns"]``,
        ``info["scales"]``)."""
        B, b, (drop, tie), info = self.assemble_band(scene, params)
        faces, pin = self.choice(params, "loads") == "faces", self.choice(params, "pin")
        A, rhs, free, unknowns, scales = with_supports(scene, params, B, b, drop, self.grid(scene, params), faces, pin)
        return System(A, rhs, free, dict(info, ties=tie, unknowns=unknowns, scales=scales))

    def discretisation_warnings(self, scene: Scene, params: dict, x: np.ndarray, info: dict) -> list[str]:
        """The warnings of the space discretisation (the operator and the load vector on the points ``x``;
        ``info``: the assembly's, its ``cuts``, ``ends`` and ``loads``): point loads inside the ends' layer, point
        loads off a cut point or deforming the section, a clamp's layer in transition, loads beside a support inside
        that holds the rotation. A static solve and a transient share them (:mod:`.dynamics` integrates the same
        operator and loads); the recovered moment and shear's own warnings are the static solve's
        (:func:`.outputs.recovery_warnings`)."""
        dx = x[1] - x[0]
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        reach = 2 * int(np.ceil(params["horizon"] + 0.015)) + 2  # the end layer of 2J + 1 points and one bond
        flags = boundary_layer_warnings(scene, x, reach, horizon_layer(params, dx, reach, 2))
        # beside a support inside that holds the rotation the families turn the other side (a model error of the
        # horizon), more where its bonds are not cut; point forces nearer than the cut's 4J + 1 spacings carry their
        # own warning (point_load_warnings)
        J = int(np.ceil(delta / dx - 1e-9))
        held = [s.position for s in scene.supports.inner if s.holds_rotation]
        constant = HIGHER_ORDER_LOADS_NEAR_HELD_ROTATION["not cut" if not_cut(scene, held, info) else "cut"]
        near = held_rotation_warnings(scene, dx, 4 * J + 1, delta, constant)
        layer = clamp_layer_warning(scene, dx) + section_fields_warning(scene, dx)
        spurious = spurious_shear_warning(scene, delta) if info.get("shear") == "point" else []
        return flags + point_load_warnings(scene, params, info) + layer + near + shear_stiff_warning(scene) + spurious

    def solve(self, scene: Scene, params: dict) -> Result:
        if dynamics.dynamic(scene, params):
            return dynamics.transient(self, scene, params)
        timer = Timer()
        with timer("assemble"):
            system = self.assemble(scene, params)
            binfo = dict(system.info)
            tie = binfo.pop("ties")
            end_rows = binfo.pop("end_rows")
            unknowns, scales = binfo.pop("unknowns"), binfo.pop("scales")
        with timer("solve"):
            n = params["points"]
            z, info = solve_linear(
                system.matrix,
                system.rhs,
                what=f"pd-higher-order ({params['variant']})",
                watch=(np.arange(W, NF * n, NF), np.arange(TH, NF * n, NF)),  # in its own units each
            )
            u, lam = z[: NF * n].copy(), z[NF * n :]
            for slave, master, c in tie:
                u[slave] = c * u[master]
        u = u.reshape(n, NF)
        x = self.grid(scene, params)
        dx = x[1] - x[0]
        delta = (params["horizon"] + (0.015 if params["variant"] == "paper" else 0.0)) * dx
        merge_info(info, binfo, spacing=dx, horizon_factor=params["horizon"], horizon=delta, variant=params["variant"])
        fields = {"theta": u[:, TH], "theta_star": u[:, TS], "w_star": u[:, WS]}
        layer = LAYER_HORIZONS * int(np.ceil(params["horizon"] + 0.015))  # the ends' layers of M and V
        own = reactions(end_rows, u.ravel(), scene.section.A) if end_rows else {}
        if unknowns:
            own = closed_reactions(
                scene, dict(own, **{r["key"]: float(v / s) for r, v, s in zip(unknowns, lam, scales)})
            )
        if own:
            info["reactions"] = own
        forces, loads, supports = section_forces(scene, x, u, self.constants(scene)[0], binfo["depth"], layer, own)
        fields.update(forces)
        flags = self.discretisation_warnings(scene, params, x, info)
        if flags := flags + recovery_warnings(
            scene, [ld for ld in interior_point_loads(scene) if ld in loads], supports
        ):
            info.setdefault("warnings", []).extend(flags)
        if clamp := clamp_layer_warning(scene, dx):  # no Richardson estimate on such grids (measure/richardson.py)
            info["irregular"] = clamp[0]
        stations = parse_stations(params.get("stations", ""), scene.length)
        if len(stations):
            mat = scene.material
            info["sections"] = section_stresses(x, u, stations, binfo["depth"], mat.E, mat.poissons_ratio)
        return self.new_result(
            scene,
            params,
            x,
            u[:, W].copy(),
            rotation=-u[:, TH],
            fields=fields,
            dofs=system.unknowns,
            timings=timer.timings,
            info=info,
        )


MODELS = [PDHigherOrder()]
