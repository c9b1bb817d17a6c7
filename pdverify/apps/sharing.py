"""What one factorisation per operator saves: a model's verification suite run twice in one process, with the
factorisation cache (:mod:`pdverify.numerics.factorcache`) and without it, cases per second of each beside the
number of distinct operators and whether the two runs' errors are the same to the bit."""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from ..numerics import factorcache
from ..study import load_study, run_study
from ..verify.suite import plan, write_study


def _run(study: Path, out: Path):
    """The suite's results and the seconds they took, serial, every case computed."""
    t0 = time.perf_counter()
    df = run_study(load_study(study), out, workers=1, progress=False, artefacts=False)
    return df, time.perf_counter() - t0


def sharing_gain(model_name: str, options: dict | None = None) -> dict:
    """One row: the suite's cases, the operators factorised with and without sharing, cases per second of each,
    the gain, and ``same`` (every error column equal to the bit)."""
    from ..registry import get_model  # after the study layer: the registry is already imported through it

    model = get_model(model_name)
    options = dict(options or {})
    keep = factorcache.ENTRIES
    with tempfile.TemporaryDirectory(prefix="pdverify-sharing-") as tmp:
        study = write_study(plan(model, False, options), model, options, Path(tmp) / "suite")
        try:
            factorcache.clear()
            factorcache.ENTRIES = 0
            apart, t_apart = _run(study, Path(tmp) / "apart")
            made_apart = factorcache.stats["made"]
            factorcache.clear()
            factorcache.ENTRIES = keep
            shared, t_shared = _run(study, Path(tmp) / "shared")
            made_shared = factorcache.stats["made"]
        finally:
            factorcache.ENTRIES = keep
            factorcache.clear()
    errors = [c for c in apart.columns if c.startswith("err_")]
    key = ["scene_file", "points", "options"]
    a = apart.sort_values(key)[errors].reset_index(drop=True)
    b = shared.sort_values(key)[errors].reset_index(drop=True)
    n = len(apart)
    return {
        "model": model_name,
        "options": options,
        "cases": n,
        "factorisations_apart": made_apart,
        "factorisations_shared": made_shared,
        "cases_per_s_apart": n / t_apart,
        "cases_per_s_shared": n / t_shared,
        "gain": t_apart / t_shared,
        "same": bool(a.equals(b)),
        "max_error": float(shared["err_max"].max()),
    }
