"""The card's nonlocal check (docs/nonlocal.md): a PD model at a fixed horizon length, its error split in two.

On the suite's member under a sine load, pinned-pinned (a beam) or clamped-clamped (a rod or torsion bar), L = 1 m:

* the discretisation order: discrete - continuum at delta = 0.1 L on m = 8, 16, 32 (m-convergence), judged like the
  convergence check (at least the expected order less the slack);
* the model-error order: continuum - local at delta = 0.2, 0.1, 0.05 L (m = 16), reported, not judged (the order in
  delta of the model's nonlocality, 2 for every PD kernel, is a property of the model, not a defect).

Not run for curved-axis models (their extrapolation in m does not settle), models whose continuum stops below
m = :data:`CONTINUUM_M` (their cost) or a model without a horizon; a continuum
whose own estimate is above :data:`SETTLED` makes the check informative only.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import PdverifyError
from ..core.scene_file import parse_scene
from ..measure.metrics import errors, observed_order
from ..registry import run
from .checks import ORDER_SLACK, check
from .suite import loads_for, rod_kind, straight

NAME = "nonlocal (fixed horizon length)"
M_PATH = (8, 16, 32)  # m at delta = 0.1 L
DELTAS = (0.2, 0.1, 0.05)  # delta / L at m = 16
SETTLED = 1e-6  # a continuum estimate above this: its orders are shown, not judged
CONTINUUM_M = 64  # the finest m of an extrapolated continuum


def _pair(model, reference) -> tuple[float, float, float]:
    """(err_disc, err_model, the continuum's estimate) of one grid."""
    d, c, e = model
    return errors(d, c)["err_max"], errors(c, reference)["err_max"], e


def nonlocal_check(model, options: dict, reference) -> dict:
    """The card's nonlocal check of ``model`` with ``options`` against the local ``reference`` (its name or table)."""
    if model.option("horizon") is None:
        return check(NAME, "n/a", f"model {model.name} has no horizon")
    if model.curved:
        return check(NAME, "n/a", "curved-axis model: its extrapolation in m at fixed delta does not settle")
    if model.continuum_m < CONTINUUM_M:
        return check(NAME, "n/a", f"its continuum is extrapolated to m = {model.continuum_m} only (its cost)")
    if reference is None:
        return check(NAME, "n/a", "no exact solution of the model's theory to measure the model error against")
    kind = rod_kind(model)
    pair = ("pinned", "pinned") if kind is None else ("clamped", "clamped")
    scene = parse_scene(straight(*pair, loads_for(kind)["sine"], name=f"{pair[0]}-{pair[1]} sine"))
    ref = dict(reference) if isinstance(reference, dict) else {"model": reference}
    ref_name = ref.pop("model")
    try:
        rows = {}
        for delta, m in [(0.1, m) for m in M_PATH] + [(d, 16) for d in DELTAS if d != 0.1]:
            points = int(round(m / delta)) + 1
            opts = {**options, "points": points, "horizon_length": delta}
            d = run(scene, model, **opts)
            c = run(scene, model, **opts, continuum=True, continuum_m=CONTINUUM_M)
            r = run(scene, ref_name, points=points, **ref)
            q = model.measures
            values = [np.asarray(v.w if q == "w" else v.fields[q], float) for v in (d, c, r)]
            rows[(delta, m)] = _pair((values[0], values[1], c.info.get("error_bound", np.inf)), values[2])
    except PdverifyError as exc:
        return check(NAME, "info", f"not measured: {' '.join(exc.lines)}")
    h = np.array([0.1 / m for m in M_PATH])
    disc = np.array([rows[(0.1, m)][0] for m in M_PATH])
    model_err = np.array([rows[(d, 16)][1] for d in DELTAS])
    settled = max(r[2] for r in rows.values()) <= SETTLED
    p_disc = observed_order(h, disc)[0] if np.all(disc > 0) else float("nan")
    p_model = observed_order(np.array(DELTAS), model_err)[0] if np.all(model_err > 0) else float("nan")
    expected = float(model.order)
    text = (
        f"discretisation order {p_disc:.2f} at delta = 0.1 L (m = 8, 16, 32: {', '.join(f'{e:.1e}' for e in disc)}); "
        f"model-error order {p_model:.2f} in delta (delta = 0.2, 0.1, 0.05 L: "
        f"{', '.join(f'{e:.1e}' for e in model_err)}), the model's nonlocality, not judged"
    )
    if not settled or not np.isfinite(p_disc):
        return check(NAME, "info", text + "; the continuum's estimate is too coarse to judge the discretisation order")
    verdict = "pass" if p_disc >= expected - ORDER_SLACK else "fail"
    return check(
        NAME,
        verdict,
        text + f"; expected discretisation order {expected:g}",
        discretisation_order=p_disc,
        model_error_order=p_model,
    )
