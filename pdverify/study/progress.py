"""The progress bar of a study's run (:func:`pdverify.study.runner.run_study`)."""

from __future__ import annotations


class CaseProgress:
    """A rich progress bar of a study's cases: cases done, failures, time left (nothing when disabled)."""

    def __init__(self, total, enabled):
        self.enabled = enabled and total > 0
        self.failed = 0
        if self.enabled:
            # rich is imported only when a bar is drawn
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self.p = Progress(
                TextColumn("cases"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn("failed {task.fields[failed]}"),
                TimeRemainingColumn(),
                transient=False,
            )
            self.p.start()
            self.task = self.p.add_task("cases", total=total, failed=0)

    def advance(self, failed=False):
        self.failed += int(failed)
        if self.enabled:
            self.p.update(self.task, advance=1, failed=self.failed)

    def close(self):
        if self.enabled:
            self.p.stop()
