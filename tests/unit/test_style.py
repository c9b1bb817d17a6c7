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


def test_a_models_info_is_merged_not_replaced():
    """A dict merged into a result's ``info`` goes through ``core.result.merge_info``, which joins the two
    ``warnings`` lists: ``info.update(other)`` keeps only ``other``'s, and a model's own warning was lost that way
    (pd-timoshenko's couple on two points, under a solve's round-off warning). Keyword updates name what they set."""
    found = []
    for path in sorted([*(ROOT / "pdverify").rglob("*.py"), *(ROOT / "reference_fem").rglob("*.py")]):
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr == "update"
                and isinstance(node.func.value, ast.Name)
                and node.func.value.id == "info"
                and (node.args or any(k.arg is None for k in node.keywords))
                and path.name != "result.py"  # merge_info itself
            ):
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not found, "merge these with core.result.merge_info:\n" + "\n".join(found)
