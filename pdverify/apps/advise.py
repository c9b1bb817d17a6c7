"""``pdverify advise``: the cheapest model and grid that is accurate enough for one scene.

1. What the scene needs. Curved axis -> models with ``curved``; shear: the exact Euler–Bernoulli and
   Timoshenko solutions of the scene are compared; when the shear deflection is below half the tolerance,
   Euler–Bernoulli models qualify, else only models whose ``theory`` includes shear. 2D effects: when
   h / span (a clamp or a point load: their layers) or (h / span)^2 (none) exceeds half the tolerance, span the
   shortest between the ends and the supports inside (:func:`pdverify.theory.deep_beam.span_slenderness`), a q8
   plane-stress solve is compared with exact Timoshenko; if they
   differ by more than half the tolerance only the continuum model qualifies. Dynamics: the estimate is
   of static solutions, so a scene with a ``[dynamics]`` table is refused unless the static part is asked
   for (``static = True``, CLI ``--static``): then only models that can solve that part qualify (the
   declared capabilities, :func:`pdverify.registry.problems`).
2. The grid, per candidate: the packaged priors (:mod:`.priors`, ``pdverify/data/advisor_priors.json``: per
   model and options, the error constant C and order p of clean convergence series, err = C (dx / L)^p, with
   the code digest they were made from; ``pdverify advise --rebuild-priors`` regenerates them) predict the
   points needed; the ladder of nested grids N, 2N-1, 4N-3 starts two refinements below that prediction
   and stops when the a-posteriori estimate on this very scene (:func:`pdverify.measure.richardson.richardson`,
   as ``solve --estimate``: observed order p from three grids, |w_2 - w_3| / (2^p - 1) relative to max |w|) is
   below a third of the tolerance (:data:`SPREAD`: an estimate is within a factor 3 of the true error, docs/cli.md)
   with p near the model's promised order and the coarsest of the three grids resolving the
   scene's features (:func:`pdverify.measure.richardson.feature_gap`); an estimate that fails either is refined further
   within the budget and, if kept, says it is not asymptotic.
3. The cheapest candidate whose estimate is below a third of the tolerance wins (cost = its measured solve time);
   the runner-up is the next cheapest. On straight scenes whose exact solution applies (no end motions)
   the exact error is printed as a check.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..core.errors import InputError, SolveError
from ..core.scene import Scene, bends
from ..exact.straight import solve_straight
from ..measure.richardson import richardson
from ..registry import get_model, models, problems, run
from ..theory.deep_beam import span_slenderness
from ..verify.suite import reference_for
from .priors import (  # noqa: F401 (PRIORS, load_priors, fit_series, rebuild_priors: re-exported)
    CANDIDATE_OPTIONS,
    PRIORS,
    fit_series,
    load_priors,
    predicted_points,
    prior_order,
    rebuild_priors,
)


@dataclass
class Candidate:
    model: str
    options: dict
    points: int
    estimate: float
    order: float
    seconds: float
    exact_error: float | None = None
    basis: str = ""


@dataclass
class Advice:
    scene: str
    tolerance: float
    needs: list[str]
    choice: Candidate | None
    runner_up: Candidate | None
    rejected: list[str] = field(default_factory=list)
    static: bool = False  # the static part of a [dynamics] scene (solve it with -o static=true)


def shear_gap(scene: Scene) -> float:
    x = np.linspace(0, scene.length, 201)
    eb = solve_straight(scene, False).fields(x)["w"]
    ti = solve_straight(scene, True).fields(x)["w"]
    scale = np.abs(ti).max()
    return float(np.abs(ti - eb).max() / scale) if scale > 0 else 0.0


def moves_ends(scene: Scene) -> bool:
    """True when the scene's [dynamics] table prescribes an end motion (the exact solutions leave it out)."""
    d = scene.dynamics
    return d is not None and any(
        getattr(em, k) is not None
        for em in (d.left, d.right)
        if em is not None
        for k in ("displacement", "axial", "rotation", "twist")
    )


SPREAD = 3  # an estimate counts as meeting tol when it is below tol / SPREAD: asymptotic and resolved estimates are
# within a factor 3 of the true error in 106 of 107 measured cases (docs/cli.md, benchmarks/estimate_sweep.py)


def steady_below(order: float, before: float, promised: float, found) -> bool:
    """An observed order below the promised one that the last two ladders of three grids agree on within 0.1 (a point
    load's first order on pd-rod): its estimate is then the error's (an order that later rises makes it an
    overestimate), so a ladder may stop there. ``found``: the last estimate (its grids resolve the scene)."""
    return bool(found.resolved and order < promised - 0.1 and abs(order - before) < 0.1)


