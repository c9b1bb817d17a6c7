"""pd-curved's collocation system (Curved PDDO beam 2024, Eq. 27–35): the mixed form with the resultants as
unknowns written straight into a band, the three-unknown forms (primal, Eq. 14–16; mixed with the resultants
substituted) as sparse products, and the boundary (Eq. 11–13) and interface rows both share. The model and its solve:
:mod:`pdverify.papers.curved.model`."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...core.scene import Scene
from ...numerics.band import Band, Extent
from ...numerics.loads import force_components
from . import pddo as _pddo
from .supports import held_slots, particle_stiffness, spring_slots, support_at


def conditions(scene: Scene, N: int, offs, segs, inner, ends, t, nv, eq0: int, six: bool, resultant):
    """Boundary (Eq. 11–13) and interface rows, component-major numbering (unknown c N + k, constitutive row
    c N + k, equilibrium row eq0 + c N + k): (rows replaced, their right-hand sides, (rows, cols, values)
    of their entries)."""
    # Boundary and interface conditions replace the equilibrium rows of the segment-end particles; with
    # N, Q, M as unknowns and one kinematic end in a slot, the continuity at an interface replaces the
    # constitutive row instead, on the side away from that end (else a segment between a load and a free end
    # has only resultant conditions and a spurious discrete compatibility condition). At the outer ends the
    # conditions stay in the equilibrium rows: dropping a constitutive row there too is less accurate.
    rr, rc, rv = [], [], []
    rb = {}

    def add(row, cols, vals):
        rr.append(np.full(len(cols), row)), rc.append(np.asarray(cols)), rv.append(np.asarray(vals, float))

    for side, sup in ((0, scene.supports.left), (1, scene.supports.right)):
        k = 0 if side == 0 else N - 1
        sign = -1.0 if side == 0 else 1.0
        F = np.zeros(3)
        for load in ends[side]:
            F += force_components(load, t[k], nv[k])
        springs = spring_slots(sup)
        for c, kin in enumerate(held_slots(sup)):
            row = eq0 + c * N + k
            if kin:
                add(row, [c * N + k], [1.0])
                rb[row] = 0.0
            else:  # sign R = F - k u (an elastic end's force with the loads there, .supports)
                cols, vals = resultant(c, k)
                add(row, np.r_[cols, c * N + k], np.r_[vals, sign * springs[c]])
                rb[row] = sign * F[c]
    for i in range(len(segs) - 1):
        ka, kb = offs[i + 1] - 1, offs[i + 1]
        F = np.zeros(3)
        for load in inner.get(i, []):
            F += force_components(load, t[ka], nv[ka])
        held = support_at(scene, segs[i][-1])
        for c in range(3):
            kl, kr = held_slots(scene.supports.left)[c], held_slots(scene.supports.right)[c]
            if six and kl != kr:  # one kinematic end: continuity into the constitutive row away from it
                kc, kj = (kb, ka) if kl else (ka, kb)
                row = c * N + kc
            else:  # both or neither (mirror-symmetric): both conditions replace equilibrium rows
                kc, kj = ka, kb
                row = eq0 + c * N + kc
            add(row, [c * N + ka, c * N + kb], [1.0, -1.0])
            rb[row] = 0.0
            if held is not None and held_slots(held)[c]:  # a rigid support inside the span: u_c = 0, the jump its
                add(eq0 + c * N + kj, [c * N + ka], [1.0])  # reaction
                rb[eq0 + c * N + kj] = 0.0
                continue
            k_c = spring_slots(held)[c] if held is not None else 0.0
            cb, vb = resultant(c, kb)
            ca, va = resultant(c, ka)
            add(eq0 + c * N + kj, np.r_[cb, ca, c * N + ka], np.r_[vb, -va, -k_c])  # R+ - R- - k u = -F
            rb[eq0 + c * N + kj] = -F[c]
    rows = np.array(sorted(rb))
    return rows, np.array([rb[r] for r in rows]), (np.concatenate(rr), np.concatenate(rc), np.concatenate(rv))


def unit_load(b: np.ndarray) -> float:
    """The power of two nearest max |b| (1 for a zero or non-finite b): the system solved for b / it and the column
    scales times it, the same bits, so that neither the solution nor its round-off bound's products come near the
    ends of the float range (a modulus of 1e-300 or 1e300)."""
    top = float(np.abs(b).max()) if len(b) else 0.0
    return float(2.0 ** np.round(np.log2(top))) if top > 0 and np.isfinite(top) else 1.0


def resultant_units(length: float, EA: np.ndarray, EI: np.ndarray) -> np.ndarray:
    """Column scales (interleaved per particle) that take (u_t, u_n, φ, N, Q, M) in the beam's own units: lengths
    in L, forces in F = sqrt(EA) sqrt(EI) / L (the geometric mean of the axial force scale EA and the bending one
    EI / L²), moments in F L. The matrix is then the same for a scene in any units, and so is its equilibration by
    largest entries, which a change of the unknowns' units alone would alter. Of the force scales EA, EI / L² and
    their mean, the mean keeps the condition estimate lowest over thick and slender beams (docs/models/curved.md)."""
    F = np.sqrt(EA) * np.sqrt(EI) / length
    ones = np.ones_like(F)
    return np.stack([length * ones, length * ones, ones, F, F, F * length], 1).ravel()


def assemble_resultants(scene, segs, offs, inner, ends, size, P, kap, t, nv, loads):
    """Mixed form with N, Q, M as unknowns, straight into a band: (B, b, column scales), unknowns
    (u_t, u_n, φ, N, Q, M) and rows (constitutive t, n, φ; equilibrium t, n, φ) interleaved per particle:

        ε(u) - N/EA = 0,  γ(u) - Q/kGA = 0,  χ(u) - M/EI = 0        (Eq. 3–4)
        D1 N - κ Q + p_t = 0,  D1 Q + κ N + p_n = 0,  D1 M + Q + m = 0   (Eq. 8–10)

    with ε = D1 u_t - κ u_n, γ = D1 u_n + κ u_t - φ, χ = D1 φ. Every entry is written once (no sums), then
    the unknowns are taken in the beam's own units (:func:`resultant_units`), each row is divided by its largest
    coefficient and each column by its largest after that. The column scales returned include the units."""
    N, nf = len(kap), 6
    EA, kGA, EI = particle_stiffness(scene, segs)  # each particle's segment's (.supports)
    bw = nf * (size - 1)  # the end families reach size - 1 particles
    B = Band(nf * N, bw, bw)
    ext = Extent(B)
    # particle's own block (offset 0): curvature couplings, compliances, Q in the moment equation
    C0 = [[0.0] * nf for _ in range(nf)]
    C0[0][1], C0[0][3] = -kap, -(1 / EA)
    C0[1][0], C0[1][2], C0[1][4] = kap, -1.0, -(1 / kGA)
    C0[2][5] = -(1 / EI)
    C0[3][4], C0[4][3], C0[5][4] = -kap, kap, 1.0
    ext.block(nf, 0, C0, 0, N)
    for i, g in enumerate(segs):  # a few segments (load discontinuities), never a loop over particles
        fam, W = _pddo.derivative_weights(g, P, size, (1,))
        W = W[1]
        first = fam[:, 0] - np.arange(len(g))  # offset of each family's first member (non-increasing)
        for o in range(-(size - 1), size):  # one band diagonal per family offset and unknown
            j = o - first
            k = np.flatnonzero((j >= 0) & (j < size))  # the particles reaching offset o: contiguous
            if not len(k):
                continue
            k1, k2 = int(k[0]), int(k[-1]) + 1
            c = W[np.arange(k1, k2), j[k1:k2]]
            ext.block(nf, o, [[c if a == b else 0.0 for b in range(nf)] for a in range(nf)], offs[i] + k1, offs[i] + k2)
    # boundary and interface rows (component-major numbering -> interleaved)
    rows, vals, (rr, rc, rv) = conditions(
        scene,
        N,
        offs,
        segs,
        inner,
        ends,
        t,
        nv,
        3 * N,
        True,
        lambda c, k: (np.array([(3 + c) * N + k]), np.array([1.0])),
    )
    inter = lambda i: (i % N) * nf + i // N  # noqa: E731
    rows, rr, rc = inter(rows), inter(rr), inter(rc)
    B.clear_rows(rows)
    B.add_entries(rr, rc, rv)
    ext.entries(rr, rc)
    b = np.zeros((N, nf))
    b[:, 3], b[:, 4], b[:, 5] = -loads[0], -loads[1], -loads[2]
    b = b.ravel()
    b[rows] = vals
    units = resultant_units(scene.length, EA, EI)
    ext.scale(units, rows=False)
    # equilibrate: each row divided by its largest coefficient, then each column
    rs = 1.0 / ext.abs_max(rows=True)
    ext.scale(rs, rows=True)
    b *= rs
    cs = 1.0 / ext.abs_max(rows=False)
    ext.scale(cs, rows=False)
    beta = unit_load(b)
    return B, b / beta, cs * units * beta


def assemble_displacements(scene, params, segs, offs, inner, ends, size, P, kap, dkap, t, nv, loads):
    """Three unknowns (u_t, u_n, φ) per particle: ``primal`` (Eq. 14–16) or ``mixed`` with the resultants
    substituted. Sparse assembly: (K interleaved CSR, b, column scales (the length L on u_t, u_n), strain operators)."""
    N = len(kap)
    D1s, D2s = [], []
    for g in segs:  # a few segments (load discontinuities), never a loop over particles
        D = _pddo.derivative_matrices(g, P, size, (1, 2))
        D1s.append(D[1]), D2s.append(D[2])
    D1 = sp.block_diag(D1s, format="csr")
    D2 = sp.block_diag(D2s, format="csr")
    I = sp.identity(N, format="csr")
    Z = sp.csr_matrix((N, N))
    K_ = sp.diags(kap)
    Kp = sp.diags(dkap)
    EA, kGA, EI = (sp.diags(v) for v in particle_stiffness(scene, segs))  # each particle's segment's (.supports)
    # strain operators (rows: particles; block columns u_t, u_n, φ)
    Eps = sp.hstack([D1, -K_, Z], format="csr")
    Gam = sp.hstack([K_, D1, -I], format="csr")
    Chi = sp.hstack([Z, Z, D1], format="csr")
    if params["form"] == "mixed":  # condensed: the resultants substituted, D1 applied twice
        dEps, dGam, dChi = D1 @ Eps, D1 @ Gam, D1 @ Chi
    else:  # primal: the derivative of each strain written out, second derivatives by g^2
        dEps = sp.hstack([D2, -Kp - K_ @ D1, Z], format="csr")
        dGam = sp.hstack([Kp + K_ @ D1, D2, -D1], format="csr")
        dChi = sp.hstack([Z, Z, D2], format="csr")
    Kt = EA @ dEps - kGA @ (K_ @ Gam)
    Kn = kGA @ dGam + EA @ (K_ @ Eps)
    Kf = EI @ dChi + kGA @ Gam
    K = sp.vstack([Kt, Kn, Kf], format="csr")
    b = -np.concatenate(loads)
    res = [(EA @ Eps).tocsr(), (kGA @ Gam).tocsr(), (EI @ Chi).tocsr()]  # N, Q, M

    def resultant(c, k):
        r = res[c].getrow(k).tocoo()
        return r.col, r.data

    rows, vals, (rr, rc, rv) = conditions(scene, N, offs, segs, inner, ends, t, nv, 0, False, resultant)
    n_all = 3 * N
    keep = np.ones(n_all)
    keep[rows] = 0.0
    R = sp.csr_matrix((rv, (rr, rc)), shape=(n_all, n_all))
    K = (sp.diags(keep) @ K + R).tocsr()
    b = b * keep
    b[rows] = vals
    # the displacements in units of the beam's length (the rows' scales below then do not depend on the
    # scene's units), and each row divided by its largest coefficient
    units = np.concatenate([np.full(2 * N, scene.length), np.ones(N)])
    K = (K @ sp.diags(units)).tocsr()
    scale = 1.0 / abs(K).max(axis=1).toarray().ravel()
    K = (sp.diags(scale) @ K).tocsr()
    b = b * scale
    # interleave (particle-major) so the matrix is banded
    perm = np.arange(n_all).reshape(3, N).T.ravel()  # new index i -> old index perm[i]
    inv = np.empty_like(perm)
    inv[perm] = np.arange(n_all)
    Cm = K.tocoo()
    K = sp.csr_matrix((Cm.data, (inv[Cm.row], inv[Cm.col])), shape=K.shape)
    beta = unit_load(b)
    return K, b[perm] / beta, units[perm] * beta, dict(Eps=Eps, Gam=Gam, Chi=Chi)
