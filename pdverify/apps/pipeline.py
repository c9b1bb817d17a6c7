"""The pipeline a study runs through: its cases (:func:`pdverify.study.run_study`), the verification cards it asks
for, JUnit XML, the HTML report and the exit status. ``pdverify study`` and :func:`pdverify.run_study` both call
:func:`run`, so a script gets the same verdict, cards and exit code as the command line.

Exit status (docs/ci.md): 0 every benchmark and order check passes (an expected-fail row that fails counts) and
every case ran; 1 a benchmark or check fails or is missing, a case failed outside an expected-fail row, or (with
``verify_required``) a card fails; 2 bad input; 3 a failed computation; 4 output could not be written.
"""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ..core.errors import OutputError
from ..report import build_report
from ..study import load_study as _load_study
from ..study import run_study as _run_study
from ..study.checks import Outcome
from ..study.junit import write_junit
from ..study.spec import Study
from ..verify import entry_errors
from ..verify.published import run_cards
from .output import write_file


def load_study(path) -> Study:
    """Read and validate a study file, its ``verify`` cards included (whether the suite applies to each)."""
    return _load_study(path, card_errors=entry_errors)


@dataclass
class StudyRun:
    """What a study run gives: ``results`` (a row per case), the benchmarks' and order checks' verdicts
    (``outcome``), the cards' summaries, the exit code and its one-line ``summary``, and the paths written.
    Where a DataFrame was expected it behaves as ``results`` (``run["err_max"]``, ``run.plot``, ``len(run)``)."""

    study: Study
    out: Path
    results: pd.DataFrame
    outcome: Outcome
    cards: list[dict]
    exit_code: int
    summary: str
    wall_s: float
    report: Path | None = None
    junit: Path | None = None
    lines: list[str] = field(default_factory=list)  # what the command line prints on stderr before the summary

    @property
    def passed(self) -> bool:
        return self.exit_code == 0

    def __getattr__(self, name):  # the results table's attributes (only reached for names not defined here)
        if name.startswith("__") or name == "results":
            raise AttributeError(name)
        return getattr(self.results, name)

    def __getitem__(self, key):
        return self.results[key]

    def __len__(self) -> int:
        return len(self.results)


def run(
    study: Study,
    out: Path,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
    report: bool = False,
    junit: Path | None = None,
    echo=None,
) -> StudyRun:
    """Run ``study`` into ``out``, then its cards, then write ``junit`` (before the report: a report that cannot
    be written loses no verdict) and the report; ``echo``: called with each line the command line prints on
    stderr, as it happens."""
    lines: list[str] = []

    def say(line: str) -> None:
        lines.append(line)
        if echo is not None:
            echo(line)

    if junit is not None and Path(junit).is_dir():
        raise OutputError(f"--junit {junit}: is a folder; give a file name, e.g. {Path(junit) / 'pdverify.xml'}")
    out = Path(out)
    t0 = time.perf_counter()
    df = _run_study(study, out, workers=workers, scheduler=scheduler, progress=progress)
    wall = time.perf_counter() - t0
    counts = dict(Counter(df["status"]).most_common())
    say(f"{study.name}: {len(df)} cases ({counts}); results in {out}/results.csv")
    if study.skipped:  # combinations a run lists but its model cannot solve: not cases, and not silent
        kinds = dict(Counter(line.split(": ", 1)[0] for line in study.skipped))
        for what, n in kinds.items():
            first = next(line for line in study.skipped if line.startswith(what + ": "))
            say(f"skipped: {n} case{'s' * (n > 1)} of {first} (meta.json: skipped)")
    outcome = Outcome(study, out, df)
    for _, r in df[df["status"] != "ok"].iterrows():
        say(f"{r['status']}: {r['model']} on {r['scene_file']}: {r['message']}")  # failed / suspect
    for line in outcome.failures():
        say(line)
    cards = run_cards(study, out, workers=workers, scheduler=scheduler, progress=progress, echo=say)
    failed_cards = sum(c["verdict"] == "fail" for c in cards)
    code = 1 if outcome.exit_code == 0 and study.verify_required and failed_cards else outcome.exit_code
    written_junit = None
    if junit is not None:
        junit = Path(junit)
        try:
            write_file(junit, lambda path: write_junit(outcome, Path(path), wall), "--junit")
        except OutputError as exc:
            raise OutputError(f"{exc.lines[0]}; the study's tables are in {out}") from None
        written_junit = junit
        say(f"junit: {junit}")
    index = build_report(out) if report else None
    summary = outcome.line()
    if cards:  # the cards' verdicts before the exit code they may change (verify_required)
        head, _, _ = summary.rpartition("; exit ")
        summary = (
            f"{head}; cards {len(cards) - failed_cards} pass, {failed_cards} fail "
            f"({'required' if study.verify_required else 'not required'}); exit {code}"
        )
    return StudyRun(study, out, df, outcome, cards, code, summary, wall, index, written_junit, lines)
