# SPDX-License-Identifier: GPL-3.0-or-later
"""Faults lose nothing in Blender (issue 30): a farm cache that is not provably the scene's is
ignored with a warning, never trusted; files are written whole; NaN settings are refused by
name or repaired, never spread into the brush's keyframes or a preset file; a bake that would
be refused is refused before the long work."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from sim.engine.simulation import Simulation
from tests.blender.helpers import ext, keyframe_stroke, pixels, setup_scene
from tests.faults import disk_full_at, leftovers, lost_files, snapshot
from tests.paths import ADDON, ROOT

bpy = pytest.importorskip("bpy")


def farm_scene(tmp_path, y=0.0):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, y=y, frames=(1, 8, 70, 80))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "shot.blend"))
    return st, tmp_path / "hairy_brush_cache_shot" / "Scene"


def shown_equals_simulated(st, frame) -> bool:
    sc = bpy.context.scene
    sc.frame_set(frame)
    rec = ext().blender.recordings.recording_from_scene(sc)
    want = Simulation(rec).run(ext().blender.frames.samples_at_frame(rec, sc, frame))
    return np.abs(pixels(st.paper_image)[..., :3] - want.paper.rgb()).max() <= 0.5 / 4095 + 1e-6


def fresh_playback():
    ext().blender.runtime.get().forget_playbacks()
    return ext().blender.playback.playback_for(bpy.context.scene)


# ------------------------------------------------------------------ 1. files written whole
def test_an_export_on_a_full_disk_keeps_the_earlier_export(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    out = tmp_path / "take.json"
    assert bpy.ops.hairy_brush.export_recording(filepath=str(out)) == {"FINISHED"}
    before = out.read_bytes()
    st.quality.ren = 0.5 if st.quality.ren != 0.5 else 0.4
    with disk_full_at("take"), pytest.raises(RuntimeError, match="cannot write .*No space"):
        bpy.ops.hairy_brush.export_recording(filepath=str(out))
    assert out.read_bytes() == before and not leftovers(tmp_path)


def test_an_image_sequence_on_a_full_disk_keeps_every_earlier_frame(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=(1, 2, 5, 6))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    st.sequence_dir = str(tmp_path / "frames")
    assert bpy.ops.hairy_brush.bake_sequence() == {"FINISHED"}
    before = snapshot(tmp_path / "frames")
    assert len(before) == 6
    st.quality.ren = 0.5 if st.quality.ren != 0.5 else 0.4
    with disk_full_at("paper_0004"), pytest.raises(RuntimeError, match="cannot write"):
        bpy.ops.hairy_brush.bake_sequence()
    assert lost_files(before, tmp_path / "frames") == []
    assert not leftovers(tmp_path / "frames")


KILLED_EXPORT = """
import resource, signal, sys
import bpy  # first: it puts addon_utils on the path
import addon_utils
signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # Python ignores it: the kernel's kill back
addon_utils.enable({addon!r}, default_set=True)
st = bpy.context.scene.hairy_brush
st.px_per_mm = 2.0
bpy.ops.hairy_brush.setup()
b = st.brush_object
for f, x, z in ((1, -0.05, 0.03), (8, -0.05, 0.005), (200, 0.05, 0.005), (210, 0.06, 0.03)):
    b.location = (x, 0.0, z)
    b.keyframe_insert("location", frame=f)
