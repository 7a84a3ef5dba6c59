# SPDX-License-Identifier: GPL-3.0-or-later
"""The Blender extension, installed from its built zip into a temporary user folder and enabled
as a user would; every operator on a real scene (real bpy, no mocks of Blender)."""

from __future__ import annotations

import json
import math
import sys
import zipfile

import numpy as np
import pytest
from conftest import ADDON

bpy = pytest.importorskip("bpy")

from sim.core.nurbs import CIRCLE_KNOTS, evaluate_nurbs_surface  # noqa: E402
from sim.core.params import load_preset  # noqa: E402
from sim.core.recording import DEFAULT_BRUSH  # noqa: E402
from sim.core.recording import load as load_recording  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from sim.paper.display import linear_to_srgb  # noqa: E402

HAIR = load_preset("brush", DEFAULT_BRUSH).data["geometry"]["hair_length_mm"]  # the default's


def ext():
    """The installed extension's own modules (not the repository's copy)."""
    return sys.modules[ADDON]


def pixels(img) -> np.ndarray:
    """RGBA as the engine's visible colour (a float image holds linear light: decoded)."""
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    a = a.reshape(img.size[1], img.size[0], 4)
    if img.is_float:
        a[..., :3] = linear_to_srgb(a[..., :3])
    return a


def setup_scene(bpy, ppm=2.0, **settings):
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = ppm
    for k, v in settings.items():
        setattr(st, k, v)
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    return st


def keyframe_stroke(bpy, st, press=4.0, y=0.0, frames=(1, 8, 40, 48)):
    """A horizontal stroke across the paper's middle: touch down, press, travel, lift."""
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = frames[0], frames[-1]
    b = st.brush_object
    for f, x, z in zip(
        frames,
        (-0.05, -0.05, 0.05, 0.06),
        (HAIR + 5, HAIR - press, HAIR - press, HAIR + 5),
        strict=True,
    ):
        b.location = (x, y, z / 1000)
        b.keyframe_insert("location", frame=f)


def mesh_without_uv(bpy, name="NoUV"):
    """A one-triangle mesh object with no UV map, in the scene."""
    me = bpy.data.meshes.new(name)
    me.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [(0, 1, 2)])
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def select_only(*objs):
    for ob in bpy.context.scene.objects:
        ob.select_set(ob in objs)


def undo_step(bpy, message):
    # Blender's UI pushes an undo step after each REGISTER/UNDO operator; a script does it here
    with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
        bpy.ops.ed.undo_push(message=message)


def call(bpy, fn_name, *args):
    win = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=win):
        getattr(bpy.ops.ed, fn_name)(*args)


# ----------------------------------------------------------------------------- packaging
def test_zip_holds_the_extension_and_no_dev_files(extension_zip):
    names = zipfile.ZipFile(extension_zip).namelist()
    assert "blender_manifest.toml" in names and "__init__.py" in names
    assert any(n.startswith("wheels/geomdl-") and n.endswith(".whl") for n in names)
    assert "sim/engine/simulation.py" in names and "presets/brushes/mixed.json" in names
    assert "operators/paint.py" in names and "panels/sidebar.py" in names
    for bad in ("tests/", "scripts/", ".venv/", ".ci/", "out/", "docs/", "pyproject.toml"):
        assert not any(n.startswith(bad) for n in names), bad


def test_installed_copy_is_the_one_enabled(hb):
    mod = ext()
    assert ADDON in bpy.context.preferences.addons
    user = bpy.utils.user_resource("EXTENSIONS")
    assert mod.__file__.startswith(user)
    assert hasattr(bpy.types.Scene, "hairy_brush")
    assert mod.sim.__name__ == ADDON + ".sim"  # the engine travels inside the extension


# ----------------------------------------------------------------------------- set-up
def test_setup_builds_paper_and_brush_in_metres(hb):
    st = setup_scene(bpy, ppm=3.0, paper_width_mm=150.0, paper_height_mm=100.0)
    paper, brush, img = st.paper_object, st.brush_object, st.paper_image
    xs = [v.co.x for v in paper.data.vertices]
    ys = [v.co.y for v in paper.data.vertices]
    assert math.isclose(max(xs) - min(xs), 0.150, abs_tol=1e-6)
    assert math.isclose(max(ys) - min(ys), 0.100, abs_tol=1e-6)
    assert tuple(img.size) == (450, 300) and img.is_float
    color = (
        ext()
        .sim.core.params.paper_from_preset(
            ext().sim.core.params.load_preset("paper", st.paper_preset)
        )
        .color
    )
    np.testing.assert_allclose(
        pixels(img)[..., :3], np.broadcast_to(color, (300, 450, 3)), atol=1e-3
    )
    mat = paper.data.materials[0]
    assert any(n.type == "TEX_IMAGE" and n.image == img for n in mat.node_tree.nodes)
    assert brush.type == "EMPTY" and brush.rotation_mode == "ZYX"
    assert math.isclose(brush.matrix_world.translation.z, (HAIR + 5) / 1000, abs_tol=1e-6)


