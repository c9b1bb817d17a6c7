"""The code stays as ruff (configured in pyproject.toml: lint and format, lines of at most 120) leaves it."""

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
