"""Scene validation: every bad field gets one line naming the field, the value and what is allowed."""

import subprocess
import sys

import pytest
from helpers import ROOT, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene, parse_scene


def rejects(d):
    with pytest.raises(InputError) as exc:
        parse_scene(d)
    return exc.value.lines


def set_(d, path, value):
    node = d
    *head, last = path
    for k in head:
        node = node[k]
    node[last] = value
    return d


BAD = [
    # (what, path, value, words that must all appear in the single message)
    ("unknown support", ("supports", "left"), "clampd", ["supports.left", "'clampd'", "clamped, pinned, free, guided"]),
    ("negative modulus", ("material", "youngs_modulus"), -1.0, ["material.youngs_modulus", "-1.0", "greater than 0"]),
    ("zero modulus", ("material", "youngs_modulus"), 0.0, ["material.youngs_modulus", "greater than 0"]),
    ("zero length", ("beam", "length"), 0.0, ["beam.length", "0.0", "greater than 0"]),
    ("negative length", ("beam", "length"), -2.0, ["beam.length", "-2.0"]),
    ("poisson too large", ("material", "poissons_ratio"), 0.5, ["material.poissons_ratio", "0.5", "less than 0.5"]),
    ("poisson too small", ("material", "poissons_ratio"), -1.0, ["material.poissons_ratio", "greater than -1"]),
    ("typo at top", ("lenght",), 1.0, ["unknown key 'lenght'", "allowed keys"]),
    (
        "typo in table",
        ("material", "youngs_modulos"),
        1.0,
        ["material.youngs_modulos", "unknown key", "youngs_modulus"],
    ),
    ("string for number", ("beam", "length"), "long", ["beam.length", "'long'"]),
    ("negative height", ("section", "height"), -0.1, ["section.height", "greater than 0"]),
]


@pytest.mark.parametrize("what,path,value,words", BAD, ids=[b[0] for b in BAD])
def test_rejects_field(what, path, value, words):
    lines = rejects(set_(scene_dict(), path, value))
    assert len(lines) == 1, lines
    for w in words:
        assert w in lines[0], (w, lines[0])


LOAD_BAD = [
    (
        "load outside the beam",
        {"type": "point_force", "position": 2.5, "value": 1.0},
        ["loads[0].position", "2.5", "outside the beam [0, 2.0]"],
    ),
    ("load before the beam", {"type": "point_moment", "position": -0.1, "value": 1.0}, ["loads[0].position", "-0.1"]),
    (
        "start >= end",
        {"type": "distributed", "value": 1.0, "start": 1.5, "end": 0.5},
        ["loads[0].start = 1.5, end = 0.5", "start must be below end"],
    ),
    ("span beyond the beam", {"type": "distributed", "value": 1.0, "end": 3.0}, ["loads[0].end = 3.0", "outside"]),
    (
        "unknown load type",
        {"type": "pressure", "value": 1.0},
        ["loads[0].type", "'pressure'", "point_force, point_moment, distributed"],
    ),
    (
        "unknown shape",
        {"type": "distributed", "value": 1.0, "shape": "cosine"},
        ["loads[0].shape", "'cosine'", "uniform"],
    ),
    ("typo in load", {"type": "point_force", "positon": 1.0, "value": 1.0}, ["loads[0]", "positon"]),
]


@pytest.mark.parametrize("what,load,words", LOAD_BAD, ids=[b[0] for b in LOAD_BAD])
def test_rejects_load(what, load, words):
    lines = rejects(scene_dict(loads=[load]))
    text = "\n".join(lines)
    for w in words:
        assert w in text, (w, text)


@pytest.mark.parametrize(
    "left,right", [("free", "free"), ("pinned", "free"), ("free", "pinned"), ("guided", "guided"), ("guided", "free")]
)
def test_rejects_mechanism(left, right):
    lines = rejects(scene_dict(left, right, [{"type": "point_force", "position": 1.0, "value": -1.0}]))
    assert len(lines) == 1 and f"supports = {left}-{right}" in lines[0] and "mechanism" in lines[0]


def test_missing_table_and_section():
    d = scene_dict()
    del d["material"]
    assert any("material: missing" in l for l in rejects(d))
    d = scene_dict()
    d["section"] = {"width": 0.1}
    assert any("section" in l and "width and height" in l for l in rejects(d))


def test_accepts_area_inertia_and_defaults():
    d = scene_dict()
    d["section"] = {"area": 1.0, "inertia": 0.0833}
    s = parse_scene(d)
    assert s.section.k == pytest.approx(5 / 6) and s.section.A == 1.0
    assert s.slenderness == pytest.approx(2.0 / (12 * 0.0833) ** 0.5)


def test_with_slenderness_rescales_height():
    s = parse_scene(scene_dict()).with_slenderness(100)
    assert s.section.height == pytest.approx(0.02) and s.section.width == 0.05


def cli(*args):
    return subprocess.run([sys.executable, "-m", "pdverify.apps.cli", *args], capture_output=True, text=True, cwd=ROOT)


def test_cli_bad_scene_one_line_exit_2(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text((ROOT / "studies/examples/cantilever_tip_load.toml").read_text().replace('"free"', '"freee"'))
    r = cli("solve", str(p), "--model", "exact-eb")
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    assert r.stderr.strip().count("\n") == 0
    assert "supports.right = 'freee': unknown support" in r.stderr


@pytest.mark.slow
def test_cli_toml_syntax_error_and_missing_file(tmp_path):
    p = tmp_path / "broken.toml"
    p.write_text("name = 'x'\n[beam\nlength = 1\n")
    r = cli("solve", str(p), "--model", "exact-eb")
    assert r.returncode == 2 and "TOML syntax error" in r.stderr and "Traceback" not in r.stderr
    r = cli("solve", str(tmp_path / "nope.toml"), "--model", "exact-eb")
    assert r.returncode == 2 and "no such scene file" in r.stderr


@pytest.mark.slow
def test_cli_unknown_model_lists_available():
    r = cli("solve", "studies/examples/cantilever_tip_load.toml", "--model", "pd-nothing")
    assert (
        r.returncode == 2 and "unknown model" in r.stderr and "exact-eb" in r.stderr and "exact-timoshenko" in r.stderr
    )


@pytest.mark.slow
def test_cli_option_the_model_does_not_take():
    r = cli("solve", "studies/examples/cantilever_tip_load.toml", "--model", "exact-eb", "--horizon", "3")
    assert r.returncode == 2 and "takes no option 'horizon'" in r.stderr


@pytest.mark.slow
def test_cli_spacing_must_divide_length():
    r = cli("solve", "studies/examples/cantilever_tip_load.toml", "--model", "exact-eb", "--spacing", "0.3")
    assert r.returncode == 2 and "spacing = 0.3" in r.stderr
    r = cli(
        "solve",
        "studies/examples/cantilever_tip_load.toml",
        "--model",
        "exact-eb",
        "--spacing",
        "0.25",
        "--format",
        "csv",
    )
    assert r.returncode == 0 and len(r.stdout.strip().splitlines()) == 6


def test_example_scenes_in_studies_are_valid():
    files = sorted((ROOT / "studies").rglob("*.toml"))
    scenes = [f for f in files if "[beam]" in f.read_text()]
    assert scenes
    for f in scenes:
        load_scene(f)
