"""pdverify: how far is a peridynamic beam model from the truth, in numbers."""

__version__ = "0.1.0"