def test_brush_pose_is_read_as_the_papers_six_dof(hb):
    st = setup_scene(bpy)
    b = st.brush_object
    b.location = (0.010, -0.020, 0.004)  # 4 mm above the paper
    b.rotation_euler = (math.radians(-12), math.radians(20), math.radians(35))  # q, d, r
    bpy.context.view_layer.update()
    s = ext().blender.transforms.sample_from_matrices(
        st, b.matrix_world, st.paper_object.matrix_world
    )
    np.testing.assert_allclose(s, [110.0, 80.0, 4.0, 20.0, -12.0, 35.0], atol=1e-4)
    # the engine's rotation is Blender's ZYX Euler matrix
    R = ext().sim.core.frames.rotation_matrix(20.0, -12.0, 35.0)
    np.testing.assert_allclose(R, np.array(b.matrix_world.to_3x3()), atol=1e-6)
    # and back
    mw = ext().blender.transforms.matrix_from_sample(st, st.paper_object.matrix_world, s)
    np.testing.assert_allclose(mw, np.array(b.matrix_world), atol=1e-6)


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
        assert obj.parent == st.brush_object
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


def test_presets_shipped_and_the_users_own(hb):
    st = bpy.context.scene.hairy_brush
    assert bpy.ops.hairy_brush.apply_preset(kind="brush", name="wolf_stiff") == {"FINISHED"}
    wolf = json.loads(
        (ext().sim.core.params.PRESET_DIR / "brushes" / "wolf_stiff.json").read_text()
    )
    for k, v in wolf["quality"].items():
        assert math.isclose(getattr(st.quality, k), v, abs_tol=1e-6)
    with pytest.raises(RuntimeError, match="unknown brush preset"):
        bpy.ops.hairy_brush.apply_preset(kind="brush", name="no_such_brush")
    # a fitted quality preset sets the quality values and leaves the chosen brush
    assert bpy.ops.hairy_brush.apply_preset(kind="quality", name="kaishu_fit") == {"FINISHED"}
    fitted = json.loads(
        (ext().sim.core.params.PRESET_DIR / "qualities" / "kaishu_fit.json").read_text("utf-8")
    )
    for k, v in fitted["quality"].items():
        assert math.isclose(getattr(st.quality, k), v, abs_tol=1e-6)
    assert st.brush_preset == "wolf_stiff"
    # the user's own preset, through Blender's preset system
    st.quality.e = 0.123
    st.ink_preset = "indigo"
    assert bpy.ops.hairy_brush.add_settings_preset(name="My Wolf") == {"FINISHED"}
    path = bpy.utils.preset_find("My Wolf", "hairy_brush/settings", display_name=True)
    assert path and path.startswith(bpy.utils.resource_path("USER"))
    st.quality.e = 0.9
    st.ink_preset = "sumi_black"
    bpy.ops.script.execute_preset(filepath=path, menu_idname="HAIRY_BRUSH_MT_settings_presets")
    assert math.isclose(st.quality.e, 0.123, abs_tol=1e-6) and st.ink_preset == "indigo"
    bpy.ops.hairy_brush.add_settings_preset(name="My Wolf", remove_name=True)
    assert not bpy.utils.preset_find("My Wolf", "hairy_brush/settings", display_name=True)


# ----------------------------------------------------------------------------- import/export
def test_import_export_round_trip_and_bad_files(hb, tmp_path):
    from conftest import ROOT

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


