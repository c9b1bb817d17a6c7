"""The code stays as ruff (configured in pyproject.toml: lint and format, lines of at most 120) leaves it."""

import ast
import subprocess
import sys

import pytest
from helpers import ROOT


@pytest.mark.parametrize("args", [["check", "."], ["format", "--check", "."]], ids=["lint", "format"])
def test_ruff_is_clean(args):
    out = subprocess.run([sys.executable, "-m", "ruff", *args], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-1000:]


MODULE_LINES = 450  # tests/README.md: a module holds one idea; a longer one says why in a "# long module:" comment


def test_modules_are_short_or_say_why():
    long = []
    for path in sorted([*(ROOT / "pdverify").rglob("*.py"), *(ROOT / "reference_fem").rglob("*.py")]):
        lines = path.read_text().splitlines()
        if len(lines) > MODULE_LINES and not any(line.startswith("# long module:") for line in lines):
            long.append(f"{path.relative_to(ROOT)}: {len(lines)} lines")
    assert not long, "split these or say why (# long module: ...):\n" + "\n".join(long)


def _replaces_info(node) -> bool:
    """``info.update(<a mapping>)`` (positional or ``**``) or ``info["warnings"] = ...``: what can replace the list."""
    if isinstance(node, ast.Call):
        f = node.func
        return (
            isinstance(f, ast.Attribute)
            and f.attr == "update"
            and isinstance(f.value, ast.Name)
            and f.value.id == "info"
            and bool(node.args or any(k.arg is None for k in node.keywords))
        )
    return isinstance(node, ast.Assign) and any(
        isinstance(t, ast.Subscript)
        and isinstance(t.value, ast.Name)
        and t.value.id == "info"
        and isinstance(t.slice, ast.Constant)
        and t.slice.value == "warnings"
        for t in node.targets
    )


def test_a_models_info_is_merged_not_replaced():
    """A dict merged into a result's ``info`` goes through ``core.result.merge_info``, which joins the two
    ``warnings`` lists, and a warning is appended to the list: ``info.update(other)`` or ``info["warnings"] = [...]``
    keeps only the last list, and a model's own warning was lost that way (pd-timoshenko's couple on two points,
    under a solve's round-off warning). Keyword updates name what they set."""
    found = [
        f"{path.relative_to(ROOT)}:{node.lineno}"
        for path in sorted([*(ROOT / "pdverify").rglob("*.py"), *(ROOT / "reference_fem").rglob("*.py")])
        if path.name != "result.py"  # merge_info itself
        for node in ast.walk(ast.parse(path.read_text()))
        if _replaces_info(node)
    ]
    assert not found, "merge these with core.result.merge_info, or append the warning:\n" + "\n".join(found)


def test_test_modules_have_names_no_other_has():
    """The tests' folders are not packages, so pytest imports each test module by its file name: two of one name
    (tests/unit/numerics/test_recovery.py beside tests/papers/ogrady/test_recovery.py) stop the collection."""
    names = [p.name for p in (ROOT / "tests").rglob("test_*.py")]
    assert sorted({n for n in names if names.count(n) > 1}) == []
