"""External models: a command in any language, described by a TOML manifest.

```toml
name = "my-julia-pd"                        # the model's name in pdverify
title = "My PD beam (Julia)"
command = ["julia", "solve.jl", "{input}"]  # {input}: path of the input JSON (else the JSON is on stdin)
                                            # {output}: path to write the result to (else: stdout)
                                            # {python}: this Python; {dir}: the manifest's folder
timeout = 60                                # seconds per solve (default 60)
[capabilities]                              # all optional; defaults as a built-in model's
theory = "euler-bernoulli"                  # euler-bernoulli | timoshenko | higher-order | continuum | axial | torsion
measures = "w"                              # what a study measures: w, or a field of the result (u, twist)
curved = false
axial = false
torsion = false
[options.points]                            # every option: type (int | float | str | bool), default
type = "int"
default = 101
minimum = 2
[options.horizon]
type = "float"
default = 3.0
help = "horizon / spacing"
```

The command runs in the manifest's folder. Input JSON: ``{"model": name, "scene": <the scene as a
table, the scene file's keys>, "options": {...}}``. Result JSON: ``{"x": [...], "w": [...]}`` and optionally
``"rotation"`` (same length), ``"fields"`` ({name: same-length list}), ``"timings"`` ({"assemble_s": s,
"solve_s": s}), ``"dofs"``, ``"info"``. Any failure (non-zero exit, timeout, not JSON, missing or
ragged arrays, NaN) is a :class:`~pdverify.core.errors.SolveError` of one line naming the model and the case.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from ..core.contract import Model, Option
from ..core.errors import InputError, SolveError
from ..core.result import Result
from ..core.scene import Scene
from ..core.scene_file import read_toml

KINDS = {"int": int, "float": float, "str": str, "bool": bool}
CAPABILITIES = {
    "theory": str,
    "measures": str,
    "curved": bool,
    "axial": bool,
    "torsion": bool,
    "bending": bool,
    "kind": str,
}
MANIFEST_KEYS = {"name", "title", "source", "command", "timeout", "capabilities", "options"}


def _option(path: Path, name: str, spec) -> Option:
    where = f"{path}: options.{name}"
    if not isinstance(spec, dict) or spec.get("type") not in KINDS or "default" not in spec:
        raise InputError(f"{where}: give a table with type (int, float, str or bool) and default")
    extra = set(spec) - {"type", "default", "help", "choices", "minimum", "maximum"}
    if extra:
        raise InputError(
            f"{where}: unknown key {sorted(extra)[0]!r}; allowed: type, default, help, choices, minimum, maximum"
        )
    choices = spec.get("choices")
    return Option(
        name,
        KINDS[spec["type"]],
        spec["default"],
        spec.get("help", ""),
        tuple(choices) if choices else None,
        spec.get("minimum"),
        False,
        spec.get("maximum"),
    )


def load_manifest(path: str | Path) -> ExternalModel:
    """Read and check a manifest; InputError naming the file and the field otherwise."""
    path = Path(path).resolve()
    _, data = read_toml(path, "external model manifest")
    for key in data:
        if key not in MANIFEST_KEYS:
            raise InputError(f"{path}: unknown key {key!r}; allowed: {', '.join(sorted(MANIFEST_KEYS))}")
    name, command = data.get("name"), data.get("command")
    if not isinstance(name, str) or not name or any(c.isspace() for c in name):
        raise InputError(f"{path}: name = {name!r}: give the model a name without spaces")
    if not isinstance(command, list) or not command or not all(isinstance(c, str) for c in command):
        raise InputError(f'{path}: command = {command!r}: give a list of strings, e.g. ["{{python}}", "model.py"]')
    timeout = data.get("timeout", 60)
    if not isinstance(timeout, (int, float)) or isinstance(timeout, bool) or not timeout > 0:
        raise InputError(f"{path}: timeout = {timeout!r}: give a positive number of seconds")
    caps = data.get("capabilities", {})
    for key, value in caps.items():
        if key not in CAPABILITIES or not isinstance(value, CAPABILITIES[key]):
            raise InputError(
                f"{path}: capabilities.{key} = {value!r}: allowed: "
                + ", ".join(f"{k} ({t.__name__})" for k, t in CAPABILITIES.items())
            )
    options = tuple(
        _option(path, k, v) for k, v in data.get("options", {"points": {"type": "int", "default": 101}}).items()
    )
    return ExternalModel(
        path,
        name,
        data.get("title", f"external command {command[0]}"),
        data.get("source", str(path)),
        list(command),
        float(timeout),
        options,
        caps,
    )


class ExternalModel(Model):
    """A model whose solve runs the manifest's command (see the module docstring for the protocol)."""

    def __init__(
        self,
        path: Path,
        name: str,
        title: str,
        source: str,
        command: list[str],
        timeout: float,
        options: tuple,
        capabilities: dict,
    ):
        self.path, self.name, self.title, self.source = path, name, title, source
        self.command, self.timeout, self.options = command, timeout, options
        for key, value in capabilities.items():
            setattr(self, key, value)

    def _case(self, scene: Scene, params: dict) -> str:
        return f"model {self.name} on scene {scene.name!r} (" + ", ".join(f"{k}={v}" for k, v in params.items()) + ")"

    def solve(self, scene: Scene, params: dict) -> Result:
        case = self._case(scene, params)
        payload = json.dumps({"model": self.name, "scene": scene.to_dict(), "options": params})
        with tempfile.TemporaryDirectory(prefix="pdverify-external-") as tmp:
            inp, outp = Path(tmp) / "input.json", Path(tmp) / "result.json"
            subst = {
                "{input}": str(inp),
                "{output}": str(outp),
                "{python}": sys.executable,
                "{dir}": str(self.path.parent),
            }
            argv = [subst.get(a, a) for a in self.command]
            via_file = "{input}" in self.command
            if via_file:
                inp.write_text(payload)
            t0 = time.perf_counter()
            out, err, code = _run(argv, None if via_file else payload, self.path.parent, self.timeout, case)
            wall = time.perf_counter() - t0
            if code != 0:
                last = (err.strip().splitlines() or ["(nothing on stderr)"])[-1][:300]
                raise SolveError(f"{case}: command exited with status {code}: {last}")
            if "{output}" in self.command:
                if not outp.exists():
                    raise SolveError(f"{case}: the command wrote no result file ({{output}})")
                out = outp.read_text(errors="replace")
        return _result(case, out, scene, self.name, params, wall)


