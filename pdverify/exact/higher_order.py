"""Model ``exact-higher-order``: the exact solution of the (local) higher-order beam theory that ``pd-higher-order``
makes peridynamic (Yang, Oterkus & Oterkus 2020, Eq. 2-9), on any straight scene.

Kinematics (Eq. 2-3): u = z theta + z^3 theta*, w = w + z^2 w*; y = (theta, theta*, w, w*). The strain energy per
unit length is (b/2) Q(m) with Q = m^T C m (Eq. 9, :func:`~pdverify.papers.yang.bonds.coefficients`) and
the measures (the local forms of the bond measures of Eq. 14)::

    a = theta'   s = 2 w*   c = theta*'   g = w' + theta   e = w*' + 3 theta*,   i.e. m = D1 y' + D0 y.

With the generalised section forces N = b (K11 y' + K10 y) (K11 = D1^T C D1, K10 = D1^T C D0, K00 = D0^T C D0; N_theta
is the moment of sigma_xx, N_w the shear force), the Euler-Lagrange equations of Eq. 9 with loads f per length are
N' = b (K10^T y' + K00 y) - f: eight first-order equations z' = M z - (0, f) for z = (y, N). The loads are applied
as the corrected variant of ``pd-higher-order`` applies them (its options ``loads`` and ``pin``, the same names
here): ``loads = faces`` puts transverse loads on the top face (work on w + h^2/4 w*), end forces as a parabolic
shear traction (w + h^2/20 w*) and end moments as a linear normal traction (theta + 3 h^2/20 theta*); ``mid``
puts them on the mid-surface (Eq. 16b). A point load makes N jump by minus its generalised force.

End conditions: an end holds the combinations ``H y = 0`` of its support (clamped: all four, the whole end face
fixed; guided: theta, theta*; pinned and roller: w + h^2/20 w* with ``pin = face``, w with ``pin = mid``, w and w*
with ``pin = held`` (the end conditions of pd-higher-order's mirror layers at a pinned end, Appendix B); free:
none) and, in the complementary directions, the natural conditions Z^T (N -+ P_end) = 0 (Z spanning the null space
of H): the variational statement of the same end conditions.

Solution: exact piecewise by matrix exponentials. Every load is constant or a sine on a piece between the
breakpoints (ends, point loads, spans' ends), so on each piece the state augmented with (1, sin kx, cos kx) obeys a
constant linear system. In the modal coordinates of M (:func:`modal_basis`) it splits into three blocks: the slow
one (the polynomial beam solutions, an exact 4 x 4 Jordan chain), the boundary layer's decaying pair (eigenvalues of
order 1/h: layers a fraction of h wide), propagated from the piece's left end, and its growing
pair, propagated back from the piece's right end, so no exponential exceeds the polynomial growth of the slow block
however long the beam. Eight unknowns per piece meet the end conditions and, at every break, continuity and the
jumps: one small dense system. Everything is written in units of h (length) and E' b h (force), where every
coefficient is O(1). Exact to round-off at any x (no grid; tests/exact/test_exact_higher_order.py): the reference ``pd-
higher-order`` converges to, and the theory's own answer to questions such as where the deflection under a point
load peaks (docs/models/yang.md).
"""

# long module: one closed form (its modal basis, pieces, end and support conditions, fields) of one derivation
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from ..core.contract import POINTS, Model, Option
from ..core.errors import SolveError
from ..core.result import Result, Timer
from ..core.scene import Distributed, PointForce, PointMoment, Scene, Spring
from ..numerics.error_bound import BOUND_LIMIT
from ..numerics.loads import axis_support_side
from ..theory.higher_order import point_work, system_matrix

# The generalised-force units of y's four components (theta, theta*, w, w*) in the solution's units of h
UNITS = np.array([1, 3, 0, 2])

