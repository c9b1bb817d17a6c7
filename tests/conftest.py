import copy

import pytest

BASE = {
    "name": "test beam",
    "beam": {"length": 2.0},
    "section": {"width": 0.05, "height": 0.1},
    "material": {"youngs_modulus": 70e9, "poissons_ratio": 0.33},
    "supports": {"left": "clamped", "right": "free"},
    "loads": [],
}


def scene_dict(left="clamped", right="free", loads=(), **over):
    d = copy.deepcopy(BASE)
    d["supports"] = {"left": left, "right": right}
    d["loads"] = [dict(l) for l in loads]
    for k, v in over.items():
        d[k] = v
    return d


@pytest.fixture
def make_scene():
    from pdverify.scene import parse_scene

    def make(left="clamped", right="free", loads=(), **over):
        return parse_scene(scene_dict(left, right, loads, **over))

    return make
