"""The trust sweep: every static model's round-off bound against the round-off it actually makes (docs/trust.md).

    PYTHONPATH=. python benchmarks/trust_sweep.py --out trust_sweep.csv            # all (about an hour on 2 cores)
    PYTHONPATH=. python benchmarks/trust_sweep.py --models fem-eb pd-eb --points 101 1001 --slenderness 20 1e4

Each case (model x support pair x points x slenderness, mixed loads: a force, a couple, a partial and a sine load;
a rod or torsion bar its own) is solved four times: as given, and with the scene scaled in length, modulus and load
by factors that are not powers of two. In exact arithmetic the four relative results w / max |w| are one; their
largest difference samples the rounding of the assembled data. A fifth solve with every system refined in extended
precision (linalg.SMALL raised: the converted, refined path at any size) gives the solve's own error on the in-place
path, which the scaled copies share (their scaled systems are the same numbers). The measured round-off is the larger
of the two; ``ratio`` = bound / measured, the bound being ``info["error_bound"]`` or, for a closed form that reports
only the condition number of its small system, ``SCALE_EPS cond eps``. Below 1: the bound missed; above 100: it
cries wolf.
Measured differences below FLOOR (a few eps: the output's own rounding) count as FLOOR.

Blind spot: a rounding that is the same in every scaling (a dimensionless weight computed once) moves all four
solutions alike and is not measured; the bound covers it, so such a model's ratio reads high.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pandas as pd

import pdverify.numerics.linalg as linalg
from pdverify.core.errors import InputError, SolveError
from pdverify.core.scene import SUPPORTS, is_mechanism
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, models, run

FIXED = [(1.1, 3.7, 0.3), (0.77, 1 / 7, 13.0), (math.pi, math.e, math.sqrt(2))]  # (length, modulus, load)
FACTORS = list(FIXED)  # the scaled copies of a case (--copies)
FLOOR = 4 * np.finfo(float).eps
SCALE_EPS = 64  # a closed form's rounding: a few dozen operations on each value (tests/verification/test_scale.py)
PAIRS = [(a, b) for a in SUPPORTS for b in SUPPORTS if not is_mechanism(a, b) and "spring" not in (a, b)]
SKIP = {  # not a linear static model of the scene's loads, or a reference without a bound of its own
    "exact-curved-manufactured",
    "pd-curved-mms",
    "exact-elastica",
    "exact-eb",
    "exact-timoshenko",
    "exact-rod",
    "exact-torsion",
    "exact-curved-cantilever",
}


def copies(n: int) -> list[tuple[float, float, float]]:
    """The first ``n`` scalings (length, modulus, load): the three fixed ones, then log-uniform factors in 0.1 ... 10
    from a seeded generator (the same on every run)."""
    rng = np.random.default_rng(7)
    extra = [tuple(float(v) for v in 10 ** rng.uniform(-1, 1, 3)) for _ in range(max(0, n - 3))]
    return (FIXED + extra)[:n]


def loads(model, length: float, load: float) -> list[dict]:
    """The loads of a case at scale (length, load): forces by ``load``, couples by load x length, line loads by
    load / length."""
    if model.torsion and not model.bending:
        return [
            {"type": "point_torque", "position": 0.35 * length, "value": 300.0 * load * length},
            {"type": "distributed", "value": 0.0, "torque": 200.0 * load, "start": 0.1 * length, "end": 0.55 * length},
        ]
    if model.axial and not model.bending:
        return [
            {"type": "point_force", "position": 0.35 * length, "value": 0.0, "axial": -300.0 * load},
            {
                "type": "distributed",
                "value": 0.0,
                "axial": 400.0 * load / length,
                "start": 0.1 * length,
                "end": 0.55 * length,
            },
        ]
    return [
        {"type": "point_force", "position": 0.35 * length, "value": -300.0 * load},
        {"type": "point_moment", "position": 0.65 * length, "value": 150.0 * load * length},
        {"type": "distributed", "value": -500.0 * load / length, "start": 0.1 * length, "end": 0.55 * length},
        {"type": "distributed", "value": 400.0 * load / length, "shape": "sine"},
    ]


def scene(model, pair, slenderness: float, length=1.0, modulus=1.0, load=1.0):
    d = {
        "name": "trust sweep",
        "beam": {"length": 2.0 * length},
        "section": {"width": 0.05 * length, "height": 2.0 * length / slenderness},
        "material": {"youngs_modulus": 70e9 * modulus, "poissons_ratio": 0.33},
        "supports": {"left": pair[0], "right": pair[1]},
        "loads": loads(model, 2.0 * length, load),
    }
    return parse_scene(d)


def quantity(model) -> str:
    return "w" if model.bending else "twist" if model.torsion else "u"


def relative(result, q: str) -> np.ndarray:
    v = np.asarray(result.measured(q), float)
    top = np.abs(v).max()
    return v / top if top > 0 else v


def bound_of(result) -> tuple[float, str]:
    if result.info.get("error_bound") is not None:
        return float(result.info["error_bound"]), "error_bound"
    if result.info.get("cond") is not None:
        return SCALE_EPS * float(result.info["cond"]) * np.finfo(float).eps, "64 cond eps"
    return math.nan, "none"


def refined(sc, name: str, opts: dict):
    """The same solve with every linear system converted and refined in extended precision."""
    small = linalg.SMALL
    linalg.SMALL = 1 << 62
    try:
        return run(sc, name, **opts)
    finally:
        linalg.SMALL = small


def case(name: str, pair, points: int, slenderness: float, options: dict | None = None) -> dict:
    """One case of the sweep (module docstring); ``options``: the model's options besides ``points``."""
    model = get_model(name)
    q = quantity(model)
    opts = ({"points": points} if model.option("points") is not None else {}) | (options or {})
    row = {"model": name, "left": pair[0], "right": pair[1], "points": points, "slenderness": slenderness}
    row |= {"options": ", ".join(f"{k}={v}" for k, v in sorted((options or {}).items()))}
    t0 = time.perf_counter()
    try:
        base = run(scene(model, pair, slenderness), name, **opts)
    except (InputError, SolveError) as exc:
        return {**row, "status": "refused", "message": str(exc)[:200]}
    w0 = relative(base, q)
    spread = 0.0
    for length, modulus, load in FACTORS:
        other = run(scene(model, pair, slenderness, length, modulus, load), name, **opts)
        spread = max(spread, float(np.abs(relative(other, q) - w0).max()))
    solve_err = float(np.abs(relative(refined(scene(model, pair, slenderness), name, opts), q) - w0).max())
    bound, kind = bound_of(base)
    measured = max(spread, solve_err, FLOOR)
    return {
        **row,
        "status": "ok",
        "bound": bound,
        "bound_kind": kind,
        "spread": spread,
        "solve_error": solve_err,
        "measured": measured,
        "ratio": bound / measured,
        "warned": any("round-off bound" in w for w in base.info.get("warnings", [])),
        "seconds": time.perf_counter() - t0,
    }


