"""``pdverify verify MODEL``: a fixed, versioned verification suite and its report card.

The suite (:mod:`.suite`) is written as a study and run by :func:`pdverify.study.run_study` (a process
pool, or Dask with ``scheduler``; resumable). The checks (:mod:`.checks`) judge its results; symmetry and
superposition solve a handful of scenes here. The card (:mod:`.card`) is JSON, HTML and JUnit XML.
"""

from __future__ import annotations

import time
from pathlib import Path

from .. import __version__
from ..errors import InputError
from ..registry import get_model, run
from ..scene import parse_scene
from . import checks as C
from .dynamics import dynamics_check
from .suite import GAP_REFERENCE, LOADS, SUITE_VERSION, end_force, finer, mirror, plan, straight, write_study

__all__ = ["verify", "SUITE_VERSION", "parse_entry", "entry_errors", "card_folder"]

MIRROR_PAIRS = (("clamped", "pinned"), ("clamped", "free"), ("clamped", "guided"), ("pinned", "guided"))
ASYMMETRIC = {
    "point force": [{"type": "point_force", "position": 0.25, "value": -1000.0}],
    "point moment": LOADS["point moment"],
    "partial": [{"type": "distributed", "value": -1000.0, "start": 0.25, "end": 0.5}],
}


def _solve(scene: dict, model, options: dict, points: int):
    return run(parse_scene(scene), model, **options, points=points)


def _declines(model, scene: dict) -> bool:
    return bool(model.check(parse_scene(scene)))


def symmetry(model, options: dict, points: int) -> list[tuple[str, float]]:
    out = []
    for left, right in MIRROR_PAIRS:
        for load, lds in ASYMMETRIC.items():
            sc = straight(left, right, lds, name=f"{left}-{right}, {load}")
            if _declines(model, sc) or _declines(model, mirror(sc)):
                continue
            out.append(
                (sc["name"], C.mirrored(_solve(sc, model, options, points), _solve(mirror(sc), model, options, points)))
            )
    return out


def sharing_positions(loads: list[dict], every: list[dict]) -> list[dict]:
    """``loads`` and a zero-valued copy of each point load of ``every``: the three scenes of the superposition
    check then carry the same point-load positions, so a model that adapts its grid or bonds to them (e.g.
    pd-higher-order's ``cuts = loads``) is judged on one operator, and linearity is what is measured."""
    return loads + [{**ld, "value": 0.0} for ld in every if ld["type"] in ("point_force", "point_moment")]


def superposition(model, options: dict, points: int) -> list[tuple[str, float]]:
    out = []
    for left, right in (("clamped", "clamped"), ("clamped", "free"), ("pinned", "guided")):
        a = LOADS["point force"] + LOADS["point moment"]
        b = LOADS["sine"] + (end_force(left, right) or LOADS["partial"])
        a, b = sharing_positions(a, b), sharing_positions(b, a)
        if any(_declines(model, straight(left, right, lds)) for lds in (a, b, a + b)):
            continue
        ra, rb, rab = (_solve(straight(left, right, lds), model, options, points) for lds in (a, b, a + b))
        out.append((f"{left}-{right}: force + moment, sine + end force or partial", C.superposition_diff(ra, rb, rab)))
    return out


def parse_entry(entry) -> tuple[str, dict]:
    """A study file's ``verify`` entry: ``"pd-eb variant=paper horizon=3"`` (values typed as TOML types them:
    ``3`` a number, ``true`` a boolean, anything else a string) or a table ``{model = "pd-eb", variant = "paper"}``.
    Raises InputError (one line) for an entry of neither form."""
    import tomllib

    if isinstance(entry, dict) and isinstance(entry.get("model"), str):
        return entry["model"], {k: v for k, v in entry.items() if k != "model"}
    if not isinstance(entry, str) or not entry.split():
        raise InputError(f'{entry!r}: give a model and its options, e.g. "pd-eb variant=paper"')
    name, *pairs = entry.split()
    options = {}
    for item in pairs:
        k, eq, v = item.partition("=")
        if not eq or not k or not v:
            raise InputError(f"{entry!r}: option {item!r}: write key=value")
        try:
            options[k] = tomllib.loads(f"v = {v}")["v"]
        except tomllib.TOMLDecodeError:
            options[k] = v
    return name, options


def card_folder(model_name: str, options: dict) -> str:
    """The card's folder name, as ``pdverify verify`` names it: ``pd_eb_variant_paper``."""
    import re

    text = (model_name + "".join(f"_{k}_{v}" for k, v in options.items())).lower()
    return re.sub(r"[^a-z0-9]+", "_", text).strip("_") or "model"


def _declined(model, p) -> dict:
    """Why the model declines each scene of the plan (the floor scene repeats a convergence scene: left out)."""
    return {f: model.check(parse_scene(sc)) for f, sc in p.scenes.items() if p.meta[f]["set"] != "floor"}


