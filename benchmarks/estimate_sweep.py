"""`solve --estimate` against the true error on the trust sweep's scenes (docs/cli.md, "What solve --estimate adds"):

    PYTHONPATH=. python benchmarks/estimate_sweep.py [--points 41 161] [--slenderness 20] [--out rows.csv]

Each case (every static model with a grid but the 2D strip, every support pair that holds the beam, the trust
sweep's mixed loads: a force, a couple, a partial and a sine load; rods and torsion bars their own) is solved with
its Richardson estimate (`pdverify.measure.richardson.with_estimate`: two more nested grids) and against its theory's
exact solution at the same points (exact-eb, exact-timoshenko, exact-higher-order, exact-rod, exact-torsion,
exact-curved on a straight axis for pd-curved): the true error is max |w - w_exact| / max |w_exact| (the
measured quantity's), whatever its source (a PD model's horizon shrinks with its grid, so its model error is part of
it). Printed: per model, how many estimates call themselves asymptotic and resolved, and of those how many are within
a factor 3 of the true error; apart, those whose grids agree to their round-off (a nodally exact FEM beam: no order to
hold, the error is the solve's rounding); the misses.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, "benchmarks")
from trust_sweep import PAIRS, quantity, scene  # noqa: E402

from pdverify.core.errors import InputError, SolveError  # noqa: E402
from pdverify.measure.richardson import with_estimate  # noqa: E402
from pdverify.registry import get_model, models, run  # noqa: E402

EXACT = {"euler-bernoulli": "exact-eb", "timoshenko": "exact-timoshenko", "higher-order": "exact-higher-order"}
SKIP = ("fem-plane-stress", "pd-curved-mms")  # the 2D strip: minutes a case; manufactured loads
FACTOR = 3.0  # the "within a factor 3"


def reference(model) -> str:
    if model.torsion and not model.bending:
        return "exact-torsion"
    if model.axial and not model.bending:
        return "exact-rod"
    return EXACT.get(model.theory, "exact-timoshenko")


def case(name: str, pair, points: int, slenderness: float) -> dict:
    model = get_model(name)
    q = quantity(model)
    row = {"model": name, "left": pair[0], "right": pair[1], "points": points, "slenderness": slenderness}
    sc = scene(model, pair, slenderness)
    try:
        r = with_estimate(sc, model, {"points": points}, run)
        e = run(sc, reference(model), points=points)
    except (InputError, SolveError) as exc:
        return {**row, "status": "refused", "message": str(exc)[:120]}
    got, want = np.asarray(r.measured(q), float), np.asarray(e.measured(q), float)
    if got.shape != want.shape:
        want = np.interp(np.asarray(r.x, float), np.asarray(e.x, float), want)
    true = float(np.abs(got - want).max() / np.abs(want).max())
    est = r.info["estimate"]
    ok = bool(est["asymptotic"]) and bool(est.get("resolved", True))
    roundoff = "round-off" in (est.get("why") or "")  # the grids agree to their round-off: no order to hold
    return {
        **row,
        "status": "ok",
        "true": true,
        "estimate": est["error"],
        "order": est["order"],
        "trusted": ok and not roundoff,
        "roundoff": roundoff,
        "why": est.get("why", ""),
        "within": bool(ok and not roundoff and est["error"] > 0 and 1 / FACTOR <= true / est["error"] <= FACTOR),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, nargs="+", default=[41, 161])
    ap.add_argument("--slenderness", type=float, nargs="+", default=[20.0])
    ap.add_argument("--models", nargs="+", default=None)
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    names = args.models or sorted(
        n
        for n, m in models().items()
        if "static" in m.analyses and m.option("points") is not None and not m.reference and n not in SKIP
    )
    rows = [
        case(n, p, k, s)
        for n in names
        for p in PAIRS
        for k in args.points
        for s in args.slenderness
        if not get_model(n).check(scene(get_model(n), p, s))
    ]
    df = pd.DataFrame(rows)
    if args.out:
        df.to_csv(args.out, index=False)
    ok = df[df.status == "ok"]
    for name, g in ok.groupby("model"):
        t = g[g.trusted]
        line = f"{name}: {len(g)} cases, {len(t)} trusted, {int(t.within.sum())} of them within {FACTOR:g}x"
        if g.roundoff.any():
            line += f"; {int(g.roundoff.sum())} agree to round-off (true error at most {g[g.roundoff].true.max():.1g})"
        print(line)
    t = ok[ok.trusted]
    print(f"all: {len(ok)} cases, {len(t)} trusted, {int(t.within.sum())} within {FACTOR:g}x ({t.within.mean():.1%})")
    for _, r in t[~t.within].iterrows():
        print(f"  missed: {r.model} {r.left}-{r.right} {r.points} points: estimate {r.estimate:.2g}, true {r.true:.2g}")


if __name__ == "__main__":
    main()