def summary(df: pd.DataFrame) -> pd.DataFrame:
    ok = df[df["status"] == "ok"]
    g = ok.groupby("model")
    return pd.DataFrame(
        {
            "cases": g.size(),
            "missed (ratio < 1)": g["ratio"].apply(lambda r: int((r < 1).sum())),
            "within 100x": g["ratio"].apply(lambda r: int(((r >= 1) & (r <= 100)).sum())),
            "above 100x": g["ratio"].apply(lambda r: int((r > 100).sum())),
            "ratio min": g["ratio"].min(),
            "ratio median": g["ratio"].median(),
            "ratio max": g["ratio"].max(),
            "warned": g["warned"].sum(),
            "largest measured": g["measured"].max(),
        }
    )


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    default = sorted(n for n, m in models().items() if "static" in m.analyses and m.straight and n not in SKIP)
    p.add_argument("--models", nargs="+", default=default)
    p.add_argument("--points", nargs="+", type=int, default=[11, 101, 1001, 10001])
    p.add_argument("--slenderness", nargs="+", type=float, default=[10.0, 300.0, 1e4])
    p.add_argument("--max-plane-points", type=int, default=401, help="fem-plane-stress (2D) only up to this size")
    p.add_argument("--out", default=None, help="write every case to this CSV")
    p.add_argument(
        "--copies", type=int, default=len(FACTORS), help="scaled copies per case (beyond the three: seeded random)"
    )
    a = p.parse_args(argv)
    FACTORS[:] = copies(a.copies)
    rows = []
    for name in a.models:
        for points in a.points:
            if name == "fem-plane-stress" and points > a.max_plane_points:
                continue
            for slenderness in a.slenderness:
                for pair in PAIRS:
                    rows.append(case(name, pair, points, slenderness))
                    r = rows[-1]
                    if r["status"] == "ok" and not 1 <= r["ratio"] <= 100:
                        print(
                            f"{name} {pair} n={points} L/h={slenderness:g}: bound {r['bound']:.2g} ({r['bound_kind']}) "
                            f"measured {r['measured']:.2g} (spread {r['spread']:.2g}, solve {r['solve_error']:.2g})",
                            flush=True,
                        )
    df = pd.DataFrame(rows)
    if a.out:
        df.to_csv(a.out, index=False)
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(summary(df).to_string(float_format=lambda v: f"{v:.3g}"))


if __name__ == "__main__":
    main()