def estimate(
    scene: Scene,
    name: str,
    options: dict,
    tol: float,
    budget: float,
    start: int = 11,
    max_points: int = 20_001,
    static: bool = False,
) -> Candidate:
    """Refine nested grids until the Richardson estimate is below tol / :data:`SPREAD` (asymptotic, or at a steady
    order below the promised one: :func:`steady_below`); SolveError naming the last estimate when the budget or the
    grid limit runs out first. ``static``: the static part of a scene with a [dynamics] table (``run(...,
    static=True)``)."""
    if static:
        options = dict(options, static=True)
    if name == "fem-plane-stress":
        max_points = min(max_points, 401)
    model = models()[name]
    sols, n, spent = [], start, 0.0
    est, order, found, before = np.inf, float("nan"), None, float("nan")
    while n <= max_points:
        t0 = time.perf_counter()
        try:
            r = run(scene, name, points=n, **options)
        except InputError as exc:  # below the model's fewest points (e.g. pd-timoshenko energy: 6m + 2): refine
            if sols or not exc.lines[0].startswith(f"points = {n}:"):
                raise
            n = 2 * n - 1
            continue
        dt = time.perf_counter() - t0
        spent += dt
        sols.append((n, r, dt))
        if len(sols) >= 3:  # the three finest grids: pdverify.measure.richardson, the estimate solve --estimate gives
            promised = model.promised_order(model.with_defaults(options))
            found = richardson([r for _, r, _ in sols[-3:]], 2, model.measures, promised, scene)
            est, order, before = found.error, found.order, order
            if found.error * SPREAD < tol and (found.asymptotic or steady_below(order, before, promised, found)):
                break
        if spent > budget:
            break
        n = 2 * n - 1
    if found is None or not np.isfinite(est) or est * SPREAD >= tol or not found.resolved:
        limit = f"its grid limit, {max_points} points" if n > max_points else f"the budget, {budget:g} s"
        last = "no estimate" if found is None else f"estimate {est:.2g} on N = {found.grids}"
        why = "" if found is None or found.asymptotic else f", not asymptotic: {found.why}"
        raise SolveError(f"did not reach {tol:g} / {SPREAD:g} before {limit} ({last}{why})")
    n_best, r_best, dt_best = sols[-1]
    ex = None
    options = {k: v for k, v in options.items() if k != "static"}
    prior = prior_order(name, options)
    theory = models()[name].theory
    if scene.is_straight and theory in ("euler-bernoulli", "timoshenko") and not moves_ends(scene):
        exw = solve_straight(scene, theory != "euler-bernoulli").fields(r_best.x)["w"]
        scale = np.abs(exw).max()
        ex = float(np.abs(r_best.w - exw).max() / scale) if scale > 0 else None
    elif scene.is_straight and theory in ("axial", "torsion") and not moves_ends(scene):  # exact-rod, exact-torsion
        q = models()[name].measures
        exf = get_model(reference_for(theory)).evaluator(scene, {})(r_best.x)[q]
        scale = np.abs(exf).max()
        ex = float(np.abs(r_best.measured(q) - exf).max() / scale) if scale > 0 else None
    return Candidate(
        name,
        options,
        n_best,
        float(est),
        order,
        dt_best,
        ex,
        f"three-grid Richardson on this scene (N = {sols[-3][0]}, {sols[-2][0]}, {n_best}; p = {order:.2f}"
        + (
            f"; observed order {order:.2f} on the last two ladders, below the model's {promised:g}: the estimate "
            "holds (a higher order later would make it an overestimate)"
            if not found.asymptotic and steady_below(order, before, promised, found)
            else (f"; {'' if found.asymptotic else 'not asymptotic: '}{found.why}" if found.why else "")
        )
        + f"); {prior}",
    )


def continuum_gap(scene: Scene) -> float:
    """Relative difference, at the largest deflection, between exact Timoshenko and a q8 plane-stress solve."""
    r = run(scene, "fem-plane-stress", element="q8", points=161, layers=8)
    ex = solve_straight(scene, True).fields(r.x)["w"]
    i = int(np.argmax(np.abs(ex)))
    return float(abs(r.w[i] / ex[i] - 1)) if ex[i] else 0.0