# the forcing's largest entry in the augmented generators: small beside the modal blocks (entries ~1-10), so their
# exponential sets the Pade degree and scaling of expm (a very large entry would cost digits, and even one of 1
# makes expm much slower)
FORCING = 1e-7
BLOCKS = {"slow": slice(0, 4), "decay": slice(4, 6), "grow": slice(6, 8)}  # the modal coordinates' blocks
# The slow block's basis (the Jordan chain of :func:`modal_basis`) is stored in float64: its columns meet M z_(j+1) =
# z_j only to eps |M| |z|, and that defect, carried along a piece of length x (in depths) by the polynomial solutions,
# grows as eps x^2. Measured against exact-timoshenko on 21 scenes (7 support sets, uniform, point and sine loads) at
# L/h = 1e5 and 1e6, where the theories' own gap is below 3e-7: at most 5.1 eps (L/h)^2 of the largest deflection
# (1.1e-5 at 1e5, 1.1e-3 at 1e6, 9.8e-2 at 1e7 on a cantilever). The results carry ROUNDOFF eps (L/h)^2 as their
# round-off bound, warned past BOUND_LIMIT (from L/h of about 2e4).
ROUNDOFF = 16.0
# The pieces' dense system, rows and columns scaled: a condition number past this is dependent conditions (exact-eb's
# rank test, pdverify/exact/straight.py, at the same relative tolerance), not a beam the supports hold
DEPENDENT = 1e10
# its solve's rounding: cond eps times a few dozen operations a value (tests/verification/test_scale.py)
CLOSED_FORM = 64


