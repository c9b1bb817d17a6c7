"""Values and names as the report prints them: numbers to the precision they carry, a case's label, a model's
variant key, references and options as text, units of a scene's quantities."""

from __future__ import annotations

import json
import re

import numpy as np
import pandas as pd

from ..core.scene import UNITS
from ..registry import get_model
from ..study.spec import scene_folder


def missing(v) -> bool:
    """None, NaN or pandas' NA."""
    return v is None or v is pd.NA or (isinstance(v, (float, np.floating)) and not np.isfinite(v))


def fmt(v) -> str:
    """A value of a results table as text: 6 significant digits (what a computed deflection carries on a table),
    integers whole, booleans yes/no, missing values empty."""
    if missing(v):
        return ""
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        return f"{float(v):.6g}"
    return str(v)


def sig(v, digits: int) -> str:
    """``v`` to ``digits`` significant digits, exponents without padding ('1.23e-5'); missing values empty."""
    if missing(v):
        return ""
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    text = f"{float(v):.{digits}g}"
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m.group(1) == "-" else "") + m.group(2), text)


def fixed(v, decimals: int) -> str:
    """``v`` with ``decimals`` decimals (orders of convergence: two); missing values empty."""
    return "" if missing(v) else f"{float(v):.{decimals}f}"


def case_anchor(case_id) -> str:
    """The id of a case's row in the 'All results' table of index.html."""
    return "case-" + "".join(ch for ch in str(case_id) if ch.isalnum() or ch in "-_")


def slug(text: str) -> str:
    """Lower-case letters, digits and dashes: an element id or file name made from a name."""
    return re.sub(r"[^a-z0-9]+", "-", str(text).lower()).strip("-") or "x"


def folder(scene_file) -> str:
    """The name of the scene's folder (one report page per folder: a paper's scenes)."""
    return scene_folder(scene_file)


def options_of(options) -> dict:
    """The JSON options of a row as a dict ({} when missing or not JSON)."""
    try:
        d = json.loads(options)
    except (TypeError, ValueError):
        return {}
    return d if isinstance(d, dict) else {}


def _model(name: str):
    try:
        return get_model(name)
    except Exception:  # a model of another installation: no defaults known
        return None


def string_options(model: str, opts: dict) -> dict[str, str]:
    """The string options of a run that differ from the model's defaults (the variant always), sorted by name:
    what tells two runs of one model apart besides the grid."""
    m = _model(model)
    parts = {}
    for k, v in sorted(opts.items()):
        if k in ("horizon", "degree") or not isinstance(v, str):
            continue
        opt = m.option(k) if m is not None else None
        if opt is not None and opt.default == v and k != "variant":
            continue
        parts[k] = v
    return parts


def label(r) -> str:
    """Model, then its string options that differ from the model's defaults, then grid and horizon."""
    parts = [str(r["model"]), *string_options(str(r["model"]), options_of(r.get("options"))).values()]
    for k, short in (("points", "n"), ("horizon_factor", "m"), ("degree", "P"), ("slenderness", "L/h")):
        if k in r and pd.notna(r[k]):
            parts.append(f"{short}={fmt(r[k])}")
    return " ".join(parts)


def key_options(model: str, opts: dict) -> dict[str, str]:
    """The string options that tell a model's runs apart (:func:`string_options`), the model's defaults filled
    in first: a card run with defaults and a study row with the defaults written out give the same."""
    m = _model(model)
    full = {}
    if m is not None:
        full = {o.name: o.default for o in m.options if isinstance(o.default, str)}
    full.update({k: v for k, v in opts.items() if isinstance(v, str)})
    return string_options(model, full)


def variant_key(model: str, opts: dict) -> str:
    """'pd-bond-pair paper mirror': a model and the string options that tell its runs apart."""
    return " ".join([model, *key_options(model, opts).values()])


def variant_of(model: str, opts: dict) -> str:
    """The run's variant (its ``variant`` option, the model's default when not given); '' for a model without."""
    if isinstance(opts.get("variant"), str):
        return opts["variant"]
    m = _model(model)
    opt = m.option("variant") if m is not None else None
    return str(opt.default) if opt is not None and isinstance(opt.default, str) else ""


def short_reference(ref) -> str:
    """'fem-plane-stress (element=q8, layers=16, points=201)' for the JSON reference of a row."""
    try:
        d = json.loads(ref)
    except (TypeError, ValueError):
        return "" if missing(ref) else str(ref)
    if not isinstance(d, dict):
        return str(d)
    model = d.pop("model", "?")
    return f"{model} ({', '.join(f'{k}={v}' for k, v in sorted(d.items()))})" if d else str(model)


def options_text(options, model: str | None = None) -> str:
    """'grid=cells, horizon=2' for the JSON options of a row: with ``model``, only the options that differ from its
    defaults (the variant always; 'defaults' when nothing else differs); every option otherwise."""
    try:
        d = json.loads(options)
    except (TypeError, ValueError):
        return "" if missing(options) else str(options)
    if not isinstance(d, dict):
        return str(d)
    m = _model(model) if model else None
    if m is not None:
        d = {k: v for k, v in d.items() if k == "variant" or (o := m.option(k)) is None or o.default != v}
    return ", ".join(f"{k}={v}" for k, v in sorted(d.items())) or ("defaults" if m is not None else "")


def readable_options(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with its JSON ``options`` column as 'key=value, ...' text: the options that differ from the row's
    model's defaults (results.csv keeps them all)."""
    if df is None or df.empty or "options" not in df:
        return df
    models = df["model"] if "model" in df else pd.Series(None, index=df.index)
    return df.assign(
        options=[options_text(o, m if isinstance(m, str) else None) for o, m in zip(df["options"], models)]
    )


def readable(v) -> str:
    """A value of meta.json as text: 'numpy 2.4.6, scipy 1.17.1' for a table, 'a; b' for a list."""
    if isinstance(v, dict):
        sep = " " if all(isinstance(x, str) for x in v.values()) else ": "
        return ", ".join(f"{k}{sep}{readable(x)}" for k, x in v.items())
    if isinstance(v, list):
        return "; ".join(readable(x) for x in v) or "none"
    return fmt(v)


# the unit kind of each point output a study measures or a benchmark names (others: a length)
QUANTITY_KIND = {
    "twist": "angle",
    "rotation": "angle",
    "theta": "angle",
    "psi": "angle",
    "M": "moment",
    "N": "force",
    "Q": "force",
    "V": "force",
    "moment": "moment",
    "shear": "force",
    "axial": "force",
}


def unit_of(quantity: str, units: str | None) -> str:
    """The unit of a point output (``quantity``: w, u, twist, M, ...; a benchmark's 'w at max' by its first word)
    in a scene's unit system (``units``: 'SI' or 'inch-pound', the results' column)."""
    system = UNITS.get(units or "SI", UNITS["SI"])
    kind = QUANTITY_KIND.get(str(quantity).split(" ")[0], "length")
    if kind == "angle":
        return "rad"
    if kind == "moment":
        return f"{system['force']} {system['length']}"
    return system[kind]
