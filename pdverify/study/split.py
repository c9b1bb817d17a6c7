"""Every PD error split in two (docs/nonlocal.md): the model's nonlocal continuum at the case's horizon
(:mod:`pdverify.theory.continuum`) stands between the case's discrete solution and the local reference.

* ``err_model``: continuum - local reference (the nonlocality, a property of the model at this horizon);
* ``err_disc``: discrete - continuum (the discretisation, which m-convergence removes at fixed horizon);
* ``err_max``: discrete - local reference, the total, as in every study.

Max errors relative to the largest value of the second field (``*_l2``: relative L2), ``continuum_error`` the
continuum's own estimate, ``continuum_no_limit`` why the model has no limit at this horizon ("" when it has one:
docs/nonlocal.md, "A limit at fixed δ?"). Both are measured at the points of the coarsest grid with m >= 8 that the
case's grid holds (``split_points`` of them: :func:`~pdverify.theory.continuum.coarsest_nested`), so that the rows
of one horizon share one continuum extrapolated from m = 8 up, whatever their own m. A case gets them when its model
is a PD model (a ``horizon`` option), it gives its horizon as a length (``horizon_length``) and its run has a local
reference. A run whose reference is ``{model = ..., continuum = true}`` measures against the continuum itself on its
own grid (:func:`continuum_at`).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..core.errors import InputError, PdverifyError
from ..core.result import quantity_of
from ..measure.metrics import errors
from ..registry import get_model, model_options, run
from ..theory.continuum import coarsest_nested
from .spec import Case

GRID = ("points", "spacing")


def continuum_items(case: Case, own: bool = False) -> tuple[str, tuple]:
    """(model, options) of a case's continuum: the reference's (``own``: the case's own model's) with continuum on.
    The reference's model takes the case's options when it is the case's model (its own continuum at the case's
    horizon), else its own options and the case's horizon."""
    ref = {} if own else {k: v for k, v in case.reference.items() if k != "model"}
    model = case.model if own else case.reference["model"]
    if model == case.model:
        opts = {**case.given, **ref}
    else:
        opts = {**{k: case.given[k] for k in ("horizon", "horizon_length") if k in case.given}, **ref}
    opts = {k: v for k, v in opts.items() if k not in GRID}
    opts["continuum"] = True
    return model, tuple(sorted(opts.items()))


@lru_cache(maxsize=64)
def _continuum(scene_text: str, scene_file: str, slenderness, model: str, items: tuple, quantity: str, x_bytes: bytes):
    """(values of ``quantity`` at the points x, the continuum's error estimate, why the model has no limit there or
    ""): the continuum solved on the grid of len(x) points, which must hold x (the case's own grid)."""
    scene = Case(scene_file, scene_text, slenderness, "", {}, {}).scene()
    x = np.frombuffer(x_bytes, "<f8")
    result = run(scene, model, **dict(items), points=len(x))
    if len(result.x) != len(x) or np.abs(np.asarray(result.x) - x).max() > 1e-9 * scene.length:
        raise InputError(f"continuum of {model}: its grid of {len(x)} points is not the case's")
    got = quantity_of(result.w, result.rotation, result.fields, quantity)
    if got is None:
        raise InputError(f"continuum of {model} gives no {quantity}")
    values = np.array(got, float)
    values.flags.writeable = False
    return values, result.info.get("error_bound"), result.info.get("no_limit", "")


def continuum_at(case: Case, scene, x: np.ndarray, quantity: str | None = None, own: bool = False):
    """(values, error estimate, why there is no limit or "") of the case's continuum reference (``own``: its own
    model's continuum) of what its model measures (or ``quantity``) at the points x."""
    model, items = continuum_items(case, own)
    quantity = quantity or get_model(case.model).measures
    x = np.ascontiguousarray(x, "<f8")
    return _continuum(case.scene_text, case.scene_file, case.slenderness, model, items, quantity, x.tobytes())


def splits(case: Case) -> bool:
    """Whether a case's row carries the split: a PD model with its horizon as a length against a local reference."""
    ref = case.reference
    if ref.get("model") == "none" or ref.get("continuum") or case.given.get("horizon_length") is None:
        return False
    return get_model(case.model).option("horizon") is not None


def split_errors(case: Case, scene, solved: dict, w_ref: np.ndarray, row: dict) -> None:
    """Fill ``err_model``, ``err_disc`` (and their ``_l2``) and ``continuum_error`` of a case that :func:`splits`
    (NaN and ``continuum_message`` when its continuum fails)."""
    if not splits(case):
        return
    row.update(err_model=np.nan, err_disc=np.nan, err_model_l2=np.nan, err_disc_l2=np.nan, continuum_error=np.nan)
    x = np.asarray(solved["x"], float)
    quantity = row["quantity"]
    w = np.asarray(quantity_of(solved["w"], solved.get("rotation"), solved["fields"], quantity), float)
    try:
        model = get_model(case.model)
        params = model.resolve(
            scene, {k: v for k, v in model_options(case.given).items() if k not in ("continuum", "continuum_m")}
        )
        points, at = coarsest_nested(model, scene, params, x)
        cont, bound, no_limit = continuum_at(case, scene, x[at], own=True)
    except PdverifyError as exc:
        row["continuum_message"] = " ".join(exc.lines)
        return
    d, m = errors(w[at], cont), errors(cont, np.asarray(w_ref, float)[at])
    row.update(
        err_model=m["err_max"],
        err_disc=d["err_max"],
        err_model_l2=m["err_l2"],
        err_disc_l2=d["err_l2"],
        continuum_error=np.nan if bound is None else float(bound),
        split_points=points,
        continuum_no_limit=no_limit,
    )
