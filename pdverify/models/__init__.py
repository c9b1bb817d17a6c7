"""Peridynamic beam models, one module each; each module lists its models in ``MODELS``."""
