"""Headless Chromium driven over its DevTools protocol through a pipe (``--remote-debugging-pipe``: messages are
JSON, each ended by a NUL byte, on file descriptors 3 (to the browser) and 4 (from it)): no port, no websocket,
nothing beyond the standard library. The browser is started with no network use of its own (no background
networking, component updates or sync) and a fresh profile; the page's requests are recorded, so a test can
check that none leaves the page."""

from __future__ import annotations

import base64
import json
import os
import select
import shutil
import subprocess
from pathlib import Path

FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-default-apps",
    "--disable-extensions",
    "--no-first-run",
    "--no-default-browser-check",
    "--remote-debugging-pipe",
)
TIMEOUT_S = 60.0  # one protocol answer: far above any load of a local page, only a hung browser reaches it


class BrowserError(RuntimeError):
    pass


class Browser:
    """One Chromium process and one page (tab) in it; use as a context manager."""

    def __init__(self, chromium: str, profile: Path, width: int = 1280, height: int = 900):
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def wire():  # in the child: the protocol's descriptors are 3 (commands in) and 4 (answers out)
            os.dup2(to_browser_r, 3)
            os.dup2(from_browser_w, 4)

        self.proc = subprocess.Popen(
            [chromium, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}", "about:blank"],
            preexec_fn=wire,
            pass_fds=(3, 4),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._buf = b""
        self._id = 0
        self.events: list[dict] = []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        for domain in ("Page", "Runtime", "Network", "Log"):
            self.send(f"{domain}.enable")
        self.send("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(timeout=30)
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass

    # -- the protocol --------------------------------------------------------------------------------------
    def _message(self) -> dict:
        while b"\0" not in self._buf:
            ready, _, _ = select.select([self._from_browser], [], [], TIMEOUT_S)
            if not ready:
                raise BrowserError(f"no answer from chromium in {TIMEOUT_S:g} s")
            chunk = os.read(self._from_browser, 1 << 20)
            if not chunk:
                raise BrowserError("chromium closed the protocol pipe (it exited)")
            self._buf += chunk
        msg, _, self._buf = self._buf.partition(b"\0")
        return json.loads(msg)

    def call(self, method: str, session: str | None = None, **params) -> dict:
        """Send a command and wait for its answer; events that arrive meanwhile are kept in ``events``."""
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        while data:
            data = data[os.write(self._to_browser, data) :]
        while True:
            answer = self._message()
            if answer.get("id") == self._id:
                if "error" in answer:
                    raise BrowserError(f"{method}: {answer['error']}")
                return answer.get("result", {})
            self.events.append(answer)

    def send(self, method: str, **params) -> dict:
        """A command to the page."""
        return self.call(method, self.session, **params)

    def wait_for(self, method: str) -> dict:
        for i, e in enumerate(self.events):
            if e.get("method") == method:
                return self.events.pop(i)
        while True:
            msg = self._message()
            if msg.get("method") == method:
                return msg
            self.events.append(msg)

    # -- what a test needs -----------------------------------------------------------------------------------
    def open(self, url: str) -> None:
        """Navigate and wait for the load event."""
        self.events.clear()
        self.send("Page.navigate", url=url)
        self.wait_for("Page.loadEventFired")

    def evaluate(self, expression: str):
        """The value of a JavaScript expression in the page (an exception in it raises BrowserError)."""
        r = self.send("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise BrowserError(f"{expression[:80]}: {r['exceptionDetails'].get('text')}")
        return r["result"].get("value")

    def console_errors(self) -> list[str]:
        """Errors the page reported: uncaught exceptions, console.error and .warn calls, log entries of level error."""
        out = []
        for e in self.events:
            m, p = e.get("method"), e.get("params", {})
            if m == "Runtime.exceptionThrown":
                out.append(str(p.get("exceptionDetails", {}).get("exception", {}).get("description") or p))
            elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "warning", "assert"):
                out.append(" ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", [])))
            elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
                out.append(p["entry"].get("text", ""))
        return out

    def requests(self) -> list[str]:
        """The URLs the page requested since it was opened (the page itself included)."""
        return [e["params"]["request"]["url"] for e in self.events if e.get("method") == "Network.requestWillBeSent"]

    def screenshot(self, path: Path, selector: str | None = None) -> Path:
        """A PNG of the viewport at the top of the page, or of the first element matching ``selector``."""
        params = {"format": "png"}
        if selector is not None:
            # sticky and fixed elements (a filter bar) would lie over the element: they stay in the page's flow;
            # content the page lays out only when scrolled to (content-visibility) is laid out and painted now; the
            # element is measured once two frames have passed and it no longer moves
            measure = (
                f"(function () {{ var e = document.querySelector({json.dumps(selector)}); if (!e) return null;"
                " document.querySelectorAll('body *').forEach(function (x) {"
                "   var p = getComputedStyle(x).position;"
                "   if (p === 'sticky' || p === 'fixed') x.style.position = 'static'; });"
                " if (!document.getElementById('shot-style')) { var st = document.createElement('style');"
                "   st.id = 'shot-style'; st.textContent = '* { content-visibility: visible !important; }';"
                "   document.head.appendChild(st); }"
                " e.scrollIntoView();"
                " return new Promise(function (done) { requestAnimationFrame(function () {"
                "   requestAnimationFrame(function () { var r = e.getBoundingClientRect();"
                "     done({x: r.left + scrollX, y: r.top + scrollY, width: r.width, height: r.height}); }); }); });"
                " })()"
            )
            box, last = self.evaluate(measure), None
            for _ in range(10):
                if box is None or box == last:
                    break
                box, last = self.evaluate(measure), box
            if box is None:
                raise BrowserError(f"no element {selector} to photograph")
            params.update(clip=dict(box, scale=1), captureBeyondViewport=True)
        data = self.send("Page.captureScreenshot", **params)["data"]
        path.write_bytes(base64.b64decode(data))
        return path


def find() -> str | None:
    """The Chromium executable on PATH, or None."""
    return shutil.which("chromium") or shutil.which("chromium-browser")
