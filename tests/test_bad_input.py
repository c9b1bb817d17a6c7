"""Malformed scene files: each gives one clear line naming the field, exit code 2, no traceback.

Each file in tests/bad_inputs/ starts with ``# expect: <text>``; the CLI's stderr must contain it.
"""

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdverify.errors import InputError
from pdverify.scene import parse_scene

ROOT = Path(__file__).parents[1]
BAD = sorted((ROOT / "tests" / "bad_inputs").glob("scene_*.toml"))


def expected(path):
    first = path.read_text().splitlines()[0]
    assert first.startswith("# expect: ")
    return first[len("# expect: "):]


def test_enough_bad_inputs():
    assert len(BAD) >= 30


@pytest.mark.parametrize("path", BAD, ids=[p.stem for p in BAD])
def test_bad_scene_file(path):
    r = subprocess.run([sys.executable, "-m", "pdverify.cli", "solve", str(path), "--model", "exact-eb"],
                       capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 2, r.stdout
    assert "Traceback" not in r.stderr
    assert expected(path) in r.stderr, r.stderr
    assert all(line.startswith("error: ") for line in r.stderr.strip().splitlines())
    assert r.stdout == ""


VALID = tomllib.loads((ROOT / "studies/examples/cantilever_tip_load.toml").read_text())
atoms = st.one_of(st.none(), st.booleans(), st.integers(-10, 10), st.floats(allow_nan=True, allow_infinity=True),
                  st.text(max_size=8), st.lists(st.integers(), max_size=3))


def mutate(data, path, value):
    import copy

    d = copy.deepcopy(data)
    node = d
    for k in path[:-1]:
        node = node[k] if isinstance(node, dict) else node[0]
    if isinstance(node, list):
        node = node[0]
    node[path[-1]] = value
    return d


PATHS = [("name",), ("beam",), ("beam", "length"), ("section", "width"), ("section", "height"), ("section", "area"),
         ("material", "youngs_modulus"), ("material", "poissons_ratio"), ("material", "density"),
         ("supports", "left"), ("supports", "right"), ("loads",), ("loads", "type"), ("loads", "position"),
         ("loads", "value"), ("loads", "start"), ("loads", "shape"), ("axis",), ("extra",)]


@settings(max_examples=300, deadline=None)
@given(path=st.sampled_from(PATHS), value=atoms)
def test_fuzz_scene_parser_never_crashes(path, value):
    """Any mutation either parses or raises InputError with non-empty one-line messages."""
    try:
        parse_scene(mutate(VALID, path, value))
    except InputError as exc:
        assert exc.lines and all(l and "\n" not in l for l in exc.lines)


@settings(max_examples=200, deadline=None)
@given(st.recursive(atoms, lambda c: st.dictionaries(st.text(max_size=6), c, max_size=4) | st.lists(c, max_size=3), max_leaves=12))
def test_fuzz_arbitrary_documents(doc):
    try:
        parse_scene(doc if isinstance(doc, dict) else {"x": doc})
    except InputError as exc:
        assert exc.lines
