# SPDX-License-Identifier: GPL-3.0-or-later
"""Command line: ``python -m sim render REC.json -o OUT.png`` (from the repository root); the
commands are in ``sim.cli``."""

import sys

from .cli.main import main

if __name__ == "__main__":
    sys.exit(main())
