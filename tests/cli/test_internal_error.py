"""A defect of pdverify (an exception no input should cause) is one line naming the exception and where it was
raised, exit code 70, no traceback; PDVERIFY_DEBUG=1 lets the traceback through (pdverify/apps/cliargs.py)."""

import pytest
from helpers import ROOT, cli

from pdverify.apps.cliargs import INTERNAL_EXIT

SCENE = ROOT / "studies/examples/cantilever_tip_load.toml"


def _bug(*args, **kwargs):
    return {}["spacing"]  # a KeyError, as a defect raises one


def test_a_defect_is_one_line_and_its_own_exit_code(capsys, monkeypatch):
    monkeypatch.delenv("PDVERIFY_DEBUG", raising=False)
    monkeypatch.setattr("pdverify.registry.run", _bug)
    code, out, err = cli(["solve", SCENE, "-m", "exact-eb"], capsys)
    assert code == INTERNAL_EXIT == 70 and out == "" and "Traceback" not in err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: internal error of pdverify (KeyError: 'spacing' at "), err
    assert "test_internal_error.py" in lines[0] and "PDVERIFY_DEBUG=1" in lines[0]


def test_pdverify_debug_shows_the_traceback(capsys, monkeypatch):
    monkeypatch.setenv("PDVERIFY_DEBUG", "1")
    monkeypatch.setattr("pdverify.registry.run", _bug)
    with pytest.raises(KeyError):
        cli(["solve", SCENE, "-m", "exact-eb"], capsys)


def test_user_errors_keep_their_codes(capsys):
    """Exit codes 0-4 are unchanged: a bad option is 2, a passing run 0."""
    assert cli(["solve", SCENE, "-m", "nosuch"], capsys)[0] == 2
    assert cli(["solve", SCENE, "-m", "exact-eb"], capsys)[0] == 0
