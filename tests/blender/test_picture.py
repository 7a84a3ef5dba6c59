# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 19 in Blender: hairy_brush.imitate_image from a PNG file and from an image datablock,
as a job with progress that Esc stops leaving the scene as it was, keyframing the brush empty
so the writing replays; bad pictures reported in one message (real bpy)."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

from tests.blender.helpers import ext
from tests.paths import ROOT

bpy = pytest.importorskip("bpy")

from sim.image.png import write_png  # noqa: E402
from sim.writing.outline import rasterise  # noqa: E402


def setup_scene(ppm=1.0):
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = ppm
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    return st


def picture(n=128) -> np.ndarray:
    char = json.loads((ROOT / "tests" / "data" / "unseen" / "王.json").read_text("utf-8"))
    return np.where(rasterise(char, n), 0.05, 0.95)


@pytest.mark.slow
def test_imitate_a_jpeg_through_blender(hb, tmp_path):
    setup_scene()
    img = bpy.data.images.new("pic", 128, 128)
    rgba = np.ones((128, 128, 4), np.float32)
    rgba[..., :3] = picture()[::-1, :, None]
    img.pixels.foreach_set(rgba.ravel())
    img.filepath_raw = str(tmp_path / "wang.jpg")
    img.file_format = "JPEG"
    img.save()
    bpy.data.images.remove(img)
    res = bpy.ops.hairy_brush.imitate_image(
        filepath=str(tmp_path / "wang.jpg"), size_mm=80.0, passes=1, detail=128
    )
    assert res == {"FINISHED"}
    assert "wang.jpg" not in bpy.data.images  # the picture was read, not kept


@pytest.mark.slow
def test_imitate_a_png_keyframes_the_brush_and_replays(hb, tmp_path):
    st = setup_scene()
    path = tmp_path / "wang.png"
    write_png(path, picture())
    res = bpy.ops.hairy_brush.imitate_image(filepath=str(path), size_mm=90.0, passes=1, detail=128)
    assert res == {"FINISHED"}
    stored = json.loads(st.recording.as_string())
    written = np.array(stored["samples"])
    assert st.paper_width_mm == 90.0 and len(written) > 100
    # written as ``sim imitate`` writes a picture (``write_imitation``): a dip before each of
    # 王's four strokes, the picture's tone matched, not the brush's (it dipped once before)
    assert len(stored["dips"]) == 4
    assert st.brush_object.animation_data.action is not None
    bpy.ops.hairy_brush.bake_samples()  # the keyframes give the same writing back
    baked = np.array(json.loads(st.recording.as_string())["samples"])
    np.testing.assert_allclose(baked[: len(written)], written, atol=2e-3)


@pytest.mark.slow
def test_imitate_a_piece_of_two_characters(hb, tmp_path):
    # two columns, 王 on the left and 口 on the right: with Several Characters each is read in
    # its own square, the right column first (read as one character, 王 comes first)
    st = setup_scene()
    kou = json.loads((ROOT / "tests" / "data" / "unseen" / "口.json").read_text("utf-8"))
    pic = np.full((140, 280), 0.95)
    pic[6:134, 5:133] = picture()
    pic[6:134, 147:275] = np.where(rasterise(kou, 128), 0.05, 0.95)
    path = tmp_path / "piece.png"
    write_png(path, pic)
    res = bpy.ops.hairy_brush.imitate_image(
        filepath=str(path), size_mm=120.0, passes=1, detail=192, piece=True
    )
    assert res == {"FINISHED"}
    samples = np.array(json.loads(st.recording.as_string())["samples"])
    down = samples[:, 2] < samples[:, 2].max() - 1e-6  # the brush on the paper
    starts = np.flatnonzero(down[1:] & ~down[:-1]) + 1
    left = (samples[starts, 0] < 60.0).astype(int)  # landings in the left half of the paper
    assert 0 < left.sum() < len(left) and np.all(np.diff(left) >= 0), samples[starts, 0]


