"""An interruptible pool (the verification cards side by side): Ctrl-C stops the batches in flight and those queued,
where a study's case pool lets them finish (pdverify/study/execute.py)."""

import os
import signal
import sys
import threading
import time

import pytest

from pdverify.study import execute


def _slow(case, artefacts, cid):
    """A batch that runs until it is stopped (two minutes at most)."""
    for _ in range(1200):
        time.sleep(0.1)
    return case


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers, /proc")
def test_ctrl_c_stops_the_batches_in_flight_and_queued():
    """SIGINT to this process alone, as a script sends it, while two workers each run a batch and more are queued:
    KeyboardInterrupt at once, nothing yielded (the batches stopped, not finished), no worker left."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    got, t0 = [], time.monotonic()
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            for item in execute.pool(_slow, list(range(6)), list(range(6)), None, 2, interruptible=True):
                got.append(item)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert got == []
    assert time.monotonic() - t0 < 100  # a batch finished would take 120 s
    children = [p for p in os.listdir("/proc") if p.isdigit() and _parent(p) == os.getpid()]
    assert children == []


def _parent(pid: str) -> int:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except (OSError, IndexError, ValueError):
        return -1
