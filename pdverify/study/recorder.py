"""A child process that measures and stores the cases a serial run solves, on the machine's other core.

Why: in a serial run (``--workers 1``) the runner's own work per case (the reference at the model's
points, the errors, encoding the record, creating its file) cost ~0.6 ms beside a 6-8 ms solve when done
between solves, about three times its cost in a tight loop, because each solve leaves the caches cold
(``benchmarks/runner_overhead.py``). Here the solving process only writes what the model returned into a
pipe; the child, a ``fork`` made before the first solve (of the runner: it has the study, the models and
every cache the runner has; or of the zygote, :mod:`pdverify.zygote`, given its work pickled; either way
it computes the same numbers with the same code), does the rest and writes each case file at once. At
the end it sends back what it recorded, then writes the derived tables while the runner writes the
results table.

Each message's arrays are written as they are, beside the rest, pickled (``encode``). The pipe holds
up to 1 MB (a few cases; the child, several times faster than the solves and polling it every
millisecond, empties it): when the child falls behind, ``put`` waits, so the cases waiting to be
recorded are only ever those in the pipe (a killed run loses them, like the case being solved; if only
the runner is killed, the child still records them), and those the runner has not handed over yet (it
hands its cases over in batches of at most ``runner.HANDOFF_S``, 20 ms of solving). The child ignores
SIGINT: after Ctrl-C it still records what it was given (the runner sends its pending batch first). A
failure in the child (a case file that cannot be written) is sent back and raised in the runner. Used only on Linux (``fork``) when the process may run on at least two CPUs (on
one CPU the child would take the solver's time instead of an idle core's).
"""

from __future__ import annotations

import fcntl
import os
import pickle
import resource
import signal
import struct
import sys
import time
import warnings
from typing import Any, Callable

import numpy as np

from .. import zygote
from .store import write_all

HEAD = struct.Struct("<QQ")


