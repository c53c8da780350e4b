"""`python -m coatsim.cli`: the coatsim command."""

from coatsim.cli import main

main()
