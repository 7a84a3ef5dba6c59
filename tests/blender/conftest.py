# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the extension's tests: the zip built once and installed as a user installs it,
and every test given a fresh empty scene with the extension enabled (autouse)."""

import subprocess
import sys
from pathlib import Path

import pytest

from tests.paths import ADDON, ROOT


@pytest.fixture(scope="session")
def extension_zip(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    res = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "build_extension.py"), str(out)],
        capture_output=True,
        text=True,
        check=True,
    )
    return Path(res.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="session")
def installed(extension_zip):
    """The extension installed from the built zip and enabled (returns its module name)."""
    bpy = pytest.importorskip("bpy")
    res = bpy.ops.extensions.package_install_files(
        filepath=str(extension_zip), repo="user_default", enable_on_install=True
    )
    assert res == {"FINISHED"}
    yield ADDON
    # disabled at the end, as a user would: its timers and handlers go (a timer left registered
    # crashes Blender 4.2's bpy module at exit)
    import addon_utils

    addon_utils.disable(ADDON, default_set=True)


@pytest.fixture(autouse=True)
def hb(installed):
    """Each test starts from a fresh empty scene with the extension enabled (loading it clears
    the extension's runtime state); returns the bpy module."""
    import addon_utils
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    if installed not in bpy.context.preferences.addons:
        addon_utils.enable(installed, default_set=True)
    return bpy
