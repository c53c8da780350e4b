"""``python -m coatsim``: the command line, as the ``coatsim`` command."""

from coatsim.cli import main

main()
