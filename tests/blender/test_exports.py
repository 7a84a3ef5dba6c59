# SPDX-License-Identifier: GPL-3.0-or-later
"""The writing out of Blender (issue 29.4): the ink matte as an image datablock that follows the
paper and in Bake Image Sequence, prints at a size and DPI, the SVG outline and the recording as
Grease Pencil strokes, on the running Blender (legacy Grease Pencil on 4.2, v3 from 4.3)."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from PIL import Image

from sim.image.matte import paper_matte8
from tests.blender.helpers import ext, keyframe_stroke, setup_scene

bpy = pytest.importorskip("bpy")
pytestmark = pytest.mark.slow  # each writes and simulates a stroke first (over a second)


def written(ppm=2.0):
    st = setup_scene(bpy, ppm=ppm)
    keyframe_stroke(bpy, st)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    return st


def engine_paper():
    return ext().blender.playback.playback_for(bpy.context.scene).sim.paper


def rgba(img) -> np.ndarray:
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    return a.reshape(img.size[1], img.size[0], 4)


def test_the_ink_matte_image_is_the_inks_density_and_follows_the_paper(hb):
    setup_scene(bpy)
    with pytest.raises(RuntimeError, match="Nothing written yet"):
        bpy.ops.hairy_brush.ink_matte()
    st = written()
    assert bpy.ops.hairy_brush.ink_matte() == {"FINISHED"}
    matte = ext().blender.images.matte_image(st.paper_image)
    assert matte is not None and matte.alpha_mode == "STRAIGHT"
    alpha = rgba(matte)[..., 3]
    density = np.clip(engine_paper().ink.max(axis=2), 0, 1)  # both bottom row first
    np.testing.assert_allclose(alpha, density, atol=1e-6)
    assert alpha.max() > 0.8 and rgba(matte)[alpha > 0.5][:, :3].max() < 0.05  # black ink
    sc = bpy.context.scene
    sc.frame_set(20)  # Follow Frames: the matte goes back with the paper
    early = rgba(matte)[..., 3].sum()
    assert 0 < early < 0.8 * alpha.sum()
    sc.frame_set(sc.frame_end)
    np.testing.assert_allclose(rgba(matte)[..., 3].sum(), alpha.sum(), rtol=1e-6)


def test_bake_image_sequence_writes_the_ink_matte_too(hb, tmp_path):
    st = written()
    sc = bpy.context.scene
    st.sequence_dir = str(tmp_path) + "/"
    sc.frame_start, sc.frame_end = 46, 48
    assert bpy.ops.hairy_brush.bake_sequence(content="BOTH") == {"FINISHED"}
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [f"{k}_{f:04d}.png" for k in ("ink", "paper") for f in (46, 47, 48)]
    last = np.asarray(Image.open(tmp_path / "ink_0048.png"))
    assert last.shape[2] == 4
    np.testing.assert_array_equal(last, paper_matte8(engine_paper()))


def test_export_print_image_writes_png_and_tiff_at_the_size_and_dpi(hb, tmp_path):
    import tifffile

    st = written()  # 200 x 200 mm
    path = tmp_path / "print.png"
    res = bpy.ops.hairy_brush.export_image(filepath=str(path), width_mm=100.0, dpi=254.0)
    assert res == {"FINISHED"}
    im = Image.open(path)
    assert im.size == (1000, 1000) and im.mode == "RGB"
    assert im.info["dpi"] == pytest.approx((254, 254), abs=0.01)
    grey = np.asarray(im).mean(axis=2)
    assert grey.min() < 60 and np.median(grey) > 200  # ink on paper
    tif = tmp_path / "matte.tif"
    res = bpy.ops.hairy_brush.export_image(filepath=str(tif), content="MATTE", depth="16", dpi=50.0)
    assert res == {"FINISHED"}
    with tifffile.TiffFile(tif) as tf:
        img = tf.pages[0].asarray()
        assert tf.pages[0].tags["XResolution"].value == (500000, 10000)
    assert img.shape == (394, 394, 4) and img.dtype == np.uint16  # 200 mm at 50 dpi
    assert img[..., 3].max() > 50000 and (img[..., 3] == 0).mean() > 0.5
    with pytest.raises(RuntimeError, match=r"\.png, \.tif"):
        bpy.ops.hairy_brush.export_image(filepath=str(tmp_path / "x.jpg"))
    assert st.paper_image is not None


def test_export_svg_writes_the_inks_outline_in_mm(hb, tmp_path):
    written(ppm=4.0)
    path = tmp_path / "ink.svg"
    assert bpy.ops.hairy_brush.export_svg(filepath=str(path)) == {"FINISHED"}
    doc = ET.parse(path).getroot()
    assert doc.get("width") == "200.000mm" and doc.get("viewBox") == "0 0 200.000 200.000"
    d = doc.find("{http://www.w3.org/2000/svg}path").get("d")
    assert d.count("M") >= 1 and d.count("Z") == d.count("M")
    # the stroke runs across the middle: x from about 50 to 160 mm, y about 100 mm
    xy = np.array(d.replace("M", " ").replace("C", " ").replace("Z", " ").split(), float)
    xy = xy.reshape(-1, 2)
    assert 40 < xy[:, 0].min() < 60 and 140 < xy[:, 0].max() < 170
    assert 90 < xy[:, 1].min() < xy[:, 1].max() < 110


def test_the_recording_becomes_grease_pencil_strokes_with_pressure(hb):
    st = written()
    assert bpy.ops.hairy_brush.export_grease_pencil() == {"FINISHED"}
    obj = bpy.data.objects[ext().operators.export_grease_pencil.OBJECT]
    assert obj.parent == st.paper_object
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    want = ext().sim.engine.pen.pen_strokes(rec)
    if ext().operators.export_grease_pencil.grease_pencil_v3_data() is not None:
        assert obj.type == "GREASEPENCIL"
        drawing = obj.data.layers[0].frames[0].drawing
        strokes = list(drawing.strokes)
        pts = np.array([p.position for s in strokes for p in s.points])
        radius = np.array([p.radius for s in strokes for p in s.points])
        pressure = np.empty(len(pts), np.float32)
        drawing.attributes["pressure"].data.foreach_get("value", pressure)
    else:  # Blender 4.2: the legacy Grease Pencil
        assert obj.type == "GPENCIL"
        strokes = list(obj.data.layers[0].frames[0].strokes)
        pts = np.array([p.co for s in strokes for p in s.points])
        pressure = np.array([p.pressure for s in strokes for p in s.points])
        radius = None
    assert len(strokes) == len(want) >= 1
    np.testing.assert_allclose(pressure, np.concatenate([s.pressure for s in want]), atol=1e-6)
    assert pressure.max() == pytest.approx(1.0) and pressure.min() < 0.5  # touch down, press
    if radius is not None:
        full = np.concatenate([s.radius_mm for s in want]) / 1000
        np.testing.assert_allclose(radius, full, rtol=1e-5)
    # the points lie on the paper along the stroke: z just above it, x from -5 to 5 cm
    world = np.array(obj.matrix_world)
    p = pts @ world[:3, :3].T + world[:3, 3]
    assert np.abs(p[:, 2] - 0.0001).max() < 1e-5
    assert -0.06 < p[:, 0].min() < -0.03 and 0.03 < p[:, 0].max() < 0.06
    assert np.abs(p[:, 1]).max() < 0.005
    assert bpy.ops.hairy_brush.export_grease_pencil() == {"FINISHED"}  # again: replaced
    assert sum(o.name.startswith("HairyBrush Strokes") for o in bpy.data.objects) == 1


def test_grease_pencil_strokes_of_writing_on_a_surface_lie_on_it(hb):
    import math

    from tests.blender.helpers import HAIR

    bpy.ops.mesh.primitive_cylinder_add(vertices=48, radius=0.04, depth=0.12)
    cyl = bpy.context.active_object
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = 2.0
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    b = st.brush_object
    b.rotation_mode = "XYZ"
    sc = bpy.context.scene
    angles = np.radians(np.linspace(-30, 30, 16))
    press = np.r_[-5.0, np.full(14, 3.0), -5.0]
    for f, (a, p) in enumerate(zip(angles, press, strict=True), start=1):
        d = (40.0 + HAIR - p) / 1000
        b.location = (d * math.sin(a), -d * math.cos(a), 0.0)
        b.rotation_euler = (math.pi / 2, 0.0, a)
        b.keyframe_insert("location", frame=f)
        b.keyframe_insert("rotation_euler", frame=f)
    sc.frame_start, sc.frame_end = 1, 16
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.export_grease_pencil() == {"FINISHED"}
    obj = bpy.data.objects[ext().operators.export_grease_pencil.OBJECT]
    assert obj.parent == cyl
    if obj.type == "GREASEPENCIL":
        pts = np.array([p.position for s in obj.data.layers[0].frames[0].drawing.strokes
                        for p in s.points])  # fmt: skip
    else:
        pts = np.array([p.co for s in obj.data.layers[0].frames[0].strokes for p in s.points])
    world = np.array(obj.matrix_world)
    p = pts @ world[:3, :3].T + world[:3, 3]
    r = np.hypot(p[:, 0], p[:, 1]) * 1000
    assert len(p) > 50 and np.abs(r - 40.0).max() < 1.0  # on the cylinder's side
    ang = np.degrees(np.arctan2(p[:, 0], -p[:, 1]))
    assert ang.min() < -15 and ang.max() > 15  # round it, as the brush went
