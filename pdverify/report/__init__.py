"""HTML report of a study directory: self-contained (inline SVG figures, inline CSS/JS), offline."""

from .build import build_report  # noqa: F401
