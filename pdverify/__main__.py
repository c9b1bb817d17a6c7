"""``python -m pdverify``: the command line (:func:`pdverify.apps.cli.main`)."""

from .apps.cli import main

main()
