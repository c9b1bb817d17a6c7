"""Atomic file writes, and the case-writer process that makes them off the solving thread.

Standard library only, because the writer runs this file as a script (``python -S -I _case_writer.py``:
no site-packages, no pdverify import) with the runner's pipe on its standard input. Each message is
``<u8 path length> <u8 data length> path data`` (little-endian). At end of file the writer exits 0; on
the first failure it prints the error on standard output (the runner's status pipe) and exits 1.
SIGINT is ignored, so after Ctrl-C it still writes what the runner gave it, then sees end of file.
"""

import os
import struct
import sys
import threading

MESSAGE = struct.Struct("<QQ")  # path length, data length


def write_atomic(path, data) -> None:
    """Write to a temporary file beside ``path`` and rename it over ``path`` (atomic on POSIX): a killed
    process leaves the old file or the new one, never a partial one. No fsync: the rename is atomic
    against a killed process, which is what resume needs. The temporary name is unique per process and
    thread (mkstemp's random names cost 0.25 ms a file here)."""
    path = os.fspath(path)
    head, name = os.path.split(path)
    tmp = os.path.join(head, f".tmp-{os.getpid()}-{threading.get_ident()}-{name}")
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    except FileNotFoundError:
        os.makedirs(head or ".", exist_ok=True)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    try:
        write_all(fd, data)
    finally:
        os.close(fd)
    os.replace(tmp, path)


def write_all(fd: int, data) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def read_exactly(fd: int, n: int):
    """n bytes from a pipe, or None at end of file before the first byte."""
    parts, got = [], 0
    while got < n:
        b = os.read(fd, min(n - got, 1 << 20))
        if not b:
            if got == 0:
                return None
            raise EOFError("the pipe closed inside a record")
        parts.append(b)
        got += len(b)
    return b"".join(parts)


def serve(fd: int = 0, status: int = 1) -> int:
    """Write every (path, data) message read from ``fd`` until end of file (exit status 0); on the first
    failure report it on ``status`` and stop (1), so the runner sees it."""
    try:
        while (head := read_exactly(fd, MESSAGE.size)) is not None:
            n_path, n_data = MESSAGE.unpack(head)
            path = os.fsdecode(read_exactly(fd, n_path))
            write_atomic(path, read_exactly(fd, n_data) if n_data else b"")
        return 0
    except BaseException as exc:  # noqa: BLE001 - reported to the runner, which raises it
        write_all(status, f"{type(exc).__name__}: {exc}".encode("utf-8", "replace"))
        return 1


if __name__ == "__main__":
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sys.exit(serve())