def usable_cpus() -> int:
    """CPUs this process may run on (its affinity mask where the platform has one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def read_exactly(fd: int, n: int, poll: float = 0.0) -> bytearray | None:
    """``n`` bytes from ``fd`` (writable), or None at end of file (also when it comes in the middle).
    ``poll``: for a non-blocking ``fd``, the seconds to sleep when nothing is there yet."""
    buf = bytearray(n)
    view, got = memoryview(buf), 0
    while got < n:
        try:
            k = os.readv(fd, [view[got:]])
        except BlockingIOError:
            time.sleep(poll)
            continue
        if not k:
            return None
        got += k
    return buf


def encode(obj, arrays=()) -> tuple[bytes, list]:
    """(encoded object, arrays to write beside it): ``arrays`` as they are (made contiguous), ``obj`` by a
    plain pickle (one C call: ~25 us between two solves on the host this was written on, where a pickle
    with a Python callback per object to take its arrays out cost ~110 us and a checked marshal ~40 us).
    Arrays inside ``obj`` are pickled with it (a copy): hand large ones over in ``arrays``."""
    arrays = [a if a.flags.c_contiguous else np.ascontiguousarray(a) for a in arrays]
    return pickle.dumps((obj, [(a.dtype.str, a.shape) for a in arrays]), protocol=pickle.HIGHEST_PROTOCOL), arrays


def decode(data: bytes, buffers: list) -> tuple[Any, list]:
    """:func:`encode` undone: (object, the arrays given beside it), every array backed by its buffer."""
    obj, specs = pickle.loads(data)
    return obj, [np.frombuffer(b, dtype).reshape(shape) for b, (dtype, shape) in zip(buffers, specs)]


def send(fd: int, obj, arrays=()) -> None:
    """``obj`` and ``arrays`` (:func:`encode`), the arrays' memory written as it is (no copy of a case's
    curves in the runner). Layout: ``<u8 object length> <u8 array count>``, the arrays' lengths (u8
    each), the object, the arrays."""
    _write_encoded(fd, *encode(obj, arrays))


def _write_encoded(fd: int, data: bytes, arrays=()) -> None:
    head = struct.pack(f"<QQ{len(arrays)}Q", len(data), len(arrays), *(a.nbytes for a in arrays))
    write_all(fd, [head, data, *arrays])


def receive(fd: int, poll: float = 0.0) -> tuple[Any, list] | None:
    """The next (object, arrays), or None at end of file (also inside a message). The arrays are
    writable, each backed by its own buffer. ``poll``: see :func:`read_exactly`."""
    head = read_exactly(fd, HEAD.size, poll)
    if head is None:
        return None
    n_data, n_buffers = HEAD.unpack(head)
    sizes = read_exactly(fd, 8 * n_buffers, poll)
    if sizes is None:
        return None
    lengths = struct.unpack(f"<{n_buffers}Q", sizes)
    data = read_exactly(fd, n_data, poll)
    buffers = [read_exactly(fd, n, poll) for n in lengths]
    if data is None or any(b is None for b in buffers):
        return None
    return decode(bytes(data), buffers)


PIPE_BYTES = 1 << 20  # Linux's default limit for a pipe an unprivileged process widens (fs/pipe-max-size)


def _widen(fd: int) -> None:
    """Widen a pipe to PIPE_BYTES where the system allows (else it keeps its 64 kB): a case of 12,001
    points (288 kB) went through a 64 kB pipe in pieces, the writer waiting for the reader to wake up and
    drain each one (0.53-0.55 ms a case against 0.16-0.17 ms)."""
    try:
        fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, PIPE_BYTES)
    except (AttributeError, OSError):  # not Linux, or a lower limit
        pass


class RecorderDied(RuntimeError):
    """The child ended without sending its answer back: killed (out of memory, a signal) or, for a child of
    the zygote, never started."""


_unreaped: list[int] = []  # finished children not waited for yet (their exit is not waited on: see close)


def _reap() -> None:
    for pid in list(_unreaped):
        try:
            done, _ = os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            done = pid
        if done:
            _unreaped.remove(pid)


class Recorder:
    """``put(message, arrays)`` in the runner calls ``handle(message, arrays)`` in the child, in order
    (``arrays``: a list of arrays, written to the pipe as they are; ``message``: anything picklable, best
    small). ``close()`` ends the input and returns ``finish()``'s value from the child; then the child runs
    ``after()`` (if given) while the runner goes on, and ``join()`` returns its value. ``abort()`` (the
    runner is stopping: Ctrl-C, an error) lets the child handle what it was given, skips ``after`` and
    waits for it. ``start()`` (if given) runs in the child before the first message is read (work it can
    do while the first case is solved).

    ``start``, ``handle``, ``finish`` and ``after`` run in the child. When they can be pickled (bound
    methods of a module-level class, say) and the zygote (:mod:`pdverify.zygote`) is ready, they are
    pickled here and the child is a fork of the zygote: they work on copies of the objects as pickled,
    and this process is never forked (``started == "zygote"``). Otherwise (closures, no zygote) the child
    is a fork of this process and sees its objects as they were at the fork (``started == "fork"``).
    The zygote's child works in this process's working directory, with the zygote's environment
    variables and ``sys.path`` (this process's when it started the zygote).
    Either way, whatever they change stays in the child, and their exceptions are sent back and raised in
    the runner by ``put``, ``close`` or ``join``."""

    # Linux only: on macOS a forked child of a process that has used the system's frameworks (Accelerate,
    # libdispatch) may crash, which is why multiprocessing spawns there.
    available = sys.platform.startswith("linux") and usable_cpus() >= 2

    def __init__(self, handle: Callable[[Any, list], None], finish: Callable[[], Any],
                 after: Callable[[], Any] | None = None, start: Callable[[], None] | None = None):
        _reap()
        jobs_r, jobs_w = os.pipe()
        back_r, back_w = os.pipe()
        _widen(jobs_w)
        _widen(back_w)
        work = (handle, finish, after, start)
        job = _pickled((os.getcwd(), work)) if zygote.ready() else None  # (relative paths: the runner's)
        if job is not None and zygote.fork([jobs_r, back_w]):
            pid, self.started = None, "zygote"
        else:
            with warnings.catch_warnings():
                # Python >= 3.12 warns when a process with threads forks. The only other threads here are
                # OpenBLAS's pool, which is fork-safe (its pthread_atfork handler stops the pool before the
                # fork; the child starts its own on demand). The progress bar's thread starts after the fork.
                warnings.filterwarnings("ignore", category=DeprecationWarning, message=r".*fork\(\)")
                pid = os.fork()
            if pid == 0:  # the child: never returns
                code = 1
                try:
                    signal.signal(signal.SIGINT, signal.SIG_IGN)
                    os.close(jobs_w)
                    os.close(back_r)
                    _serve(jobs_r, back_w, work)
                    code = 0
                finally:
                    os._exit(code)  # no atexit handlers, no flushing of the parent's buffers
            self.started = "fork"
        os.close(jobs_r)
        os.close(back_w)
        self._pid, self._jobs, self._back, self._after = pid, jobs_w, back_r, after is not None
        if job is not None and pid is None:
            try:
                _write_encoded(jobs_w, job)  # the zygote's child reads its work first (serve_job)
            except OSError:  # no child (the zygote could not fork): the caller measures in its own process
                os.close(jobs_w)
                os.close(back_r)
                raise

    @property
    def closed(self) -> bool:
        return self._jobs < 0

    def put(self, message, arrays=()) -> None:
        try:
            send(self._jobs, (_JOB, message), arrays)
        except BrokenPipeError:  # the child stopped after a failure: raise what it sent back
            self._end_input()
            self._reply()
            raise

    def close(self) -> tuple[Any, float]:
        """End of input: ``finish()``'s value and the child's CPU seconds so far."""
        try:
            send(self._jobs, (_END, None))
        except BrokenPipeError:  # the child stopped after a failure: its reply raises it
            pass
        self._end_input()
        if not self._after:
            return self._last(self._reply())
        return self._reply()

    def join(self) -> tuple[Any, float]:
        """``after()``'s value and the child's CPU seconds in all. The child's exit (unmapping its copy of
        the runner: milliseconds) is not waited for; it is reaped later."""
        return self._last(self._reply())

    def abort(self) -> None:
        """Stop: the child handles the messages already sent and exits without ``after``; waited for (its
        end of the reply pipe closes when it exits)."""
        if self._back < 0:
            return
        if not self.closed:
            self._end_input()  # end of file without the end message: no after()
        while os.read(self._back, 1 << 16):  # its replies, unread
            pass
        self._end_reply()
        if self._pid is not None:
            os.waitpid(self._pid, 0)

    def _end_input(self) -> None:
        if self._jobs >= 0:
            os.close(self._jobs)
            self._jobs = -1

    def _end_reply(self) -> None:
        os.close(self._back)
        self._back = -1

    def _reply(self):
        outcome = receive(self._back)
        if outcome is None:
            self._end_reply()
            how = ""
            if self._pid is not None:
                status = os.waitpid(self._pid, 0)[1]
                how = (f" (killed by {signal.Signals(os.WTERMSIG(status)).name})" if os.WIFSIGNALED(status)
                       else f" (exit status {os.waitstatus_to_exitcode(status)})")
            raise RecorderDied(f"the recorder process ended without an answer{how}")
        (kind, value, cpu), _ = outcome
        if kind == "error":
            self.abort()
            raise value
        return value, cpu

    def _last(self, reply):
        self._end_reply()
        if self._pid is not None:
            _unreaped.append(self._pid)
            _reap()
        return reply


def _pickled(work) -> bytes | None:
    """``work`` encoded for the zygote's child (:func:`encode`), or None when it cannot be pickled."""
    try:
        return encode(work)[0]
    except (pickle.PicklingError, TypeError, AttributeError):
        return None


