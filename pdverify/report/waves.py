"""The report's dispersion figures: the interior stencils of pd-rod and pd-timoshenko at horizons 1–4 on a scene's
grid against the continuum they discretise (:mod:`pdverify.numerics.dispersion`), wavenumbers up to the grid's
π/Δ. A branch below zero marks a negative ω² (an unstable interior: none for these stencils).

A dispersion relation depends on the grid and the section and material, not on the scene's supports or loads:
:func:`dispersion_sets` draws each distinct relation once and names the scenes it belongs to."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..core.errors import PdverifyError
from ..core.scene import Scene, Supports
from ..numerics.dispersion import stencil_branches, timoshenko_branches
from ..papers.moyer import operator as O
from . import figures
from .plots import Axis, Figure, Series
from .text import folder

HORIZONS = (1, 2, 3, 4)
MODELS = ("pd-rod", "pd-timoshenko")


@dataclass
class Dispersion:
    """The branches of one (model, variant, grid, section, material): discrete per horizon, the continuum's."""

    model: str
    variant: str
    points: int
    discrete: list[tuple[str, np.ndarray, np.ndarray]]
    continuum: list[tuple[str, np.ndarray, np.ndarray]]
    length: str = "m"  # the scene's length unit (wavenumbers in 1/length)
    scenes: list[str] = field(default_factory=list)
    papers: list[str] = field(default_factory=list)

    @property
    def title(self) -> str:
        return f"{self.model} ({self.variant}) dispersion, {self.points} points"

    def key(self) -> tuple:
        arrays = [np.round(a, 12).tobytes() for _, k, w in self.discrete + self.continuum for a in (k, w)]
        return (self.model, self.variant, self.points, *arrays)


def dispersion_data(scene: Scene, model: str, points: int, variant: str) -> Dispersion | None:
    """The branches for ``model`` (pd-rod or pd-timoshenko) at ``points``; None for other models, a scene without
    density or a grid no horizon fits."""
    rho = scene.material.density
    if model not in MODELS or rho is None or scene.segments:  # segments: no one relation along the beam
        return None
    beam = model == "pd-timoshenko"
    scene = bulk(scene)
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
    return Dispersion(model, variant, points, discrete, continuum, scene.length_unit)


def bulk(scene: Scene) -> Scene:
    """The scene's beam, section and material between clamped ends, unloaded: the interior stencil the relation is of
    (a spring end, a support inside the span or a load changes the rows near them only)."""
    supports = Supports(left="clamped", right="clamped")
    return scene.model_copy(update={"supports": supports, "loads": [], "dynamics": None, "loading": None})


def dispersion_figure(scene: Scene, model: str, points: int, variant: str) -> str | None:
    """The matplotlib figure for ``model`` at ``points`` on ``scene``'s section and material (None as
    :func:`dispersion_data`)."""
    data = dispersion_data(scene, model, points, variant)
    return None if data is None else svg(data)


def svg(data: Dispersion) -> str:
    return figures.dispersion(data.discrete, data.continuum, data.title, data.length)


def dispersion_sets(rows: pd.DataFrame, scene_of) -> list[Dispersion]:
    """Each distinct dispersion relation of the PD rod / beam runs in ``rows`` (model, variant, finest grid per
    scene), with the scenes it belongs to; ``scene_of(scene_file)``: the scene as run (None when unknown)."""
    pd_rows = rows[rows["model"].isin(MODELS)]
    found: dict[tuple, Dispersion] = {}
    for sfile, g in pd_rows.groupby("scene_file", sort=False):
        scene = scene_of(sfile)
        if scene is None:
            continue
        for (model, variant), gg in g.groupby(["model", g["variant"].replace("", np.nan).fillna("corrected")]):
            data = dispersion_data(scene, model, int(gg["points"].max()), variant)
            if data is None:
                continue
            data = found.setdefault(data.key(), data)
            if scene.name not in data.scenes:
                data.scenes.append(scene.name)
                data.papers.append(folder(sfile))
    return list(found.values())


def dispersion_plot(data: Dispersion) -> Figure:
    """The in-page figure of one relation (:mod:`.plots`): discrete branches per horizon, the continuum dashed."""
    series = [
        Series(name, k, w, model=data.model, variant=data.variant, colour=i)
        for i, (name, k, w) in enumerate(data.discrete)
    ]
    series += [Series(name, k, w, colour=-1, style="dash", guide=True) for name, k, w in data.continuum]
    return Figure(
        data.title,
        Axis(f"wavenumber k (1/{data.length})", f"1/{data.length}"),
        Axis("ω (rad/s)", "rad/s"),
        series,
        caption="scenes: " + "; ".join(data.scenes),
    )
