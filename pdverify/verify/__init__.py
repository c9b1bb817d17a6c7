"""``pdverify verify MODEL``: a fixed, versioned verification suite and its report card.

The suite (:mod:`.suite`) is written as a study and run by :func:`pdverify.study.run_study` (a process
pool, or Dask with ``scheduler``; resumable). The checks (:mod:`.checks`) judge its results; symmetry and
superposition solve a handful of scenes here. The card (:mod:`.card`) is JSON, HTML and JUnit XML.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from pathlib import Path

from ..core.errors import InputError
from ..core.scene_file import parse_scene
from ..core.text import PAST_RANGE
from ..core.version import __version__
from ..registry import RUN_FLAGS, as_flag, get_model, model_options, run
from ..study import forked, load_study, run_study
from ..study.checks import strict_type
from ..study.runner import whole_workers
from . import checks as C
from .card import write_card
from .dynamics import dynamics_check
from .fixed_horizon import nonlocal_check
from .suite import (
    CURVED_QUANTITIES,
    GAP_REFERENCE,
    MAX_ORDER,
    SUITE_VERSION,
    end_force,
    engineering_reference,
    finer,
    loads_for,
    mirror,
    plan,
    reference_name,
    rod_kind,
    straight,
    write_study,
)

__all__ = ["verify", "SUITE_VERSION", "entry_errors"]

ENGINEERING = "convergence (continuous, overhanging, spring, stepped, bi-material)"
MIRROR_PAIRS = (("clamped", "pinned"), ("clamped", "free"), ("clamped", "guided"), ("pinned", "guided"))
# the mirror scene's solution at L - x is this times the scene's at x (an axial force and u reverse)
MIRROR_SIGN = {None: 1.0, "axial": -1.0, "torsion": 1.0}


def asymmetric(kind: str | None) -> dict:
    """Loads without mirror symmetry: the suite's point load moved to L/4 and its partial load on [L/4, L/2]
    (and the point moment at L/4, for a beam)."""
    loads = loads_for(kind)
    point, partial = next(iter(loads)), "partial"
    out = {
        point: [{**loads[point][0], "position": 0.25}],
        partial: [{**loads[partial][0], "start": 0.25, "end": 0.5}],
    }
    return out if kind is not None else {**out, "point moment": loads["point moment"]}


def _solve(scene: dict, model, options: dict, points: int):
    return run(parse_scene(scene), model, **options, points=points)


def _declines(model, scene: dict, options: dict) -> bool:
    return bool(model.declines(parse_scene(scene), options))


def symmetry(model, options: dict, points: int) -> list[tuple[str, float]]:
    out, kind = [], rod_kind(model)
    for left, right in MIRROR_PAIRS:
        for load, lds in asymmetric(kind).items():
            sc = straight(left, right, lds, name=f"{left}-{right}, {load}")
            if _declines(model, sc, options) or _declines(model, mirror(sc), options):
                continue
            a, b = _solve(sc, model, options, points), _solve(mirror(sc), model, options, points)
            out.append((sc["name"], C.mirrored(a, b, model.measures, MIRROR_SIGN[kind])))
    return out


def sharing_positions(loads: list[dict], every: list[dict]) -> list[dict]:
    """``loads`` and a zero-valued copy of each point load of ``every``: the three scenes of the superposition
    check then carry the same point-load positions, so a model that adapts its grid or bonds to them (e.g.
    pd-higher-order's ``cuts = loads``) is judged on one operator, and linearity is what is measured."""
    zero = {"point_force": {"value": 0.0, "axial": 0.0}, "point_moment": {"value": 0.0}, "point_torque": {"value": 0.0}}
    return loads + [{**ld, **zero[ld["type"]]} for ld in every if ld["type"] in zero]


def superposition(model, options: dict, points: int) -> list[tuple[str, float]]:
    out, kind = [], rod_kind(model)
    loads = loads_for(kind)
    for left, right in (("clamped", "clamped"), ("clamped", "free"), ("pinned", "guided")):
        a = loads[next(iter(loads))] + (loads["point moment"] if kind is None else loads["uniform"])
        b = loads["sine"] + (end_force(left, right, kind) or loads["partial"])
        a, b = sharing_positions(a, b), sharing_positions(b, a)
        if any(_declines(model, straight(left, right, lds), options) for lds in (a, b, a + b)):
            continue
        ra, rb, rab = (_solve(straight(left, right, lds), model, options, points) for lds in (a, b, a + b))
        what = "force + moment" if kind is None else "point + uniform"
        out.append(
            (f"{left}-{right}: {what}, sine + end load or partial", C.superposition_diff(ra, rb, rab, model.measures))
        )
    return out


def _declined(model, p, options: dict | None = None) -> dict:
    """Why the model declines each scene of the plan (the floor scene repeats a convergence scene: left out); an
    engineers' scene also when the model with these options refuses it as input (a variant that takes no segments:
    a solve on the coarsest grid, one line); any scene whose supports the variant does not define (``refusals``)."""
    out = {f: model.check(parse_scene(sc)) for f, sc in p.scenes.items() if p.meta[f]["set"] != "floor"}
    for f, why in out.items():
        if why or options is None:
            continue
        scene = parse_scene(p.scenes[f])
        try:
            if p.meta[f]["set"] == "engineering":
                run(scene, model, **options, points=p.grids[0])
            else:
                out[f] = model.refusals(scene, model.resolve(scene, {**model_options(options), "points": p.grids[0]}))
        except InputError as exc:
            out[f] = list(exc.lines)
        except Exception:  # noqa: BLE001 - a failed solve is judged by the suite, not declined here
            pass
    return out


def _solves_none(model, declined: dict) -> str | None:
    """The error line of a model that declines every scene of the plan (None when it solves one)."""
    if not all(declined.values()):
        return None
    return (
        f"model {model.name} solves none of the suite's scenes ({next(iter(declined.values()))[0]}); "
        "verify needs a beam (transverse loads), rod (axial loads) or torsion-bar model (torques)"
    )


def entry_errors(model_name: str, options: dict, full: bool = False) -> list[str]:
    """What stops ``verify(model_name, ..., options)`` before it runs anything: an unknown model or option, a
    value of the wrong type, a grid option (the suite sets the grids), a model that solves none of the
    suite's scenes. One line each (without the caller's prefix)."""

    try:
        model = get_model(model_name)
    except InputError as exc:
        return [exc.lines[0]]
    errors = [f"{k}: the suite sets the grids; drop it" for k in options if k in ("points", "spacing")]
    for k, v in options.items():
        opt = model.option(k)
        if opt is not None and (why := strict_type(opt, v)):
            errors.append(why)
    if errors:
        return errors
    p = plan(model, full, options)
    declined = _declined(model, p)
    if why := _solves_none(model, declined):
        return [why]
    solved = [f for f, why in declined.items() if not why]
    try:
        _resolve_coarsest(model, p, solved[0], options)
    except InputError as exc:
        return list(exc.lines)
    return []


def _resolve_coarsest(model, p, scene_file: str, options: dict) -> None:
    """The options resolved on one of the suite's scenes at its coarsest grid (InputError, one line each, before
    anything is written: a horizon that does not fit the grid is refused here, not by the suite's study)."""
    model.resolve(parse_scene(p.scenes[scene_file]), {**model_options(options), "points": min(p.grids)})


def verify(
    model_name: str,
    out: Path,
    options: dict | None = None,
    full: bool = False,
    order: float | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
) -> dict:
    """Run the suite on ``model_name`` with ``options``, judge it, write the card into ``out``; the card."""

    t0 = time.perf_counter()
    options = dict(options or {})
    model = get_model(model_name)
    out = Path(out)
    workers = whole_workers(workers)  # a bad --workers: one line before the suite is written
    grid = [f"{k}: the suite sets the grids; drop it" for k in options if k in ("points", "spacing")]
    if grid:
        raise InputError(grid)
    p = plan(model, full, options)
    declined = _declined(model, p, options)
    if why := _solves_none(model, declined):
        raise InputError(why)
    solved = next(f for f, why in declined.items() if not why)
    _resolve_coarsest(model, p, solved, options)  # bad options: one line each before anything runs
    typed = model.with_defaults(model_options(options))
    typed.update({k: as_flag(v, k) for k, v in options.items() if k in RUN_FLAGS})
    options = {k: typed[k] for k in options}  # -o degree=4.0: 4, as solve reads it (the suite's study file holds it)
    expected = expected_order(model, options, order)
    run_plan = runnable(p, declined)
    df = _run_suite(run_plan, model, options, out, workers, scheduler, progress)
    found, scenes, df = _judge(model, options, p, df, expected, declined, order)
    card = _card(model, options, p, expected, found, scenes, df, declined) | {"wall_s": time.perf_counter() - t0}
    write_card(card, out)
    return card


def expected_order(model, options: dict, order: float | None = None) -> float:
    """The order a card holds the model to: ``order`` (``--order``) when given, else the order its equations
    promise with these options (:meth:`~pdverify.core.contract.Model.promised_order`: pd-curved's degree sets it).
    InputError unless ``order`` is a positive number up to :data:`~pdverify.verify.suite.MAX_ORDER`."""
    if order is not None and not (math.isfinite(order) and 0 < order <= MAX_ORDER):
        raise InputError(
            f"--order {order:g}{PAST_RANGE if math.isinf(order) else ''}: give the "
            f"expected order of convergence, a positive number up to {MAX_ORDER:.4g} "
            "(e.g. 2; a higher order cannot be observed on the suite's grids within float64's round-off)"
        )
    return float(order) if order is not None else model.promised_order(model.with_defaults(options))


def runnable(p, declined: dict):
    """The plan without the engineers' scenes the model declines (its check or its options' refusal: not run), their
    reference chosen over the scenes it takes (a variant that refuses the segments an exact reference cannot hold is
    judged against that reference on the rest)."""
    refused = {f for f, why in declined.items() if why and p.meta[f]["set"] == "engineering"}
    taken = [sc for f, sc in p.scenes.items() if p.meta[f]["set"] == "engineering" and f not in refused]
    return replace(
        p,
        scenes={f: sc for f, sc in p.scenes.items() if f not in refused},
        engineering_reference=engineering_reference(p.reference, taken),
    )


def _run_suite(p, model, options: dict, out: Path, workers, scheduler, progress: bool):
    """Write the plan as a study into ``out/suite`` and run it into ``out/study`` (a stale folder of another suite
    version dropped first); its results."""
    study_path = write_study(p, model, options, out / "suite")
    drop_other_suite(out / "study", model.name)
    return run_study(  # no VTU, PNG or history files: the card reads the errors
        load_study(study_path), out / "study", workers=workers, scheduler=scheduler, progress=progress, artefacts=False
    )


def _judge(model, options: dict, p, df, expected: float, declined: dict | None = None, order=None) -> tuple:
    """The card's checks in their order, its scenes (the straight and curved convergence series) and the results
    they judge (the theory-gap run, judged on its own, left out)."""
    # the dynamics and nonlocal checks solve models of their own: in a forked copy while this process judges the rest
    side = forked.start(
        lambda: (dynamics_check(model, options, p.grids, expected), nonlocal_check(model, options, p.reference, order))
    )
    sets = ("convergence", "locking", "floor", "curved", "engineering", "curved_locking")
    files = {s: [f for f, m in p.meta.items() if m["set"] == s and not (declined or {}).get(f)] for s in sets}
    files["locking"] = files["locking"] + files["curved_locking"]  # one locking check, straight and curved axes
    # the theory-gap run (self-convergence only): the convergence scenes on the reference grid, finer than any other
    gap = (p.reference is None) & (df["points"] == finer(p.grids)) & df["scene_file"].isin(files["convergence"])
    df, gap_df = df[~gap], df[gap]
    conv = C.series(df, files["convergence"])
    found = _straight_checks(model, p, df, gap_df, conv, files, expected) + _identity_checks(model, options, p)
    engineering = C.series(df, files["engineering"])
    found.append(
        C.convergence(engineering, expected, ENGINEERING)
        if engineering
        else C.check(ENGINEERING, "n/a", "the model takes no supports inside the span, springs or segments")
    )
    curved = C.series(df, files["curved"])
    found.append(
        C.convergence(curved, expected, "convergence (curved axes)")
        if curved
        else C.check("convergence (curved axes)", "n/a", "the model does not declare curved axes")
    )
    found += [_curved_quantity(df, files["curved"], q, expected) for q in CURVED_QUANTITIES] if curved else []
    found.extend(side())
    return found, [{**p.meta[r["scene_file"]], **r} for r in conv + engineering + curved], df


def _curved_quantity(df, files: list[str], quantity: str, expected: float) -> dict:
    """The convergence of one more quantity on the curved scenes (``err_max_<q>``), where the model and the
    reference give it."""
    label = f"convergence (curved axes): {quantity}"
    col = f"err_max_{quantity}"
    given = df[df[col].notna()] if col in df else df.iloc[:0]
    rows = C.series(given, files, col)
    if not rows:
        return C.check(label, "n/a", f"the model or its curved reference gives no {quantity}")
    found = C.convergence(rows, expected, label)
    finest = max((r["errors"][-1] for r in rows if r["errors"]), default=float("nan"))
    grid = max((r["points"][-1] for r in rows if r["points"]), default=0)
    return found | {"summary": f"{found['summary']}; largest error at {grid} points {finest:.2e}", "series": rows}


def _straight_checks(model, p, df, gap_df, conv: list[dict], files: dict, expected: float) -> list[dict]:
    """Convergence, accuracy, agreement, locking, round-off floor and cost of the straight scenes, and the theory
    gap of a self-converged model."""
    return [
        C.convergence(conv, expected, "convergence (straight)"),
        C.accuracy(conv),
        C.within(conv),
        C.locking(df, files["locking"], p.meta)
        if files["locking"]
        else C.check(
            "locking (error vs slenderness 5 ... 10000)",
            "n/a",
            f"the error of {model.theory} models does not depend on the slenderness: no locking scenes",
        ),
        C.floor(C.series(df, files["floor"])),
        C.cost(conv),
        C.theory_gap(gap_df, p.meta, GAP_REFERENCE, finer(p.grids))
        if p.reference is None
        else C.check(
            "theory gap",
            "n/a",
            f"errors are against the exact solution of the model's theory: {reference_name(p.reference)}",
        ),
    ]


def _identity_checks(model, options: dict, p) -> list[dict]:
    """Symmetry and superposition of a beam or rod, solved here on the suite's third grid (none for others)."""
    beam = model.bending and model.theory in ("euler-bernoulli", "timoshenko", "higher-order", "continuum")
    if not (beam or rod_kind(model)):
        return []
    mid = p.grids[min(2, len(p.grids) - 1)]
    return [
        C.identity("symmetry (mirror scenes)", _guarded(symmetry, model, options, mid)),
        C.identity("superposition (two loads vs their sum)", _guarded(superposition, model, options, mid)),
    ]


def _card(model, options: dict, p, expected: float, found: list[dict], scenes: list[dict], df, declined) -> dict:
    """The card: the model, suite and references, the checks and their verdict, the scenes, the cases that
    failed or are suspect and the scenes the model declines (without ``wall_s``)."""
    return {
        "model": model.name,
        "title": model.title,
        "options": options,
        "theory": model.theory,
        "suite_version": SUITE_VERSION,
        "pdverify_version": __version__,
        "reference": reference_name(p.reference)
        or f"{model.name} itself at {finer(p.grids)} points (self-convergence)",
        "curved_reference": p.curved_reference,
        "measures": model.measures,
        "grids": list(p.grids),
        "floor_grids": list(p.floor_grids),
        "expected_order": expected,
        "verdict": "fail" if any(c["verdict"] == "fail" for c in found) else "pass",
        "checks": found,
        "scenes": scenes,
        "failed_cases": int((~df["status"].isin(C.SOLVED)).sum()),
        "suspect_cases": int((df["status"] == "suspect").sum()),
        "skipped": [f"{p.meta[f]['name']}: {why[0]}" for f, why in declined.items() if why],
        "cases": len(df),
    }


def drop_other_suite(folder: Path, model_name: str) -> None:
    """Remove ``folder`` when it holds this card's cases from another suite version (``pdverify verify MODEL (suite
    X)``): verify's own cache, stale once the suite changes, which the study runner would otherwise refuse as another
    study's folder. Any other study there is left alone (and refused by the runner)."""
    import shutil
    import tomllib

    try:
        name = tomllib.loads((folder / "study.toml").read_text(encoding="utf-8")).get("name", "")
    except (OSError, ValueError):
        return
    mine = f"pdverify verify {model_name} (suite "
    if isinstance(name, str) and name.startswith(mine) and name != f"{mine}{SUITE_VERSION})":
        shutil.rmtree(folder)


def _guarded(fn, model, options, points) -> list[tuple[str, float]]:
    """A solve that fails in the direct checks counts as an infinite difference (the check fails, the card is
    still written)."""
    try:
        return fn(model, options, points)
    except Exception as exc:  # noqa: BLE001 - the model's failure is the finding
        return [(f"failed: {type(exc).__name__}: {exc}", float("inf"))]
