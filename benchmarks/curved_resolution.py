"""pd-curved's error on coarse grids of a curved axis against its frame defect (docs/models/curved.md, "Coarse grids
on a curved axis"; pdverify/papers/curved/resolution.py):

    PYTHONPATH=. python benchmarks/curved_resolution.py [--workers 2] [--out rows.csv]

Scenes: the curved studies' scenes (studies/curved, studies/paper_curved's semicircles and steep quintic); a cubic
axis y = 0.1 - 0.5 x + 0.8 x^2 + 0.6 x^3 on [-0.5, 1] (h = 0.05) on every support pair of clamped, pinned, roller,
free and guided ends that holds it; arcs of 10, 90, 180 and 350 degrees (R = 1) clamped-free, clamped-clamped,
pinned-roller and pinned-pinned at L/h = 10 and 1000; rings of 359 and 359.9 degrees pinned-pinned (near mechanisms)
at L/h = 10 and 1000; quadratic, cubic and sine axes (two steepnesses each) clamped-
free at L/h = 5 and 1e4, pinned-roller at 5, 100 and 1e4, clamped-clamped at 100. Loads (not on the studies' scenes):
a point force with an axial part at 0.25 L, a couple at 0.7 L, a global line load from 0.4 L, forces at both ends.
Each at 11, 21, 41, 81, 161 and 321 particles, degree 2 to 6, the mixed form; error = max |w - w_exact| / max
|w_exact| against exact-curved on the same grid. Prints, per degree, how the runs past the limit and within it split
by their error (> 10 %, 1-10 %, < 1 %), and what the grid check (the same solve on half the points) adds over every
field."""

from __future__ import annotations

import argparse
import glob
import math
import tomllib
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from pdverify.core.errors import InputError, SolveError
from pdverify.core.geometry import axis_length
from pdverify.core.scene import Axis
from pdverify.core.scene_file import parse_scene
from pdverify.papers.curved.resolution import limit
from pdverify.registry import run
from pdverify.registry.grid_check import fields_of

GRID = ("the same solve on", "is not estimated")  # the grid check's two warnings

ROOT = Path(__file__).resolve().parents[1]
POINTS = (11, 21, 41, 81, 161, 321)
DEGREES = [2, 3, 4, 5, 6]  # --degrees
CUBIC = {"type": "polynomial", "coefficients": [0.1, -0.5, 0.8, 0.6], "x_range": [-0.5, 1.0]}
SUPPORTS = ("clamped", "pinned", "roller", "free", "guided")


def loads(L: float) -> list[dict]:
    return [
        {"type": "point_force", "position": 0.25 * L, "value": -500.0, "axial": 100.0},
        {"type": "point_moment", "position": 0.7 * L, "value": 80.0},
        {"type": "distributed", "value": -400.0, "start": 0.4 * L, "end": L, "frame": "global"},
        {"type": "point_force", "position": 0.0, "value": 50.0, "axial": 20.0},
        {"type": "point_force", "position": L, "value": -60.0, "axial": 30.0, "frame": "global"},
    ]


def scene(axis: dict, left: str, right: str, h: float) -> dict:
    L = axis_length(Axis(**axis))
    return {"name": "c", "beam": {"length": L}, "section": {"width": 0.05, "height": h}, "axis": axis,
            "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33},
            "supports": {"left": left, "right": right}, "loads": loads(L)}  # fmt: skip


