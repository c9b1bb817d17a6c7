"""Shared pieces of the test suite: a base scene and its variants, the support pairs and load sets every model is
checked on, and ways to run pdverify's command line (in this process, or in a child process)."""

import copy
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pdverify.core.scene import is_mechanism

ROOT = Path(__file__).resolve().parents[1]  # the repository
STUDIES = ROOT / "studies"
TESTS = ROOT / "tests"

BASE = {
    "name": "test beam",
    "beam": {"length": 2.0},
    "section": {"width": 0.05, "height": 0.1},
    "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33},
    "supports": {"left": "clamped", "right": "free"},
    "loads": [],
}


SUPPORTS = ("clamped", "pinned", "free", "guided")
# every support pair that holds the beam (the mechanisms are rejected by the scene validator)
PAIRS = [(l, r) for l in SUPPORTS for r in SUPPORTS if not is_mechanism(l, r)]
# forces and moments anywhere, also at both ends, uniform and sine loads on partial spans
MIXED_LOADS = [
    {"type": "point_force", "position": 0.7, "value": -300.0},
    {"type": "point_moment", "position": 1.3, "value": 150.0},
    {"type": "distributed", "value": -500.0, "start": 0.2, "end": 1.1},
    {"type": "distributed", "value": 400.0, "shape": "sine"},
    {"type": "point_force", "position": 2.0, "value": 80.0},
    {"type": "point_moment", "position": 0.0, "value": -60.0},
]
# a force, a moment and span ends between the grid points of the usual grids (L = 2)
OFF_GRID_LOADS = [
    {"type": "point_force", "position": 0.733, "value": -100.0},
    {"type": "point_moment", "position": 1.417, "value": 40.0},
    {"type": "distributed", "value": -70.0, "start": 0.311, "end": 1.29},
]


def _sigint_default() -> None:
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start_in_own_group(cmd: list[str]) -> subprocess.Popen:
    """``cmd`` in a process group of its own (a test signals the whole group, as a terminal sends Ctrl-C), run
    from the repository, pipes for its output, SIGINT at its default as for a terminal's foreground job: a
    process started in the background by a non-interactive shell (``cmd &``, e.g. a CI runner) inherits
    SIGINT ignored, and Python then installs no KeyboardInterrupt handler."""
    return subprocess.Popen(
        cmd,
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
        preexec_fn=_sigint_default,
    )


def pdverify_process(*args, cwd=ROOT, timeout: float = 300) -> subprocess.CompletedProcess:
    """``python -m pdverify.apps.cli ARGS`` in a child process (text output captured; pdverify from this checkout):
    for what only a real process shows (exit codes, stderr, signals, start-up)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "pdverify.apps.cli", *map(str, args)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def own_grid(line: str) -> bool:
    """Whether a warning is a static solve's own estimate from the same solve on about half the points
    (pdverify/registry/grid_check.py: "the same solve on N points differs from this one on n by ...")."""
    return ": the same solve on " in line


def scene_dict(left="clamped", right="free", loads=(), **over):
    d = copy.deepcopy(BASE)
    d["supports"] = {"left": left, "right": right}
    d["loads"] = [dict(l) for l in loads]
    for k, v in over.items():
        d[k] = v
    return d


def load_edge_error(model: str, right, spacings: float, **options) -> tuple[float, list[str]]:
    """A 1 m steel beam (10 x 10 mm) clamped at the left, ``right`` at the right, under a uniform load from 0.3 m to
    ``spacings`` spacings of 101 points from the right end, solved with ``options``: (the model's largest error of w
    against exact-eb relative to its largest value, the warnings about a load edge inside the ghosts' fit)."""
    import numpy as np

    from pdverify.core.scene_file import parse_scene
    from pdverify.exact.straight import solve_straight
    from pdverify.registry import run

    d = scene_dict(
        "clamped", right, [{"type": "distributed", "value": -1.0, "start": 0.3, "end": 1.0 - spacings / 100}]
    )
    d.update(beam={"length": 1.0}, section={"width": 0.01, "height": 0.01})
    d["material"] = {"youngs_modulus": 2e11, "poissons_ratio": 0.3}
    sc = parse_scene(d)
    r = run(sc, model, points=101, **options)
    exact = solve_straight(sc, False).fields(r.x)["w"]
    said = [w for w in r.info.get("warnings", []) if "its ghosts are fitted on" in w]
    return float(np.abs(r.w - exact).max() / np.abs(exact).max()), said


def cli(args, capsys) -> tuple[int, str, str]:
    """(exit code, stdout, stderr) of ``pdverify ARGS`` run in this process."""
    from pdverify.apps.cli import main

    capsys.readouterr()
    with pytest.raises(SystemExit) as exc:
        main([str(a) for a in args])
    out, err = capsys.readouterr()
    return exc.value.code, out, err
