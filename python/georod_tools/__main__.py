"""``python -m georod_tools``: the command line (see :mod:`georod_tools.cli`)."""

from georod_tools.cli import entry

entry()
