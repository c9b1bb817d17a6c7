"""The verification cards a study asks for (its ``verify`` key): run after the study's cases into
``OUT/verify/<folder>/`` (each card resumes its own cases there) and listed in ``OUT/verify/cards.json``, which
the report reads (docs/verify.md, "Cards in a study's report")."""

from __future__ import annotations

import json
import time
from pathlib import Path

from ..core.errors import OutputError
from ..study.store import write_atomic
from . import verify

INDEX = "cards.json"


def run_cards(
    study, out: Path, workers: int | None = None, scheduler: str | None = None, progress: bool = False, echo=None
) -> list[dict]:
    """Run ``study.verify``'s cards into ``out / "verify"``; their summaries (model, options, folder, verdict,
    the checks' verdicts). ``echo``: called with one line per card as it ends."""

    root = Path(out) / "verify"
    if not study.verify:  # a study that no longer asks for cards: its report lists none
        (root / INDEX).unlink(missing_ok=True)
        return []
    done, t0 = [], time.perf_counter()
    for entry in study.verify:
        card = verify(
            entry["model"],
            root / entry["folder"],
            entry["options"],
            workers=workers,
            scheduler=scheduler,
            progress=progress,
        )
        row = {
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
        done.append(row)
        if echo is not None:
            failed = [c["check"] for c in card["checks"] if c["verdict"] == "fail"]
            echo(
                f"card: {entry['folder']}: {card['verdict']}"
                + (f" ({', '.join(failed)})" if failed else "")
                + f"; {root / entry['folder'] / 'card.html'}"
            )
    write_index(root, done, study.verify_required, time.perf_counter() - t0)
    return done


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
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    return data if isinstance(data, dict) and isinstance(data.get("cards"), list) else None
