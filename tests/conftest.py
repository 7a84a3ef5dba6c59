# SPDX-License-Identifier: GPL-3.0-or-later
"""For the whole suite: the repository on the path, and Blender's user folders and the command
line's cache in temporary folders (nothing is written into the user's home). The engine's tests
are in tests/sim (no Blender), the extension's in tests/blender; tests that take over a second
are marked ``slow`` (``bash scripts/test.sh --fast`` leaves them out)."""

import os
import sys
import tempfile
from pathlib import Path

# the repository: ``sim`` and the tests' own modules (``tests.paths``, ``tests.blender.helpers``)
# import from here (the tests run with --import-mode=importlib: no test folder is a package, as
# the repository's own __init__.py, the add-on's, must not be imported by pytest)
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

# Blender reads its user folders once, at `import bpy`: give the test session its own, so the
# extension is installed into a temporary Blender user folder, as a user would install it.
os.environ.setdefault("BLENDER_USER_RESOURCES", tempfile.mkdtemp(prefix="hairy-brush-user-"))
# and the command line's cache (the brush's calibrated response) goes to a temporary folder too,
# never into the user's home
os.environ["HAIRY_BRUSH_CACHE"] = tempfile.mkdtemp(prefix="hairy-brush-cache-")


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: takes over a second (left out by --fast)")
