"""The report's dispersion figures (issue 30 item 5): the interior stencils of pd-rod and pd-timoshenko at horizons
1–4 on a scene's grid against the continuum they discretise (:mod:`pdverify.numerics.dispersion`), wavenumbers up to the
grid's π/Δ. A branch below zero marks a negative ω² (an unstable interior: none for these stencils)."""

from __future__ import annotations

import numpy as np

from ..core.errors import PdverifyError
from ..core.scene import Scene
from ..numerics.dispersion import stencil_branches, timoshenko_branches
from ..papers.moyer import operator as O
from . import figures

HORIZONS = (1, 2, 3, 4)


def dispersion_figure(scene: Scene, model: str, points: int, variant: str) -> str | None:
    """The figure for ``model`` (pd-rod or pd-timoshenko) at ``points``; None for other models, a scene without
    density or a grid no horizon fits."""
    rho = scene.material.density
    if model not in ("pd-rod", "pd-timoshenko") or rho is None:
        return None
    beam = model == "pd-timoshenko"
    kdx = np.linspace(np.pi / 200, np.pi, 200)
    discrete = []
    for m in HORIZONS:
        try:
            disc = O.beam_operator(scene, points, m, variant) if beam else O.rod_operator(scene, points, m, variant)
        except PdverifyError:  # too few points for this horizon
            continue
        dx = disc.x[1] - disc.x[0]
        branches = stencil_branches(disc.op.blocks, np.asarray(disc.field_mass), kdx)
        names = ("bending", "shear") if beam else ("axial",)
        discrete += [(f"m = {m}, {n}", kdx / dx, branches[:, j]) for j, n in enumerate(names)]
    if not discrete:
        return None
    k = discrete[0][1]
    A, inertia = scene.section.A, scene.section.I
    if beam:
        cont = timoshenko_branches(k, scene.EI, scene.kGA, rho * A, rho * inertia)
        continuum = [("Timoshenko, bending", k, cont[:, 0]), ("Timoshenko, shear", k, cont[:, 1])]
    else:
        continuum = [("rod: c k", k, np.sqrt(scene.EA / (rho * A)) * k)]
    title = f"{model} ({variant}) dispersion, {points} points: {scene.name}"
    return figures.dispersion(discrete, continuum, title)
