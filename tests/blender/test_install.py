# SPDX-License-Identifier: GPL-3.0-or-later
"""The extension installed from its built zip into a temporary user folder and enabled as a user
would: what the zip holds, and registering it again leaves nothing behind."""

from __future__ import annotations

import zipfile

import pytest

from tests.blender.helpers import (
    ext,
)
from tests.paths import ADDON

bpy = pytest.importorskip("bpy")


# ----------------------------------------------------------------------------- packaging
def test_zip_holds_the_extension_and_no_dev_files(extension_zip):
    names = zipfile.ZipFile(extension_zip).namelist()
    assert "blender_manifest.toml" in names and "__init__.py" in names
    assert any(n.startswith("wheels/geomdl-") and n.endswith(".whl") for n in names)
    assert "sim/engine/simulation.py" in names and "presets/brushes/mixed.json" in names
    assert "operators/paint.py" in names and "panels/sidebar.py" in names
    for bad in ("tests/", "scripts/", ".venv/", ".ci/", "out/", "docs/", "pyproject.toml"):
        assert not any(n.startswith(bad) for n in names), bad


def test_blenders_own_tool_validates_the_zip_and_builds_the_same_files(extension_zip, tmp_path):
    """The zip is built in plain Python (scripts/build_extension.py); Blender's extension tool
    accepts it and, building from the same checkout, packs the same files."""
    import subprocess
    import sys

    from tests.paths import ROOT

    sys.path.insert(0, str(ROOT / "scripts"))
    import build_extension

    tool = build_extension.blender_ext_tool()
    res = subprocess.run([sys.executable, str(tool), "validate", str(extension_zip)], text=True)
    assert res.returncode == 0
    theirs = build_extension.build_with_tool(tmp_path)
    assert theirs.name == extension_zip.name
    assert sorted(zipfile.ZipFile(theirs).namelist()) == zipfile.ZipFile(extension_zip).namelist()


def test_installed_copy_is_the_one_enabled(hb):
    mod = ext()
    assert ADDON in bpy.context.preferences.addons
    user = bpy.utils.user_resource("EXTENSIONS")
    assert mod.__file__.startswith(user)
    assert hasattr(bpy.types.Scene, "hairy_brush")
    assert mod.sim.__name__ == ADDON + ".sim"  # the engine travels inside the extension


def test_register_unregister_register_leaves_nothing_behind(hb):
    import addon_utils

    from_handlers = lambda: [  # noqa: E731
        f
        for lst in (bpy.app.handlers.frame_change_post, bpy.app.handlers.undo_post)
        for f in lst
        if getattr(f, "__module__", "").startswith(ADDON)
    ]
    assert len(from_handlers()) == 2
    addon_utils.disable(ADDON, default_set=True)
    assert not hasattr(bpy.types.Scene, "hairy_brush")
    assert not hasattr(bpy.types, "HAIRY_BRUSH_PT_main")
    assert not hasattr(bpy.types, "HAIRY_BRUSH_OT_setup")
    with pytest.raises(AttributeError):
        bpy.ops.hairy_brush.setup()
    assert from_handlers() == []
    addon_utils.enable(ADDON, default_set=True)
    assert hasattr(bpy.types.Scene, "hairy_brush") and len(from_handlers()) == 2
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
