"""Spectrum of the Moyer & Miraglia operators (:mod:`.operator`): the eigenvalues of M⁻¹K on the free
DOFs that set the explicit scheme's stable step (dt_limit = 2 / ω_max) and the first natural frequency.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...numerics.timeint import symbol_max
from .system import Discrete


def mass_scaled(disc: Discrete, free: np.ndarray) -> sp.csr_matrix:
    return sp.diags(1.0 / disc.mass[free]) @ disc.K[free][:, free]


EIG_DOFS = 1000  # up to this many free DOFs the largest eigenvalue is computed on the whole operator (ARPACK,
# k = 4, whose time grows faster than the DOFs), above on the operator shortened to this size and the symbol


def stable_time_step(disc: Discrete) -> float:
    """dt_limit = 2 / ω_max, ω_max² the largest |eigenvalue| of M⁻¹K on the free DOFs
    (:func:`largest_eigenvalue`)."""
    return 2.0 / np.sqrt(largest_eigenvalue(disc))


def _eig_max(disc: Discrete) -> float:
    import scipy.sparse.linalg as spla

    A = mass_scaled(disc, disc.free)
    if A.shape[0] < 20:
        return float(np.abs(np.linalg.eigvals(A.toarray())).max())
    # fixed start vector: ARPACK's default is random, which would make dt (and every transient) differ
    # between runs in the 11th digit. Not the ones vector, and k = 4: with v0 = ones and k = 1 ARPACK
    # misses an end mode of the rod's traction closure (m = 2, 61 points)
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])
    return float(
        np.abs(spla.eigs(A, k=min(4, A.shape[0] - 2), which="LM", return_eigenvectors=False, tol=1e-6, v0=v0)).max()
    )


def largest_eigenvalue(disc: Discrete) -> float:
    """The largest |eigenvalue| of M⁻¹K on the free DOFs. Above ``EIG_DOFS`` free DOFs the operator is a
    stencil away from its end rows: its spectrum is the end modes, which are those of the same operator
    shortened to ``EIG_DOFS`` DOFs (same end rows and stencil; ARPACK), and the interior modes, bounded by
    the maximum of the stencil's symbol over the wavenumbers (:func:`pdverify.numerics.timeint.symbol_max`).
    (A Gershgorin row-sum bound would over-estimate it and so give a smaller step than needed.) The beam's top
    modes are end modes (~2x the symbol's maximum at m = 3), so the short grid carries the estimate."""
    if disc.n_free <= EIG_DOFS:
        return _eig_max(disc)
    nf, n = disc.nf, len(disc.x)
    ns = EIG_DOFS // nf
    op = disc.op.shortened(ns)
    shift = nf * (n - ns)
    pres = {(d if d < nf * n // 2 else d - shift): v for d, v in disc.prescribed.items()}
    short = Discrete(disc.x[:ns], op, np.zeros(nf * ns), disc.field_mass, disc.field_translational, pres, nf)
    return max(_eig_max(short), symbol_max(op.blocks, 1.0 / np.asarray(disc.field_mass, float)))


def first_frequency(disc: Discrete) -> float:
    """ω_1 (rad/s): the smallest |eigenvalue| of M⁻¹K on the free DOFs, square-rooted (shift-invert)."""
    import scipy.sparse.linalg as spla

    free = disc.free
    A = mass_scaled(disc, free).tocsc()
    if A.shape[0] < 40:
        lam = np.linalg.eigvals(A.toarray())
        return float(np.sqrt(np.abs(lam).min()))
    lam = spla.eigs(A, k=1, sigma=0.0, which="LM", return_eigenvectors=False, v0=np.ones(A.shape[0]))
    return float(np.sqrt(np.abs(lam[0])))
