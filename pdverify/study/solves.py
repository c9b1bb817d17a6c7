"""One solve per (scene, model, options) in a process.

A model judged against itself (``self_reference``) is solved on the reference grid twice in a verification card:
as the reference of its coarser grids and as the case of its theory-gap run, which measures that same solution
against exact Timoshenko theory. Both go through :func:`solve`, so a process that meets both solves once. A solve
is deterministic (the same operator, factorisation and right-hand side give the same bits), so a kept result is the
result a second solve would give; its timings are those of the solve that made it.
"""

from __future__ import annotations

import json

from ..core.result import Result
from ..numerics.kept import Kept
from ..registry import run
from .spec import _scene

KEPT_DOFS = 50_000  # larger solves are not kept (their arrays, and a 2D strip's basis in its writers)
_kept = Kept(8)  # results, the most recent first out


def solve(scene_text: str, scene_file: str, slenderness, model: str, given: dict) -> Result:
    """``registry.run`` of the scene (its text, file name and slenderness, as a case holds them) with ``model`` and
    the ``given`` options, or the result of the same call made before in this process."""
    key = (scene_text, scene_file, slenderness, model, json.dumps(given, sort_keys=True, default=str))
    return _kept.get(
        key,
        lambda: run(_scene(scene_text, scene_file, slenderness), model, **given),
        keep=lambda result: result.dofs <= KEPT_DOFS,
    )
