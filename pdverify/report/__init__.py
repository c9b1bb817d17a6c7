"""HTML report of a study directory: self-contained (figures drawn by the page from inline data, matplotlib SVG on
the paper pages, inline CSS/JS), offline."""

from .build import build_report  # noqa: F401
