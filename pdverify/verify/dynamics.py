"""The suite's dynamics check (suite 1.1): a model that declares dynamics and gives its transient operator
(``eigenproblem``, :mod:`pdverify.measure.modes`) has its lowest natural frequencies measured against the analytic
ones (Timoshenko beam: roots of the characteristic determinant) for every support pair of the suite, on the
suite's grids. The frequencies are what its time integration resolves, so their order of convergence and their
error at the finest grid are judged as the static deflections are.
"""

from __future__ import annotations

import numpy as np

from ..core.scene_file import parse_scene
from ..measure.metrics import ROUND_OFF_LEVEL, observed_order
from ..measure.modes import gives_modes, modes
from . import checks as C
from .suite import PAIRS, straight

MODES = 3  # the lowest frequencies compared per support pair
DENSITY = 2700.0  # kg/m^3, the suite's material (the frequencies' relative errors do not depend on it)


def frequency_series(model, options: dict, grids: tuple) -> list[dict]:
    """Per support pair the model takes: the largest relative error of its lowest MODES frequencies on each
    grid, and the order fitted over the three finest grids above round-off level."""
    out = []
    for left, right in PAIRS:
        d = straight(left, right, [], name=f"{left}-{right}, free vibration")
        d["material"] = dict(d["material"], density=DENSITY)
        scene = parse_scene(d)
        if model.declines(scene, dict(options, points=grids[0])):  # its capabilities, its variant's refusals
            continue
        errors, failed = [], []
        for n in grids:
            try:
                table = modes(scene, model.name, dict(options, points=n), MODES)
                errors.append(float(np.max(np.abs(table.columns()["rel_error"]))))
            except Exception as exc:  # noqa: BLE001 - a failed eigensolve is the finding, the card is still written
                errors.append(float("nan"))
                failed.append(f"{n} points: {type(exc).__name__}: {exc}")
        h = 1.0 / (np.asarray(grids, float) - 1)
        e = np.asarray(errors)
        above = np.isfinite(e) & (e >= ROUND_OFF_LEVEL)
        order = observed_order(h[above][-3:], e[above][-3:])[0] if above.sum() >= 3 else float("nan")
        exact = bool(np.all(np.isfinite(e)) and np.all(e < ROUND_OFF_LEVEL))
        out.append(
            {
                "pair": f"{left}-{right}",
                "points": list(grids),
                "errors": errors,
                "order": order,
                "exact": exact,
                "failed": failed,
            }
        )
    return out


def dynamics_check(model, options: dict, grids: tuple, expected: float) -> dict:
    """pass: every pair converges at the expected order (less ORDER_SLACK) or is exact to round-off, and its
    finest-grid error is within ACCURACY; n/a for a model without dynamics or without an eigenproblem."""
    label = "dynamics (natural frequencies)"
    if "dynamic" not in model.analyses:
        return C.check(label, "n/a", "the model declares no dynamics")
    if not gives_modes(model):
        return C.check(label, "n/a", "the model declares dynamics but gives no mass and stiffness operator")
    if model.theory == "higher-order":  # its modes' reference is the slender limit, ~(k h)^2 away on the suite's beams
        return C.check(
            label,
            "n/a",
            "no closed-form frequencies of the higher-order theory: `pdverify modes` compares with its slender limit "
            "(Euler-Bernoulli) and warns with the theories' distance (docs/models/yang.md)",
        )
    rows = frequency_series(model, options, grids)
    if not rows:
        return C.check(label, "n/a", "the model takes none of the suite's support pairs without loads")
    bad = [
        r
        for r in rows
        if r["failed"]
        or not (r["exact"] or r["order"] >= expected - C.ORDER_SLACK)
        or not r["errors"][-1] <= C.ACCURACY
    ]
    orders = [r["order"] for r in rows if not r["exact"] and np.isfinite(r["order"])]
    summary = (
        f"lowest {MODES} frequencies against the analytic ones on {len(rows)} support pairs, {grids[0]}-{grids[-1]} "
        f"points: orders {min(orders, default=float('nan')):.2f}..{max(orders, default=float('nan')):.2f} "
        f"(expected {expected:g}), finest-grid error at most {max(r['errors'][-1] for r in rows):.2e}"
    )
    if bad:
        summary += "; below: " + ", ".join(f"{r['pair']} (order {r['order']:.2f}, {r['errors'][-1]:.1e})" for r in bad)
    return C.check(label, "fail" if bad else "pass", summary, pairs=rows)
