"""Rotation, bending moment and shear force of pd-bond-pair (O'Grady & Foster 2014, §2.2: the moment of the bond-pair
forces, M_PD = ∫ T⟨xi⟩ xi dxi, read as the statics of the pair forces across a section).

A pair's bonds carry T = f / xi (Eq. 2 with small rotations, f = alpha omega sin(phi) ≈ a phi the spring's moment)
at levers up to xi from its centre: about a section at distance s from the centre it exerts f (1 - s / xi). The bending
moment at a point is the sum over every pair that straddles it (:meth:`.pairs.Pairs.section_moment`): EI kappa under
uniform curvature, and in equilibrium with the loads exactly (its second difference is the load). The shear force is
its centred difference, V = dM/dx; the rotation the centred difference of w (one-sided at the ends).
"""

from __future__ import annotations

import numpy as np

from ...core.scene import Distributed, PointForce, PointMoment, Scene
from ...numerics.features import joint_steps
from ...numerics.loads import body_loads, cell_integral, support_side
from ...numerics.statics import jump_share
from .calibration import alpha, pair_family
from .conditions import nodal_loads, value_row
from .pairs import Pairs, build_pairs


def shear(scene: Scene, M: np.ndarray, dx: float, couples: np.ndarray, reactions=()) -> np.ndarray:
    """V = dM/dx at the points. Between neighbours the statical shear (M_{p+1} - M_p) / dx less the shear of the force
    pairs that stand for couples (``couples``: their nodal forces; a couple carries no shear) is V at the middle
    x_{p+1/2} (the loads are the cells' integrals, cut at the half points); V at a point adds the distributed load on
    the half cell between (V jumps at a point force: a point on it inside the span carries the mean of its sides,
    :func:`~pdverify.numerics.statics.jump_share`; an end point the beam's side, which ``support_side`` then moves).
    ``reactions``: (position, force) of the supports inside the span, whose conditions split their force onto the two
    points around them as a point force's; those between two points are corrected as one."""
    n = len(M)
    x = np.arange(n) * dx
    Vh = np.diff(M) / dx - np.cumsum(couples)[:-1]
    dist = [ld for ld in scene.loads if isinstance(ld, Distributed)]
    left = sum((cell_integral(ld, scene, np.clip(x - dx / 2, 0, None), x) for ld in dist), np.zeros(n))
    right = sum((cell_integral(ld, scene, x, np.clip(x + dx / 2, None, scene.length)) for ld in dist), np.zeros(n))
    V = np.r_[Vh[0] - right[0], Vh + left[1:]]  # from the interval before each point (after it at x = 0)
    nodal = np.zeros(n)  # the point forces' nodal parts
    # a point force between two points is split onto both: the shear at the second carries the whole force
    between = [(a, R) for a, R in reactions if np.abs(x - a).min() > 1e-9 * dx]
    for position, value in [(ld.position, ld.value) for ld in scene.loads if isinstance(ld, PointForce)] + between:
        parts = np.zeros(n)
        for p, c in value_row(position, n, dx).items():
            parts[p] += c * value
        nodal += parts
        step = jump_share(x, position, dx)
        step[-1] = x[-1] > position + 1e-9 * dx
        V += value * step - np.r_[0.0, np.cumsum(parts)[:-1]]
    # a support inside the span on a point: its reaction, the jump between the values from the intervals before and
    # after the point less the point forces there, half on the point (the mean of its sides)
    for sup in scene.supports.inner:
        p = int(round(sup.position / dx))
        if sup.holds_deflection and 0 < p < n - 1 and abs(x[p] - sup.position) <= 1e-9 * dx:
            V[p] += 0.5 * ((Vh[p] - right[p]) - (Vh[p - 1] + left[p]) - nodal[p])
    return V


def inner_forces(scene: Scene, reactions: dict) -> list[tuple[float, float]]:
    """(position, force) of each support inside the span, from the solve's ``reactions`` (``force_inner_i``)."""
    return [(s.position, reactions.get(f"force_inner_{i}", 0.0)) for i, s in enumerate(scene.supports.inner)]


