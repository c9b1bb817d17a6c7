"""A pre-started process that forks the serial run's recorder (a "zygote"), so the runner never forks.

Why: a fork marks every page of the forking process copy-on-write, and the first write to each page
afterwards is a page fault. The recorder forked from the runner cost the runner ~12,000 such faults per
study (its solves write ~50 MB of heap it had before the fork): 200 small pd-eb cases took 3-4 % longer
than the same loop without the fork (``benchmarks/runner_overhead.py``), time the runner's own clock
counts as the models'. The zygote is a fresh interpreter started with ``subprocess`` (``vfork`` + exec on
Linux: no page of the runner is touched) that imports the study code once; each recorder is a fork of
*it*, so the runner's pages stay its own.

``start()`` launches it and returns at once (it imports for ~1 s on the other core); :func:`fork` asks
it for a child holding given file descriptors, or returns False when it cannot serve (not started, still
importing, dead, or running other code: a model registered at run time, an edited source file), and
the caller forks itself as before. It exits when the process that started it closes its socket (exit
or kill), and ignores Ctrl-C like the recorder.

Opt-in, for a process that runs several serial studies (a notebook, a script sweeping studies, the
runner's benchmark): call ``start()`` once. The CLI runs one study and does not: started there beside
its own imports, the zygote slowed them by ~120 ms (medians of 6 fresh processes each way: 0.99 s
against 0.87 s), more than the fork it saves costs on a small study (~15-40 ms).

This module imports only the standard library.
"""

from __future__ import annotations

import json
import os
import pickle
import select
import signal
import socket
import struct
import subprocess
import sys

BOOT = ("import sys, json; sys.path[:] = json.loads(sys.argv[1]); "
        "from pdverify.zygote import main; main(int(sys.argv[2]))")
_LEN = struct.Struct("<Q")

available = sys.platform.startswith("linux") and hasattr(socket, "send_fds")


class _Zygote:
    def __init__(self, proc: subprocess.Popen, sock: socket.socket):
        self.owner, self.proc, self.sock = os.getpid(), proc, sock
        self.fingerprint = None  # what it runs, once it said it is ready
        self.dead = False


_zygote: _Zygote | None = None


def start() -> bool:
    """Launch the zygote once per process (returns at once; it imports in the background). False where
    it cannot be had (not Linux, no process to be had)."""
    global _zygote
    if not available or len(os.sched_getaffinity(0)) < 2:  # on one CPU it would take the runner's time
        return False
    if _zygote is not None and _zygote.owner == os.getpid() and not _zygote.dead:
        return True
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        proc = subprocess.Popen([sys.executable, "-c", BOOT, json.dumps(sys.path), str(theirs.fileno())],
                                pass_fds=[theirs.fileno()], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
    except OSError:
        ours.close()
        return False
    finally:
        theirs.close()
    _zygote = _Zygote(proc, ours)
    return True


def stop(timeout: float = 30.0) -> None:
    """End this process's zygote (it exits when its socket closes) and wait for it; killed if it has not
    exited within ``timeout`` seconds (it reads the socket only once its imports are done)."""
    global _zygote
    z, _zygote = _zygote, None
    if z is None or z.owner != os.getpid():
        return
    if not z.dead:
        z.sock.close()
    try:
        z.proc.wait(timeout)
    except subprocess.TimeoutExpired:
        z.proc.kill()
        z.proc.wait()


def fingerprint() -> tuple:
    """What a recorder computes with: the code digest and every registered model's class."""
    from .registry import models
    from .study.spec import code_digest

    return code_digest(), tuple((name, type(m).__module__, type(m).__qualname__) for name, m in models().items())


def ready(wait: float = 0.0) -> bool:
    """Whether the zygote is up and runs the code this process runs; one still importing is waited for up
    to ``wait`` seconds."""
    z = _zygote
    if z is None or z.owner != os.getpid() or z.dead:
        return False
    if z.fingerprint is None:
        if not select.select([z.sock], [], [], wait)[0]:
            return False  # still importing
        head = _recv_exactly(z.sock, _LEN.size)
        body = _recv_exactly(z.sock, _LEN.unpack(head)[0]) if head else None
        if body is None:
            return _dead(z)
        z.fingerprint = pickle.loads(body)
    return z.fingerprint == fingerprint()


def fork(fds: list[int]) -> bool:
    """Ask the zygote for a child holding ``fds`` (it closes its copies; the caller keeps its own). The
    child reads its work from ``fds[0]`` (:func:`pdverify.study.recorder.serve_job`). False when the
    zygote cannot serve (never waits for one still importing): the caller forks itself."""
    if not ready():
        return False
    try:
        socket.send_fds(_zygote.sock, [b"F"], fds)
    except OSError:
        return _dead(_zygote)
    return True


def _dead(z: _Zygote) -> bool:
    z.dead = True
    z.sock.close()
    z.proc.poll()
    return False


def _recv_exactly(sock: socket.socket, n: int) -> bytes | None:
    buf = b""
    while len(buf) < n:
        part = sock.recv(n - len(buf))
        if not part:
            return None
        buf += part
    return buf


def main(fd: int) -> None:
    """The zygote: import the study code, say so with its fingerprint, then fork a recorder for each
    request until the socket closes."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # children are reaped by the kernel
    sock = socket.socket(fileno=fd)
    from .study import recorder, runner  # the recorder's code, imported once here

    body = pickle.dumps(fingerprint())
    sock.sendall(_LEN.pack(len(body)) + body)
    runner.environment()  # what every recorder reads once (~15 ms: after saying it is ready, the runner
    #                       does not wait for a fork)
    runner.warm_up()  # Arrow's writers' first use, paid here once instead of in every recorder
    while True:
        try:
            msg, fds, _, _ = socket.recv_fds(sock, 1, 2)
        except OSError:
            return
        if not msg:
            return  # the runner's process closed its end: it ended
        try:
            pid = os.fork()
        except OSError:
            pid = -1
        if pid == 0:
            code = 1
            try:
                signal.signal(signal.SIGCHLD, signal.SIG_DFL)
                sock.close()
                recorder.serve_job(*fds)
                code = 0
            finally:
                os._exit(code)
        for f in fds:
            os.close(f)  # the child's now (or nobody's, if the fork failed: the runner sees the pipes end)
