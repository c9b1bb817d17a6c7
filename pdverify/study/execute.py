"""Where a study's cases run: one after another in this process (:func:`serial`), in a local process pool
(:func:`pool`), or on a Dask cluster (:func:`on_dask`). Each is a generator of ``(case id, record)`` in
the order the cases finish; the caller stores each record as it comes (outdir.Keeper), so a run stopped
in any way keeps every case it received. ``run`` is the function that computes one case's record
(runner.run_case), given by the caller.

Pool workers are forked on Linux (they start in milliseconds with the models imported), ignore Ctrl-C
(the main process lets the cases in flight finish, stores them and stops) and die with the main process:
a ``kill -9`` of the run leaves no worker behind (``PR_SET_PDEATHSIG`` on Linux, a watchdog thread
elsewhere).
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import re
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool  # noqa: F401 (what a killed worker raises)

from ..core.errors import InputError

SCHEDULER_TIMEOUT_S = 5  # how long to wait for a Dask scheduler to answer before giving up (Dask's own: 30 s)
_ADDRESS = re.compile(r"(?:(?:tcp|tls|ws|wss|ucx)://)?(?:\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):(\d{1,5})")


def serial(run, todo, ids, artefacts, groups: list | None = None, sizes: list | None = None, order=None):
    """The cases one after another in this process, batch by batch as :func:`pool` would hand them out
    (:func:`batches`): the cases on one operator back to back, so a kept factorisation or solve is met again
    before the few a process keeps are pushed out."""
    for batch in batches(len(todo), groups, sizes, order):
        for i in batch:
            yield ids[i], run(todo[i], artefacts, ids[i])


def batches(n: int, groups: list | None = None, sizes: list | None = None, order=None) -> list[list[int]]:
    """The indices of ``n`` cases in batches: the cases with the same key in ``groups`` (one key per case; None:
    each case alone) in one batch, sorted inside by ``order`` (one sort key per case; None: as given); the largest
    batches first (by the sum of their cases' ``sizes``, else by their count)."""
    found: dict = {}
    for i, key in enumerate(groups if groups is not None else range(n)):
        found.setdefault(key, []).append(i)
    if order is not None:
        found = {k: sorted(b, key=lambda i: order[i]) for k, b in found.items()}
    weight = (lambda b: sum(sizes[i] for i in b)) if sizes is not None else len
    return sorted(found.values(), key=weight, reverse=True)


def pool(
    run,
    todo,
    ids,
    artefacts,
    workers: int,
    groups: list | None = None,
    sizes: list | None = None,
    order=None,
    interruptible: bool = False,
):
    """The cases in ``workers`` processes, one batch of cases per task: the cases with the same key in ``groups``
    (one key per case; None: each case alone) run one after another in one process, so that those on one operator
    share its factorisation and their reference (:mod:`pdverify.numerics.factorcache`); the largest batches go
    first (by the sum of their cases' ``sizes``, one number per case, e.g. its points; else by their count), so
    that the last batches to end are short ones. Inside a batch the cases run sorted by ``order`` (one sort key per
    case; None: as given). Ctrl-C: no further batch starts, the batches already handed to the
    workers (those running and up to ``workers + 1`` queued) finish and are yielded, then KeyboardInterrupt goes on.
    Any other way out (the caller's error, the generator closed) cancels the batches not started and waits for those
    in flight, which are dropped. The workers are never killed from here: a worker killed while it sends a record
    back leaves a partial message that the pool's reader then waits for forever.

    ``interruptible`` (batches that take minutes, e.g. a verification card): Ctrl-C, or SIGINT to this process alone
    (passed on to the workers), stops the batches in flight too, at their next step (a worker raises
    KeyboardInterrupt only while it runs a batch; what the batch stores as it goes, e.g. a card's cases, is kept);
    they are dropped, not yielded, and the workers have ended when KeyboardInterrupt goes on."""
    by_weight = batches(len(todo), groups, sizes, order)
    # fork on Linux whatever the Python version (3.14 made forkserver the default)
    ctx = multiprocessing.get_context("fork") if sys.platform.startswith("linux") else None
    ex = ProcessPoolExecutor(
        max_workers=workers, mp_context=ctx, initializer=_worker_start, initargs=(os.getpid(), interruptible)
    )
    futs, given = [], set()
    try:
        for batch in by_weight:
            futs.append(ex.submit(_run_batch, run, [todo[i] for i in batch], artefacts, [ids[i] for i in batch]))
        for fut in as_completed(futs):
            records = fut.result()
            given.add(fut)
            yield from records
    except KeyboardInterrupt:
        procs = list((getattr(ex, "_processes", None) or {}).values())  # before the shutdown forgets them
        ex.shutdown(wait=False, cancel_futures=True)
        if interruptible:  # a SIGINT sent to this process alone: to the workers too (a terminal's reached them)
            for proc in procs:
                with contextlib.suppress(OSError):
                    os.kill(proc.pid, signal.SIGINT)
        # polled, not as_completed: a future the pool cancels at shutdown never tells its waiters (3.11)
        rest = [f for f in futs if f not in given]
        while rest:
            for fut in [f for f in rest if f.done()]:
                rest.remove(fut)
                if not fut.cancelled() and fut.exception() is None:
                    yield from fut.result()
            time.sleep(0.02)
        if interruptible:  # the shutdown above forgot them: they end once told (at once, their batches stopped)
            for proc in procs:
                proc.join()
        raise
    finally:
        ex.shutdown(wait=True, cancel_futures=True)


_BUSY = [False]  # in a worker of an interruptible pool: whether it runs a batch (Ctrl-C stops it then only) ...
_STOPPED = [False]  # ... and whether it had a Ctrl-C: the batches already queued to it are dropped too


def _run_batch(run, cases, artefacts, ids) -> list:
    """[(case id, record)] of a batch, in one process."""
    if _STOPPED[0]:
        raise KeyboardInterrupt
    _BUSY[0] = True
    try:
        return [(cid, run(case, artefacts, cid)) for case, cid in zip(cases, ids)]
    finally:
        _BUSY[0] = False


def _interrupt_if_busy(signum, frame) -> None:
    """SIGINT in a worker of an interruptible pool: KeyboardInterrupt in the batch it runs, nothing while it waits for
    one (a worker interrupted there would die with a traceback and break the pool); the batches queued to it after
    that are dropped."""
    _STOPPED[0] = True
    if _BUSY[0]:
        raise KeyboardInterrupt


def _worker_start(parent: int, interruptible: bool = False) -> None:
    """A pool worker's first act: leave Ctrl-C to the main process (``interruptible``: stop the batch it runs, if
    any), and die when it dies."""
    signal.signal(signal.SIGINT, _interrupt_if_busy if interruptible else signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        import ctypes

        PR_SET_PDEATHSIG = 1
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    else:  # pragma: no cover - not Linux
        threading.Thread(target=_watch, args=(parent,), daemon=True, name="pdverify-parent-watch").start()
    if os.getppid() != parent:  # the main process died before the line above
        os._exit(1)


def _watch(parent: int) -> None:  # pragma: no cover - not Linux
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(1)


def check_scheduler(address: str) -> None:
    """A Dask scheduler address (tcp://HOST:PORT, or HOST:PORT); InputError (exit 2) otherwise."""
    m = _ADDRESS.fullmatch(address.strip())
    if not m or not 0 < int(m.group(1)) < 65536:
        raise InputError(
            f"--scheduler {address!r}: not a Dask scheduler address; write tcp://HOST:PORT (e.g. tcp://127.0.0.1:8786)"
        )


def connect(address: str):
    """A Dask client of the scheduler at ``address``; InputError (exit 2) when none is reached there within
    :data:`SCHEDULER_TIMEOUT_S` seconds (refused, no such host, or another kind of server)."""
    check_scheduler(address)
    try:
        from dask.distributed import Client
    except ImportError:
        raise InputError(
            f"--scheduler {address}: dask.distributed is not installed; pip install "
            "'dask[distributed]' or run without --scheduler"
        ) from None
    try:
        return Client(address.strip(), timeout=SCHEDULER_TIMEOUT_S)
    except Exception as exc:  # noqa: BLE001 - refused, timed out, no such host, or not a Dask scheduler there
        why = (str(exc).splitlines() or [""])[0][:100]
        raise InputError(
            f"--scheduler {address}: no Dask scheduler reached there ({type(exc).__name__}: {why}; "
            f"connect timeout {SCHEDULER_TIMEOUT_S} s); start one (dask scheduler) or check the "
            "address"
        ) from None


class ClusterLost(Exception):
    """The Dask cluster could not give a case's record (a worker killed, the scheduler gone)."""


def on_dask(run, todo, ids, scheduler: str):
    """The cases on the Dask cluster at ``scheduler`` (no artefact files: the workers may be remote), connected at
    once: an address where no scheduler answers is one error before anything is shown (a progress bar)."""
    return _on_client(connect(scheduler), run, todo, ids)


def _on_client(client, run, todo, ids):
    """The records of :func:`on_dask` as they finish; the client closed with the loop."""
    from dask.distributed import as_completed as dask_completed

    with client:
        try:
            futures = client.map(run, todo, [None] * len(todo), ids, pure=False)
            by_key = {f.key: cid for f, cid in zip(futures, ids)}
            for fut in dask_completed(futures):
                rec = fut.result()
                yield by_key[fut.key], rec
        except Exception as exc:  # run never raises: the cluster failed (KilledWorker, connection lost)
            why = (str(exc).splitlines() or [""])[0][:100]
            raise ClusterLost(f"{type(exc).__name__}: {why}") from None
