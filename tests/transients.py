"""Shared pieces of the transient tests: a dynamic scene of the Moyer & Miraglia examples' kind, probes, and the
exact solution in time of a discrete operator (its modes), against which a time integrator's error is measured."""

import numpy as np
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene

PROBES = [1.0, 2.0]

MATERIAL = {"youngs_modulus": 70e9, "poissons_ratio": 0.33, "density": 2700.0}
LOADS = [{"type": "distributed", "value": -1000.0, "start": 0.3, "end": 1.2}]
AXIAL = [{"type": "distributed", "value": 0.0, "axial": 3000.0, "start": 0.3, "end": 1.2}]


def transient_scene(left="clamped", right="clamped", height=0.1, loads=LOADS, **dyn):
    return parse_scene(
        scene_dict(
            left,
            right,
            loads,
            section={"width": 0.05, "height": height},
            material=MATERIAL,
            dynamics=dict({"end_time": 0.02}, **dyn),
        )
    )


def semi_discrete(disc, t, stride=1):
    """The exact solution in time of the same operator (M u'' + K u = b from rest): u = V (1 - cos √λ t) V⁻¹ u_s, at
    the probes (stride 2: a beam's w, its DOFs interleaved with γ)."""
    free = disc.free
    K = disc.K[free][:, free].toarray()
    lam, V = np.linalg.eig(K / disc.mass[free][:, None])
    c = np.linalg.solve(V, np.linalg.solve(K, disc.b[free]))
    u = np.zeros((len(t), len(disc.b)))
    u[:, free] = (((1 - np.cos(np.sqrt(lam.astype(complex))[None, :] * t[:, None])) * c) @ V.T).real
    return np.stack([np.interp(PROBES, disc.x, row[::stride]) for row in u])
