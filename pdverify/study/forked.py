"""One more core: a function run in a forked copy of this process while the caller goes on (Linux), its value sent
back through a pipe (the report's sweep figures, a card's dynamics and nonlocal checks). The copy shares what the caller
has read (a study's tables and cases): nothing is pickled but the value. Where fork is unavailable, in a copy itself
(a daemonic process cannot fork), or when the copy fails or dies, the function runs here when its value is asked for,
so the result is the same either way (the functions given are deterministic)."""

from __future__ import annotations

import multiprocessing
import sys


def start(fn):
    """Start ``fn()``; a function that returns its value."""
    if not sys.platform.startswith("linux"):
        return fn
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)

    def child() -> None:
        try:
            value = ("ok", fn())
        except BaseException:  # noqa: BLE001 - the parent runs fn itself and meets the error there
            value = ("failed", None)
        send.send(value)

    proc = ctx.Process(target=child, daemon=True)
    try:
        proc.start()
    except (OSError, AssertionError):  # no process to spare, or this is a (daemonic) copy itself: run it here
        receive.close()
        send.close()
        return fn
    send.close()

    def result():
        try:
            kind, value = receive.recv()
        except (EOFError, OSError):  # the copy died
            kind, value = "failed", None
        finally:
            receive.close()
            proc.join()
        return value if kind == "ok" else fn()

    return result
