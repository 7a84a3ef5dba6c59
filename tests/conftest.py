# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

# Blender reads its user folders once, at `import bpy`: give the test session its own, so the
# extension is installed into a temporary Blender user folder, as a user would install it.
os.environ.setdefault("BLENDER_USER_RESOURCES", tempfile.mkdtemp(prefix="hairy-brush-user-"))
# and the command line's cache (the brush's calibrated response) goes to a temporary folder too,
# never into the user's home
os.environ["HAIRY_BRUSH_CACHE"] = tempfile.mkdtemp(prefix="hairy-brush-cache-")

from sim.brush.primitive import HairyBrush  # noqa: E402
from sim.core.params import BrushGeometry, QualityParams  # noqa: E402

ADDON = "bl_ext.user_default.hairy_brush"


@pytest.fixture
def brush():
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.Generator(np.random.PCG64(0)))
    b.place([50.0, 50.0, 40.0, 0.0, 0.0, 0.0])
    return b


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
    return ADDON


@pytest.fixture
def hb(installed):
    """A fresh empty scene with the extension enabled; returns the bpy module."""
    import addon_utils
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    if installed not in bpy.context.preferences.addons:
        addon_utils.enable(installed, default_set=True)
    return bpy