def sine_axis(A: float) -> dict:
    """y = A sin(2 pi x) on [0, 1] by its Taylor polynomial of degree 15."""
    c = [0.0] * 16
    for k in range(1, 16, 2):
        c[k] = A * (-1) ** ((k - 1) // 2) * (2 * math.pi) ** k / math.factorial(k)
    return {"type": "polynomial", "coefficients": c, "x_range": [0.0, 1.0]}


def scenes() -> list[tuple[str, dict]]:
    out = []
    files = sorted(glob.glob(str(ROOT / "studies/curved/*.toml"))) + [
        str(ROOT / f"studies/paper_curved/{n}.toml")
        for n in ("semicircle_normal", "semicircle_tangential", "steep_quintic_uniform")
    ]
    for f in files:
        out.append(("study:" + Path(f).stem, tomllib.loads(Path(f).read_text())))
    out += [(f"cubic:{a}-{b}", scene(dict(CUBIC), a, b, 0.05)) for a in SUPPORTS for b in SUPPORTS]
    pairs = [("clamped", "free"), ("clamped", "clamped"), ("pinned", "roller"), ("pinned", "pinned")]
    for angle in (10, 90, 180, 350):
        arc = {"type": "arc", "radius": 1.0, "opening_angle_deg": float(angle)}
        for a, b in pairs:
            for slender in (10, 1000):
                out.append((f"arc{angle}:{a}-{b}:{slender}", scene(arc, a, b, math.radians(angle) / slender)))
    for angle in (359, 359.9):  # near mechanisms: pins a degree and a tenth of one apart (resolution.amplification)
        arc = {"type": "arc", "radius": 1.0, "opening_angle_deg": float(angle)}
        for slender in (10, 1000):
            out.append(
                (f"ring{angle}:pinned-pinned:{slender}", scene(arc, "pinned", "pinned", math.radians(angle) / slender))
            )
    axes = {
        "quad0.25": {"type": "polynomial", "coefficients": [0, 0, 0.25], "x_range": [0.0, 2.0]},
        "quad2": {"type": "polynomial", "coefficients": [0, 0, 2.0], "x_range": [-1.0, 1.0]},
        "cubic0.3": {"type": "polynomial", "coefficients": [0.03, -0.15, 0.24, 0.18], "x_range": [-0.5, 1.0]},
        "cubic2": {"type": "polynomial", "coefficients": [0.2, -1.0, 1.6, 1.2], "x_range": [-0.5, 1.0]},
        "sine0.1": sine_axis(0.1),
        "sine0.3": sine_axis(0.3),
    }
    combos = [("clamped", "free", 5), ("clamped", "free", 1e4), ("pinned", "roller", 5), ("pinned", "roller", 100),
              ("pinned", "roller", 1e4), ("clamped", "clamped", 100)]  # fmt: skip
    for name, axis in axes.items():
        L = axis_length(Axis(**axis))
        out += [(f"{name}:{a}-{b}:{s:g}", scene(dict(axis), a, b, L / s)) for a, b, s in combos]
    return out


def rows_of(item: tuple[str, dict]) -> list[dict]:
    name, d = item
    try:
        sc = parse_scene(d)
    except InputError:  # a mechanism (free-free, roller-free, ...)
        return []
    out = []
    for n in POINTS:
        try:
            exact = run(sc, "exact-curved", points=n)
        except (InputError, SolveError):
            return out
        top = np.abs(exact.w).max()
        for P in DEGREES:
            try:
                r = run(sc, "pd-curved", points=n, degree=P)
            except (InputError, SolveError):
                continue
            a, b = fields_of(r), fields_of(exact)
            out.append(
                {
                    "scene": name,
                    "points": n,
                    "degree": P,
                    "error": float(np.abs(r.w - exact.w).max() / top),
                    "error_fields": max(float(np.abs(a[k] - b[k]).max() / np.abs(b[k]).max()) for k in a if k in b),
                    "frame_defect": r.info["frame_defect"],
                    "amplification": r.info.get("amplification", 1.0),
                    "warned": any("too coarsely" in w for w in r.info.get("warnings", [])),
                    "near": any("near a mechanism (" in w for w in r.info.get("warnings", [])),
                    "grid": any(g in w for g in GRID for w in r.info.get("warnings", [])),
                    "grid_difference": r.info.get("grid_estimate", {}).get("difference", np.nan),
                }  # fmt: skip
            )
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", default=None)
    ap.add_argument("--degrees", type=int, nargs="+", default=list(DEGREES))
    a = ap.parse_args()
    DEGREES[:] = a.degrees
    with ProcessPoolExecutor(a.workers) as pool:
        df = pd.DataFrame([r for rows in pool.map(rows_of, scenes()) for r in rows])
    if a.out:
        df.to_csv(a.out, index=False)
    df = df[df.frame_defect > 0]  # curved axes
    print(f"{df.scene.nunique()} curved scenes, {len(df)} runs")
    for P, g in [*df.groupby("degree"), ("all", df)]:
        for past, h in ((True, g[g.warned]), (False, g[~g.warned])):
            e, where = h.error, "past" if past else "within"
            lim = f" {limit(P):g}" if P != "all" else ""
            split = f"> 10 %: {(e > 0.1).sum()}, 1-10 %: {((e >= 0.01) & (e <= 0.1)).sum()}, < 1 %: {(e < 0.01).sum()}"
            print(f"degree {P}, {where} the limit{lim}: {len(h)} runs, {split}, median {e.median():.2g}")
    for said, h in (
        ("warned (too coarsely or near a mechanism)", df[df.warned | df.near]),
        ("silent", df[~(df.warned | df.near)]),
    ):
        e = h.error
        split = f"> 10 %: {(e > 0.1).sum()}, 1-10 %: {((e >= 0.01) & (e <= 0.1)).sum()}, < 1 %: {(e < 0.01).sum()}"
        print(f"{said}: {len(h)} runs, {split}")
    # the grid check (pdverify/registry/grid_check.py) on every field, each against its own largest value
    e, said = df.error_fields, df.warned | df.near | df.grid
    alone = df[df.grid & ~(df.warned | df.near) & (e <= 1e-3)]
    over = (alone.grid_difference / alone.error_fields.clip(lower=1e-300)).quantile([0.5, 1.0])
    print(
        f"every field: {(e > 1e-3).sum()} runs past 1e-3, {((e > 1e-3) & ~(df.warned | df.near)).sum()} of them "
        f"without the frame-defect or mechanism warning, {((e > 1e-3) & ~said).sum()} with no warning at all; the grid "
        f"check alone on {len(alone)} runs within 1e-3 (its difference {over.iloc[0]:.3g} times their error at the "
        f"median, {over.iloc[1]:.3g} at most)"
    )


if __name__ == "__main__":
    main()
