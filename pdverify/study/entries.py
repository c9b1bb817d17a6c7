"""A study's ``verify`` entries: a model and its options, written as ``"pd-eb variant=paper"`` or as a table,
the folder each card is written to, and the entries' error lines (:func:`verify_entries`). Whether the
verification suite applies to the model is the verify layer's question (:func:`pdverify.verify.entry_errors`),
asked through :func:`pdverify.study.spec.load_study`'s ``card_errors``."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from ..core.errors import InputError
from ..registry import get_model


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


def verify_entries(data: dict, path: Path, card_errors=None) -> tuple[list[dict], bool, list[str]]:
    """The study's ``verify`` cards (model, options, folder), ``verify_required`` and their error lines;
    ``card_errors(model, options)``: what else stops a card (:func:`pdverify.verify.entry_errors`), else only
    the model's name is checked."""

    entries, errors = data.get("verify", []), []
    required = data.get("verify_required", False)
    if not isinstance(required, bool):
        errors.append(f"{path}: verify_required = {required!r}: give true or false")
    if not isinstance(entries, list):
        return (
            [],
            False,
            errors + [f'{path}: verify = {entries!r}: give a list of models, e.g. ["pd-eb", "pd-eb variant=paper"]'],
        )
    cards, folders = [], set()
    for i, entry in enumerate(entries):
        where = f"{path}: verify[{i}] = {entry!r}"
        try:
            name, options = parse_entry(entry)
        except InputError as exc:
            errors.append(f"{path}: verify[{i}] = {exc.lines[0]}")
            continue
        found = card_errors(name, options) if card_errors is not None else model_errors(name)
        errors += [f"{where}: {line}" for line in found]
        folder = card_folder(get_model(name).name if not found else name, options)
        if not found and folder in folders:
            errors.append(f"{where}: listed twice; drop one")
        elif not found:
            folders.add(folder)
            cards.append({"model": name, "options": options, "folder": folder})
    return cards, required is True, errors


def model_errors(name: str) -> list[str]:
    """The error line of a model name that is not installed (none for one that is)."""
    try:
        get_model(name)
    except InputError as exc:
        return [exc.lines[0]]
    return []
