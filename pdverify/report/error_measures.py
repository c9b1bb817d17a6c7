"""A paper page's table of error measures per scene: each run's maximum relative error of the deflection and of
every other quantity the study measured (``err_max_<q>``: rotation, bending moment M, shear force V, axial force
N), one row per model, options, degree, slenderness and grid. The curved PDDO paper reports four such measures
(displacement, rotation, axial force, bending moment) per degree and grid; this table is where they are read."""

from __future__ import annotations

import pandas as pd

from .inputs import StudyFolder
from .quantity_figures import NAME, QUANTITIES

KEY_COLUMNS = ["scene", "model", "options", "degree", "slenderness", "points"]


def measure_columns(rows: pd.DataFrame) -> list[str]:
    """err_max and the err_max_<q> columns with a value in ``rows`` (in the order rotation, moment, shear, axial)."""
    return ["err_max"] + [
        f"err_max_{q}" for q in QUANTITIES if f"err_max_{q}" in rows and rows[f"err_max_{q}"].notna().any()
    ]


def scene_measures(data: StudyFolder, scene_file: str) -> tuple[pd.DataFrame, str] | None:
    """The rows and columns of one scene's table of error measures and a note naming the quantities that are
    missing (a model or reference that gives none, as the study recorded in ``missing_quantities``); None when the
    study measured no quantity besides the model's own on this scene."""
    ok = data.ok
    rows = ok[(ok["scene_file"] == scene_file) & ok["err_max"].notna()]
    columns = measure_columns(rows)
    if rows.empty or len(columns) == 1:
        return None
    rows = rows.sort_values([c for c in ["model", "options", "degree", "slenderness", "points"] if c in rows])
    keep = [c for c in KEY_COLUMNS if c in rows] + columns + ["case_id"]
    missing = {}
    if "missing_quantities" in rows:
        for (model, text), _ in rows.groupby(["model", rows["missing_quantities"].fillna("")], sort=True):
            for q in str(text).split():
                missing.setdefault(q, set()).add(model)
    note = "; ".join(
        f"no {NAME.get(q, q)} from {', '.join(sorted(models))} or its reference" for q, models in missing.items()
    )
    return rows[keep], note[:1].upper() + note[1:]