def entry_errors(model_name: str, options: dict, full: bool = False) -> list[str]:
    """What stops ``verify(model_name, ..., options)`` before it runs anything: an unknown model or option, a
    value of the wrong type, a grid option (the suite sets the grids), a model that solves none of the
    suite's scenes. One line each (without the caller's prefix)."""
    from ..study.checks import strict_type

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
    p = plan(model, full)
    declined = _declined(model, p)
    solved = [f for f, why in declined.items() if not why]
    if not solved:
        return [
            f"model {model.name} solves none of the suite's scenes ({next(iter(declined.values()))[0]}); "
            "verify needs a beam model that takes straight (or curved) beams with transverse loads"
        ]
    try:
        model.resolve(parse_scene(p.scenes[solved[0]]), options)
    except InputError as exc:
        return list(exc.lines)
    return []


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
    from ..study import load_study, run_study
    from .card import write_card

    t0 = time.perf_counter()
    options = dict(options or {})
    model = get_model(model_name)
    expected = order if order is not None else model.order
    out = Path(out)
    p = plan(model, full)
    declined = _declined(model, p)
    if all(declined.values()):
        first = next(iter(declined.values()))[0]
        raise InputError(
            f"model {model.name} solves none of the suite's scenes ({first}); verify needs a beam model "
            "that takes straight (or curved) beams with transverse loads"
        )
    study_path = write_study(p, model, options, out / "suite")
    df = run_study(  # no VTU, PNG or history files: the card reads the errors
        load_study(study_path), out / "study", workers=workers, scheduler=scheduler, progress=progress, artefacts=False
    )
    files = {s: [f for f, m in p.meta.items() if m["set"] == s] for s in ("convergence", "locking", "floor", "curved")}
    # the theory-gap run (self-convergence only): the convergence scenes on the reference grid, finer than any other
    gap = (p.reference is None) & (df["points"] == finer(p.grids)) & df["scene_file"].isin(files["convergence"])
    df, gap_df = df[~gap], df[gap]
    conv = C.series(df, files["convergence"])
    found = [
        C.convergence(conv, expected, "convergence (straight)"),
        C.accuracy(conv),
        C.within(conv),
        C.locking(df, files["locking"], p.meta),
        C.floor(C.series(df, files["floor"])),
        C.cost(conv),
        C.theory_gap(gap_df, p.meta, GAP_REFERENCE, finer(p.grids))
        if p.reference is None
        else C.check(
            "theory gap", "n/a", f"errors are against the exact solution of the model's theory: {p.reference}"
        ),
    ]
    if model.bending and model.theory in ("euler-bernoulli", "timoshenko", "higher-order", "continuum"):
        mid = p.grids[min(2, len(p.grids) - 1)]
        found.append(C.identity("symmetry (mirror scenes)", _guarded(symmetry, model, options, mid)))
        found.append(C.identity("superposition (two loads vs their sum)", _guarded(superposition, model, options, mid)))
    curved = C.series(df, files["curved"])
    found.append(
        C.convergence(curved, expected, "convergence (curved axes)")
        if curved
        else C.check("convergence (curved axes)", "n/a", "the model does not declare curved axes")
    )
    found.append(dynamics_check(model, options, p.grids, expected))
    scenes = [{**p.meta[r["scene_file"]], **r} for r in conv + curved]
    skipped = [f"{p.meta[f]['name']}: {why[0]}" for f, why in declined.items() if why]
    verdict = "fail" if any(c["verdict"] == "fail" for c in found) else "pass"
    card = {
        "model": model.name,
        "title": model.title,
        "options": options,
        "theory": model.theory,
        "suite_version": SUITE_VERSION,
        "pdverify_version": __version__,
        "reference": p.reference or f"{model.name} itself at {finer(p.grids)} points (self-convergence)",
        "curved_reference": p.curved_reference,
        "grids": list(p.grids),
        "floor_grids": list(p.floor_grids),
        "expected_order": expected,
        "verdict": verdict,
        "checks": found,
        "scenes": scenes,
        "failed_cases": int((~df["status"].isin(C.SOLVED)).sum()),
        "suspect_cases": int((df["status"] == "suspect").sum()),
        "skipped": skipped,
        "cases": len(df),
        "wall_s": time.perf_counter() - t0,
    }
    write_card(card, out)
    return card


def _guarded(fn, model, options, points) -> list[tuple[str, float]]:
    """A solve that fails in the direct checks counts as an infinite difference (the check fails, the card is
    still written)."""
    try:
        return fn(model, options, points)
    except Exception as exc:  # noqa: BLE001 - the model's failure is the finding
        return [(f"failed: {type(exc).__name__}: {exc}", float("inf"))]
