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
from tests.faults import disk_full_at

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
