"""The advisor's priors (``pdverify/data/advisor_priors.json``, package data): per model and options, the error
constant C and order p of the clean convergence series of a small study, err = C (dx / L)^p
(:func:`fit_series`), with the code digest they were made from. ``pdverify advise`` reads them to predict the
points a tolerance needs (:func:`predicted_points`); ``pdverify advise --rebuild-priors`` regenerates them
(:func:`rebuild_priors`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..core.errors import InputError, OutputError
from ..registry import models
from ..study import load_study, run_study
from ..study.spec import code_digest

PRIORS = Path(__file__).resolve().parents[1] / "data" / "advisor_priors.json"
# the options advise tries per model (others: their defaults); the priors are fitted for the same
CANDIDATE_OPTIONS = {
    "pd-timoshenko": {"variant": "energy"},
    "pd-eb": {"variant": "corrected"},
    "pd-bond-pair": {"variant": "corrected", "ends": "taylor"},
    "fem-plane-stress": {"element": "q8"},
}


def _matches(opts: dict, options: dict) -> bool:
    return all(opts.get(k) == v for k, v in options.items())


def load_priors(path: Path | str | None = None) -> dict:
    """The advisor's priors (a small JSON file shipped in the package; independent of the working
    directory): ``{"code_digest", "series": [{model, options, scene, constant, order, points}]}``."""
    p = Path(path) if path is not None else PRIORS
    try:
        return json.loads(p.read_text())
    except (OSError, ValueError):
        return {"code_digest": None, "series": []}


def prior_order(model: str, options: dict, priors: dict | None = None) -> str:
    """Observed orders of the prior convergence series for this model with these options."""
    priors = load_priors() if priors is None else priors
    orders = [s["order"] for s in priors.get("series", []) if s["model"] == model and _matches(s["options"], options)]
    if not orders:
        return "no prior series"
    return f"priors: median observed order {np.median(orders):.2f} over {len(orders)} series"


def predicted_points(model: str, options: dict, tol: float, priors: dict | None = None) -> tuple[int | None, str]:
    """Points the priors say this model needs for tol: each clean series' err = C (dx / L)^p solved for
    dx, the most pessimistic series taken. (None, why) without a series."""
    priors = load_priors() if priors is None else priors
    needs = [
        int(np.ceil((tol / s["constant"]) ** (-1.0 / s["order"]))) + 1
        for s in priors.get("series", [])
        if s["model"] == model and _matches(s["options"], options)
    ]
    if not needs:
        return None, "no clean prior convergence series for these options"
    n = max(needs)
    return n, f"priors: {len(needs)} convergence series predict up to {n} points"


def fit_series(results) -> list[dict]:
    """Clean convergence series of a study's results table (rows: model, options, scene_file, points,
    err_max, status; slenderness sweeps left out): per scene and option set with >= 3 grids, the
    least-squares fit of log err = log C + p log(dx / L); kept when p > 0.5 and r^2 > 0.9 (a
    discretisation-error series, not round-off or a plateau)."""
    import pandas as pd

    df = results if isinstance(results, pd.DataFrame) else pd.read_csv(results)
    ok = (df["status"] == "ok") & df["err_max"].notna() & (df["err_max"] > 1e-12) & df["slenderness"].isna()
    out = []
    for (model, scene, options), g in df[ok].groupby(["model", "scene_file", "options"]):
        if g["points"].nunique() < 3:
            continue
        lh, le = np.log(1.0 / (g["points"].to_numpy(float) - 1)), np.log(g["err_max"].to_numpy(float))
        p, c = np.polyfit(lh, le, 1)
        r2 = 1 - np.sum((le - (p * lh + c)) ** 2) / max(np.sum((le - le.mean()) ** 2), 1e-300)
        if p > 0.5 and r2 > 0.9:
            out.append(
                {
                    "model": model,
                    "options": json.loads(options),
                    "scene": scene,
                    "constant": float(np.exp(c)),
                    "order": float(p),
                    "r2": float(r2),
                    "points": sorted(int(n) for n in g["points"]),
                }
            )
    return out


PRIOR_SCENES = {
    "euler-bernoulli": (
        "exact-eb",
        (
            "paper_diyaroglu/clamped_clamped.toml",
            "paper_diyaroglu/simply_supported.toml",
            "paper_diyaroglu/clamped_free.toml",
        ),
    ),
    "timoshenko": (
        "exact-timoshenko",
        ("paper_diyaroglu/clamped_clamped.toml", "paper_diyaroglu/clamped_free.toml", "paper_yang/cc_uniform.toml"),
    ),
}  # per theory: reference, scenes
PRIOR_POINTS = (21, 41, 81, 161)


def rebuild_priors(
    out: Path | str | None = None,
    names: list[str] | None = None,
    points=PRIOR_POINTS,
    studies: Path | None = None,
    workdir: Path | None = None,
) -> dict:
    """Regenerate the priors (``pdverify advise --rebuild-priors``): a small study (every advise candidate
    that bends, with :data:`CANDIDATE_OPTIONS`, on the scenes of :data:`PRIOR_SCENES` against their exact
    solution, at ``points``), fitted by :func:`fit_series`, written with the code digest it was made from.
    Needs the source checkout's ``studies/`` folder (the scenes)."""
    import tempfile

    studies = Path(studies) if studies is not None else Path(__file__).resolve().parents[2] / "studies"
    if not studies.is_dir():
        raise InputError(
            f"studies = {str(studies)!r}: the scenes of the priors study are not there; run "
            "--rebuild-priors from a source checkout of pdverify"
        )
    cands = [
        m
        for m in models().values()
        if not m.reference
        and "static" in m.analyses
        and m.bending
        and m.option("points") is not None
        and (names is None or m.name in names)
    ]
    if not cands:
        raise InputError(f"models = {names!r}: no advise candidate among them")
    runs, used = [], set()
    for m in cands:
        ref, scenes = PRIOR_SCENES["euler-bernoulli" if m.theory == "euler-bernoulli" else "timoshenko"]
        used.update(scenes)
        opts = "".join(f"{k} = {json.dumps(v)}\n" for k, v in CANDIDATE_OPTIONS.get(m.name, {}).items())
        listed = ", ".join(f'"{(studies / sc).as_posix()}"' for sc in scenes)
        runs.append(
            f'[[runs]]\nmodel = "{m.name}"\nscenes = [{listed}]\nreference = {{model = "{ref}"}}\n'
            f"points = {list(points)}\n{opts}"
        )
    head = ", ".join(f'"{(studies / sc).as_posix()}"' for sc in sorted(used))
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        spec = Path(tmp) / "priors.toml"
        spec.write_text(f'name = "advisor priors"\nscenes = [{head}]\nreference = "none"\n\n' + "\n".join(runs))
        df = run_study(load_study(spec), Path(tmp) / "run", workers=1, progress=False)
    series = fit_series(df)
    for one in series:  # scene files relative to studies/ (the file is versioned: no machine's paths)
        one["scene"] = (
            Path(one["scene"]).relative_to(studies).as_posix() if Path(one["scene"]).is_absolute() else one["scene"]
        )
    data = {
        "format": 1,
        "code_digest": code_digest(),
        "points": list(points),
        "made_by": "pdverify advise --rebuild-priors",
        "series": series,
    }
    target = Path(out) if out is not None else PRIORS
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    except OSError as exc:
        raise OutputError(f"{target}: cannot write the priors ({exc.strerror or exc})") from None
    return data
