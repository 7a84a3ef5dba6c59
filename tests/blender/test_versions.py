# SPDX-License-Identifier: GPL-3.0-or-later
"""The Blender versions the manifest promises (issue 29.9): what made Blender 4.2's bpy module
crash at exit (a PropertyGroup with methods, a Python timer Blender freed itself), and the smoke
test CI runs on each LTS (scripts/smoke.sh), here on the running Blender."""

from __future__ import annotations

import inspect
import subprocess
import sys

import pytest

from tests.blender.helpers import ext, keyframe_stroke, setup_scene
from tests.paths import ADDON, ROOT

bpy = pytest.importorskip("bpy")


def test_no_property_group_of_the_extension_has_methods(hb):
    groups = [
        cls
        for mod in list(sys.modules.values())
        if getattr(mod, "__name__", "").startswith(ADDON)
        for _name, cls in inspect.getmembers(mod, inspect.isclass)
        if issubclass(cls, bpy.types.PropertyGroup) and cls.__module__ == mod.__name__
    ]
    assert {c.__name__ for c in groups} >= {"HAIRY_BRUSH_PG_settings", "HAIRY_BRUSH_PG_quality"}
    for cls in groups:
        methods = [n for n, v in vars(cls).items() if callable(v) and not n.startswith("__")]
        assert methods == [], f"{cls.__name__} has methods {methods} (Blender 4.2 crashes)"


def test_the_catch_up_timer_ends_with_its_file_and_with_the_extension(hb, monkeypatch):
    import addon_utils

    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    handlers = ext().blender.handlers
    monkeypatch.setattr(handlers, "exact_frames", lambda: False)  # as while the artist works
    monkeypatch.setattr(handlers, "FRAME_BUDGET_S", 0.0)

    def catch_up():
        bpy.context.scene.frame_set(45)
        (timer,) = ext().blender.runtime.get().timers
        assert bpy.app.timers.is_registered(timer)
        return timer

    timer = catch_up()
    bpy.ops.wm.read_homefile(use_empty=True)  # another file: the runtime stops it
    assert not bpy.app.timers.is_registered(timer)
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    timer = catch_up()
    addon_utils.disable(ADDON, default_set=True)  # and so does disabling the extension
    try:
        assert not bpy.app.timers.is_registered(timer)
    finally:
        addon_utils.enable(ADDON, default_set=True)


@pytest.mark.slow
def test_the_smoke_test_passes_on_this_blender(extension_zip):
    """What CI runs on each LTS: install, write, simulate, render, save, reopen, exit cleanly."""
    res = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "smoke.py"), str(extension_zip)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    lines = [ln for ln in res.stdout.splitlines() if ln.startswith("smoke:")]
    assert res.returncode == 0, "\n".join(lines) + res.stderr[-2000:]
    assert lines[-1].startswith("smoke: ok on Blender")