# ----------------------------------------------------------------------------- 3D surfaces
def test_apply_to_mesh_puts_the_ink_over_the_meshs_own_material(hb):
    st = setup_scene(bpy)
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    mat = bpy.data.materials.new("Clay")
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (0.6, 0.4, 0.3, 1.0)
    sphere.data.materials.append(mat)
    assert bpy.ops.hairy_brush.apply_to_mesh() == {"FINISHED"}
    nt = mat.node_tree
    tex = nt.nodes["HairyBrush Ink"]
    assert tex.image == st.paper_image
    mix = nt.nodes["HairyBrush Ink Multiply"]
    assert bsdf.inputs["Base Color"].links[0].from_node == mix
    a = next(s for s in mix.inputs if s.identifier == "A_Color")
    assert tuple(a.default_value)[:3] == pytest.approx((0.6, 0.4, 0.3))
    # a mesh without UVs gets a clear error
    select_only(mesh_without_uv(bpy))
    with pytest.raises(RuntimeError, match="has no UV map"):
        bpy.ops.hairy_brush.apply_to_mesh()


# ----------------------------------------------------------------------------- live painting
def test_live_stroke_is_kept_in_the_recording_and_replays_identically(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class

    st = setup_scene(bpy)
    sc = bpy.context.scene
    paint = ext().operators.paint
    sim, fresh = paint.start_simulation(sc, (60.0, 100.0))
    assert fresh
    live = ext().sim.engine.live.LiveBrush(sim, press_mm=5.0, step_deg=2.0, xy=(60.0, 100.0))
    events = [LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0))]
    for i in range(60):
        events.append(LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + i, 100.0)))
        events.append(LiveEvent("TIMER", "NOTHING"))
    events.append(LiveEvent("LEFTMOUSE", "RELEASE", (120.0, 100.0)))
    for ev in events:
        state = live.handle(ev)
    assert state == "FINISHED"
    paint.keep_stroke(sc, live)
    ext().blender.images.show_paper(st.paper_image, live.sim.paper, live.sim.index)
    rec = ext().blender.recordings.recording_from_scene(sc)
    assert len(rec.samples) == 61
    replay = Simulation(rec).run().paper.rgb()
    np.testing.assert_array_equal(replay, live.sim.paper.rgb())
    assert (replay[..., 0] < 0.5).sum() > 100
    # a second stroke continues the stored recording; the frame cache adopts the live state
    sim2, fresh = paint.start_simulation(sc, (60.0, 60.0))
    assert not fresh and sim2.index == 61
    live2 = ext().sim.engine.live.LiveBrush(sim2, press_mm=5.0, xy=(60.0, 60.0))
    live2.handle(LiveEvent("LEFTMOUSE", "PRESS", (60.0, 60.0)))
    for i in range(30):
        live2.handle(LiveEvent("MOUSEMOVE", "NOTHING", (60.0, 60.0 + i)))
        live2.handle(LiveEvent("TIMER", "NOTHING"))
    assert live2.handle(LiveEvent("RET", "PRESS")) == "FINISHED"
    paint.keep_stroke(sc, live2)
    assert ext().blender.playback.playback_for(sc).sim is live2.sim  # no re-simulation
    rec2 = ext().blender.recordings.recording_from_scene(sc)
    assert len(rec2.samples) == 91
    np.testing.assert_array_equal(Simulation(rec2).run().paper.rgb(), live2.sim.paper.rgb())


def test_register_unregister_register_leaves_nothing_behind(hb):
    import addon_utils

    from_handlers = lambda: [  # noqa: E731
        f
        for lst in (bpy.app.handlers.frame_change_post, bpy.app.handlers.undo_post)
        for f in lst
        if getattr(f, "__module__", "").startswith(ADDON)
    ]
    assert len(from_handlers()) == 2
    addon_utils.disable(ADDON, default_set=True)
    assert not hasattr(bpy.types.Scene, "hairy_brush")
    assert not hasattr(bpy.types, "HAIRY_BRUSH_PT_main")
    assert not hasattr(bpy.types, "HAIRY_BRUSH_OT_setup")
    with pytest.raises(AttributeError):
        bpy.ops.hairy_brush.setup()
    assert from_handlers() == []
    addon_utils.enable(ADDON, default_set=True)
    assert hasattr(bpy.types.Scene, "hairy_brush") and len(from_handlers()) == 2
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}


def test_write_character_keyframes_bake_back_into_the_same_samples(hb):
    from conftest import ROOT

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


def test_fit_parameters_sets_the_quality_and_saves_a_user_preset(hb):
    import os

    st = setup_scene(bpy, ppm=1.0)
    before = st.quality.as_dict()
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
    after = st.quality.as_dict()
    assert all(0.0 <= v <= 1.0 for v in after.values()) and after != before
    folder = bpy.utils.user_resource("SCRIPTS", path="presets/hairy_brush/settings")
    text = open(os.path.join(folder, "My_Fit.py"), encoding="utf-8").read()
    assert f"st.quality.e = {st.quality.e!r}" in text
    with pytest.raises(RuntimeError, match="no image named"):
        bpy.ops.hairy_brush.fit_parameters(source="IMAGE", image="nope")


