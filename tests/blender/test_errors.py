# SPDX-License-Identifier: GPL-3.0-or-later
"""Bad input and broken state get one clear message and change nothing."""

from __future__ import annotations

import pytest

from tests.blender.helpers import (
    ext,
    keyframe_stroke,
    setup_scene,
)

bpy = pytest.importorskip("bpy")


# ----------------------------------------------------------------------------- bad input
def test_clear_errors_for_bad_input(hb):
    with pytest.raises(RuntimeError, match="No brush empty"):
        bpy.ops.hairy_brush.bake_samples()
    with pytest.raises(RuntimeError, match="No recording"):
        bpy.ops.hairy_brush.simulate()
    st = bpy.context.scene.hairy_brush
    st.paper_width_mm, st.px_per_mm = 5000.0, 100.0
    with pytest.raises(RuntimeError, match="too large"):
        bpy.ops.hairy_brush.setup()
    assert st.paper_object is None  # nothing half-built
    st.paper_width_mm, st.px_per_mm = 200.0, 2.0
    setup_scene(bpy, ppm=2.0)
    keyframe_stroke(bpy, st)
    fcurve = ext().blender.keyframes.fcurves(st.brush_object.animation_data)[0]
    fcurve.keyframe_points[1].co.y = float("nan")
    with pytest.raises(RuntimeError, match="not a number on location"):
        bpy.ops.hairy_brush.bake_samples()
    st.recording = bpy.data.texts.new("junk")
    st.recording.from_string("{not json")
    with pytest.raises(RuntimeError, match="not valid JSON"):
        bpy.ops.hairy_brush.simulate()


# ----------------------------------------------------------------------------- nothing is lost
def test_bake_refuses_a_deleted_brush_and_keeps_the_recording(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    text = st.recording.as_string()
    brush = st.brush_object
    for ob in bpy.context.scene.objects:
        ob.select_set(ob == brush)
    bpy.context.view_layer.objects.active = brush
    bpy.ops.object.delete()
    with pytest.raises(RuntimeError, match="No brush empty in the scene"):
        bpy.ops.hairy_brush.bake_samples()
    assert st.recording.as_string() == text


def test_settings_that_are_not_numbers_get_one_message(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    st["px_per_mm"] = float("nan")  # as a hand-edited .blend can hold it
    for op in (bpy.ops.hairy_brush.bake_samples, bpy.ops.hairy_brush.simulate):
        with pytest.raises(RuntimeError, match="Resolution is not a number"):
            op()
    bpy.context.scene.frame_set(20)  # the handler reports, never raises
    assert "Resolution is not a number" in ext().blender.runtime.get().last_error
    st.px_per_mm = 2.0
    st.paper_object.scale = (0.0, 1.0, 1.0)
    with pytest.raises(RuntimeError, match="scaled to nothing"):
        bpy.ops.hairy_brush.bake_samples()


def test_a_broken_recording_is_parsed_once_and_frame_changes_stay_bounded(hb, monkeypatch):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    good = st.recording.as_string()
    st.recording.from_string("{not json")
    calls = []
    real = ext().blender.recordings.recording_from_scene
    monkeypatch.setattr(
        ext().blender.recordings, "recording_from_scene", lambda sc: calls.append(1) or real(sc)
    )
    sc = bpy.context.scene
    for f in (5, 6, 7):
        sc.frame_set(f)
    assert len(calls) == 1 and "not valid JSON" in ext().blender.runtime.get().last_error
    st.recording.from_string(good)
    # while the artist works (not rendering), a frame change simulates for a bounded time
    monkeypatch.setattr(ext().blender.handlers, "exact_frames", lambda: False)
    monkeypatch.setattr(ext().blender.handlers, "FRAME_BUDGET_S", 0.0)
    sc.frame_set(45)
    pb = ext().blender.playback.playback_for(sc)
    assert 0 < pb.sim.index < ext().blender.frames.samples_at_frame(pb.rec, sc, 45)


def test_a_paper_larger_than_free_memory_an_invalid_preset_and_a_utf16_file_get_one_message(
    hb, tmp_path, monkeypatch
):
    st = bpy.context.scene.hairy_brush
    monkeypatch.setattr(ext().blender.checks, "available_memory", lambda: 100 * 2**20)
    with pytest.raises(RuntimeError, match="MB of memory and 100 MB are free"):
        bpy.ops.hairy_brush.setup()
    assert st.paper_object is None  # nothing was made
    monkeypatch.undo()
    st["brush_preset"] = 999  # an enum value no item has, as a hand-edited .blend can hold
    with pytest.raises(RuntimeError, match="brush preset"):
        bpy.ops.hairy_brush.setup()
    path = tmp_path / "utf16.json"
    path.write_text('{"format": "hairy-brush-recording"}', encoding="utf-16")
    with pytest.raises(RuntimeError, match="save it as UTF-8"):
        bpy.ops.hairy_brush.import_recording(filepath=str(path))
