"""Deformed shapes of a nonlinear load path beside the exact ones: each load step of a large-rotation run
(``info["load_steps"]``: ``factor``, ``x``, ``z``) gains the exact elastica's shape at that load factor
(``exact_x``, ``exact_z``) where ``exact-elastica`` solves the scene (a cantilever under one end load)."""

from __future__ import annotations

import numpy as np

from ..core.scene import Scene
from ..registry import get_model


def with_exact_shapes(scene: Scene, load_steps: list[dict], samples: int = 201) -> list[dict]:
    """``load_steps`` with ``exact_x``, ``exact_z`` (the extensible elastica, ``samples`` points) added to each
    step; unchanged where the exact elastica does not solve ``scene``."""
    elastica = get_model("exact-elastica")
    if elastica.reasons(scene):
        return load_steps
    s = np.linspace(0.0, scene.length, samples)
    (load,) = scene.loads
    out = []
    for step in load_steps:
        at = scene.model_copy(update={"loads": [load.model_copy(update={"value": step["factor"] * load.value})]})
        f = elastica.evaluate(at, {"extensible": True}, s)
        out.append({**step, "exact_x": (s + f["u"]).tolist(), "exact_z": f["w"].tolist()})
    return out
