"""Assertions for a PD code's own test suite: what pdverify measures, as pytest-friendly checks.

```python
from pdverify.testing import assert_converges, assert_matches

def test_my_model_is_second_order():
    assert_converges("my-model", "scenes/cantilever.toml", order=2, grids=(21, 41, 81, 161))

def test_my_model_matches_fem():
    assert_matches("my-model", "fem-eb", "scenes/cantilever.toml", rtol=1e-3, points=201)
```

A failing assertion raises AssertionError whose message is the table of grids, errors and orders (or of the
worst points), so the CI log says what went wrong. What is compared is what the model ``measures`` (w; a
rod's u, a torsion bar's twist). ``model`` and ``reference`` are a registered model's
name (built-in, plug-in, or an external model's manifest path) or a :class:`~pdverify.registry.Model`;
``scene`` a :class:`~pdverify.core.scene.Scene`, a scene table (dict) or a scene file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .core.contract import Model
from .core.scene import Scene
from .core.scene_file import load_scene, parse_scene
from .measure.metrics import errors, observed_order
from .registry import get_model, model_argument, run
from .verify.suite import exact_reference, finer

__all__ = ["assert_converges", "assert_matches", "convergence_table"]


def _model(m) -> Model:
    if isinstance(m, Model):
        return m

    return get_model(model_argument(str(m)))


def _scene(s) -> Scene:
    if isinstance(s, Scene):
        return s
    if isinstance(s, dict):
        return parse_scene(s)
    return load_scene(Path(s))


def default_reference(model: Model, scene: Scene, grids=(21, 41, 81, 161), **options):
    """The exact solution of the model's declared theory with the options that match the model's
    (:func:`pdverify.verify.suite.exact_reference`; curved axes: exact-curved); for a theory pdverify has no exact
    solution of (continuum), or equations that converge to something else, the model itself with ``options`` on the
    nested grid ``pdverify verify`` uses (4x the finest grid's spacings): self-convergence."""
    if not scene.is_straight:
        return get_model("exact-curved")
    ref = exact_reference(model, options)
    if ref is None:
        fine = run(scene, model, **options, points=finer(grids))
        return lambda x: np.interp(x, fine.x, fine.measured(model.measures))
    if isinstance(ref, str):
        return get_model(ref)
    exact = get_model(ref["model"])
    fields = exact.evaluator(scene, exact.resolve(scene, {k: v for k, v in ref.items() if k != "model"}))
    return lambda x: fields(np.asarray(x, float))[model.measures]


def _reference_w(reference, scene: Scene, x: np.ndarray, options: dict, quantity: str = "w") -> np.ndarray:
    """The reference's ``quantity`` (w, u, twist) at ``x``: its evaluate(), else its solution on its own points
    interpolated."""
    if callable(reference) and not isinstance(reference, Model):
        return np.asarray(reference(x), float)
    fn = reference.evaluator(scene, reference.resolve(scene, options))
    if fn is not None:
        return np.asarray(fn(x)[quantity], float)
    r = run(scene, reference, **options)
    return np.interp(x, r.x, r.measured(quantity))


def convergence_table(model, scene, grids=(21, 41, 81, 161), reference=None, **options) -> list[dict]:
    """Rows (points, spacing, error, order vs the previous grid): error = max |w - w_ref| / max |w_ref| (w: what the
    model measures)."""
    m, sc = _model(model), _scene(scene)
    ref = (
        default_reference(m, sc, grids, **options)
        if reference is None
        else reference
        if callable(reference)
        else _model(reference)
    )
    rows = []
    for n in grids:
        r = run(sc, m, **options, points=n)
        e = errors(r.measured(m.measures), _reference_w(ref, sc, np.asarray(r.x), {}, m.measures))["err_max"]
        h = float(np.diff(r.x).max())
        prev = rows[-1] if rows else None
        order = (
            (np.log(prev["error"] / e) / np.log(prev["spacing"] / h))
            if prev and e > 0 and prev["error"] > 0
            else np.nan
        )
        rows.append({"points": n, "spacing": h, "error": e, "order": float(order)})
    return rows


def format_table(rows: list[dict]) -> str:
    lines = [f"{'points':>8} {'spacing':>10} {'error':>10} {'order':>7}"]
    for r in rows:
        order = "-" if np.isnan(r["order"]) else f"{r['order']:.2f}"
        lines.append(f"{r['points']:>8d} {r['spacing']:>10.3e} {r['error']:>10.3e} {order:>7}")
    return "\n".join(lines)


def assert_converges(
    model, scene, order: float = 2.0, grids=(21, 41, 81, 161), tol: float = 0.1, reference=None, **options
) -> list[dict]:
    """Assert that the order fitted over ``grids`` (least squares, pdverify.measure.metrics.observed_order) is
    ``order`` within ``tol``. ``reference``: a model (name or Model), a function x -> w, or None for the
    exact solution of the model's theory (the model itself on a 4x finer grid when its theory has none here,
    as ``pdverify verify`` does). Returns the table."""
    m, sc = _model(model), _scene(scene)
    rows = convergence_table(m, sc, grids, reference, **options)
    fitted = observed_order([r["spacing"] for r in rows], [r["error"] for r in rows])[0]
    if not abs(fitted - order) <= tol:
        ref = (
            ("the exact solution" if exact_reference(m, options) or not sc.is_straight else "itself on a finer grid")
            if reference is None
            else getattr(reference, "name", getattr(reference, "__name__", reference))
        )
        raise AssertionError(
            f"{m.name} on {sc.name!r} against {ref}: fitted order {fitted:.2f}, expected {order:g} "
            f"± {tol:g}\n{format_table(rows)}"
        )
    return rows


def assert_matches(model, reference, scene, rtol: float = 1e-3, **options) -> float:
    """Assert max |w - w_ref| / max |w_ref| <= ``rtol`` at the model's points (``options``: the model's). The
    message lists the worst points. Returns the error."""
    m, sc = _model(model), _scene(scene)
    ref = reference if callable(reference) and not isinstance(reference, (str, Model)) else _model(reference)
    r = run(sc, m, **options)
    x = np.asarray(r.x)
    q = m.measures
    w, w_ref = r.measured(q), _reference_w(ref, sc, x, {}, q)
    e = errors(w, w_ref)["err_max"]
    if not e <= rtol:
        scale = max(np.abs(w_ref).max(), 1e-300)
        rel = np.abs(w - w_ref) / scale
        worst = np.sort(np.argsort(rel)[-8:])
        lines = [f"{'x':>10} {q:>12} {q + '_ref':>12} {f'|diff|/max|{q}_ref|':>18}"]
        lines += [f"{x[i]:>10.4g} {w[i]:>12.5e} {w_ref[i]:>12.5e} {rel[i]:>18.3e}" for i in worst]
        name = getattr(ref, "name", getattr(ref, "__name__", "the reference"))
        raise AssertionError(
            f"{m.name} on {sc.name!r} against {name}: error {e:.3e} > rtol {rtol:g} "
            f"({len(x)} points)\n" + "\n".join(lines)
        )
    return e