def advise(
    scene: Scene, tolerance: float, budget: float = 30.0, include_reference: bool = False, static: bool = False
) -> Advice:
    """The cheapest model and grid whose a-posteriori error estimate on ``scene`` is below ``tolerance`` (steps
    1-3 of the module's docstring), and the runner-up. ``static``: advise on the static part of a scene with a
    [dynamics] table (without it such a scene is refused: the estimates are of static solutions)."""
    _check_request(scene, tolerance, static)
    cands, unable = _capable(scene, static, include_reference)
    needs, rejected, cands = _needs(scene, tolerance, cands)
    found, failed = _estimates(scene, cands, tolerance, budget, static)
    rejected += failed + unable
    if not found:
        raise SolveError(
            f"tolerance = {tolerance:g}: no installed model reaches it on this scene within {budget:g} s each; "
            + "; ".join(grouped(rejected))
        )
    return Advice(
        scene.name,
        tolerance,
        needs,
        found[0],
        found[1] if len(found) > 1 else None,
        rejected,
        static and scene.dynamics is not None,
    )


def _check_request(scene: Scene, tolerance: float, static: bool) -> None:
    """Refuse (InputError) a tolerance outside (0, 1), a transient scene unless its static part is asked for,
    and a scene with nothing to respond to."""
    if not 0 < tolerance < 1:
        raise InputError(f"tolerance = {tolerance!r}: give a relative tolerance between 0 and 1, e.g. 1e-3")
    if scene.dynamics is not None and not static:
        dyn = ", ".join(n for n, m in models().items() if "dynamic" in m.analyses)
        raise InputError(
            "dynamics: the scene asks for a transient run and advise estimates the error of static "
            f"solutions only; give --static to advise on its static part, or run a dynamic model ({dyn})"
        )
    if not scene.loads and not moves_ends(scene):
        raise InputError("loads: the scene carries no load (its static response is zero); nothing to advise on")
    carried = [ld for ld in scene.loads if any(getattr(ld, k, None) for k in ("value", "axial", "torque"))]
    if not carried and not moves_ends(scene):
        raise InputError("loads: every load is zero (the static response is zero); nothing to advise on")


def _capable(scene: Scene, static: bool, include_reference: bool) -> tuple[list, list[str]]:
    """The static models whose declared capabilities (supports, loads, axes, dynamics) cover the scene, and one
    line for each that cannot solve it (references only with ``include_reference``)."""
    cands, unable = [], []
    for m in models().values():
        if "static" not in m.analyses or (m.reference and not include_reference):
            continue
        why = problems(scene, m, static)  # the declared capabilities (supports, loads, axes, dynamics)
        if why:
            unable.append(f"{m.name}: {why[0]}")
        else:
            cands.append(m)
    return cands, unable


def _needs(scene: Scene, tolerance: float, cands: list) -> tuple[list[str], list[str], list]:
    """What the scene needs of a model (step 1 of the module's docstring), the candidates rejected for it and
    those left."""
    rejected = []
    if not bends(scene):  # axial loads or torques only: a beam model's deflection would be zero, and exact
        needs = ["no bending (axial loads or torques only): rod and torsion models; no shear or 2D check"]
        for m in cands:
            if m.bending:
                rejected.append(f"{m.name}: the scene does not bend the beam, and {m.name} is judged on its deflection")
        cands = [m for m in cands if not m.bending]
    elif not scene.is_straight:
        needs = ["curved axis: models that solve curved beams"]
    elif moves_ends(scene):  # the exact beam solutions leave prescribed end motions out
        needs = ["prescribed end motions: the exact beam solutions leave them out, so no shear or 2D check"]
    else:
        shear, rejected, cands = _shear_need(scene, tolerance, cands)
        continuum, more, cands = _continuum_need(scene, tolerance, cands)
        needs, rejected = [shear, *continuum], rejected + more
    if scene.dynamics is not None:
        needs.append(
            "static part (--static): the response to the loads and settled end motions; the transient "
            "run is not estimated"
        )
    else:
        needs.append("static: the scene has no [dynamics] table")
    return needs, rejected, cands


def _shear_need(scene: Scene, tolerance: float, cands: list) -> tuple[str, list[str], list]:
    """Whether Euler–Bernoulli theory is enough: the exact shear deflection against half the tolerance; the
    need, the Euler–Bernoulli candidates rejected when it is not, and the candidates left."""
    gap = shear_gap(scene)
    if gap <= tolerance / 2:
        need = (
            f"Euler–Bernoulli is enough: the shear deflection is {gap:.2e} of the deflection (tolerance {tolerance:g})"
        )
        return need, [], cands
    rejected = [
        f"{m.name}: Euler–Bernoulli theory misses the shear deflection ({gap:.1e})"
        for m in cands
        if m.theory == "euler-bernoulli"
    ]
    need = f"shear matters: Timoshenko and EB differ by {gap:.2e} > tolerance/2; EB models excluded"
    return need, rejected, [m for m in cands if m.theory != "euler-bernoulli"]


