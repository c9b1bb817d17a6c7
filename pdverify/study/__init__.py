"""Study runner: sweeps of scenes x models x options, errors against a reference, derived tables."""

from .runner import run_study  # noqa: F401
from .spec import Study, load_study  # noqa: F401
