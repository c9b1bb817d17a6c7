"""Where the report goes: its folder, its files written whole, the page templates."""

from __future__ import annotations

from pathlib import Path

import jinja2

from ..core.errors import OutputError
from ..study.store import write_atomic


def make_folder(out: Path) -> None:
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(
            f"{out}: cannot make the report folder ({exc.strerror or exc}); choose another --out"
        ) from None


def write(path: Path, data) -> None:
    """A report file written whole (temporary file, then renamed) or OutputError naming it (exit code 4)."""
    try:
        write_atomic(path, data)
    except OSError as exc:
        raise OutputError(f"{path}: cannot write the report ({exc.strerror or exc}); choose another --out") from None


def environment() -> jinja2.Environment:
    """The templates, every value escaped unless it is Markup (tables and figures built here)."""
    return jinja2.Environment(loader=jinja2.FileSystemLoader(Path(__file__).parent / "templates"), autoescape=True)
