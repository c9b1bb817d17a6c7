"""An interruptible pool (the verification cards side by side): Ctrl-C stops the batches in flight and those queued,
where a study's case pool lets them finish (pdverify/study/execute.py)."""

import os
import signal
import sys
import threading
import time
from pathlib import Path

import pytest

from pdverify.study import execute


def _slow(case, folder, cid):
    """A batch that notes its worker's pid in ``folder`` and runs until it is stopped (two minutes at most)."""
    (Path(folder) / f"{os.getpid()}.pid").touch()
    for _ in range(1200):
        time.sleep(0.1)
    return case


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers, /proc")
def test_ctrl_c_stops_the_batches_in_flight_and_queued(tmp_path):
    """SIGINT to this process alone, as a script sends it, while two workers each run a batch and more are queued:
    KeyboardInterrupt at once, nothing yielded (the batches stopped, not finished), the workers ended."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    got = []
    timer = threading.Thread(target=_interrupt_when_both_run, args=(tmp_path,), daemon=True)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            for item in execute.pool(_slow, list(range(6)), list(range(6)), str(tmp_path), 2, interruptible=True):
                got.append(item)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert got == []  # a batch that finished (two minutes) would have been yielded
    workers = [p.stem for p in tmp_path.glob("*.pid")]
    assert len(workers) == 2 and [w for w in workers if Path(f"/proc/{w}").exists()] == []


def _interrupt_when_both_run(folder: Path) -> None:
    """SIGINT to this process once both workers run a batch (a wait for the machine, not a check: 300 s at most)."""
    deadline = time.monotonic() + 300
    while len(list(folder.glob("*.pid"))) < 2 and time.monotonic() < deadline:
        time.sleep(0.02)
    os.kill(os.getpid(), signal.SIGINT)
