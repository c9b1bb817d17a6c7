"""The verification cards a study asks for (its ``verify`` key): run after the study's cases into
``OUT/verify/<folder>/`` (each card resumes its own cases there) and listed in ``OUT/verify/cards.json``, which
the report reads (docs/verify.md, "Cards in a study's report").

With more than one worker and no Dask scheduler the cards run side by side, one card per worker process and each
card's cases one after another in it (:func:`pdverify.study.execute.pool`, the 2D model's cards first): a card's own
pool leaves a core idle at its end and around its forked checks, which side by side the next card fills. The cards
are the same either way (their checks and cases; the cost check's seconds differ from run to run)."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from ..core.errors import OutputError
from ..registry import get_model
from ..study import execute
from ..study.store import write_atomic
from . import verify

INDEX = "cards.json"


def run_cards(
    study, out: Path, workers: int | None = None, scheduler: str | None = None, progress: bool = False, echo=None
) -> list[dict]:
    """Run ``study.verify``'s cards into ``out / "verify"``; their summaries (model, options, folder, verdict,
    the checks' verdicts), in the study's order. ``echo``: called with one line per card as it ends."""

    root = Path(out) / "verify"
    if not study.verify:  # a study that no longer asks for cards: its report lists none
        (root / INDEX).unlink(missing_ok=True)
        return []
    t0 = time.perf_counter()
    n = min(workers or os.cpu_count() or 1, len(study.verify))
    if n > 1 and scheduler is None:
        folders = [e["folder"] for e in study.verify]  # root: what the pool hands every run besides its card
        made = execute.pool(_card, study.verify, folders, root, n, sizes=_weights(study), interruptible=True)
    else:
        made = (
            (
                e["folder"],
                verify(
                    e["model"],
                    root / e["folder"],
                    e["options"],
                    workers=workers,
                    scheduler=scheduler,
                    progress=progress,
                ),
            )
            for e in study.verify
        )
    cards = {}
    try:
        for folder, card in made:
            cards[folder] = card
            if echo is not None:
                failed = [c["check"] for c in card["checks"] if c["verdict"] == "fail"]
                echo(
                    f"card: {folder}: {card['verdict']}"
                    + (f" ({', '.join(failed)})" if failed else "")
                    + f"; {root / folder / 'card.html'}"
                )
    except execute.BrokenProcessPool:  # a worker killed: the cards' cases stored before are kept in their folders
        raise OutputError(
            f"a process running a verification card ended abruptly (killed: out of memory, a signal); the cards' "
            f"cases finished before are kept in {root}: run the study again to resume"
        ) from None
    done = [_summary(entry, cards[entry["folder"]]) for entry in study.verify]
    write_index(root, done, study.verify_required, time.perf_counter() - t0)
    return done


def _card(entry: dict, root: Path, folder: str) -> dict:
    """One card in a pool worker (:func:`pdverify.study.execute.pool`'s ``run``): its cases one after another there."""
    return verify(entry["model"], root / folder, entry["options"], workers=1)


def _weights(study) -> list[int]:
    """The cards' relative costs, the largest run first: a 2D model's card (theory ``continuum``: every case a 2D
    solve, its reference four times finer) costs about as much as all the others together."""
    return [len(study.verify) if get_model(e["model"]).theory == "continuum" else 1 for e in study.verify]


def _summary(entry: dict, card: dict) -> dict:
    """A card's line in cards.json."""
    return {
        "model": card["model"],
        "options": entry["options"],
        "folder": entry["folder"],
        "verdict": card["verdict"],
        # a caveat: the check judged errors against a reference whose round-off bound passes 1e-6
        "checks": [
            {"check": c["check"], "verdict": c["verdict"], **({"caveat": c["caveat"]} if c.get("caveat") else {})}
            for c in card["checks"]
        ],
        "cases": card["cases"],
        "failed_cases": card["failed_cases"],
        "wall_s": card["wall_s"],
    }


def write_index(root: Path, cards: list[dict], required: bool, wall_s: float | None = None) -> None:
    """``cards.json``: whether the study requires them, each card's summary and the seconds all of them took."""
    try:
        root.mkdir(parents=True, exist_ok=True)
        index = {"required": required, "cards": cards, "wall_s": wall_s}
        write_atomic(root / INDEX, json.dumps(index, indent=1) + "\n")
    except OSError as exc:
        raise OutputError(
            f"{root / INDEX}: the list of cards could not be written ({exc.strerror or exc}); the "
            "cards themselves are in their folders"
        ) from None


def read_index(out: Path) -> dict | None:
    """``OUT/verify/cards.json`` or None when the study ran no cards (or the file is unreadable)."""
    p = Path(out) / "verify" / INDEX
    try:
        data = json.loads(p.read_text())
    except (OSError, ValueError, UnicodeDecodeError, RecursionError):
        return None
    return data if isinstance(data, dict) and isinstance(data.get("cards"), list) else None
