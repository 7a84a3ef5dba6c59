# SPDX-License-Identifier: GPL-3.0-or-later
"""What is kept in files: save and reload, import and export of recordings, a large recording, a
refused import that changes nothing."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from sim.core.recording import load as load_recording  # noqa: E402
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


def test_save_and_reload_keep_everything(hb, tmp_path):
    st = setup_scene(bpy, brush_preset="wolf_stiff", ink_preset="vermilion")
    st.quality.ren = 0.83
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    want = pixels(st.paper_image)
    rec_text = st.recording.as_string()
    path = tmp_path / "scene.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.wm.open_mainfile(filepath=str(path))
    st = bpy.context.scene.hairy_brush
    assert st.brush_preset == "wolf_stiff" and st.ink_preset == "vermilion"
    assert math.isclose(st.quality.ren, 0.83, abs_tol=1e-6)
    assert st.recording.as_string() == rec_text
    assert st.brush_object is not None and st.paper_object is not None
    assert st.paper_image.packed_file is not None
    np.testing.assert_array_equal(pixels(st.paper_image), want)


# ----------------------------------------------------------------------------- import/export
def test_import_export_round_trip_and_bad_files(hb, tmp_path):

    st = setup_scene(bpy)
    src = ROOT / "examples" / "strokes.json"
    assert bpy.ops.hairy_brush.import_recording(filepath=str(src)) == {"FINISHED"}
    rec = load_recording(src)
    assert math.isclose(st.px_per_mm, rec.px_per_mm) and st.paper_preset == rec.paper_preset
    out = tmp_path / "out.json"
    bpy.ops.hairy_brush.export_recording(filepath=str(out))
    back = load_recording(out)
    np.testing.assert_allclose(back.samples, rec.samples, atol=1e-5)
    assert back.dips == rec.dips
    # a malformed file is refused with the field named; the scene's recording is untouched
    text = st.recording.as_string()
    bad = tmp_path / "bad.json"
    d = json.loads(src.read_text())
    d["samples"][3][2] = "high"
    bad.write_text(json.dumps(d))
    with pytest.raises(RuntimeError, match=r"samples\[3\]\[2\]"):
        bpy.ops.hairy_brush.import_recording(filepath=str(bad))
    assert st.recording.as_string() == text


@pytest.mark.slow
def test_a_large_recording_is_stored_a_sample_a_line(hb, tmp_path):
    st = setup_scene(bpy, ppm=1.0)
    n = 100_000
    x = 20.0 + 160.0 * np.arange(n) / n
    samples = np.c_[x, np.full(n, 100.0), np.full(n, HAIR + 5), np.zeros((n, 3))]
    rec = ext().sim.core.recording.Recording(samples, width_mm=200, height_mm=200, px_per_mm=1.0)
    path = tmp_path / "big.json"
    rec.save(path)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(path)) == {"FINISHED"}
    text = st.recording.as_string()
    assert text.count("\n") >= n  # one sample a line: Blender's text stays linear
    assert len(json.loads(text)["samples"]) == n


def test_a_refused_import_changes_nothing_and_overrides_survive(hb, tmp_path):
    st = setup_scene(bpy, ppm=2.0)
    samples = [[60.0, 100.0, HAIR + 5, 0, 0, 0], [60.0, 100.0, HAIR - 4, 0, 0, 0]]
    samples += [[60.0 + i, 100.0, HAIR - 4, 0, 0, 0] for i in range(60)]
    rec = ext().sim.core.recording.Recording(np.array(samples), width_mm=150.0, px_per_mm=2.0)
    d = rec.to_dict()
    d["seed"] = 3_000_000_000
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(d))
    # a seed larger than Blender's Seed holds is kept, and simulated with
    assert bpy.ops.hairy_brush.import_recording(filepath=str(bad)) == {"FINISHED"}
    assert ext().blender.recordings.recording_from_scene(bpy.context.scene).seed == 3_000_000_000
    st.seed = 5  # the artist's own seed replaces it
    assert ext().blender.recordings.recording_from_scene(bpy.context.scene).seed == 5
    # a recording that does not fit the settings changes nothing
    st.recording = None
    before = (st.paper_width_mm, st.px_per_mm, st.seed)
    d["paper"]["width_mm"] = 120.0
    d["brush"] = {"preset": "no_such_brush"}
    bad.write_text(json.dumps(d))
    with pytest.raises(RuntimeError, match="no_such_brush"):
        bpy.ops.hairy_brush.import_recording(filepath=str(bad))
    assert (st.paper_width_mm, st.px_per_mm, st.seed) == before and st.recording is None
    # a brush geometry override in the recording is kept by simulate and export
    d["seed"] = 7
    d["brush"] = {"preset": "mixed", "geometry": {"hair_length_mm": 24.0}}
    good = tmp_path / "good.json"
    good.write_text(json.dumps(d))
    assert bpy.ops.hairy_brush.import_recording(filepath=str(good)) == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    want = Simulation(load_recording(good)).run().paper.rgb()
    assert np.abs(pixels(st.paper_image)[..., :3] - want).max() <= 0.5 / 4095 + 1e-6
    out = tmp_path / "out.json"
    assert bpy.ops.hairy_brush.export_recording(filepath=str(out)) == {"FINISHED"}
    assert json.loads(out.read_text())["brush"]["geometry"] == {"hair_length_mm": 24.0}
