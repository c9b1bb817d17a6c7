"""A case's reference: the reference model's value of what the case measures at the case's points, built once per
(scene, slenderness, reference options, quantity) and kept per grid, and the round-off bound of the reference's own
solve."""

from __future__ import annotations

import json
from functools import lru_cache

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.result import quantity_of
from ..registry import get_model
from ..theory.curved_beam import thick_ring_warning
from ..theory.deep_beam import deep_beam_warning
from . import solves
from .spec import Case


def measured(values: dict, quantity: str, model: str) -> np.ndarray:
    """The output ``quantity`` (a model's ``measures``: w, or a point field such as u or twist) of ``values``
    (a solve's {"w": ..., "fields": {...}} or an evaluator's fields); InputError naming the model when it has none."""
    if "fields" in values:  # a solve's {"w", "rotation", "fields"}
        got = quantity_of(values["w"], values.get("rotation"), values["fields"], quantity)
    else:  # an evaluator's fields
        got = quantity_of(values.get("w"), values.get("rotation"), values, quantity)
    if got is None:
        raise InputError(f"model {model} gives no {quantity}: the study measures {quantity} (the model's `measures`)")
    return np.asarray(got, float)


@lru_cache(maxsize=256)  # a card: ~110 scenes, the curved ones with 5 quantities
def _reference_fn(scene_text: str, scene_file: str, slenderness, ref_items: tuple, quantity: str = "w"):
    """(x -> the reference's ``quantity``, its solve's round-off bound), built once per (scene, slenderness,
    reference options, quantity): the reference model's ``evaluator`` where it has one (exact models: exact at any
    x; no bound), else its own solution interpolated by a cubic spline, with the bound of that solve (None when it
    made none). ``quantity``: what the case's model measures (``Model.measures``: w, u, twist)."""
    from scipy.interpolate import CubicSpline

    ref = dict(ref_items)
    model = get_model(ref.pop("model"))
    scene = Case(scene_file, scene_text, slenderness, "", {}, {}).scene()
    ev = model.evaluator(scene, model.resolve(scene, ref))
    if ev is not None:  # exact (no bound), or a solve's interpolant that carries its bound (fem-eb)
        return lambda x: measured(ev(x), quantity, model.name), getattr(ev, "error_bound", None)
    solved = solves.solve(scene_text, scene_file, slenderness, model.name, ref)
    values = {"w": solved.w, "rotation": solved.rotation, "fields": solved.fields}
    return CubicSpline(solved.x, measured(values, quantity, model.name)), solved.info.get("error_bound")


REFERENCE_CACHE_POINTS = 20_000  # grids up to this size keep their reference values (64 grids: <= 10 MB)


@lru_cache(maxsize=64)
def _reference_values(
    scene_text: str, scene_file: str, slenderness, ref_items: tuple, quantity: str, x_bytes: bytes
) -> np.ndarray:
    """The reference at one grid, kept: a sweep over horizon, variant or form solves many cases on the
    same points, and the exact solutions cost as much as the rest of a small case's bookkeeping
    (0.18 ms at 1,200 points). Read-only, so a caller cannot change the cached values."""
    fn = _reference_fn(scene_text, scene_file, slenderness, ref_items, quantity)[0]
    w = np.array(fn(np.frombuffer(x_bytes, "<f8")), float)
    w.flags.writeable = False
    return w


def _key(case: Case, quantity: str | None = None) -> tuple:
    """(scene text, scene file, slenderness, reference options, quantity): what a case's reference depends on;
    the quantity by default the one the case's model is measured on (``Model.measures``)."""
    quantity = quantity or get_model(case.model).measures
    return (case.scene_text, case.scene_file, case.slenderness, tuple(sorted(case.reference.items())), quantity)


def reference_at(case: Case, scene, x: np.ndarray, quantity: str | None = None) -> np.ndarray:
    """The reference's value of what the case's model measures (its deflection, or e.g. pd-rod's u), or of
    ``quantity``, at the model's points (see :func:`_reference_fn`); the values of grids of up to
    ``REFERENCE_CACHE_POINTS`` points are kept per (scene, slenderness, reference, quantity, grid)."""
    key = _key(case, quantity)
    x = np.asarray(x, "<f8")
    if x.size <= REFERENCE_CACHE_POINTS:
        return _reference_values(*key, x.tobytes())
    return np.asarray(_reference_fn(*key)[0](x), float)


def reference_bound(case: Case) -> float | None:
    """The round-off bound of the case's reference solve (None for exact references and models without one)."""
    return _reference_fn(*_key(case))[1]


@lru_cache(maxsize=256)
def _reference_text(items: tuple) -> str:
    """The reference's options as the results table stores them (one per study, not one per case)."""
    return json.dumps(dict(items), sort_keys=True)


EXACT_OF = {"euler-bernoulli": "exact-eb", "timoshenko": "exact-timoshenko", "higher-order": "exact-higher-order"}
GAP_SHARE = 0.1  # a theories' difference above this share of a row's error may be what the row measures


def theory_gap_warning(case: Case, x: np.ndarray | None = None, err: float = float("nan")) -> str | None:
    """What of the row's error (``err`` at the model's points ``x``) may be the difference of the model's theory and
    its reference's, not the model's own: when the model is the 2D continuum and the reference a beam theory, the
    thick-ring warning of a curved axis (:func:`pdverify.theory.curved_beam.thick_ring_warning`) and the deep-beam one
    of a short beam (:func:`pdverify.theory.deep_beam.deep_beam_warning`); and on a straight
    static scene, a beam model (Euler-Bernoulli, Timoshenko, higher-order) against a reference of another theory,
    when the exact solution of the model's own theory differs from the reference by more than GAP_SHARE of the
    row's error (pd-eb against exact-timoshenko on a thick beam)."""
    ref = case.reference.get("model")
    if ref in (None, "none"):
        return None
    model, reference = get_model(case.model), get_model(ref)
    if model.theory == "continuum" and reference.theory != "continuum":
        scene = case.scene()
        found = [w for w in (thick_ring_warning(scene), deep_beam_warning(scene)) if w]
        return "; ".join(f"the reference {ref}: {w}" for w in found) or None
    own = EXACT_OF.get(model.theory)
    if x is None or own is None or reference.theory == model.theory or model.measures != "w" or not np.isfinite(err):
        return None
    scene = case.scene()  # read only for a row of two theories: a case's scene is parsed from its text
    if not scene.is_straight or scene.dynamics is not None:
        return None
    try:
        exact = get_model(own)
        w = np.asarray(exact.evaluate(scene, exact.resolve(scene, {}), np.asarray(x, float))["w"], float)
    except (InputError, SolveError):  # a scene the model's own theory has no exact solution of here
        return None
    theirs = np.asarray(reference_at(case, scene, x), float)
    top = float(np.abs(theirs).max())
    gap = float(np.abs(w - theirs).max()) / top if top > 0 else 0.0
    if not gap > GAP_SHARE * err:
        return None
    return (
        f"the reference {ref} is of another theory ({reference.theory}) than the model ({model.theory}): on this "
        f"scene {own} differs from it by {gap:.2g} of max |w|, against the row's error {err:.2g}, so the error may "
        "be the theories' difference rather than the model's"
    )
