"""A study's ``verify`` entries: a model and its options, written as ``"pd-eb variant=paper"`` or as a table,
and the folder each card is written to. Whether the verification suite applies to the model is the verify layer's
question (:func:`pdverify.verify.entry_errors`), asked through :func:`pdverify.study.spec.load_study`'s
``card_errors``."""

from __future__ import annotations

import re
import tomllib

from ..core.errors import InputError


def parse_entry(entry) -> tuple[str, dict]:
    """A study file's ``verify`` entry: ``"pd-eb variant=paper horizon=3"`` (values typed as TOML types them:
    ``3`` a number, ``true`` a boolean, anything else a string) or a table ``{model = "pd-eb", variant = "paper"}``.
    Raises InputError (one line) for an entry of neither form."""
    if isinstance(entry, dict) and isinstance(entry.get("model"), str):
        return entry["model"], {k: v for k, v in entry.items() if k != "model"}
    if not isinstance(entry, str) or not entry.split():
        raise InputError(f'{entry!r}: give a model and its options, e.g. "pd-eb variant=paper"')
    name, *pairs = entry.split()
    options = {}
    for item in pairs:
        k, eq, v = item.partition("=")
        if not eq or not k or not v:
            raise InputError(f"{entry!r}: option {item!r}: write key=value")
        try:
            options[k] = tomllib.loads(f"v = {v}")["v"]
        except tomllib.TOMLDecodeError:
            options[k] = v
    return name, options


def card_folder(model_name: str, options: dict) -> str:
    """The card's folder name, as ``pdverify verify`` names it: ``pd_eb_variant_paper``."""
    text = (model_name + "".join(f"_{k}_{v}" for k, v in options.items())).lower()
    return re.sub(r"[^a-z0-9]+", "_", text).strip("_") or "model"
