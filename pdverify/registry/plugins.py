"""Models from outside pdverify: installed plug-ins and external-command manifests.

**Plug-ins.** A package registers models under the entry-point group ``pdverify.models``
(``[project.entry-points."pdverify.models"]`` in its pyproject.toml). Each entry point names a
:class:`~pdverify.registry.Model` instance, a ``Model`` subclass (instantiated without arguments) or a
list/tuple of either. They join the built-in models in :func:`pdverify.registry.models`, so ``pdverify
models``, ``solve``, studies, ``advise``, ``bench`` and ``verify`` treat them as built-ins.

**External models.** A TOML manifest (see :mod:`pdverify.registry.external`) names a command in any language.
Manifests are found in ``PDVERIFY_MODELS_PATH`` (files or folders of ``*.toml``, separated by the
platform's path separator), named by a study file's ``external = [...]`` list, or given to ``pdverify
solve/verify --model path/to/manifest.toml``.

A broken plug-in or manifest (import error, wrong type, a name already taken) costs one warning line on
stderr naming it; every other model still works.
"""

from __future__ import annotations

import os
import sys
from importlib.metadata import PackageNotFoundError, distribution, entry_points
from pathlib import Path

from ..core.contract import Model
from ..core.errors import PdverifyError
from .external import load_manifest

GROUP = "pdverify.models"
PATH_VAR = "PDVERIFY_MODELS_PATH"


def warn(line: str) -> None:
    """One warning line on stderr (not :mod:`warnings`: that prints the source line as well)."""
    sys.stderr.write(f"warning: {line}\n")


def _as_models(obj, where: str) -> list:
    """The Model instances an entry point names; TypeError with the reason otherwise."""
    items = obj if isinstance(obj, (list, tuple)) else [obj]
    out = []
    for item in items:
        if isinstance(item, type) and issubclass(item, Model):
            item = item()
        if not isinstance(item, Model):
            raise TypeError(
                f"{where} is {type(item).__name__}, not a pdverify.registry.Model instance, subclass or list"
            )
        if not isinstance(item.name, str) or not item.name:
            raise TypeError(f"{where}: a model without a name")
        out.append(item)
    return out


def _add(found: dict, taken: dict, model, where: str) -> None:
    if model.name in taken or model.name in found:
        warn(f"{where}: model name {model.name!r} is already taken; skipped (rename the model)")
    else:
        found[model.name] = model


def entry_point_models(taken: dict) -> dict:
    """Models of the installed ``pdverify.models`` entry points whose names are not in ``taken``."""
    found: dict = {}
    for ep in sorted(entry_points(group=GROUP), key=lambda e: e.name):
        dist = getattr(ep, "dist", None)
        where = f"plug-in entry point {ep.name} = {ep.value}" + (f" ({dist.name})" if dist else "")
        try:
            loaded = _as_models(ep.load(), where)
        except Exception as exc:  # noqa: BLE001 - any failure of a third-party import is one line, not a crash
            msg = (
                str(exc)
                if isinstance(exc, TypeError) and str(exc).startswith(where)
                else f"{where}: {type(exc).__name__}: {exc}"
            )
            warn(f"{msg}; skipped")
            continue
        for m in loaded:
            _add(found, taken, m, where)
    return found


def manifest_paths() -> list[Path]:
    """The manifests named by ``PDVERIFY_MODELS_PATH``: files as given, folders' ``*.toml`` sorted."""
    out = []
    for part in filter(None, os.environ.get(PATH_VAR, "").split(os.pathsep)):
        p = Path(part)
        out.extend(sorted(p.glob("*.toml")) if p.is_dir() else [p])
    return list(dict.fromkeys(out))


def manifest_models(taken: dict) -> dict:
    found: dict = {}
    for path in manifest_paths():
        try:
            m = load_manifest(path)
        except PdverifyError as exc:
            warn(f"external model manifest {' '.join(exc.lines)}; skipped")  # the lines name the file
            continue
        _add(found, taken, m, f"external model manifest {path}")
    return found


def own_entry_points_missing() -> bool:
    """Whether pdverify runs without its installed metadata (a source tree on ``sys.path``, an install under
    way): then its own entry points, which register the finite-element references, are missing too."""
    try:
        return not any(ep.group == GROUP for ep in distribution("pdverify").entry_points)
    except PackageNotFoundError:
        return True


def discover(builtin: dict) -> dict:
    """Plug-in and external models to add to the built-in ones (called once by registry.models())."""
    if own_entry_points_missing():
        warn(
            "pdverify's entry points are not installed, so its finite-element references (fem-eb, "
            'fem-timoshenko, fem-plane-stress) are missing: install it (pip install -e ".")'
        )
    found = entry_point_models(builtin)
    found.update(manifest_models({**builtin, **found}))
    return found


def remember_manifest(path: Path) -> None:
    """Append ``path`` to ``PDVERIFY_MODELS_PATH`` (unless there), so processes started later find its model."""
    parts = [p for p in os.environ.get(PATH_VAR, "").split(os.pathsep) if p]
    if str(path) not in parts:
        os.environ[PATH_VAR] = os.pathsep.join(parts + [str(path)])
