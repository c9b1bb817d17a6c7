"""pd-curved's outputs: the map from the particles to the uniform output grid, and the round-off of the PDDO weights
and of a sum of superposed solves (:mod:`pdverify.papers.curved.model`). Arrays in, arrays out."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...numerics.linalg import ENTRY_ROUNDING
from . import pddo as _pddo


def output_map(d: dict, L: float, points: int, degree: int) -> sp.csr_matrix:
    """Sparse (points, particles) map from particle values to the uniform output grid: a particle's value where
    one sits, else the mean of the degree-P PDDO interpolants of the two families around the point
    (:func:`.pddo.nearest_families`), so that a mirrored scene gives the mirrored output. A point on a break
    (a load, a support or a joint inside the span, within 1e-12 L) takes the mean of the two coincident particles,
    the two sides of a resultant's jump (docs/contract.md; the displacements are the same on both)."""
    x = np.linspace(0.0, L, points)
    x[-1] = L
    d["x"] = x
    segs, offs, size = d["segs"], d["offs"], d["family"]
    bps = np.array([g[-1] for g in segs[:-1]])
    seg = np.searchsorted(bps, x - 1e-12 * L, side="left")  # a break belongs to its left segment
    rows, cols, vals = [], [], []
    if len(bps):
        b = np.clip(seg, 0, len(bps) - 1)
        k = np.flatnonzero((seg < len(bps)) & (np.abs(x - bps[b]) <= 1e-12 * L))
        rows += [k, k]
        cols += [offs[b[k] + 1] - 1, offs[b[k] + 1]]  # the left segment's last particle, the right one's first
        vals += [np.full(len(k), 0.5), np.full(len(k), 0.5)]
        seg[k] = -1
    for i, g in enumerate(segs):  # a few segments
        k = np.flatnonzero(seg == i)
        if not len(k):
            continue
        j = np.clip(np.searchsorted(g, x[k]), 0, len(g) - 1)
        j = np.where((j > 0) & (np.abs(g[j - 1] - x[k]) < np.abs(g[j] - x[k])), j - 1, j)
        on = np.abs(g[j] - x[k]) <= 1e-12 * L
        rows.append(k[on]), cols.append(offs[i] + j[on]), vals.append(np.ones(on.sum()))
        if (~on).any():
            xo = x[k[~on]]
            for fam in _pddo.nearest_families(g, xo, size):  # the mean of the interpolants of the two families
                c = 0.5 * _pddo.pddo_weights(g, fam, degree, (0,), centers=xo)[0]  # around xo: mirror-symmetric
                rows.append(np.repeat(k[~on], size)), cols.append((offs[i] + fam).ravel()), vals.append(c.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(points, offs[-1]))


def weight_rounding(s: np.ndarray) -> float:
    """Relative uncertainty, in units of eps, of a PDDO weight computed from the particles' arc lengths ``s``: an
    offset s_j - s_i carries the rounding of s (eps L) relative to the spacing, and the weights follow the
    offsets to first order (their spread along a uniform grid is about 0.6 L/ds eps at degree 2-6)."""
    ds = np.diff(s)
    ds = ds[ds > 0]
    return ENTRY_ROUNDING + (float(np.abs(s).max() / ds.min()) if len(ds) else 0.0)


def superposed_bound(infos: list[dict], total: dict) -> dict:
    """The round-off bound of a sum of solves: each solve's bound (relative to its own largest displacement,
    ``bound_scale``) in absolute terms, summed, relative to the sum's largest displacement."""
    if any(i.get("error_bound") is None or "bound_scale" not in i for i in infos):
        return {}
    top = max(float(np.abs(total["ux"]).max()), float(np.abs(total["uy"]).max()))
    absolute = sum(float(i["error_bound"]) * i["bound_scale"] for i in infos)
    bound = float(f"{absolute / top:.3g}") if top > 0 else (0.0 if absolute == 0 else float("inf"))
    return {"error_bound": bound}
