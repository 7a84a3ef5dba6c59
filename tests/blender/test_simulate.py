# SPDX-License-Identifier: GPL-3.0-or-later
"""Baking the brush's animation into samples and simulating them: the image is the engine's, dips
colour the stroke."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sim.core.recording import load as load_recording  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from tests.blender.helpers import (
    keyframe_stroke,
    pixels,
    setup_scene,
)

bpy = pytest.importorskip("bpy")


# ----------------------------------------------------------------------------- bake + simulate
def test_bake_and_simulate_write_where_the_brush_went(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    rec = json.loads(st.recording.as_string())
    assert len(rec["samples"]) == int((48 - 1) / 24 * 120) + 1
    before = pixels(st.paper_image)
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    after = pixels(st.paper_image)
    changed = np.abs(after - before).max(axis=2) > 0.05
    rows, cols = np.nonzero(changed)
    assert changed.sum() > 200
    # ink lies along y = middle of the paper, between x = 50 and 160 mm (2 px/mm)
    assert abs(np.median(rows) - 200) < 8
    assert cols.min() > 2 * 40 and cols.max() < 2 * 175
    assert not changed[:150].any() and not changed[250:].any()


@pytest.mark.slow
def test_simulated_image_equals_the_engines_render(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    path = tmp_path / "rec.json"
    assert bpy.ops.hairy_brush.export_recording(filepath=str(path)) == {"FINISHED"}
    rgb = Simulation(load_recording(path)).run().paper.rgb()
    got = pixels(st.paper_image)[..., :3]
    assert np.abs(got - rgb).max() <= 0.5 / 4095 + 1e-6  # the float image's sRGB table


# ----------------------------------------------------------------------------- dip, presets
def test_dip_records_the_ink_and_colours_the_stroke(hb):
    st = setup_scene(bpy, ink_preset="vermilion")
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    st.ink_color = (0.1, 0.2, 0.8)
    bpy.context.scene.frame_set(1)
    assert bpy.ops.hairy_brush.dip(at="FRAME") == {"FINISHED"}
    dips = json.loads(st.recording.as_string())["dips"]
    assert [d["before_sample"] for d in dips] == [0]
    np.testing.assert_allclose(dips[0]["color"], [0.1, 0.2, 0.8], atol=1e-6)
    bpy.ops.hairy_brush.simulate()
    px = pixels(st.paper_image)[..., :3]
    inked = px[px.min(axis=2) < 0.6]
    assert len(inked) > 50
    assert np.median(inked[:, 2] - inked[:, 0]) > 0.1  # blue ink


def test_invoked_from_the_interface_a_job_runs_through_execute(hb):
    """The Job operators share JobOperator's invoke (in_background, then execute); headless
    Blender has no window, so the job runs to the end and the paper shows the ink."""
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    before = pixels(st.paper_image)
    assert bpy.ops.hairy_brush.simulate("INVOKE_DEFAULT") == {"FINISHED"}
    assert (np.abs(pixels(st.paper_image) - before).max(axis=2) > 0.05).sum() > 200
    jobs = ("simulate", "bake_cache", "bake_sequence", "write_text", "sign_work", "rewrite_cell")
    for name in jobs:
        op = getattr(bpy.types, f"HAIRY_BRUSH_OT_{name}")
        assert op.invoke.__qualname__ == "JobOperator.invoke", name