def end_statics(M: np.ndarray, g: np.ndarray, dx: float, reach: int) -> np.ndarray:
    """M within ``reach`` points of each end re-derived by statics from the interior: the pairs that reach past a
    mirror end act on ghost points whose forces the ghost map moves onto real points, so their triangles do not give
    the section moment there. From the moment and shear at ``reach`` (exact: every pair across it is real) M is
    continued to the end with the real nodal forces ``g`` (loads and reactions: V jumps by g_p at point p)."""
    n, K = len(M), reach
    if n - 1 - K <= K + 1:
        return M
    M = M.copy()
    # left: V_{p-1/2} = V_{K+1/2} - Σ_{i=p}^{K} g_i, M_{p-1} = M_p - dx V_{p-1/2}, p = K .. 1
    VK = (M[K + 1] - M[K]) / dx
    S = np.cumsum(g[1 : K + 1][::-1])[::-1]  # S[p - 1] = Σ_{i=p}^{K} g_i
    V = VK - S  # V[p - 1] = V_{p-1/2}
    M[:K] = M[K] - dx * np.cumsum(V[::-1])[::-1]
    # right: V_{p+1/2} = V_{q-1/2} + Σ_{i=q}^{p} g_i from q = n-1-K, M_{p+1} = M_p + dx V_{p+1/2}
    q = n - 1 - K
    Vq = (M[q] - M[q - 1]) / dx
    V = Vq + np.cumsum(g[q : n - 1])  # V_{p+1/2}, p = q .. n-2
    M[q + 1 :] = M[q] + dx * np.cumsum(V)
    return M


def rotation(w: np.ndarray, dx: float) -> np.ndarray:
    """w' by centred differences (one-sided second-order differences at the ends)."""
    return np.gradient(w, dx, edge_order=2)


def mirror_pairs(EI: float, params: dict, n: int, dx: float, rules: tuple[str, str]) -> Pairs:
    """The pairs of the energy form with mirror ghosts (``ends = mirror`` on end supports), alpha from ``EI``."""
    j, beta = pair_family(params["horizon"], dx, params["variant"])
    a = alpha(EI, params["horizon"], dx, params["variant"])
    return build_pairs(n, dx, j, beta, np.ones(len(j)), np.full(n, a), "mirror", rules)


def mixed_fields(scene: Scene, r: np.ndarray, k: np.ndarray, n: int, Jk: int, dx: float) -> dict:
    """{moment, shear} of the Taylor-ends mixed form: the section moment (EI / dx²) Σ_o r_o k_{p+o} at the real points
    (k = D1 w on the positions -Jk .. n-1+Jk; the operator is (EI / dx⁴) D1 r D1, so this is the same statics) and
    its shear (the interior couples as the strong form places them, the ends' through the ghosts).

    A couple on an end point is in the ghosts' end conditions, so the section moment there is already the beam's side
    of its jump; the end point reports the other side, the support's (M(0-) = M(0+) + C, M(L+) = M(L-) - C), as the
    exact beams do."""
    h = (len(r) - 1) // 2
    full = np.convolve(k, r[::-1], mode="full")  # full[q] = Σ_o r_o k_{q - h + o}
    M = scene.EI / dx**2 * full[np.arange(n) + Jk + h]
    x = np.arange(n) * dx
    moments = [ld for ld in scene.loads if isinstance(ld, PointMoment)]
    couples = body_loads(scene.model_copy(update={"loads": moments}), x, skip_ends=skip_ends(n)) * dx
    inside = [ld for ld in moments if end_point(ld.position, n, dx) is None]
    outside = np.zeros(n)
    for ld in moments:
        if (p := end_point(ld.position, n, dx)) is not None:
            outside[p] += ld.value if p == 0 else -ld.value
    V = support_side(scene, shear(scene, M, dx, couples), "shear")
    return {"moment": M + couple_statics(inside, couples, n, dx) + outside, "shear": V}


