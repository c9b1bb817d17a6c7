"""``python -m pdverify``: the command line (:func:`pdverify.cli.main`)."""

from .cli import main

main()
