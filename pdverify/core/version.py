"""The package version (one place; ``pdverify.__version__`` and every result, case file and report record it)."""

__version__ = "0.1.0"