def end_point(position: float, n: int, dx: float) -> int | None:
    """0 or n - 1 where ``position`` is on that end point (as :func:`~pdverify.numerics.loads.body_loads` rounds
    it: within 1e-9 spacings), else None."""
    pos = position / dx
    if abs(pos) <= 1e-9:
        return 0
    return n - 1 if abs(pos - (n - 1)) <= 1e-9 else None


def skip_ends(n: int) -> dict:
    """The end loads the Taylor ghosts carry (:func:`.taylor.assemble_mixed`)."""
    return {0: {"point_force", "point_moment"}, n - 1: {"point_force", "point_moment"}}


def pair_fields(
    scene: Scene, pairs: Pairs, f: np.ndarray, mirror: bool, g=None, extra_couples=None, reactions=()
) -> dict:
    """{moment, shear} of a pair-form solution (pair forces ``f``): the section moment, re-derived by statics near
    mirror ends from the nodal forces ``g`` (default D^T f: loads and reactions), and its shear.
    ``extra_couples``: nodal forces of reaction couples (clamps and rotational springs) that, like the scene's
    couples, carry no shear; ``reactions``: (position, force) of the supports inside the span (:func:`shear`)."""
    dx, n = pairs.dx, pairs.n
    M = pairs.section_moment(f)
    if mirror:
        M = end_statics(M, pairs.D.T @ f if g is None else g, dx, 2 * int(pairs.offset.max()))
    moments = [ld for ld in scene.loads if isinstance(ld, PointMoment)]
    couples = nodal_loads(scene, n, dx, moments)
    all_couples = couples if extra_couples is None else couples + extra_couples
    V = support_side(scene, shear(scene, M, dx, all_couples, reactions), "shear")  # the pairs' statics, less couples
    return {"moment": M + couple_statics(moments, couples, n, dx), "shear": V}


def couple_statics(moments: list, couples: np.ndarray, n: int, dx: float) -> np.ndarray:
    """What the scene's couples add to the section moment, less what their force pairs (``couples``: nodal forces)
    add to it: a couple C at a makes M jump by -C there, its force pair (one-sided at an end point) spreads the jump
    over two spacings. Zero beyond the pair's points."""
    if not moments:
        return np.zeros(n)
    x = np.arange(n) * dx
    S1, S2 = np.cumsum(couples), np.cumsum(couples * x)
    pair = np.r_[0.0, x[1:] * S1[:-1] - S2[:-1]]  # Σ_{i<p} F_i (x_p - x_i)
    true = -sum(ld.value * jump_share(x, ld.position, dx) for ld in moments)
    return true - pair


JOINT_STEP = 1e-2  # relative step of EI at a joint below which it is not named: the rotation's first-order error
# there is about 1.8 x step x dx / L of max |rotation| (steps of 0.65: 1.15 % at dx = L / 160), 1.1e-4 at this step


def rotation_warnings(scene: Scene) -> list[str]:
    """The rotation is first order within a few spacings of a point moment and of a segment joint where EI changes
    (the curvature jumps there) and of a free or spring end (the end slope of the bond-pair solution carries a
    boundary layer): measured order 0.99-1.07 over the 17 support pairs with loads between the points, 1.05 at a
    joint (docs/models/ogrady.md); say so."""
    ends = [s for s in ("left", "right") if scene.supports.kind(s) in ("free", "spring")]
    moments = [i for i, ld in enumerate(scene.loads) if isinstance(ld, PointMoment)]
    joints = [i for i, _, r in joint_steps(scene) if 1.0 - 1.0 / r > JOINT_STEP]  # EI steps by JOINT_STEP or more
    if not (ends or moments or joints):
        return []
    where = ", ".join(
        [f"loads[{i}] (a point moment)" for i in moments]
        + [f"segments[{i}].start (EI steps)" for i in joints]
        + [f"the {s} end" for s in ends]
    )
    return [
        f"rotation: centred differences of w, first order in the spacing near {where} (measured order 1.0; second "
        "order elsewhere): this line is the rotation's recovery from w only and says nothing of the deflection's, "
        "moment's or shear's own errors"
    ]
