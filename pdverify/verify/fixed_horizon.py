"""The card's nonlocal check (docs/nonlocal.md): a PD model at a fixed horizon length, its error split in two.

On the suite's member under a sine load, pinned-pinned (a beam) or clamped-clamped (a rod or torsion bar), L = 1 m:

* the discretisation order: discrete - continuum at delta = 0.1 L on m = 8, 16, 32 (m-convergence) at the points of
  the coarsest grid, which every finer one holds, judged like the convergence check (at least the expected order less
  the slack) against the order the variant's equations give at a fixed delta (``Model.fixed_horizon_order``: 1 where
  its sums are first order in dx there, as derived in docs/nonlocal.md; else the model's order);
* the model-error order: continuum - local at delta = 0.2, 0.1, 0.05 L at the points of each delta's m = 8 grid,
  reported, not judged (the order in delta of the model's nonlocality, 2 for every PD kernel, is a property of the
  model, not a defect).

Each delta's continuum is extrapolated from m = 8 to :data:`CONTINUUM_M` on the m = 8 grid: four levels, where a
continuum asked on the m = 32 grid itself would have two (m = 32, 64), its finest level all but the grid's own
solution.

Not run for curved-axis models (their extrapolation in m does not settle) or a model without a horizon; a model that
declares no limit at fixed delta on the scene (``Model.continuum_limit``) says so, informative only, and so does a
continuum at delta = 0.1 L whose own estimate passes a tenth of the smallest discretisation error.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import PdverifyError
from ..core.scene_file import parse_scene
from ..measure.metrics import errors, observed_order
from ..registry import run
from ..study.nonlocal_table import CONTINUUM_SHARE
from .checks import ORDER_SLACK, check
from .suite import loads_for, rod_kind, straight

NAME = "nonlocal (fixed horizon length)"
M_PATH = (8, 16, 32)  # m at delta = M_DELTA
M_DELTA = 0.1  # delta / L of the m-path
DELTAS = (0.2, 0.1, 0.05)  # delta / L of the model-error path
CONTINUUM_M = 64  # the finest m of an extrapolated continuum


def nonlocal_check(model, options: dict, reference, order: float | None = None) -> dict:
    """The card's nonlocal check of ``model`` with ``options`` against the local ``reference`` (its name or table);
    ``order`` (``verify --order``): the discretisation order it expects, else the model's at a fixed horizon."""
    if model.option("horizon") is None:
        return check(NAME, "n/a", f"model {model.name} has no horizon")
    if model.curved:
        return check(NAME, "n/a", "curved-axis model: its extrapolation in m at fixed delta does not settle")
    if reference is None:
        return check(NAME, "n/a", "no exact solution of the model's theory to measure the model error against")
    # the check holds the horizon as a length (horizon_length = delta); a card's horizon factor has no place in it
    options = {k: v for k, v in options.items() if k not in ("horizon", "horizon_length")}
    kind = rod_kind(model)
    pair = ("pinned", "pinned") if kind is None else ("clamped", "clamped")
    scene = parse_scene(straight(*pair, loads_for(kind)["sine"], name=f"{pair[0]}-{pair[1]} sine"))
    try:
        at = dict(options, points=int(round(M_PATH[0] / M_DELTA)) + 1, horizon_length=M_DELTA)
        limit = model.continuum_limit(scene, model.resolve(scene, at))
    except PdverifyError as exc:
        return check(NAME, "info", f"not measured: {' '.join(exc.lines)}")
    if limit is not None:
        return check(NAME, "info", f"no limit at a fixed horizon on the {pair[0]}-{pair[1]} sine load: {limit[0]}")
    ref = dict(reference) if isinstance(reference, dict) else {"model": reference}
    ref_name = ref.pop("model")
    q = model.measures

    def values(result) -> np.ndarray:
        return np.asarray(result.w if q == "w" else result.fields[q], float)

    try:
        model_err = []
        for delta in DELTAS:  # each delta's continuum on the m-path's coarsest grid (levels m = 8 ... CONTINUUM_M)
            opts = {**options, "points": int(round(M_PATH[0] / delta)) + 1, "horizon_length": delta}
            got = run(scene, model, **opts, continuum=True, continuum_m=CONTINUUM_M)
            r = run(scene, ref_name, points=opts["points"], **ref)
            model_err.append(errors(values(got), values(r))["err_max"])
            if delta == M_DELTA:
                c, own = got, got.info.get("error_bound", np.inf)
        disc = []
        for m in M_PATH:  # nested grids: every M_PATH[0]-th point of the finer ones is a point of the coarsest
            d = run(scene, model, **options, points=int(round(m / M_DELTA)) + 1, horizon_length=M_DELTA)
            stride = m // M_PATH[0]
            if not np.allclose(np.asarray(d.x)[::stride], c.x, rtol=0.0, atol=1e-9 * scene.length):
                return check(NAME, "info", f"not measured: the grid of m = {m} does not hold the points of m = 8")
            disc.append(errors(values(d)[::stride], values(c))["err_max"])
    except PdverifyError as exc:
        return check(NAME, "info", f"not measured: {' '.join(exc.lines)}")
    h = np.array([M_DELTA / m for m in M_PATH])
    disc, model_err = np.array(disc), np.array(model_err)
    settled = own <= CONTINUUM_SHARE * disc.min()  # as a study's continuum_in_doubt
    p_disc = observed_order(h, disc)[0] if np.all(disc > 0) else float("nan")
    p_model = observed_order(np.array(DELTAS), model_err)[0] if np.all(model_err > 0) else float("nan")
    expected, why = (float(order), "--order") if order is not None else model.fixed_horizon_order(options)
    text = (
        f"discretisation order {p_disc:.2f} at delta = 0.1 L (m = 8, 16, 32: {', '.join(f'{e:.1e}' for e in disc)}); "
        f"model-error order {p_model:.2f} in delta (delta = 0.2, 0.1, 0.05 L: "
        f"{', '.join(f'{e:.1e}' for e in model_err)}), the model's nonlocality, not judged; the continuum's own "
        f"estimate {own:.1e} at delta = 0.1 L"
    )
    if not settled or not np.isfinite(p_disc):
        return check(NAME, "info", text + "; the continuum's estimate is too coarse to judge the discretisation order")
    verdict = "pass" if p_disc >= expected - ORDER_SLACK else "fail"
    return check(
        NAME,
        verdict,
        text + f"; expected discretisation order {expected:g}" + (f" ({why})" if why else ""),
        discretisation_order=p_disc,
        model_error_order=p_model,
    )
