"""``pdverify bench --large-horizon``: the large-horizon solver beside the banded solve at a fixed horizon length.

At a fixed horizon delta the horizon factor m = delta / dx grows with the grid, and a banded LU of the PD operator
costs O(N m^2). The Krylov path (:mod:`pdverify.numerics.krylov`: FFT Toeplitz products, a sine-transform
preconditioner) solves the same system in O(N log N) per iteration. Each row times one model on one grid with
``solver = krylov`` and with ``solver = banded`` (each in a fresh process, as every bench row) and gives the largest
difference of the two deflections relative to the largest deflection, which must be below :data:`AGREE`, beside
each solve's own round-off bound (docs/trust.md): where the bounds are larger, neither solve is known to that
accuracy and the difference says how far apart two equally trustworthy answers are.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from ..core.errors import InputError
from ..core.scene_file import load_scene
from ..registry import run
from .bench import failed_runs
from .output import check_folder

SCENE = Path(__file__).resolve().parents[2] / "studies" / "nonlocal" / "pp_sine.toml"
POINTS = 2**14 + 1  # m = 1638.4 at delta = 0.1 L
HORIZON = 0.1  # delta / L
AGREE = 1e-8  # the Krylov solution within this of the banded one (relative to the largest deflection)
# the operators the Krylov path takes: bands Toeplitz away from their ends, one contiguous run of unknowns
MODELS = {"pd-eb": {"variant": "paper"}, "pd-bond-pair": {"form": "direct"}}


def solve_once(model: str, points: int, solver: str, scene_path: str | None = None) -> dict:
    """One solve in this process: its timings and deflection (a list)."""
    scene = load_scene(scene_path or SCENE)
    # the solve's cost: no second solve on half the points (the two solvers' agreement is what is measured)
    r = run(
        scene,
        model,
        points=points,
        horizon_length=HORIZON * scene.length,
        solver=solver,
        grid_check=False,
        **MODELS[model],
    )
    return {
        "total_s": r.timings.get("total_s"),
        "assemble_s": r.timings.get("assemble_s"),
        "solve_s": r.timings.get("solve_s"),
        "m": r.info.get("m"),
        "solver_choice": r.info.get("solver_choice"),
        "error_bound": r.info.get("error_bound"),
        "w": np.asarray(r.w, float).tolist(),
    }


def _subprocess(model: str, points: int, solver: str, scene_path: str | None, timeout: float) -> dict:
    code = (
        "import json; from pdverify.apps.bench_horizon import solve_once; "
        f"print(json.dumps(solve_once({model!r}, {int(points)}, {solver!r}, {scene_path!r})))"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        raise RuntimeError((proc.stderr.strip().splitlines() or ["failed"])[-1])
    return json.loads(proc.stdout.strip().splitlines()[-1])


def large_horizon_row(model: str, points: int = POINTS, scene_path: str | None = None, timeout: float = 7200) -> dict:
    """The bench row of ``model`` at ``points``: Krylov and banded times beside each other and their difference."""
    row = {"model": model, "points": points, "horizon": f"{HORIZON:g} L", "options": MODELS[model]}
    try:
        k = _subprocess(model, points, "krylov", scene_path, timeout)
        b = _subprocess(model, points, "banded", scene_path, timeout)
    except (RuntimeError, subprocess.TimeoutExpired) as exc:
        return {**row, "status": "failed", "message": str(exc)}
    wk, wb = np.array(k.pop("w")), np.array(b.pop("w"))
    diff = float(np.abs(wk - wb).max() / np.abs(wb).max())
    row.update(
        m=k["m"],
        krylov_s=k["total_s"],
        krylov_solve_s=k["solve_s"],
        banded_s=b["total_s"],
        banded_solve_s=b["solve_s"],
        assemble_s=b["assemble_s"],
        difference=diff,
        krylov_bound=k["error_bound"],
        banded_bound=b["error_bound"],
        agrees=diff <= AGREE,
        status="ok",
    )
    return row


def _e(v) -> str:
    return "-" if v is None else f"{v:.1e}"


def describe(row: dict) -> str:
    """The row as one line of ``pdverify bench``'s table."""
    if row.get("status") != "ok":
        return f"{row['model']:18s} {row['points']:>9d}  large horizon: failed: {row.get('message')}"
    return (
        f"{row['model']:18s} {row['points']:>9d} delta={row['horizon']} m={row['m']:.1f} "
        f"krylov={row['krylov_s']:.3g}s (solve {row['krylov_solve_s']:.3g}s) "
        f"banded={row['banded_s']:.3g}s (solve {row['banded_solve_s']:.3g}s) "
        f"difference={row['difference']:.1e} ({'within' if row['agrees'] else 'NOT within'} {AGREE:g}; round-off "
        f"bounds: krylov {_e(row['krylov_bound'])}, banded {_e(row['banded_bound'])})"
    )


def bench_command(names, points, as_json: bool, scene, out, echo) -> None:
    """``pdverify bench --large-horizon``: one row per model and size, printed (``as_json``: one object per line);
    ``out``: also DIR/bench_large_horizon.jsonl and the page DIR/index.html."""
    names = names or list(MODELS)
    for n in names:
        if n not in MODELS:
            raise InputError(f"--model {n}: --large-horizon times {', '.join(MODELS)}; drop the model")
    if out is not None:
        check_folder(out, "--out")
    if scene is not None:
        load_scene(scene)  # a missing or bad scene: one line, exit 2, before any timing
    rows = [large_horizon_row(n, p, str(scene) if scene else None) for n in names for p in (points or [POINTS])]
    for row in rows:
        echo(json.dumps(row) if as_json else describe(row))
    if out is not None:
        from ..report.perf import build_large_horizon  # the report layer, only when a page is asked for

        page = build_large_horizon(rows, out)
        if not as_json:
            echo(f"performance page: {page}")
    failed_runs(rows)