@pytest.mark.slow
def test_imitate_an_image_datablock_and_bad_pictures(hb, tmp_path):
    st = setup_scene()
    pic = picture(96)
    img = bpy.data.images.new("wang", 96, 96)
    rgba = np.ones((96, 96, 4), np.float32)
    rgba[..., :3] = pic[::-1, :, None]  # Blender's rows are bottom first
    img.pixels.foreach_set(rgba.ravel())
    res = bpy.ops.hairy_brush.imitate_image(image="wang", size_mm=80.0, passes=1, detail=96)
    assert res == {"FINISHED"}
    assert st.paper_width_mm == 80.0
    blank = bpy.data.images.new("blank", 64, 64)
    blank.pixels.foreach_set(np.full(64 * 64 * 4, 0.9, np.float32))
    before = st.recording.as_string()
    with pytest.raises(RuntimeError, match="no writing"):
        bpy.ops.hairy_brush.imitate_image(image="blank")
    with pytest.raises(RuntimeError, match="no image named"):
        bpy.ops.hairy_brush.imitate_image(image="nothing")
    bad = tmp_path / "bad.png"
    bad.write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 20)
    with pytest.raises(RuntimeError, match="bad.png"):
        bpy.ops.hairy_brush.imitate_image(filepath=str(bad))
    not_a_picture = tmp_path / "notes.jpg"
    not_a_picture.write_text("not a picture")
    with pytest.raises(RuntimeError, match="not a picture Blender can read"):
        bpy.ops.hairy_brush.imitate_image(filepath=str(not_a_picture))
    assert "notes.jpg" not in bpy.data.images
    assert st.recording.as_string() == before  # user work is never lost


@pytest.mark.slow
def test_imitate_in_a_worker_stops_cleanly_and_finishes(hb):
    st = setup_scene()
    sc = bpy.context.scene
    mod = ext().blender.writing
    before = (st.paper_width_mm, sc.frame_end, st.brush_object.animation_data)
    job = mod.ImitateJob(sc, picture(96), "wang", 80.0, 1, 96)
    assert job.step(0.01) is False  # started in a worker: Blender's thread is free
    time.sleep(0.2)
    job.cancel()  # a flag the worker reads at its next progress call
    job._thread.join(60.0)
    assert not job._thread.is_alive() and job.result is None and job.error is None
    assert (st.paper_width_mm, sc.frame_end, st.brush_object.animation_data) == before
    job = mod.ImitateJob(sc, picture(96), "wang", 80.0, 1, 96)
    fractions = []
    end = time.perf_counter() + 120
    while not job.step(0.05):
        fractions.append(job.fraction)
        assert time.perf_counter() < end
    assert fractions and job.fraction == 1.0 and "strokes" in job.status_line()
    assert job.picture is None  # the picture's pixels were let go once read
    level, message = job.finish(bpy.context)
    assert level == "INFO" and message.startswith("wang: 4 strokes")
    assert st.recording is not None and st.brush_object.animation_data.action is not None


def test_imitate_is_greyed_out_without_a_brush_and_paper(hb):
    assert not bpy.ops.hairy_brush.imitate_image.poll()
    with pytest.raises(RuntimeError, match="No brush empty"):
        bpy.ops.hairy_brush.imitate_image(image="anything")


def test_the_size_tooltip_says_what_size_does_on_a_surface(hb):
    props = bpy.ops.hairy_brush.imitate_image.get_rna_type().properties
    tip = props["size_mm"].description
    assert "flat paper becomes this square" in tip and "on a surface" in tip, tip


def test_detail_is_capped_where_the_cli_caps_reading(hb):
    from sim.picture.imitate import MAX_DETAIL

    props = bpy.ops.hairy_brush.imitate_image.get_rna_type().properties
    assert props["detail"].hard_max == MAX_DETAIL == ext().sim.picture.imitate.MAX_DETAIL