def modal_basis(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(T, B): T (8 x 8, real) with T^-1 M T = B = blockdiag(slow, decaying, growing). Slow: the Jordan chain of
    the eigenvalue 0 (the polynomial beam solutions, w cubic), from the rigid translation z1 = e_w (M z1 = 0) by
    M z_(j+1) = z_j (least squares: the equations are consistent), whose block is the exact shift matrix (a
    round-off perturbation of a 4 x 4 Jordan block has eigenvalues ~1e-4, which grow without bound over a long
    beam); decaying and growing: the boundary layer's two-dimensional invariant subspaces of the eigenvalues with
    negative and positive real part (ordered real Schur forms: orthonormal bases, well conditioned since the layer's
    eigenvalues, of order 1/h, are far from 0). Their eigenvalues are a complex pair -alpha +- i beta and its mirror
    for a Poisson's ratio below about 0.4, two real pairs above it, and a defective double pair in between: the
    subspaces hold in every case, where eigenvectors would not."""
    chain = [np.eye(8)[2]]
    for _ in range(3):
        chain.append(np.linalg.lstsq(M, chain[-1], rcond=None)[0])
    re = np.sort(np.abs(np.linalg.eigvals(M).real))  # the slow block's four (0 but for round-off), the layer's four
    gap = np.sqrt(re[3] * re[4])  # between them, whatever the ratio of G to E
    layer = [sla.schur(M, output="real", sort=lambda re, im, s=sign: s * re > gap)[1][:, :2] for sign in (-1.0, 1.0)]
    T = np.column_stack(chain + layer)
    B = np.linalg.solve(T, M @ T)
    exact = np.zeros((8, 8))
    exact[0, 1] = exact[1, 2] = exact[2, 3] = 1.0  # M z_(j+1) = z_j
    for blk in (BLOCKS["decay"], BLOCKS["grow"]):
        exact[blk, blk] = B[blk, blk]
    return T, exact


def held(support: str, pin: str) -> np.ndarray:
    """H (k x 4): the combinations of y = (theta, theta*, w, w*) an end holds (unit h)."""
    rows = {
        "clamped": np.eye(4),
        "guided": np.eye(4)[:2],
        "pinned": {"face": np.array([[0.0, 0.0, 1.0, 1.0 / 20]]), "mid": np.eye(4)[2:3], "held": np.eye(4)[2:4]}[pin],
        "free": np.zeros((0, 4)),
    }
    return rows["pinned" if support == "roller" else support]


def end_rows(support: str, pin: str) -> np.ndarray:
    """B (4 x 8) on z = (y, N) at an end: its first rows the held combinations H y, the others Z^T N (Z spanning
    the null space of H: the natural conditions)."""
    H = held(support, pin)
    Z = sla.null_space(H) if len(H) else np.eye(4)
    B = np.zeros((4, 8))
    B[: len(H), :4] = H
    B[len(H) :, 4:] = Z.T
    return B


class Propagator:
    """exp(A t) stacked over t for a boundary-layer block: A (the layer's pair -alpha +- i beta or its mirror, and
    the load's (1, sin kx, cos kx) rotation, eigenvalues 0 and +-i k) has five distinct eigenvalues, so exp(A t) =
    V diag(exp(lambda t)) V^-1 with V computed once (its condition number is that of the small forcing coupling,
    near 1): exact exponentials at every t, no squarings (expm of each point squares ~log2(||A t||) times)."""

    def __init__(self, A: np.ndarray):
        self.lam, self.V = np.linalg.eig(A)
        self.Vi = np.linalg.inv(self.V)

    def __call__(self, t: np.ndarray) -> np.ndarray:
        e = np.exp(self.lam[None, :] * np.asarray(t, float)[:, None])
        return np.einsum("ij,nj,jk->nik", self.V, e, self.Vi).real


def series(A: np.ndarray, t: np.ndarray, most: int = 400) -> np.ndarray:
    """exp(A t_i) stacked (len(t), d, d) by its Taylor series, for the slow block: its modal part is nilpotent (the
    shift of the Jordan chain, so (A t)^j has no t^j growth past j = 3) and the rest is the load's (1, sin kx,
    cos kx) rotation with k t <= pi on a piece; the terms stay below e^(k t) times the polynomial part, so the sum
    keeps the accuracy of its terms (as the product of squared exponentials does not: ~1e-14 of the largest entry
    there). Stops when a term no longer changes the sum."""
    t = np.asarray(t, float)
    d = A.shape[0]
    term = np.broadcast_to(np.eye(d), (t.size, d, d)).copy()
    E = term.copy()
    for j in range(1, most + 1):
        term = term @ A * (t / j)[:, None, None]
        E += term
        if not np.any(np.abs(term) > np.finfo(float).eps * np.abs(E)):
            break
    return E


@dataclass
class Piece:
    """[x0, x1], one load state: A[block] the augmented generator of (modal block, 1, sin kx, cos kx)."""

    x0: float
    x1: float
    A: dict
    propagators: dict = field(default_factory=dict)  # the layer blocks' Propagator, made on first use

    def propagate(self, name: str, t: np.ndarray) -> np.ndarray:
        """exp(A[name] t) stacked over t: the slow block by :func:`series`, the layer's by a :class:`Propagator`
        (decaying forward from x0, growing backward from x1)."""
        if name == "slow":
            return series(self.A[name], t)
        if name not in self.propagators:
            self.propagators[name] = Propagator(self.A[name])
        return self.propagators[name](t)


class Solution:
    """The exact fields of one scene: :meth:`fields` at any x (physical units)."""

    def __init__(self, scene: Scene, loads: str = "faces", pin: str = "face"):
        mat, sec = scene.material, scene.section
        self.h = h = sec.depth
        nu = mat.poissons_ratio
        self.Ep = mat.E / (1.0 - nu * nu)
        self.b = sec.A / h  # the equivalent rectangle's width
        self.F0 = self.Ep * self.b * h  # the force unit
        self.L = L = scene.length / h
        self.defect = ROUNDOFF * np.finfo(float).eps * L * L  # the slow basis's (ROUNDOFF)
        self.k = np.pi / L  # the sine shape's wave number
        self.faces = loads == "faces"
        M = system_matrix(nu, mat.G / self.Ep)
        self.T, self.modal = modal_basis(M)
        Ti = np.linalg.inv(self.T)
        point, dist = [], []
        for load in scene.loads:
            if isinstance(load, Distributed) and load.value != 0.0:
                a, b = scene.span(load)  # its resultant: the width (b - a) / h, not that of its ends rounded in depths
                dist.append((a / h, b / h, load.shape, (b - a) / h / (b / h - a / h) * load.value / (self.Ep * self.b)))
            elif isinstance(load, (PointForce, PointMoment)) and load.value != 0.0:
                point.append((load.position / h, load))
        self.holds = [  # (label, kind, position / h, stiffness or None, end or None) of each reaction as an unknown
            (f"{kind}_inner_{i}", kind, sup.position / h, k if sup.type == "spring" else None, None)
            for i, sup in enumerate(scene.supports.inner)
            for kind, held, k in (
                ("force", sup.holds_deflection, sup.stiffness),
                ("moment", sup.holds_rotation, sup.rotational_stiffness),
            )
            if held
        ]
        for end, side in enumerate(("left", "right")):  # a spring end: a free end loaded by its springs
            sup = getattr(scene.supports, side)
            if isinstance(sup, Spring):
                for kind, k in (("force", sup.stiffness), ("moment", sup.rotational_stiffness)):
                    if k:
                        self.holds.append((f"{kind}_{side}", kind, end * L, k, end))
        inner = {p for p, _ in point if 0 < p < L} | {v for d in dist for v in d[:2] if 0 < v < L}
        self.breaks = np.array(sorted({0.0, L} | inner | {at for _, _, at, _, end in self.holds if end is None}))
        self.pieces = [
            Piece(x0, x1, self.generators(Ti, dist, (x0 + x1) / 2)) for x0, x1 in zip(self.breaks[:-1], self.breaks[1:])
        ]
        self.jumps = np.zeros((len(self.breaks), 8))  # z(x+) - z(x-) at each break (point loads; ends: end loads)
        for pos, load in point:
            i = int(np.argmin(np.abs(self.breaks - pos)))
            self.jumps[i, 4:] -= self.generalised(load, at_end=i in (0, len(self.breaks) - 1))
        kinds = [s if isinstance(s, str) else "free" for s in (scene.supports.left, scene.supports.right)]
        self.U, self.R = self.solve_pieces(*kinds, pin)
        self.error_bound = float(f"{self.defect + CLOSED_FORM * self.cond * np.finfo(float).eps:.3g}")

    def reaction_work(self, kind: str, end, pin: str) -> tuple[np.ndarray, np.ndarray, float]:
        """(J, c, scale) of a unit reaction of a support inside the span or a spring end, as pd-higher-order holds it
        (Yang et al. 2020, Eq. 16b, its supports as multipliers: pdverify/papers/yang/supports.py): inside the span
        a force on the mid-line w, a couple as an end's linear traction (-1 on theta, -3 h^2/20 on theta*); at a
        spring end the end's own loads (a force as the parabolic shear with ``loads = faces`` and ``pin = face``).
        J: the jump of N (its force units) per unit multiplier, the reaction being the multiplier times ``scale``
        (E' b h for a force, E' b h^2 for a couple); c: the combination of y (in units of h) the support holds, the
        work-conjugate of the same load."""
        unit = (PointForce if kind == "force" else PointMoment)(
            type="point_force" if kind == "force" else "point_moment", position=0.0, value=1.0
        )
        faces = kind == "moment" if end is None else self.faces and (kind == "moment" or pin == "face")
        g = point_work(unit, self.h, faces, at_end=True)  # physical units
        scale = self.F0 * (self.h if kind == "moment" else 1.0)
        return scale * g / (self.F0 * self.h**UNITS), g * self.h ** np.array([0, -2, 1, -1]), scale

    def generalised(self, load, at_end: bool) -> np.ndarray:
        """The generalised force on (theta, theta*, w, w*) of a point load (:func:`point_work`) in the units of N:
        E' b h times h, h^3, 1, h^2."""
        return point_work(load, self.h, self.faces, at_end) / (self.F0 * self.h**UNITS)

    def generators(self, Ti: np.ndarray, dist: list, xm: float) -> dict:
        """The augmented generators of the three modal blocks on a piece whose midpoint is xm: zeta' = (modal
        block) zeta + Ti (0, -f), f = (constant, sine) parts of the loads acting there. The forcing enters the
        augmented state (1, sin kx, cos kx) scaled to FORCING (its factor in ``"scale"``), so the matrix
        exponential sees the same entries whatever the load's size in the scene's units."""
        G = np.zeros((8, 3))  # forcing of z per (1, sin kx, cos kx)
        for a, b, shape, q in dist:
            if a <= xm <= b:
                G[4:, 0 if shape == "uniform" else 1] -= [0.0, 0.0, q, q / 4 if self.faces else 0.0]
        Gz = Ti @ G
        scale = float(np.abs(Gz).max()) / FORCING or 1.0
        out = {"scale": scale}
        for name, blk in BLOCKS.items():
            n = blk.stop - blk.start
            A = np.zeros((n + 3, n + 3))
            A[:n, :n], A[:n, n:] = self.modal[blk, blk], Gz[blk] / scale
            A[n + 1, n + 2], A[n + 2, n + 1] = self.k, -self.k
            out[name] = A
        return out

    def aug(self, x: np.ndarray) -> np.ndarray:
        return np.stack([np.ones_like(x), np.sin(self.k * x), np.cos(self.k * x)], axis=-1)

    def maps(self, p: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(P, c): z(x) = P @ U_p + c on piece p for each x (P: n x 8 x 8, c: n x 8), U_p = (slow and decaying
        coordinates at x0, growing at x1): each block propagated from its own anchor, so every exponential is
        bounded by the polynomial growth of the slow block."""
        piece = self.pieces[p]
        x = np.asarray(x, float)
        P = np.zeros((len(x), 8, 8))
        cz = np.zeros((len(x), 8))
        for name, blk in BLOCKS.items():
            x_ref = piece.x1 if name == "grow" else piece.x0
            n = blk.stop - blk.start
            E = piece.propagate(name, x - x_ref)
            P[:, :, blk] = self.T[:, blk] @ E[:, :n, :n]
            cz += np.einsum("ij,njk,k->ni", self.T[:, blk], E[:, :n, n:], piece.A["scale"] * self.aug(np.array(x_ref)))
        return P, cz

    def solve_pieces(self, left: str, right: str, pin: str) -> tuple[np.ndarray, np.ndarray]:
        """(U (pieces x 8), R (one multiplier per reaction of a support inside the span or a spring end)): the end
        conditions (a spring end: a free one) and, at every break between pieces, z(x+) = z(x-) + jump, where each
        such reaction adds its jump (an unknown multiplier, :meth:`reaction_work`) and holds its combination c of y:
        c . y = 0 (rigid) or R + k c . y = 0 (a spring); one dense system of 8 unknowns per piece and one per
        reaction."""
        n, k = len(self.pieces), len(self.holds)
        K, r = np.zeros((8 * n + k, 8 * n + k)), np.zeros(8 * n + k)
        for side, sup, p, at in (("left", left, 0, 0), ("right", right, n - 1, -1)):
            B = end_rows(sup, pin)
            P, c = self.maps(p, self.breaks[[at]])
            row = 0 if side == "left" else 8 * n - 4
            K[row : row + 4, 8 * p : 8 * p + 8] = B @ P[0]
            # left: N(0+) = -P(0) = the jump from zero; right: N(L-) = P(L) = -(the jump at L)
            r[row : row + 4] = B @ ((1.0 if side == "left" else -1.0) * self.jumps[at] - c[0])
        for p in range(n - 1):  # a few pieces (one per load boundary), not per point
            xb = self.breaks[[p + 1]]
            (Pl, cl), (Pr, cr) = self.maps(p, xb), self.maps(p + 1, xb)
            row = 4 + 8 * p
            K[row : row + 8, 8 * p : 8 * p + 8] = Pl[0]
            K[row : row + 8, 8 * p + 8 : 8 * p + 16] = -Pr[0]
            r[row : row + 8] = cr[0] - cl[0] - self.jumps[p + 1]
        for j, (_, kind, at, k_spring, end) in enumerate(self.holds):  # z(a+) = z(a-) - R (0, J); c . y(a) = 0
            J, c, scale = self.reaction_work(kind, end, pin)
            if end is None:
                p = int(np.argmin(np.abs(self.breaks - at))) - 1  # the piece that ends at the support
                K[4 + 8 * p + 4 : 4 + 8 * p + 8, 8 * n + j] = -J
            else:  # the free end's N(0+) = -P(0) and N(L-) = P(L), with R one of its loads
                p = 0 if end == 0 else n - 1
                K[(0 if end == 0 else 8 * n - 4) + np.arange(4), 8 * n + j] = J if end == 0 else -J
            P, cz = self.maps(p, np.array([at]) if end is not None else self.breaks[[p + 1]])
            weight = 1.0 if k_spring is None else k_spring / scale  # R + k c . y = 0, R = multiplier * scale
            K[8 * n + j, 8 * p : 8 * p + 8] = weight * (c @ P[0, :4])
            K[8 * n + j, 8 * n + j] = 0.0 if k_spring is None else 1.0
            r[8 * n + j] = -weight * (c @ cz[0, :4])
        # rows (conditions on lengths, rotations, forces) and columns (a slow coordinate multiplies x^3 at the far end
        # of a long piece) of very different sizes: each row divided by its largest entry, then each column, so the
        # condition number (the fields' round-off is cond eps) measures the system, not its units
        row = np.abs(K).max(axis=1)
        row[row == 0] = 1.0
        col = np.abs(K / row[:, None]).max(axis=0)
        col[col == 0] = 1.0
        Ks = K / row[:, None] / col[None, :]
        self.cond = float(f"{np.linalg.cond(Ks):.3g}")
        if not self.cond < DEPENDENT:
            raise SolveError(
                f"exact-higher-order: the supports' conditions are dependent at working precision (condition number "
                f"{self.cond:.2g}): a spring far softer than the beam, supports that nearly coincide, a shear "
                "modulus far below E (the layer and the beam's modes meet) or a beam so slender (here L/h = "
                f"{self.L:.3g}) that the layers' modes are lost beside the "
                "beam's; stiffen the spring, give the supports as one, or use exact-timoshenko"
            )
        out = np.linalg.solve(Ks, r / row) / col
        return out[: 8 * n].reshape(n, 8), out[8 * n :]

    def states(self, x) -> np.ndarray:
        """z (n x 8) at x (physical); at a break inside the span (a point load, a support, a joint: within 64 eps L of
        it, whatever the rounding of a scaled scene's positions) the mean of its two sides, as exact-eb's."""
        xs, tol = np.clip(np.asarray(x, float) / self.h, 0.0, self.L), 64 * np.finfo(float).eps * self.L
        lo, hi = (
            np.clip(np.searchsorted(self.breaks, xs + d, "left") - 1, 0, len(self.pieces) - 1) for d in (-tol, tol)
        )
        out = np.zeros((len(xs), 8))
        for piece, share in ((lo, np.where(lo == hi, 1.0, 0.5)), (hi, np.where(lo == hi, 0.0, 0.5))):
            for p in np.unique(piece[share > 0]):
                on = (piece == p) & (share > 0)
                P, c = self.maps(p, xs[on])
                out[on] += share[on, None] * (P @ self.U[p] + c)
        return out

    def fields(self, x) -> dict[str, np.ndarray]:
        """w, rotation (counter-clockwise, = -theta), theta, theta*, w*, M (sagging, = -N_theta) and V (= -N_w)."""
        z = self.states(x)
        h, F0 = self.h, self.F0
        return {
            "w": z[:, 2] * h,
            "rotation": -z[:, 0],
            "theta": z[:, 0],
            "theta_star": z[:, 1] / h**2,
            "w_star": z[:, 3] / h,
            "M": -z[:, 4] * F0 * h,
            "V": -z[:, 6] * F0,
        }

    def reactions(self) -> dict[str, float]:
        """The force (+z) and counter-clockwise moment each support puts on the beam: R = -N(0+) - P(0) at the left,
        N(L-) - P(L) at the right, on w and theta (as pd-higher-order reports them)."""
        z0, zL = self.states(np.array([0.0, self.L * self.h]))
        out = {}
        for side, r in (("left", -z0[4:] + self.jumps[0, 4:]), ("right", zL[4:] + self.jumps[-1, 4:])):
            out[f"force_{side}"] = float(r[2] * self.F0)
            out[f"moment_{side}"] = float(-r[0] * self.F0 * self.h)
        for (label, kind, _, _, end), R in zip(self.holds, self.R):
            if end is None:  # a spring end's is in its end's N above
                out[label] = float(R * self.F0 * (self.h if kind == "moment" else 1.0))
        return out


class ExactHigherOrder(Model):
    name = "exact-higher-order"
    shapes = frozenset({"rectangle", "given"})  # its equations use the depth of a rectangle
    title = "exact higher-order beam (the local theory of Yang et al. 2020, Eq. 9)"
    source = "exact solution of the higher-order beam equations (Yang, Oterkus & Oterkus 2020, Eq. 2-9)"
    theory = "higher-order"
    reference = True
    inner_supports = True  # held as pd-higher-order holds them (Solution.reaction_work)
    springs = True
    options = (
        POINTS,
        Option(
            "loads",
            str,
            "faces",
            "faces (as pd-higher-order's corrected variant) | mid (Eq. 16b)",
            choices=("faces", "mid"),
        ),
        Option(
            "pin",
            str,
            "face",
            "pinned end: face (w + h^2/20 w* = 0) | mid (w = 0) | held (w = w* = 0: pd-higher-order's mirror layers, "
            "Appendix B, Eq. B41)",
            choices=("face", "mid", "held"),
        ),
    )

    def evaluator(self, scene: Scene, params: dict):
        """The fields at any x, carrying the solution's round-off bound as ``error_bound`` (a study row measured
        against it is suspect where the bound could decide its error)."""
        sol = solution(scene, params.get("loads", "faces"), params.get("pin", "face"))

        def fields(x):
            return support_sides(scene, x, sol.fields(x))

        fields.error_bound = sol.error_bound
        return fields

    def evaluate(self, scene: Scene, params: dict, x: np.ndarray) -> dict[str, np.ndarray]:
        return self.evaluator(scene, params)(x)

    def solve(self, scene: Scene, params: dict) -> Result:
        timer = Timer()
        with timer("solve"):
            sol = solution(scene, params["loads"], params["pin"])
            x = np.linspace(0.0, scene.length, params["points"])
            f = support_sides(scene, x, sol.fields(x))
        info = {"reactions": sol.reactions(), "depth": sol.h, "loads": params["loads"], "pin": params["pin"]}
        info["cond"] = sol.cond
        info["error_bound"] = sol.error_bound
        if sol.error_bound > BOUND_LIMIT:
            info.setdefault("warnings", []).append(
                f"round-off bound {sol.error_bound:.2g} (relative error): {sol.defect:.2g} from its polynomial modes "
                f"on a beam of L/h = {sol.L:.3g} ({ROUNDOFF:g} eps (L/h)^2), {sol.error_bound - sol.defect:.2g} from "
                f"its pieces' system ({CLOSED_FORM} cond eps, cond {sol.cond:.2g}: a soft spring or nearly coincident "
                "supports); exact-timoshenko is within about h/L of this theory on a slender beam"
            )
        return self.new_result(
            scene,
            params,
            x,
            f.pop("w"),
            rotation=f.pop("rotation"),
            fields=f,
            dofs=8,
            timings=timer.timings,
            info=info,
        )


def solution(scene: Scene, loads: str, pin: str) -> Solution:
    """:class:`Solution`, or SolveError (exit 3) where the beam's numbers leave the float range on the way (a length
    of 1e100 m: the boundary layers' exponentials and their eigenvectors overflow, LAPACK's SVD fails)."""
    try:
        with np.errstate(all="ignore"):
            return Solution(scene, loads, pin)
    except (np.linalg.LinAlgError, ValueError, OverflowError, FloatingPointError) as exc:
        raise SolveError(
            f"exact-higher-order: the closed form overflows on this beam ({type(exc).__name__}: "
            f"{str(exc).splitlines()[0] if str(exc) else 'no detail'}; length {scene.length:g}, depth "
            f"{scene.section.depth:g}): give the scene in units that keep its numbers near 1"
        ) from None


def support_sides(scene: Scene, x: np.ndarray, f: dict) -> dict:
    """The fields ``f`` at the points ``x`` with M and V at an end point on its support's side, every load on that
    point acting (docs/contract.md: moment_left = -M(0), force_left = V(0), moment_right = M(L), force_right =
    -V(L)); the solution's pieces end on the beam's side."""
    g = axis_support_side(scene, x, {"M": f["M"], "Q": -np.asarray(f["V"], float)})
    return dict(f, M=g["M"], V=-g["Q"])


MODELS = [ExactHigherOrder()]
