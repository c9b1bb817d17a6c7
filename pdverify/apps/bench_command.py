"""``pdverify bench``: the command over :mod:`pdverify.apps.bench` (cost against the banded-solve limit per model and
size) and :mod:`pdverify.apps.sharing` (one factorisation per operator on a verification suite).

Imports are lazy, as in :mod:`pdverify.apps.cli`: ``pdverify --help`` starts without importing the library."""

from __future__ import annotations

from pathlib import Path

import typer

from ..core.contract import whole_number
from ..core.errors import InputError, OutputError
from .cliargs import given_path
from .output import Format, check_folder


def bench(
    model: list[str] | None = typer.Option(
        None, "--model", "-m", help="model(s) to time; default: all with an assembled system"
    ),
    points: list[str] | None = typer.Option(
        None, "--points", metavar="N", help="sizes; default 1e3 1e4 1e5 1e6 (1e5 max for 4-DOF/PDDO models)"
    ),
    fmt: Format = typer.Option(Format.table, "--format", help="table, or json (one object per line)"),
    scene: Path | None = typer.Option(None, help="scene to time (default: the example cantilever)"),
    out: Path | None = typer.Option(
        None, "--out", parser=given_path, help="also write DIR/bench.jsonl and the performance page DIR/index.html"
    ),
    sharing: list[str] | None = typer.Option(
        None, "--sharing", help="model(s) whose verification suite is timed with and without shared factorisations"
    ),
    large_horizon: bool = typer.Option(
        False,
        "--large-horizon",
        help="instead: the Krylov solver beside the banded one at delta = 0.1 L (default 2^14 + 1 points)",
    ),
):
    """Time assembly and solve against the banded-solve limit of the same matrix, per model and size."""
    points = [_points(p) for p in points] if points else None
    if large_horizon:
        from .bench_horizon import bench_command

        return bench_command(model, points, fmt == Format.json, scene, out, typer.echo)
    import json as _json

    from ..core.scene_file import load_scene
    from ..measure.cost import accurate, cost_slope
    from ..measure.memory import check_memory
    from ..registry import get_model, model_argument
    from .bench import DEFAULT_POINTS, SMALL_MODELS, bench_subprocess, default_models, default_scene, failed_runs

    names = [model_argument(n) for n in model] if model else default_models()  # a manifest path: an external model
    names, points = list(dict.fromkeys(names)), list(dict.fromkeys(points or ())) or None  # each once
    if out is not None:
        check_folder(out, "--out")
        others = [f for f in ("results.csv", "card.json") if (out / f).exists()]  # a study's or a card's folder
        if others:
            raise OutputError(
                f"--out {out}: holds another command's results ({others[0]}), whose index.html the performance page "
                "would replace; give another folder"
            )
    sharing = list(dict.fromkeys(model_argument(n) for n in sharing or ()))  # each once; an unknown one: exit 2 now
    for n in sharing:
        get_model(n)
    sc = load_scene(scene) if scene is not None else None  # a missing or bad scene: one line, exit 2, before timing
    for n in names:
        m = get_model(n)
        if sc is not None and (why := m.check(sc)):  # a model that cannot take the scene: before any timing
            raise InputError([f"--scene {scene}: model {n} cannot solve it: {w}" for w in why])
        grid = m.option("points")
        for p in points or ():
            if grid is None:
                raise InputError(f"--points {p}: model {n} takes no grid; drop --points or the model")
            bench_scene = sc if sc is not None else load_scene(default_scene(m))
            m.resolve(bench_scene, {"points": p})  # not a grid the model takes (its least named): one line, exit 2
            # a grid that cannot fit in memory: one line, exit 3, before any timing (as solve)
            check_memory(bench_scene, m, {"points": p})
    rows = []
    for n in names:
        sizes = points or [p for p in DEFAULT_POINTS if p <= SMALL_MODELS.get(n, 10**9)]
        for p in sizes:
            row = bench_subprocess(n, p, str(scene) if scene else None)
            rows.append(row)
            if fmt == Format.json:
                typer.echo(_json.dumps(row))
            elif row.get("status") != "ok":
                typer.echo(f"{n:18s} {p:>9d}  failed: {row.get('message')}")
            else:
                f = lambda v, spec: "-" if v is None else format(v, spec)  # noqa: E731
                typer.echo(
                    f"{n:18s} {p:>9d} dofs={row['dofs']:>9d} error={f(row.get('max_error'), '.1e')} "
                    f"assemble={f(row['assemble_s'], '.3g')}s "
                    f"solve={f(row['solve_s'], '.3g')}s total={row['total_s']:.3g}s limit={f(row['limit_s'], '.3g')}s "
                    f"ratio={f(row['ratio'], '.2f')} mem={row['peak_mem_mb']:.0f}MB "
                    f"updates/s={f(row['updates_per_s'], '.3g')}"
                    + ("" if accurate(row) else "  (error above 1e-6 or unknown: counts toward no target)")
                )
    shared = []
    from .sharing import sharing_gain

    for n in sharing:
        shared.append(sharing_gain(n) | {"kind": "sharing"})
        r = shared[-1]
        typer.echo(
            _json.dumps(r)
            if fmt == Format.json
            else f"{n:18s} suite {r['cases']} cases: {r['factorisations_apart']} -> {r['factorisations_shared']} "
            f"factorisations, {r['cases_per_s_apart']:.3g} -> {r['cases_per_s_shared']:.3g} cases/s "
            f"(x{r['gain']:.2f}), same numbers: {r['same']}, max error {r['max_error']:.1e}"
        )
    slopes = cost_slope(rows)
    for n, s in slopes.items():
        line = {"model": n, "cost_slope": s}
        typer.echo(_json.dumps(line) if fmt == Format.json else f"{n:18s} cost ~ N^{s:.2f}")
    if out:
        from ..report.perf import build_performance

        page = build_performance(rows, out, slopes, shared)
        if fmt != Format.json:
            typer.echo(f"performance page: {page}")
    failed_runs(rows)


def _points(text: str) -> int:
    """``--points`` as a whole number, as ``solve --points`` reads it (``1e3`` is 1000); InputError otherwise."""
    try:
        n = whole_number(text)
    except (ValueError, OverflowError):
        raise InputError(f"--points {text}: give a whole number of points, e.g. 1000 or 1e3") from None
    return n