def test_fit_parameters_against_an_image_of_the_artwork(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    target = st.paper_image.copy()  # "the real artwork": what these quality values make
    target.name = "Scan"
    truth = st.quality.as_dict()
    st.quality.e = min(truth["e"] + 0.3, 1.0)  # a wrong start
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
    assert abs(st.quality.e - truth["e"]) < 0.3  # moved back toward the truth
    small = bpy.data.images.new("Small", 8, 8)
    with pytest.raises(RuntimeError, match="8 x 8 px but the paper is"):
        bpy.ops.hairy_brush.fit_parameters(source="IMAGE", image=small.name)


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


def paint_operator():
    """The paint operator's own methods on a stand-in (a modal operator cannot run headless)."""
    cls = ext().operators.paint.HAIRY_BRUSH_OT_paint

    class Stroke:
        reports = []

        def report(self, kind, msg):
            self.reports.append((kind, msg))

    for name in ("start", "step", "show", "_finish"):
        setattr(Stroke, name, getattr(cls, name))
    return Stroke()


def test_paint_operator_refreshes_what_changed_moves_the_brush_and_cancels_exactly(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class
    paint = ext().operators.paint
    st = setup_scene(bpy, ppm=3.0)
    sc = bpy.context.scene
    assert bpy.ops.hairy_brush.build_primitives() == {"FINISHED"}
    prim = ext().blender.primitives.primitive_objects(sc)[0]
    sim, _ = paint.start_simulation(sc, (60.0, 100.0))
    op = paint_operator()
    op.start(
        bpy.context, st.paper_image, ext().sim.engine.live.LiveBrush(sim, 5.0, 2.0, (60.0, 100.0))
    )
    before = pixels(st.paper_image)
    t0 = op._live._t0
    op.step(bpy.context, LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0), time=t0))
    brush_z, prim_z = [], []
    for k in range(1, 41):
        t = t0 + k / 60
        op.step(bpy.context, LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + k, 100.0), time=t))
        op._last_draw = 0.0  # refresh on every tick
        op.step(bpy.context, LiveEvent("TIMER", "NOTHING", time=t))
        brush_z.append(st.brush_object.matrix_world.translation.x)
        prim_z.append(np.array(prim.data.splines[0].points[0].co)[0])
    # 40 ticks at 60 Hz: 80 samples at 120 Hz, whatever the loop cost
    assert len(op._live.new_samples) == 80
    shown = pixels(st.paper_image)[..., :3]
    assert np.abs(shown - sim.paper.rgb()).max() <= 0.5 / 4095 + 1e-6  # refreshed = full
    assert (np.abs(shown - before[..., :3]).max(axis=2) > 0.1).sum() > 100
    assert brush_z[-1] > brush_z[0] + 0.03  # the empty follows the live pose (metres)
    assert len(set(np.round(prim_z, 6))) > 1  # and the primitive surfaces follow the brush
    assert op.step(bpy.context, LiveEvent("ESC", "PRESS", time=t0 + 0.7)) == {"CANCELLED"}
    np.testing.assert_array_equal(pixels(st.paper_image), before)
    assert st.recording is None


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


def test_bake_asks_before_replacing_painted_strokes(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806
    st = setup_scene(bpy)
    sc = bpy.context.scene
    paint = ext().operators.paint
    sim, _ = paint.start_simulation(sc, (60.0, 100.0))
    live = ext().sim.engine.live.LiveBrush(sim, press_mm=5.0, xy=(60.0, 100.0))
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0)))
    for i in range(30):
        live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + i, 100.0)))
        live.handle(LiveEvent("TIMER", "NOTHING"))
    assert live.handle(LiveEvent("RET", "PRESS")) == "FINISHED"
    paint.keep_stroke(sc, live)
    text = st.recording.as_string()
    keyframe_stroke(bpy, st)
    with pytest.raises(RuntimeError, match="30 samples painted live"):
        bpy.ops.hairy_brush.bake_samples()
    assert st.recording.as_string() == text
    assert bpy.ops.hairy_brush.bake_samples(replace_painted=True) == {"FINISHED"}
    assert st.recording.as_string() != text


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


def test_write_character_keeps_the_brushs_other_animation(hb):
    from conftest import ROOT

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
