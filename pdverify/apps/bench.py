"""``pdverify bench``: cost of each model against the physical limit of its own linear system.

For a static model the limit is the banded direct solve of its own assembled matrix
(``scipy.linalg.solve_banded`` on the same band, timed in the same run). Each (model, points) case runs
in a fresh subprocess so its peak memory (resident set above the post-import baseline) is its own.
Models are probed through their declared contract (pdverify/registry.py): a model with ``assembles``
gets a limit from the :class:`~pdverify.registry.System` its ``assemble`` returns; a model with
``"dynamic"`` in its ``analyses`` gets a rate from ``bench_dynamics`` (point-updates per second).
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from ..core.contract import Model
from ..core.errors import SolveError
from ..core.scene_file import load_scene
from ..exact.straight import solve_straight
from ..numerics.band import Band
from ..numerics.linalg import diagonal_scaling
from ..registry import get_model, models, run

EXAMPLES = Path(__file__).resolve().parents[2] / "studies" / "examples"
BENCH_SCENE = EXAMPLES / "cantilever_tip_load.toml"


def default_scene(model) -> Path:
    """The bench scene a model can solve: its own ``bench_scene`` (a path under studies/) if it names
    one, else the cantilever (bending), the rod (axial) or the shaft (torsion)."""
    if model.bench_scene:
        return EXAMPLES.parent / model.bench_scene
    if model.bending:
        return BENCH_SCENE
    if model.torsion and not model.axial:
        return EXAMPLES / "shaft_tip_torque.toml"
    return EXAMPLES / "rod_tip_load.toml"


def max_error(scene, model, result) -> float | None:
    """max |w - w_exact| / max |w_exact| at the result's points against the exact beam solution of the
    model's theory (Euler–Bernoulli for ``theory = "euler-bernoulli"``, Timoshenko otherwise: a
    higher-order or continuum model's distance from it is part of its error). None where pdverify has no
    exact elastic solution of the field: a curved axis, an axial or torsion model (w identically zero), a material
    past elasticity, a load path (yield_stress, failure_strain, [loading], prescribed deflections) or a transient
    (its w is the state at the end time, not the static deflection)."""

    w = np.asarray(result.w, float)
    laws = any(mat.yield_stress is not None or mat.failure_strain is not None for *_, mat in scene.pieces())
    path = scene.loading is not None or any(ld.type == "displacement" for ld in scene.loads)
    transient = result.info.get("analysis") == "dynamic"
    if not scene.is_straight or not np.any(w) or laws or path or transient:
        return None
    shear = model.theory != "euler-bernoulli"
    exact = solve_straight(scene, shear).fields(result.x)["w"]
    top = float(np.abs(exact).max())
    return float(np.abs(w - exact).max() / top) if top > 0 else None


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: kB


def bench_case(model: str, points: int, scene_path: str | None = None, repeat: int = 2) -> dict:
    """One measurement, in this process. Returns the row printed by ``pdverify bench``.

    total = best of ``repeat`` whole runs (parse, assemble, solve), limit = best of 3 banded solves:
    both warm, so the first-touch page faults of the first run's arrays count in neither."""
    import scipy.linalg as sla

    m = get_model(model)
    path = scene_path or str(default_scene(m))
    load_scene(path)  # warm the parser (imports) outside the timing
    base = _rss_mb()
    best = None
    for _ in range(max(1, repeat)):
        t0 = time.perf_counter()
        scene = load_scene(path)
        res = run(scene, m, points=points, grid_check=False)  # the solve's cost; its error is measured (max_error)
        total = time.perf_counter() - t0
        if best is None or total < best[0]:
            best = (total, res)
    total, res = best
    peak = _rss_mb() - base  # the model's own peak, before the limit measurement below allocates its copies
    row = {
        "model": model,
        "points": points,
        "dofs": int(res.dofs),
        "max_error": max_error(scene, m, res),
        "error_bound": res.info.get("error_bound"),
        "assemble_s": res.timings.get("assemble_s"),
        "solve_s": res.timings.get("solve_s"),
        "total_s": total,
        "limit_s": None,
        "ratio": None,
        "bandwidth": None,
        "peak_mem_mb": None,
        "mem_per_point_kb": None,
        "updates_per_s": None,
    }
    params = m.resolve(scene, {"points": points})
    if m.assembles and m.linear(params):
        system = m.assemble(scene, params)
        K, b = system.matrix, system.rhs
        del system
        B = K if isinstance(K, Band) else Band.from_sparse(K)
        # the same symmetric diagonal scaling solve_linear applies (else LAPACK may call it singular)
        s = diagonal_scaling(B.diag(0))
        B.scale(s)
        lo, up = B.lower, B.upper
        ab = B.data  # solve_banded's own (lower + upper + 1, n) layout
        del B, K
        rhs = s * np.asarray(b, float)
        limit = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            sla.solve_banded((lo, up), ab, rhs, check_finite=False)
            limit = min(limit, time.perf_counter() - t0)
        row.update(limit_s=limit, ratio=total / limit, bandwidth=lo + up + 1)
    if times_dynamics(m) and scene.material.density is not None:  # a mass needs a density
        row["updates_per_s"] = float(m.bench_dynamics(scene, params, steps=200))
    row["peak_mem_mb"] = max(peak, 0.0)
    row["mem_per_point_kb"] = max(peak, 0.0) * 1024 / points
    return row


def bench_subprocess(model: str, points: int, scene_path: str | None = None, timeout: float = 600) -> dict:
    code = (
        "import json,sys; from pdverify.apps.bench import bench_case; "
        f"print(json.dumps(bench_case({model!r}, {int(points)}, {scene_path!r})))"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        msg = (proc.stderr.strip().splitlines() or ["failed"])[-1]
        return {"model": model, "points": points, "status": "failed", "message": msg}
    row = json.loads(proc.stdout.strip().splitlines()[-1])
    row["status"] = "ok"
    return row


DEFAULT_POINTS = (1_000, 10_000, 100_000, 1_000_000)
SMALL_MODELS = {
    "pd-higher-order": 100_000,
    "pd-curved": 100_000,  # the largest size timed for 4-DOF / PDDO models
    "pd-curved-mms": 10_000,
}  # a verification harness: its sympy-built loads dominate its time at 1e5


def times_dynamics(m) -> bool:
    """Whether the model's time integrator can be timed: ``"dynamic"`` in its analyses and its own
    ``bench_dynamics`` (an exact modal solution or an implicit FEM transient declares the analysis and has none)."""
    return "dynamic" in m.analyses and type(m).bench_dynamics is not Model.bench_dynamics


def default_models() -> list[str]:
    """The models with an assembled system or a timed integrator (what a row measures)."""
    return [n for n, m in models().items() if m.assembles or times_dynamics(m)]


def failed_runs(rows: list[dict]) -> None:
    """After every row is printed and written: SolveError (exit 3) naming the failed runs, if any."""
    failed = [r for r in rows if r.get("status") != "ok"]
    if failed:
        first = failed[0]
        raise SolveError(
            f"{len(failed)} of {len(rows)} timed runs failed (first: {first['model']} at {first['points']} points: "
            f"{first.get('message')}); the other rows are printed and written"
        )