def _run(argv: list[str], stdin: str | None, cwd: Path, timeout: float, case: str) -> tuple[str, str, int]:
    """Run the command in its own process group (a timeout kills its children too)."""
    try:
        proc = subprocess.Popen(
            argv,
            cwd=cwd,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
        )
    except OSError as exc:
        raise SolveError(f"{case}: cannot start {argv[0]!r}: {exc.strerror or exc}") from None
    try:
        out, err = proc.communicate(stdin, timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise SolveError(f"{case}: no result after the timeout of {timeout:g} s (manifest: timeout); killed") from None
    return out, err, proc.returncode


def _array(case: str, data: dict, key: str, n: int | None) -> np.ndarray:
    try:
        a = np.asarray(data[key], dtype=float)
    except (TypeError, ValueError):
        raise SolveError(f"{case}: result {key} is not a list of numbers") from None
    if a.ndim != 1 or (n is not None and len(a) != n):
        raise SolveError(f"{case}: result {key} has {a.size} values, x has {n}; give one value per point")
    if not np.isfinite(a).all():
        raise SolveError(
            f"{case}: result {key} holds NaN or infinite values (first at index {int(np.argmin(np.isfinite(a)))})"
        )
    return a


def _result(case: str, text: str, scene: Scene, name: str, params: dict, wall: float) -> Result:
    """Check the command's result JSON and turn it into a Result."""
    try:
        data = json.loads(text)
    except ValueError:
        first = (text.strip().splitlines() or [""])[0][:80]
        raise SolveError(f"{case}: the result is not JSON (starts {first!r})") from None
    if not isinstance(data, dict) or "x" not in data or "w" not in data:
        raise SolveError(f"{case}: the result JSON needs an object with lists x and w")
    x = _array(case, data, "x", None)
    if len(x) < 2:
        raise SolveError(f"{case}: result x has {len(x)} values; give at least 2 points")
    w = _array(case, data, "w", len(x))
    rot = _array(case, data, "rotation", len(x)) if data.get("rotation") is not None else None
    fields = data.get("fields") or {}
    if not isinstance(fields, dict):
        raise SolveError(f"{case}: result fields must be an object {{name: list}}")
    fields = {k: _array(case, fields, k, len(x)) for k in fields}
    timings = data.get("timings") or {}
    if not isinstance(timings, dict) or not all(
        isinstance(v, (int, float)) and math.isfinite(v) for v in timings.values()
    ):
        raise SolveError(f"{case}: result timings must be an object of seconds")
    timings = {k: float(v) for k, v in timings.items()}
    timings.setdefault("command_s", wall)
    info = data.get("info") if isinstance(data.get("info"), dict) else {}
    dofs = data.get("dofs", len(x))
    return Result(
        scene.name,
        name,
        dict(params),
        x,
        w,
        rot,
        fields,
        int(dofs) if isinstance(dofs, (int, float)) else len(x),
        timings,
        info,
    )
