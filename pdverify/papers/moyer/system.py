"""The discrete system of the Moyer & Miraglia 2014 PD rod / Timoshenko beam / torsion bar: the
operator on all real DOFs with its supported DOFs (:class:`Discrete`, assembled by
:mod:`.operator`), the prescribed end motions of a scene, and the direct static solve K u = b with
the supported DOFs held (Section 4: the static problem is the same operator without inertia).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ...core.errors import SolveError
from ...core.scene import Scene
from ...numerics.band import Band
from ...numerics.linalg import solve_linear
from .kernels import EndPatched, motion_final

DIRICHLET = {
    "clamped": (True, True),
    "pinned": (True, False),
    "roller": (True, False),
    "free": (False, False),
    "guided": (False, True),
}  # the beam's (w, γ) held by each support; no axial unknown: roller = pinned


def beam_prescribed(scene: Scene, n: int) -> dict:
    """dof -> (field, side) of the beam's held DOFs on n points (interleaved w, γ): :data:`DIRICHLET` at each end."""
    out = {}
    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        end = 0 if side == 0 else n - 1
        fix_w, fix_g = DIRICHLET[sup]
        if fix_w:
            out[2 * end] = ("w", side)
        if fix_g:
            out[2 * end + 1] = ("rotation", side)
    return out


@dataclass
class Discrete:
    """The assembled operator on all real DOFs: rows r: mass_r u_tt = b_r - (K u)_r (free rows only).

    K is held as an :class:`~.kernels.EndPatched` operator ``op`` (the PD sums are one stencil
    away from the ends, explicit rows where a family reaches a ghost point): ``band()`` gives it in
    LAPACK's band layout for the direct solve, ``K`` as CSR (small grids, eigenvalues), and the time
    stepping applies the stencil matrix-free."""

    x: np.ndarray
    op: EndPatched  # all DOFs x all DOFs (rows of prescribed DOFs are ignored)
    b: np.ndarray
    field_mass: tuple  # per field: rho A for translations, rho I for rotations
    field_translational: tuple  # per field: damping acts on these
    prescribed: dict  # dof -> (field, side) of Dirichlet DOFs
    nf: int  # fields per point (1 rod, 2 beam)
    info: dict = field(default_factory=dict)
    psi: tuple | None = None  # (EndPatched op, constant): the shear strain at the points used by the operator
    # per DOF: the point's share of the length in units of Δ (None: the trapezoid, 1/2 at the end points); the
    # operator times these weights is symmetric where the variant is written from an energy
    weights: np.ndarray | None = None
    # couples applied as the operator's action on their kink (variant energy, .couples): (position, C, u_s)
    kinks: list = field(default_factory=list)

    @cached_property
    def K(self) -> sp.csr_matrix:
        return self.op.tocsr()

    def band(self) -> Band:
        return self.op.band()

    @property
    def mass(self) -> np.ndarray:
        return np.tile(np.asarray(self.field_mass, float), len(self.x))

    @property
    def translational(self) -> np.ndarray:
        return np.tile(np.asarray(self.field_translational, bool), len(self.x))

    @property
    def n_free(self) -> int:
        return len(self.b) - len(self.prescribed)

    @property
    def free(self) -> np.ndarray:
        keep = np.ones(len(self.b), bool)
        keep[list(self.prescribed)] = False
        return np.flatnonzero(keep)


# -- prescribed values, static solve -----------------------------------------------------------

_MOTION_KEY = {"w": "displacement", "u": "axial", "rotation": "rotation", "twist": "twist"}


def prescribed_motions(scene: Scene, disc: Discrete) -> dict:
    """dof -> Motion (or None for a fixed zero value) from the scene's [dynamics] table."""
    out = {}
    d = scene.dynamics
    for dof, (fieldname, side) in disc.prescribed.items():
        em = None if d is None else getattr(d, "left" if side == 0 else "right")
        out[dof] = None if em is None else getattr(em, _MOTION_KEY[fieldname])
    return out


