# SPDX-License-Identifier: GPL-3.0-or-later
"""Write Character and Fit Parameters in Blender."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sim.engine.simulation import Simulation  # noqa: E402
from tests.blender.helpers import (
    HAIR,
    ext,
    keyframe_stroke,
    pixels,
    setup_scene,
)
from tests.paths import ROOT

bpy = pytest.importorskip("bpy")


@pytest.mark.slow
def test_write_character_keyframes_bake_back_into_the_same_samples(hb):

    st = setup_scene(bpy, ppm=1.0)
    path = ROOT / "data" / "hanzi" / "十.json"
    assert bpy.ops.hairy_brush.write_character(filepath=str(path), size_mm=100.0) == {"FINISHED"}
    written = np.array(json.loads(st.recording.as_string())["samples"])
    assert st.paper_width_mm == 100.0 and len(written) > 100
    bpy.ops.hairy_brush.bake_samples()
    baked = np.array(json.loads(st.recording.as_string())["samples"])
    # the frame range ends on the next whole frame: a few more samples hold the lifted end pose
    assert len(written) <= len(baked) <= len(written) + 120 / 24
    np.testing.assert_allclose(baked[: len(written)], written, atol=2e-3)  # float32 keyframes
    np.testing.assert_allclose(
        baked[len(written) :], written[-1:].repeat(len(baked) - len(written), 0), atol=2e-3
    )
    with pytest.raises(RuntimeError, match="not hanzi-writer data"):
        bad = ROOT / "examples" / "strokes.json"
        bpy.ops.hairy_brush.write_character(filepath=str(bad))


@pytest.mark.slow
def test_write_character_presses_from_the_outline_and_shows_the_writing(hb):
    st = setup_scene(bpy, ppm=1.5)
    before = (st.paper_width_mm, st.paper_height_mm)
    with pytest.raises(RuntimeError, match="no data"):
        bpy.ops.hairy_brush.write_character(character="龘", size_mm=80.0)
    assert (st.paper_width_mm, st.paper_height_mm) == before  # nothing changed on an error
    # a character looked up in the bundled data; the size follows from the brush
    assert bpy.ops.hairy_brush.write_character(character="一", passes=2) == {"FINISHED"}
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    assert rec.width_mm == pytest.approx(st.paper_width_mm) and 30 < rec.width_mm < 300
    z = rec.samples[:, 2]
    pressed = z[z < HAIR]
    assert pressed.max() - pressed.min() > 2.0  # the press follows the stroke's width
    # what the operator shows is what the stored recording renders (to the image's 8 bits)
    shown = pixels(st.paper_image)[..., :3]
    replay = Simulation(rec).run().paper.rgb()
    assert np.abs(shown - replay).max() <= 0.5 / 255 + 1e-6
    assert (shown.mean(axis=2) < 0.5).mean() > 0.03


@pytest.mark.slow
def test_a_small_character_is_written_with_a_brush_for_its_size_and_replays(hb):
    st = setup_scene(bpy, ppm=3.0)
    recs = ext().blender.recordings
    ok = bpy.ops.hairy_brush.write_character(character="一", size_mm=30.0, passes=1)
    assert ok == {"FINISHED"}
    rec = recs.recording_from_scene(bpy.context.scene)
    k = rec.brush["scale"]  # a brush made smaller for 30 mm (its own size is about 100)
    assert 0.25 <= k < 0.5 and st.recording[recs.SCALE_TAG] == pytest.approx(k)
    from tests.blender.test_sidebar import drawn, names

    labels = " ".join(names(drawn(bpy.types.HAIRY_BRUSH_PT_recording), "label"))
    assert f"Brush {k:g} times its size" in labels and "Recorded with" not in labels, labels
    assert "fit_brush" in names(drawn(bpy.types.HAIRY_BRUSH_PT_write_text_options), "prop")
    assert rec.resolve()[1].hair_length_mm == pytest.approx(HAIR * k)
    shown = pixels(st.paper_image)[..., :3]  # what the stored recording renders
    assert np.abs(shown - Simulation(rec).run().paper.rgb()).max() <= 0.5 / 255 + 1e-6
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}  # the keys baked again: the
    assert recs.recording_from_scene(bpy.context.scene).brush["scale"] == k  # same brush
    ok = bpy.ops.hairy_brush.write_character(
        character="一", size_mm=30.0, passes=1, fit_brush=False
    )
    assert ok == {"FINISHED"}
    assert "scale" not in recs.recording_from_scene(bpy.context.scene).brush
    assert recs.SCALE_TAG not in st.recording


@pytest.mark.slow
def test_fit_parameters_sets_the_quality_and_saves_a_user_preset(hb):
    import os

    st = setup_scene(bpy, ppm=1.0)
    before = ext().blender.checks.quality_values(st)
    r = bpy.ops.hairy_brush.fit_parameters(
        characters="一",
        size_px=24,
        divisions=1,
        rounds=1,
        iterations=1,
        max_grid=2,
        preset_name="My Fit",
    )
    assert r == {"FINISHED"}
    after = ext().blender.checks.quality_values(st)
    assert all(0.0 <= v <= 1.0 for v in after.values()) and after != before
    folder = bpy.utils.user_resource("SCRIPTS", path="presets/hairy_brush/settings")
    text = open(os.path.join(folder, "My_Fit.py"), encoding="utf-8").read()
    assert f"st.quality.e = {st.quality.e!r}" in text
    with pytest.raises(RuntimeError, match="no image named"):
        bpy.ops.hairy_brush.fit_parameters(source="IMAGE", image="nope")


@pytest.mark.slow
def test_fit_parameters_against_an_image_of_the_artwork(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    target = st.paper_image.copy()  # "the real artwork": what these quality values make
    target.name = "Scan"
    truth = ext().blender.checks.quality_values(st)
    st.quality.e = min(truth["e"] + 0.3, 1.0)  # a wrong start
    start = ext().blender.checks.quality_values(st)
    r = bpy.ops.hairy_brush.fit_parameters(
        source="IMAGE",
        image="Scan",
        divisions=1,
        rounds=1,
        iterations=2,
        max_grid=2,
        preset_name="From Scan",
    )
    assert r == {"FINISHED"}
    # the scene gets what the engine's fit finds from the same start against the image's
    # pixels (whether Eq. 28's landscape leads back to e itself is the engine's matter: with
    # Qp2 = 0 while Qp1 is fitted, Sec. 7.2, the bristles' gaps are gone and e may compensate)
    from sim.fitting.samples import TrainingSample
    from sim.fitting.search import FitSettings, fit

    rgb = pixels(target)[::-1, :, :3].astype(np.float32)
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    settings = FitSettings(
        divisions=1,
        rounds=1,
        iterations=2,
        max_grid=2,
        workers=1,
        seed=ext().blender.recordings.scene_seed(st),
    )
    want = fit([TrainingSample(rec, rgb, "Scan")], start, settings).quality
    got = ext().blender.checks.quality_values(st)
    assert got != start
    assert got == pytest.approx({k: float(np.float32(v)) for k, v in want.items()}, abs=1e-6)
    small = bpy.data.images.new("Small", 8, 8)
    with pytest.raises(RuntimeError, match="8 x 8 px but the paper is"):
        bpy.ops.hairy_brush.fit_parameters(source="IMAGE", image=small.name)


@pytest.mark.slow
def test_write_character_keeps_the_brushs_other_animation(hb):

    st = setup_scene(bpy, ppm=1.0)
    b = st.brush_object
    b.empty_display_size = 0.01
    b.keyframe_insert("empty_display_size", frame=1)
    b.empty_display_size = 0.05
    b.keyframe_insert("empty_display_size", frame=50)
    path = ROOT / "data" / "hanzi" / "十.json"
    assert bpy.ops.hairy_brush.write_character(filepath=str(path), size_mm=100.0, passes=1) == {
        "FINISHED"
    }
    paths = {fc.data_path for fc in ext().blender.keyframes.fcurves(b.animation_data)}
    assert {"location", "rotation_euler", "empty_display_size"} <= paths