def _continuum_need(scene: Scene, tolerance: float, cands: list) -> tuple[list[str], list[str], list]:
    """Whether beam theory is enough: h / span or (h / span)^2 (module docstring) against half the tolerance, else
    exact Timoshenko against a q8 plane-stress solve; the needs (none when fem-plane-stress cannot tell), the
    candidates rejected when only the continuum model qualifies, and the candidates left."""
    ratio, what = span_slenderness(scene)  # the shortest span's: a short span is a short beam
    layer = any(scene.supports.kind(side) == "clamped" for side in ("left", "right")) or any(
        s.type == "clamped" for s in scene.supports.inner
    )
    layer = layer or any(ld.type in ("point_force", "point_moment") for ld in scene.loads)
    power = 1 if layer else 2  # a clamp's or a point load's layer: first order in h / span (theory/deep_beam.py)
    twod = (1.0 / ratio) ** power  # order of the 2D corrections to beam theory
    if twod <= tolerance / 2:
        order = f"(h/{what[:-2]})" + ("" if power == 1 else "^2")
        return [f"beam theory is enough: 2D corrections are of order {order} = {twod:.1e} <= tolerance/2"], [], cands
    if "fem-plane-stress" not in models() or models()["fem-plane-stress"].check(scene):
        return [], [], cands
    gap2 = continuum_gap(scene)
    if gap2 <= tolerance / 2:
        return [f"beam theory is enough: Timoshenko and q8 plane stress differ by {gap2:.2e}"], [], cands
    need = (
        f"2D effects matter: Timoshenko and a q8 plane-stress solution differ by {gap2:.2e} > "
        "tolerance/2; only the continuum model qualifies"
    )
    rejected = [f"{m.name}: beam theory misses 2D effects ({gap2:.1e})" for m in cands]
    return [need], rejected, [models()["fem-plane-stress"]]


def _estimates(
    scene: Scene, cands: list, tolerance: float, budget: float, static: bool
) -> tuple[list[Candidate], list[str]]:
    """Each candidate with a grid option on its ladder of nested grids (step 2 of the module's docstring), the
    cheapest first, and one line for each that does not reach the tolerance or fails."""
    found, rejected = [], []
    for m in cands:
        if m.option("points") is None:
            continue
        opts = CANDIDATE_OPTIONS.get(m.name, {})
        n_pred, why = predicted_points(m.name, opts, tolerance / SPREAD)
        # start the ladder two refinements below the prediction, so the three grids end near it
        start = 11 if n_pred is None else max(11, min(5001, (n_pred - 1) // 4 + 1))
        try:
            c = estimate(scene, m.name, opts, tolerance, budget, start=start, static=static)
        except (InputError, SolveError) as exc:
            rejected.append(f"{m.name}: {exc.lines[0]}")
            continue
        c.basis += f"; start N = {start} ({why})"
        found.append(c)
    found.sort(key=lambda c: c.seconds)
    return found, rejected


def grouped(rejected: list[str]) -> list[str]:
    """Lines ``"model: reason"`` with one reason joined into one line naming every model it rejects, in order."""
    reasons: dict[str, list[str]] = {}
    for line in rejected:
        name, _, why = line.partition(": ")
        reasons.setdefault(why, []).append(name)
    return [f"{', '.join(names)}: {why}" for why, names in reasons.items()]


def format_advice(a: Advice) -> str:
    lines = [f"scene: {a.scene}   tolerance: {a.tolerance:g}"]
    lines += [f"  needs: {n}" for n in a.needs]
    for label, c in (("choice", a.choice), ("runner-up", a.runner_up)):
        if c is None:
            continue
        opts = [f"--{k} {v}" for k, v in c.options.items()] + (["-o static=true"] if a.static else [])
        lines.append(" ".join([f"{label}: {c.model} --points {c.points}", *opts]))
        of = get_model(c.model).measures  # the error is of what the model is measured on: w, u or the twist
        lines.append(f"  estimated error of {of} {c.estimate:.2e} ({c.basis})")
        if c.exact_error is not None:
            lines.append(f"  check against the exact solution ({of}): {c.exact_error:.2e}")
        lines.append(f"  expected cost {c.seconds:.3g} s")
    lines += [f"  not chosen: {r}" for r in a.rejected]
    return "\n".join(lines)
