"""``python -m georod_tools``: the command line (see :mod:`georod_tools.cli`)."""

import sys

from georod_tools.cli import main

sys.exit(main())
