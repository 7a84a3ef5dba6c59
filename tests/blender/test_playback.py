# SPDX-License-Identifier: GPL-3.0-or-later
"""The artwork at any frame: undo and redo, frame changes in any order, image sequences, the
primitive objects, an animation render."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.core.nurbs import CIRCLE_KNOTS, evaluate_nurbs_surface  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from tests.blender.helpers import (
    HAIR,
    call,
    ext,
    keyframe_stroke,
    pixels,
    setup_scene,
    undo_step,
)

bpy = pytest.importorskip("bpy")


def test_undo_restores_the_paper_and_redo_brings_the_ink_back(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    undo_step(bpy, "baked")
    before = pixels(st.paper_image)
    bpy.ops.hairy_brush.simulate()
    undo_step(bpy, "simulated")
    after = pixels(bpy.context.scene.hairy_brush.paper_image)
    assert np.abs(after - before).max() > 0.5
    pb = ext().blender.playback.playback_for(bpy.context.scene)
    call(bpy, "undo")
    np.testing.assert_array_equal(pixels(bpy.context.scene.hairy_brush.paper_image), before)
    assert (
        ext().blender.playback.playback_for(bpy.context.scene) is pb
    )  # cache kept: same recording
    call(bpy, "redo")
    np.testing.assert_array_equal(pixels(bpy.context.scene.hairy_brush.paper_image), after)


# ----------------------------------------------------------------------------- animation
@pytest.mark.slow
def test_frame_change_shows_the_artwork_as_at_that_frame(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    rec = ext().blender.recordings.recording_from_scene(sc)
    images = {}
    for f in (30, 12, 45, 30):  # forwards, backwards, forwards, back again
        sc.frame_set(f)
        images.setdefault(f, []).append(pixels(st.paper_image)[..., :3])
    for f, imgs in images.items():
        n = ext().blender.frames.samples_at_frame(rec, sc, f)
        direct = Simulation(rec).run(n).paper.rgb()
        for got in imgs:
            assert np.abs(got - direct).max() <= 1 / 255 + 1e-6, f
    # ink grows with time: frame 12 shows less than frame 30, which shows less than 45
    ink = {f: (imgs[0][..., 0] < 0.5).sum() for f, imgs in images.items()}
    assert ink[12] < ink[30] < ink[45]


def test_bake_sequence_writes_one_image_per_frame(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=(1, 3, 9, 10))
    bpy.ops.hairy_brush.bake_samples()
    st.sequence_dir = str(tmp_path / "seq")
    assert bpy.ops.hairy_brush.bake_sequence() == {"FINISHED"}
    files = sorted((tmp_path / "seq").glob("paper_*.png"))
    assert [f.name for f in files] == [f"paper_{i:04d}.png" for i in range(1, 11)]
    from sim.image.png import read_png

    last = read_png(files[-1])
    sim = Simulation(ext().blender.recordings.recording_from_scene(bpy.context.scene)).run()
    assert np.abs(last.astype(float) / 255 - sim.image()).max() <= 1 / 255 + 1e-6


# ----------------------------------------------------------------------------- primitives
def test_primitive_surfaces_match_the_engine(hb):
    st = setup_scene(bpy)
    b = st.brush_object
    b.location = (0.01, 0.02, (HAIR - 6) / 1000)  # pressed: a bent, deformed primitive
    b.rotation_euler = (math.radians(10), math.radians(-15), math.radians(30))
    keyframe_stroke(bpy, st, press=6.0)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(30)
    assert bpy.ops.hairy_brush.build_primitives() == {"FINISHED"}
    objs = ext().blender.primitives.primitive_objects(sc)
    pb = ext().blender.playback.playback_for(sc)
    nets, breaks = pb.sim.brush.surface_nets()
    assert len([o for o in objs if not o.hide_viewport]) == len(nets) >= 1
    to_world = ext().blender.transforms.engine_to_world(st, st.paper_object)
    dg = bpy.context.evaluated_depsgraph_get()
    for obj, net in zip(objs, nets, strict=False):
        assert obj.parent == st.paper_object
        sp = obj.data.splines[0]
        shape = pb.sim.brush.layout.bezier_net_shape()
        want = (shape.points_u, shape.points_v, shape.order_u, shape.order_v)
        assert (sp.point_count_u, sp.point_count_v, sp.order_u, sp.order_v) == want
        me = obj.evaluated_get(dg).to_mesh()
        mw = np.array(obj.matrix_world)
        V = np.array([mw @ np.r_[v.co[:], 1.0] for v in me.vertices])[:, :3]
        obj.evaluated_get(dg).to_mesh_clear()
        nu = sp.resolution_u * sp.point_count_u
        nv = sp.resolution_v * sp.point_count_v

        def mapped(n, br):  # Blender samples its uniform Bezier spans evenly
            tau = np.linspace(0, len(br) - 1, n)
            k = np.minimum(tau.astype(int), len(br) - 2)
            return br[k] + (tau - k) * (br[k + 1] - br[k])

        uu, vv = np.meshgrid(mapped(nu, breaks), mapped(nv, np.array([0, 0.25, 0.5, 0.75, 1])))
        knots = np.concatenate([[0.0], np.repeat(breaks, 3), [1.0]])
        E = evaluate_nurbs_surface(net, knots, 3, CIRCLE_KNOTS, 2, uu.ravel(), vv.ravel())
        E = (np.c_[E, np.ones(len(E))] @ to_world.T)[:, :3]
        assert len(V) == len(E)
        dist = np.sqrt(((V[:, None] - E[None]) ** 2).sum(-1)).min(axis=1)
        assert dist.max() < 1e-6  # metres: float32 round-off on a 30 mm brush


@pytest.mark.slow
def test_splitting_adds_primitive_objects_on_frame_change(hb):
    st = setup_scene(bpy, brush_preset="goat_soft")
    st.quality.tre = 0.05  # splits easily (Eq. 18)
    keyframe_stroke(bpy, st, press=12.0)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(1)
    bpy.ops.hairy_brush.build_primitives()
    assert len(ext().blender.primitives.primitive_objects(sc)) == 1
    sc.frame_set(40)
    m = ext().blender.playback.playback_for(sc).sim.brush.m
    shown = [o for o in ext().blender.primitives.primitive_objects(sc) if not o.hide_viewport]
    assert m > 1 and len(shown) == m


@pytest.mark.slow
def test_an_animation_render_shows_each_frames_artwork(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Cam", bpy.data.cameras.new("Cam"))
    sc.collection.objects.link(cam)
    cam.data.type, cam.data.ortho_scale = "ORTHO", 0.2
    cam.location = (0.0, 0.0, 0.5)
    sc.camera = cam
    st.brush_object.hide_render = True
    sc.world = bpy.data.worlds.new("W")
    sc.render.engine = "CYCLES"
    sc.cycles.samples, sc.cycles.device = 4, "CPU"
    sc.view_settings.view_transform = "Standard"
    # 1.6 mm a render pixel (0.2 m / 128), half the stroke's width: a pixel the stroke crosses
    # is dark wherever the stroke lies (at 3.1 mm a pixel a stroke about 3 mm wide on a row
    # boundary, as the default brush's is, half-darkens two rows and counts in neither)
    sc.render.resolution_x = sc.render.resolution_y = 128
    sc.render.filepath = str(tmp_path / "f_")
    sc.frame_start, sc.frame_end, sc.frame_step = 12, 45, 33
    bpy.ops.render.render(animation=True)  # Blender changes frames itself: the handler follows
    ink = {}
    for f in (12, 45):
        im = bpy.data.images.load(str(tmp_path / f"f_{f:04d}.png"))
        r = pixels(im)[..., 0]
        ink[f] = int((r < 0.5 * np.median(r)).sum())
    assert 0 < ink[12] < ink[45] / 2


def test_undo_after_a_frame_change_shows_that_frames_image(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(20)
    at20 = pixels(st.paper_image)
    undo_step(bpy, "frame 20")
    sc.frame_set(45)
    assert np.abs(pixels(st.paper_image) - at20).max() > 0.1
    undo_step(bpy, "frame 45")
    call(bpy, "undo")
    np.testing.assert_array_equal(pixels(bpy.context.scene.hairy_brush.paper_image), at20)