bpy.context.scene.frame_end = 210
bpy.ops.hairy_brush.bake_samples()
bpy.ops.hairy_brush.export_recording(filepath={out!r})
size = len(open({out!r}, "rb").read())
resource.setrlimit(resource.RLIMIT_FSIZE, (size // 2, size // 2))
st.quality.ren = 0.5 if st.quality.ren != 0.5 else 0.4
print("exporting again", flush=True)
bpy.ops.hairy_brush.export_recording(filepath={out!r})
"""


@pytest.mark.slow
def test_blender_killed_while_it_exports_keeps_the_earlier_export(hb, tmp_path):
    import subprocess
    import sys

    out = tmp_path / "take.json"
    script = KILLED_EXPORT.format(addon=ADDON, out=str(out))
    r = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300, cwd=ROOT
    )
    assert r.returncode == -25 and "exporting again" in r.stdout, r.stderr  # SIGXFSZ
    assert json.loads(out.read_text())["samples"]  # the first export, whole


# ------------------------------------------------------------------ 2. the farm cache
@pytest.mark.slow
def test_a_damaged_checkpoint_is_ignored_with_a_warning_and_simulate_still_works(hb, tmp_path):
    st, folder = farm_scene(tmp_path)
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    victim = sorted(folder.glob("checkpoint_*.npz"))[1]
    victim.write_bytes(victim.read_bytes()[:100])  # truncated, as by a full disk or a kill
    pb = fresh_playback()
    assert "not used" in pb.cache_warning and victim.name in pb.cache_warning
    assert list(pb.timeline.snaps) == [0]  # nothing of it was taken
    for frame in (60, 20, 75):
        assert shown_equals_simulated(st, frame)
        assert ext().blender.runtime.get().last_error == ""
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}


@pytest.mark.slow
def test_a_bake_that_fails_at_its_manifest_cannot_make_the_cache_lie(hb, tmp_path):
    """Issue 30: bake for A, change to B, bake again failing at the manifest, put A back: the
    frames are A's, simulated or from A's cache, never B's checkpoints under A's manifest."""
    st, folder = farm_scene(tmp_path)
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    text_a = st.recording.as_string()
    keyframe_stroke(bpy, st, y=0.03, press=6.0, frames=(1, 8, 70, 80))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    with disk_full_at("manifest"), pytest.raises(RuntimeError, match="No space left") as err:
        bpy.ops.hairy_brush.bake_cache()
    assert "Traceback" not in str(err.value)
    st.recording.from_string(text_a)
    pb = fresh_playback()
    for frame in (60, 75, 40):
        assert shown_equals_simulated(st, frame)
    assert pb.cache_warning == "" and len(pb.timeline.snaps) > 1  # A's own cache, whole
    assert [p.name for p in folder.parent.iterdir()] == ["Scene"]  # no half-made folder


@pytest.mark.slow
def test_a_stale_cache_is_named_in_the_warning(hb, tmp_path):
    st, folder = farm_scene(tmp_path)
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    st.quality.ren = 0.123 if st.quality.ren != 0.123 else 0.321
    pb = fresh_playback()
    assert "another recording or other settings" in pb.cache_warning
    assert len(pb.timeline.snaps) == 1
    manifest = json.loads((folder / "manifest.json").read_text())
    assert all(isinstance(f["bytes"], int) for f in manifest["files"])
    assert math.isfinite(st.quality.ren)


# ------------------------------------------------------------------ 7. refused before the work
def test_a_bake_of_too_many_samples_is_refused_before_stepping_the_frames(hb, monkeypatch):
    import time

    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    sc = bpy.context.scene
    sc.frame_end = 400_010  # 2,000,046 samples at 120 Hz and 24 fps
    stepped = []
    monkeypatch.setattr(ext().operators.bake_samples, "_at_frames", lambda *a: stepped.append(a))
    t0 = time.perf_counter()
    with pytest.raises(RuntimeError, match="2,000,046 samples, more than a recording holds"):
        bpy.ops.hairy_brush.bake_samples()
    assert time.perf_counter() - t0 < 5.0 and stepped == [] and st.recording is None


# ------------------------------------------------------------------ 5. NaN settings
def location_keys(st) -> np.ndarray:
    fcurves = ext().blender.keyframes.fcurves(st.brush_object.animation_data)
    return np.array(
        [kp.co[1] for fc in fcurves if fc.data_path == "location" for kp in fc.keyframe_points]
    )


def test_a_nan_touching_height_moves_nothing_when_a_brush_preset_is_applied(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    keys, where = location_keys(st), tuple(st.brush_object.location)
    st.touch_height_mm = float("nan")  # as a damaged .blend can hold it
    for name in ("goat_soft", "goat_soft"):  # another preset, then the same one again
        assert bpy.ops.hairy_brush.apply_preset(kind="brush", name=name) == {"FINISHED"}
        assert np.isfinite(location_keys(st)).all() and np.array_equal(location_keys(st), keys)
        assert tuple(st.brush_object.location) == where
        assert math.isfinite(st.touch_height_mm)
        st.touch_height_mm = float("nan")


def test_a_nan_setting_is_refused_by_name_where_it_is_used(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    paint = ext().operators.paint
    sc = bpy.context.scene
    for name, label in [("paint_angle_step", "Angle Step"), ("paper_capacity", "Ink Capacity")]:
        good = getattr(st, name)
        st[name] = float("nan")
        with pytest.raises(ext().blender.checks.UserError, match=f"{label} is not a number"):
            paint.start_simulation(sc, (60.0, 100.0))
        setattr(st, name, good)
    st.paper_color[1] = float("nan")
    with pytest.raises(RuntimeError, match="Paper Colour is not a number"):
        bpy.ops.hairy_brush.simulate()


def test_a_preset_is_written_from_data_and_a_nan_setting_is_refused(hb):
    st = setup_scene(bpy)
    st.quality.e = 0.123
    st.dip_depth = float("nan")
    with pytest.raises(RuntimeError, match="Preset not saved: Dip depth is not a number"):
        bpy.ops.hairy_brush.add_settings_preset(name="Broken")
    assert not bpy.utils.preset_find("Broken", "hairy_brush/settings", display_name=True)
    st.dip_depth = 0.5
    assert bpy.ops.hairy_brush.add_settings_preset(name="Sound") == {"FINISHED"}
    path = bpy.utils.preset_find("Sound", "hairy_brush/settings", display_name=True)
    text = open(path, encoding="utf-8").read()
    assert "nan" not in text and "st.quality.e = 0.12" in text
    st.quality.e, st.dip_depth = 0.9, 0.9
    bpy.ops.script.execute_preset(filepath=path, menu_idname="HAIRY_BRUSH_MT_settings_presets")
    assert math.isclose(st.quality.e, 0.123, abs_tol=1e-6) and st.dip_depth == 0.5
    literal = ext().operators.add_settings_preset.preset_literal
    with pytest.raises(ValueError):
        literal((0.1, float("nan"), 0.2))
    assert eval(literal((0.1, 1e16, 2))) == (0.1, 1e16, 2)  # noqa: S307 - our own literal
    assert eval(literal('a "name"\n')) == 'a "name"\n'  # noqa: S307


# ------------------------------------------------------------------ 8. messages
def test_a_nan_character_size_is_named(hb, tmp_path):
    setup_scene(bpy)
    path = ROOT / "data" / "hanzi" / "一.json"
    with pytest.raises(RuntimeError, match="Size \\(mm\\) is not a number") as err:
        bpy.ops.hairy_brush.write_character(filepath=str(path), size_mm=float("nan"))
    assert "convert" not in str(err.value)
