"""``python -m gyroshell``: the command-line interface."""

from gyroshell.cli import main

raise SystemExit(main())
