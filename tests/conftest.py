# SPDX-License-Identifier: GPL-3.0-or-later
"""For the whole suite: the repository on the path, and Blender's user folders and the command
line's cache in temporary folders (nothing is written into the user's home). The engine's tests
are in tests/sim (no Blender), the extension's in tests/blender; tests that take over a second
are marked ``slow`` (``bash scripts/test.sh --fast`` leaves them out)."""

import os
import shutil
import sys
import tempfile
from pathlib import Path

# the repository: ``sim`` and the tests' own modules (``tests.paths``, ``tests.blender.helpers``)
# import from here (the tests run with --import-mode=importlib: no test folder is a package, as
# the repository's own __init__.py, the add-on's, must not be imported by pytest)
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

# Blender reads its user folders once, at `import bpy`: give the test session its own, so the
# extension is installed into a temporary Blender user folder, as a user would install it.
# Both folders are the session's own and are removed when it ends (tens of MB each otherwise
# stay in /tmp after every run).
_MADE = []
if "BLENDER_USER_RESOURCES" not in os.environ:
    _MADE.append(tempfile.mkdtemp(prefix="hairy-brush-user-"))
    os.environ["BLENDER_USER_RESOURCES"] = _MADE[-1]
# and the command line's cache (the brush's calibrated response) goes to a temporary folder too,
# never into the user's home
_MADE.append(tempfile.mkdtemp(prefix="hairy-brush-cache-"))
os.environ["HAIRY_BRUSH_CACHE"] = _MADE[-1]


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: takes over a second (left out by --fast)")


def pytest_unconfigure(config):
    for folder in _MADE:
        shutil.rmtree(folder, ignore_errors=True)