def static_system(scene: Scene, disc: Discrete) -> tuple[Band, np.ndarray, dict]:
    """(B, rhs, held) of the direct solve: the band of K with the prescribed DOFs held (Band.fix: unit
    row, cleared column) and their settled values ``held`` {dof: value} (zero for plain supports; the
    final value of a prescribed end motion) moved to the right-hand side."""
    end_time = scene.dynamics.end_time if scene.dynamics else 0.0
    held = {
        dof: 0.0 if mot is None else motion_final(mot, end_time) for dof, mot in prescribed_motions(scene, disc).items()
    }
    B = disc.band()
    rhs = disc.b.copy()
    moved = sorted(d for d, v in held.items() if v != 0.0)
    if moved:  # rhs = b - K u0: column d of K is column d of the band's data
        acc = np.zeros(len(rhs))
        o = B.offsets
        for d in moved:  # the few supported DOFs
            r = d - o
            ok = (r >= 0) & (r < B.n)
            acc[r[ok]] += B.data[B.upper - o[ok], d] * held[d]
        touched = np.flatnonzero(acc)
        rhs[touched] = disc.b[touched] - acc[touched]
    pres = np.array(sorted(disc.prescribed), dtype=np.int64)
    B.fix(pres, rhs)
    return B, rhs, held


SOFT_SPRING = 1e-6  # a spring at or below this share of the beam's bending stiffness (EI / L^3; EI / L rotational)


def soft_springs(scene: Scene) -> str:
    """The springs (at the ends or inside) whose stiffness against the beam's own is below SOFT_SPRING, named with
    that ratio (k L^3 / EI for a deflection, k L / EI for a rotation), or "" when none is."""
    L, EI = scene.length, scene.EI
    found = []
    sides = [(f"supports.{side}", getattr(scene.supports, side)) for side in ("left", "right")]
    sides += [(f"supports.inner[{i}]", s) for i, s in enumerate(scene.supports.inner)]
    for name, sup in sides:
        if isinstance(sup, str) or getattr(sup, "type", "") != "spring":
            continue
        for value, scale, what in (
            (sup.stiffness, L**3 / EI, "k L^3 / EI"),
            (sup.rotational_stiffness, L / EI, "k L / EI"),
        ):
            if value and value * scale < SOFT_SPRING:
                found.append(f"{name} is a spring far softer than the beam ({what} = {value * scale:.2g})")
    return "; ".join(found)


def static_solution(scene: Scene, disc: Discrete, what: str, system=None) -> tuple[np.ndarray, dict]:
    """Direct banded solve of :func:`static_system` (or the given ``system``, which is consumed: factorised
    in place above 20,000 unknowns); prescribed DOFs take their settled values. Raises SolveError when
    the system is singular to working precision (condition estimate > 1/eps: e.g. the paper variant's pure
    extrapolation at a free rod end)."""
    B, rhs, held = static_system(scene, disc) if system is None else system
    fields = tuple(np.arange(f, len(rhs), disc.nf) for f in range(disc.nf))  # w and rotation: each in its units
    u, info = solve_linear(B, rhs, what=what, watch=fields if disc.nf > 1 else None)
    cond = info.get("cond", 0.0)
    if cond * np.finfo(float).eps > 1.0:  # an infinite estimate too (a zero pivot); NaN (no estimate) is not
        free = (  # what an end leaves free: the beam's w and rotation, the rod's u, the bar's twist
            "the deflection at a free end, the rotation at a pinned or free one"
            if disc.nf == 2
            else "the axial displacement or twist at an end that does not hold it"
        )
        soft = soft_springs(scene) if disc.nf == 2 else ""  # a beam's springs against its bending
        hint = (
            f"variant paper leaves an end's free unknowns ({free}) without a traction condition (Section 4 as "
            "published); use variant corrected"
            if "paper" in what
            else f"{soft}: the beam is close to a mechanism; stiffen it or hold that point"
            if soft
            else "use fewer points"
        )
        raise SolveError(f"{what}: the system is singular to working precision (condition estimate {cond:.2g}); {hint}")
    for dof, value in held.items():  # their unit rows gave zero
        u[dof] = value
    return u, info
