"""``python -m chaindrive`` runs the command line."""

from chaindrive.cli import main

main()