def serve_job(jobs: int, back: int) -> None:
    """A child of the zygote: its work is the first message on ``jobs`` (:class:`Recorder`: the runner's
    working directory and the four functions), then as a forked child."""
    _serve(jobs, back, None)


_JOB, _END = 0, 1
# The child polls its input (non-blocking reads, sleeping POLL_S when empty) instead of blocking on it:
# writing into a pipe whose reader sleeps in read() wakes that reader, which cost the solving process
# 45-50 us a case on the host this was written on (a 48 kB write: 78-84 us against 34-41 us to a polling
# reader, caches cold as after a solve). The price: up to POLL_S more at the end, and ~1,000 wake-ups a
# second of the child while the cases are solved (~1 % of the otherwise idle core).
POLL_S = 0.001


def _serve(jobs: int, back: int, work: tuple | None) -> None:
    """The child's loop: handle each job; at the end message (or end of file: the runner stopped) send
    back ``finish()``; after the end message, run ``after()`` and send back its value. The first exception
    is sent back instead, and ends the child. ``work``: (handle, finish, after, start), or None to read it
    first from ``jobs``."""

    def reply(fn):
        try:
            outcome = ("ok", fn())
        except BaseException as exc:  # raised in the runner
            outcome = ("error", exc)
        usage = resource.getrusage(resource.RUSAGE_SELF)
        send(back, (*outcome, usage.ru_utime + usage.ru_stime))
        return outcome[0] == "ok"

    ended, after = False, None

    def jobs_then_finish():
        nonlocal ended, after
        if work is None:
            try:
                got = receive(jobs)
            except Exception as exc:  # a function the runner pickled by name that this process cannot find
                raise RuntimeError(f"the recorder could not load its work from the runner: {exc!r}") from None
            if got is None:
                raise RuntimeError("the recorder's work never arrived (the runner stopped)")
            cwd, (handle, finish, after, start) = got[0]
            os.chdir(cwd)  # the runner's working directory, not the zygote's
        else:
            handle, finish, after, start = work
        if start is not None:
            start()
        if POLL_S:
            os.set_blocking(jobs, False)
        while (message := receive(jobs, POLL_S)) is not None:
            (kind, payload), arrays = message
            if kind == _END:
                ended = True
                break
            handle(payload, arrays)
        return finish()

    if reply(jobs_then_finish) and ended and after is not None:
        reply(after)
