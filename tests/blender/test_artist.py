# SPDX-License-Identifier: GPL-3.0-or-later
"""The artist's path (issue 29): the ink colour recolours the work, the primitive surfaces in
renders, the paper image saved from Blender's Image menu, a brush preset changed after a
recording was made (real bpy, headless)."""

from __future__ import annotations

import numpy as np
import pytest

from sim.paper.display import srgb_to_linear
from tests.blender.helpers import HAIR, ext, keyframe_stroke, pixels, setup_scene

bpy = pytest.importorskip("bpy")


# ----------------------------------------------------------------------------- primitives
def _primitive_collection():
    return bpy.data.collections[ext().blender.primitives.PRIMITIVE_COLLECTION]


def _rendered(obj) -> bool:
    """Whether an object is in a final render: its own and its collections' render switch."""
    return not obj.hide_render and not any(c.hide_render for c in obj.users_collection)


def test_primitive_surfaces_are_hidden_from_renders_unless_asked(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.context.scene.frame_set(30)
    assert bpy.ops.hairy_brush.build_primitives() == {"FINISHED"}
    objs = ext().blender.primitives.primitive_objects(bpy.context.scene)
    assert objs and not any(_rendered(o) for o in objs)
    assert all(not o.hide_viewport for o in objs)  # still a viewport aid
    _primitive_collection().hide_render = False  # the sidebar's Show in Renders
    bpy.context.scene.frame_set(31)
    assert all(_rendered(o) for o in objs)  # a frame change keeps the artist's choice


def _top_camera(sc, size_px: int):
    cam = bpy.data.objects.new("Cam", bpy.data.cameras.new("Cam"))
    sc.collection.objects.link(cam)
    cam.data.type, cam.data.ortho_scale = "ORTHO", 0.2
    cam.location = (0.0, 0.0, 0.5)
    sc.camera = cam
    sc.render.resolution_x = sc.render.resolution_y = size_px
    sc.render.resolution_percentage = 100


def _engine_points_px(st, sc, frame: int, size_px: int) -> np.ndarray:
    """The engine's primitive control points at ``frame`` (x, y in render pixels, bottom row
    first) under the top camera of ``_top_camera``: where the surfaces must be."""
    pb = ext().blender.playback.playback_for(sc)
    sim = pb.seek(ext().blender.frames.samples_at_frame(pb.rec, sc, frame))
    nets, _ = sim.brush.surface_nets()
    to_world = ext().blender.transforms.engine_to_world(st, st.paper_object)
    pts = ext().sim.core.placement.primitive_points(nets, to_world)[..., :3].reshape(-1, 3)
    return (pts[:, :2] / 0.2 + 0.5) * size_px


@pytest.mark.slow
def test_shown_primitives_render_at_the_pose_of_each_rendered_frame(hb, tmp_path):
    st = setup_scene(bpy, ppm=1.0)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(30)
    bpy.ops.hairy_brush.build_primitives()
    _primitive_collection().hide_render = False
    st.paper_object.hide_render = True  # only the primitives in the picture
    size = 96
    _top_camera(sc, size)
    sc.render.engine = "BLENDER_WORKBENCH"
    sc.render.film_transparent = True
    sc.render.image_settings.color_mode = "RGBA"
    sc.render.filepath = str(tmp_path / "f_")
    sc.frame_start, sc.frame_end, sc.frame_step = 10, 40, 15
    sc.frame_set(1)  # the render starts elsewhere: every frame is Blender's own change
    bpy.ops.render.render(animation=True)
    for f in (10, 25, 40):
        alpha = _alpha(tmp_path / f"f_{f:04d}.png", size)
        ys, xs = np.nonzero(alpha > 0.5)
        assert len(xs) > 3, f
        want = _engine_points_px(st, sc, f, size)
        # the surfaces lie in their control points' hull (the old placement put them up to
        # 20 px off, where the brush empty's matrix of another frame put them)
        lo, hi = want.min(axis=0) - 1.0, want.max(axis=0) + 1.0
        assert lo[0] <= xs.min() and xs.max() <= hi[0], (f, xs.min(), xs.max(), lo, hi)
        assert lo[1] <= ys.min() and ys.max() <= hi[1], (f, ys.min(), ys.max(), lo, hi)
        # and exactly as a still render of that frame, set first, shows them (the brush moves
        # 1.5 to 4 px a frame here: a frame early or late differs)
        sc.frame_set(f)
        sc.render.filepath = str(tmp_path / f"still_{f}.png")
        bpy.ops.render.render(write_still=True)
        np.testing.assert_array_equal(alpha, _alpha(tmp_path / f"still_{f}.png", size))


def _alpha(path, size: int) -> np.ndarray:
    im = bpy.data.images.load(str(path))
    a = np.empty(len(im.pixels), np.float32)
    im.pixels.foreach_get(a)
    bpy.data.images.remove(im)
    return a.reshape(size, size, 4)[..., 3]


# ----------------------------------------------------------------------------- ink colour
def _inked(st) -> np.ndarray:
    """The paper image's RGB where the ink lies (its green is below half the paper's)."""
    rgb = pixels(st.paper_image)[..., :3]
    return rgb[rgb[..., 1] < 0.5 * np.median(rgb[..., 1])]


SHORT = (1, 3, 14, 16)  # a quicker stroke: x = 50 to 150 mm over frames 3 to 14


def test_a_new_ink_colour_recolours_the_work(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=SHORT)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    black = _inked(st)
    assert len(black) > 50 and black[:, 0].mean() < 0.3
    st.ink_color = (0.8, 0.05, 0.05)  # after the bake: the recorded dips follow the ink
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    red = _inked(st)
    assert len(red) > 50 and red[:, 0].mean() > 0.6 > 0.3 > red[:, 2].mean()
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}  # baking again keeps it so
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    np.testing.assert_array_equal(_inked(st), red)


def _ink_by_side(st, split_mm: float) -> tuple:
    """Mean RGB of the ink left and right of x = split_mm (a margin of 10 mm either side)."""
    rgb = pixels(st.paper_image)[..., :3]
    ink = rgb[..., 1] < 0.5 * np.median(rgb[..., 1])
    x_mm = np.arange(rgb.shape[1]) / st.px_per_mm
    left = ink & (x_mm < split_mm - 10)[None, :]
    right = ink & (x_mm > split_mm + 10)[None, :]
    assert left.sum() > 20 and right.sum() > 20
    return rgb[left].mean(axis=0), rgb[right].mean(axis=0)


def test_a_dip_in_its_own_colour_keeps_it_until_asked(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=SHORT)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(9)  # at x = 105 mm
    blue = (0.05, 0.1, 0.8)
    assert bpy.ops.hairy_brush.dip(own_color=True, color=blue) == {"FINISHED"}
    text = st.recording
    assert text[ext().blender.recordings.OWN_COLOR_TAG] == 1
    st.ink_color = (0.8, 0.05, 0.05)
    bpy.ops.hairy_brush.simulate()
    before, after = _ink_by_side(st, 105.0)
    assert before[0] > 2 * before[2]  # red up to the dip: the Ink Colour
    assert after[2] > 2 * after[0]  # blue after it: its own colour
    assert bpy.ops.hairy_brush.follow_ink() == {"FINISHED"}
    assert text[ext().blender.recordings.OWN_COLOR_TAG] == 0
    bpy.ops.hairy_brush.simulate()
    _before, after = _ink_by_side(st, 105.0)
    assert after[0] > 2 * after[2]  # the second dip loads the Ink Colour too


def test_an_imported_recording_shows_its_ink_and_keeps_its_dips_colours(hb, tmp_path):
    from sim.core.recording import Dip, Recording

    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=SHORT)
    bpy.ops.hairy_brush.bake_samples()
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    old = Recording(rec.samples, dips=[Dip(0, 0.8, (0.1, 0.2, 0.7), 0.9)])  # as before 29
    old.ink = {"preset": "sumi_black", "color": [0.3, 0.6, 0.2]}
    path = tmp_path / "old.json"
    old.save(path)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(path)) == {"FINISHED"}
    assert np.allclose(st.ink_color, (0.3, 0.6, 0.2))  # the recording's ink, shown
    assert st.recording[ext().blender.recordings.OWN_COLOR_TAG] == 1
    bpy.ops.hairy_brush.simulate()
    ink = _inked(st)
    assert ink[:, 2].mean() > 2 * ink[:, 0].mean()  # the dip's own blue, as recorded


def test_a_recording_without_dips_counts_the_papers_default_dip_as_its_own(hb, tmp_path):
    from sim.core.recording import Recording

    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=SHORT)
    bpy.ops.hairy_brush.bake_samples()
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    path = tmp_path / "no_dips.json"
    Recording(rec.samples).save(path)  # the default dip: black, as `sim render` draws it
    bpy.ops.hairy_brush.import_recording(filepath=str(path))
    assert st.recording[ext().blender.recordings.OWN_COLOR_TAG] == 1
    st.ink_color = (0.8, 0.05, 0.05)
    bpy.ops.hairy_brush.simulate()
    assert _inked(st)[:, 0].mean() < 0.3  # still black: the sidebar says why
    assert bpy.ops.hairy_brush.follow_ink() == {"FINISHED"}
    bpy.ops.hairy_brush.simulate()
    assert _inked(st)[:, 0].mean() > 0.6


# ----------------------------------------------------------------------------- saving the paper
def _save_image_as(img, path):
    """Image > Save As in the Image Editor (the image is the editor's)."""
    with bpy.context.temp_override(edit_image=img):
        assert bpy.ops.image.save_as(filepath=str(path)) == {"FINISHED"}


def _ink_count(rgb) -> int:
    return int((rgb[..., 1] < 0.5 * np.median(rgb[..., 1])).sum())


def test_the_paper_stays_packed_after_image_save_as(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "art.blend"))
    img = st.paper_image
    sc.frame_set(12)
    _save_image_as(img, tmp_path / "paper.png")  # the artist keeps a copy of the paper
    assert (tmp_path / "paper.png").is_file()
    sc.frame_set(45)  # the paper shows more ink than the file
    assert img.packed_file is not None  # what renders is what the paper shows, not the file
    with bpy.context.temp_override(edit_image=img):  # Image > Save on it: it stays packed
        assert bpy.ops.image.save() == {"FINISHED"}
    assert img.packed_file is not None
    shown = pixels(img)
    bpy.ops.wm.save_mainfile()
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "art.blend"))
    img = bpy.context.scene.hairy_brush.paper_image
    assert img.packed_file is not None and not img.filepath_raw.endswith("paper.png")
    np.testing.assert_allclose(pixels(img), shown, atol=1e-6)


@pytest.mark.slow
def test_cycles_renders_the_paper_the_sidebar_shows_after_save_as(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(12)
    _save_image_as(st.paper_image, tmp_path / "paper.png")
    sc.frame_set(45)
    size = 128
    _top_camera(sc, size)
    st.brush_object.hide_render = True
    sc.world = bpy.data.worlds.new("W")
    sc.render.engine = "CYCLES"
    sc.cycles.samples, sc.cycles.device = 4, "CPU"
    sc.view_settings.view_transform = "Standard"
    sc.render.filepath = str(tmp_path / "r.png")
    bpy.ops.render.render(write_still=True)
    im = bpy.data.images.load(str(tmp_path / "r.png"))
    rendered = _ink_count(pixels(im)[..., :3])
    shown = pixels(st.paper_image)[..., :3]
    # the paper (200 mm, 400 px) seen at 128 px: ink pixels scale by (128 / 400)^2
    want = _ink_count(shown) * (size / shown.shape[1]) ** 2
    assert 0.6 * want < rendered < 1.6 * want, (rendered, want)


# ----------------------------------------------------------------------------- pictures
def _blender_saves(grey, tmp_path) -> dict:
    """The picture saved by Blender in the formats an artist saves renders in."""
    sc = bpy.context.scene
    sc.view_settings.view_transform = "Standard"  # the pixels as they are
    h, w = grey.shape
    img = bpy.data.images.new("pic", w, h, float_buffer=True)
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = srgb_to_linear(grey[::-1])[..., None]  # a float image holds linear light
    img.pixels.foreach_set(rgba.ravel())
    settings, paths = sc.render.image_settings, {}
    for name, fmt, depth in (
        ("blender16.png", "PNG", "16"),
        ("blender8.png", "PNG", "8"),
        ("blender16.tif", "TIFF", "16"),
        ("blender.exr", "OPEN_EXR", "32"),
        ("blender.jpg", "JPEG", None),
    ):
        settings.file_format = fmt
        if depth is not None:
            settings.color_depth = depth
        paths[name] = tmp_path / name
        img.save_render(str(paths[name]), scene=sc)
    bpy.data.images.remove(img)
    return paths


def test_imitate_picture_reads_every_picture_blender_loads(hb, tmp_path):
    from sim.picture.ink import grey_of
    from tests.blender.test_picture import picture
    from tests.picture_files import png_kinds

    grey = picture(96)
    paths = _blender_saves(grey, tmp_path)
    for name, data in png_kinds(grey).items():
        paths[name] = tmp_path / f"{name}.png"
        paths[name].write_bytes(data)
    file_picture = ext().operators.imitate_image.file_picture
    for name, path in paths.items():
        got = grey_of(file_picture(str(path)))
        err = np.abs(got - grey)
        if name.endswith(".jpg"):
            assert err.mean() < 0.02, name
        else:
            assert err.max() <= 1.5 / 255, (name, err.max())
    assert not [im for im in bpy.data.images if im.filepath]  # read, not kept


@pytest.mark.slow
def test_imitate_picture_takes_blenders_own_16_bit_png(hb, tmp_path):
    from tests.blender.test_picture import picture

    st = setup_scene(bpy, ppm=1.0)
    path = _blender_saves(picture(128), tmp_path)["blender16.png"]
    res = bpy.ops.hairy_brush.imitate_image(filepath=str(path), size_mm=80.0, passes=1, detail=128)
    assert res == {"FINISHED"}
    assert st.paper_width_mm == 80.0 and st.recording is not None


# ----------------------------------------------------------------------------- brush preset
def _stroke_recording(tmp_path, press: float, brush: dict | None = None):
    from sim.core.recording import Recording

    hair = HAIR
    xs = np.linspace(60.0, 140.0, 120)
    samples = np.zeros((len(xs) + 2, 6))
    samples[1:-1, 0], samples[1:-1, 1], samples[1:-1, 2] = xs, 100.0, hair - press
    samples[0, :3] = 60.0, 100.0, hair + 5.0
    samples[-1, :3] = 140.0, 100.0, hair + 5.0
    rec = Recording(samples, brush=brush or {"preset": "wolf_kaishu"})
    path = tmp_path / "stroke.json"
    rec.save(path)
    return path, samples


def _preset_report(kind: str, name: str) -> str:
    op = ext().operators.apply_preset.HAIRY_BRUSH_OT_apply_preset
    reports = []

    class Call:  # the operator's execute with its report kept (a test reads what it says)
        def report(self, _kind, msg):
            reports.append(msg)

    call = Call()
    call.kind, call.name = kind, name
    assert op.execute(call, bpy.context) == {"FINISHED"}
    return reports[-1]


def test_a_new_brush_re_places_an_imported_recordings_samples(hb, tmp_path):
    setup_scene(bpy)
    path, samples = _stroke_recording(tmp_path, press=3.0)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(path)) == {"FINISHED"}
    sc = bpy.context.scene
    report = _preset_report("brush", "goat_soft")  # hair 34 mm instead of 28
    assert "moved up 6 mm" in report and "recording" in report, report
    rec = ext().blender.recordings.recording_from_scene(sc)
    # pressed 3 mm into its touching height and hovering 5 mm above it, as recorded
    np.testing.assert_allclose(rec.samples[:, 2], samples[:, 2] + 6.0, atol=1e-9)
    assert bpy.ops.hairy_brush.export_recording(filepath=str(tmp_path / "out.json"))
    from sim.core.recording import load

    out = load(tmp_path / "out.json")  # what the scene writes is what it simulates
    assert out.preset_name("brush") == "goat_soft"
    np.testing.assert_allclose(out.samples[:, 2], samples[:, 2] + 6.0, atol=1e-9)
    _preset_report("brush", "wolf_kaishu")  # back: as recorded
    rec = ext().blender.recordings.recording_from_scene(sc)
    np.testing.assert_allclose(rec.samples[:, 2], samples[:, 2], atol=1e-9)


def test_a_new_brush_moves_keyframes_and_recording_alike(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    _preset_report("brush", "small_detail")  # 16 mm: 12 mm shorter
    placed = ext().blender.recordings.recording_from_scene(sc).samples
    bpy.ops.hairy_brush.bake_samples()  # from the keyframes, which moved down as much
    baked = ext().blender.recordings.recording_from_scene(sc).samples
    np.testing.assert_allclose(placed, baked, atol=2e-5)
    assert placed[:, 2].min() < 16.0  # it still presses into the paper


def test_a_recording_with_its_own_hair_length_is_not_moved(hb, tmp_path):
    setup_scene(bpy)
    own = {"preset": "wolf_kaishu", "geometry": {"hair_length_mm": HAIR}}
    path, samples = _stroke_recording(tmp_path, press=3.0, brush=own)
    bpy.ops.hairy_brush.import_recording(filepath=str(path))
    report = _preset_report("brush", "goat_soft")
    assert "its own hair length" in report, report
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    np.testing.assert_allclose(rec.samples[:, 2], samples[:, 2], atol=1e-9)


# ----------------------------------------------------------------------------- live painting
def _paint_operator():
    """The paint operator's own methods on a stand-in (a modal operator cannot run headless)."""
    cls = ext().operators.paint.HAIRY_BRUSH_OT_paint

    class Stroke:
        def report(self, _kind, _msg):
            pass

    for name in ("start", "step", "show", "_finish"):
        setattr(Stroke, name, getattr(cls, name))
    return Stroke()


def _begin(st, xy):
    """Painting started as the benchmark starts it: the operator's state, the button down at
    once under the pointer. Returns the operator and its clock's start."""
    live_mod = ext().sim.engine.live
    sim, _ = ext().operators.paint.start_simulation(bpy.context.scene, xy)
    op = _paint_operator()
    op.start(bpy.context, st.paper_image, live_mod.LiveBrush(sim, 4.0, 2.0, xy))
    t0 = op._live._t0  # events are stamped on the operator's clock
    op.step(bpy.context, live_mod.LiveEvent("LEFTMOUSE", "PRESS", xy, time=t0))
    return op, t0


def _drag(op, xy0, xy1, t0: float, n: int = 40) -> float:
    """The pointer from xy0 to xy1 at 120 Hz from t0; returns the time it gets there."""
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class
    for k in range(1, n + 1):
        xy = tuple(np.asarray(xy0) + (np.asarray(xy1) - np.asarray(xy0)) * k / n)
        op.step(bpy.context, LiveEvent("MOUSEMOVE", "NOTHING", xy, time=t0 + k / 120))
        op.step(bpy.context, LiveEvent("TIMER", "NOTHING", time=t0 + k / 120))
    return t0 + n / 120


def _stroke(st, xy0, xy1):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806
    op, t0 = _begin(st, xy0)
    t = _drag(op, xy0, xy1, t0)
    res = op.step(bpy.context, LiveEvent("LEFTMOUSE", "RELEASE", xy1, time=t + 0.01))
    assert res == {"FINISHED"}
    ext().operators.paint.keep_stroke(bpy.context.scene, op._live)
    op.show(bpy.context, final=True)


def test_ctrl_z_while_painting_takes_back_the_stroke_and_painting_goes_on(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806
    st = setup_scene(bpy)
    _stroke(st, (40.0, 60.0), (120.0, 60.0))
    before, text = pixels(st.paper_image), st.recording.as_string()
    op, t0 = _begin(st, (40.0, 140.0))
    t = _drag(op, (40.0, 140.0), (120.0, 140.0), t0)
    op._last_draw = 0.0
    op.step(bpy.context, LiveEvent("TIMER", "NOTHING", time=t + 0.01))
    assert np.abs(pixels(st.paper_image) - before).max() > 0.3  # the stroke shows
    z = LiveEvent("Z", "PRESS", time=t + 0.02, ctrl=True)
    assert op.step(bpy.context, z) == {"RUNNING_MODAL"}  # painting goes on
    np.testing.assert_array_equal(pixels(st.paper_image), before)  # without the stroke
    op.step(bpy.context, LiveEvent("LEFTMOUSE", "PRESS", (40.0, 100.0), time=t + 0.5))
    t = _drag(op, (40.0, 100.0), (120.0, 100.0), t + 0.5)
    assert op.step(bpy.context, LiveEvent("RET", "PRESS", time=t + 0.01)) == {"FINISHED"}
    ext().operators.paint.keep_stroke(bpy.context.scene, op._live)
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    kept = rec.samples[len(json_samples(text)) :]
    down = kept[kept[:, 2] < HAIR]  # pressed: the stroke at y = 100 mm, none at 140
    assert len(down) >= 40 and np.all(np.abs(down[:, 1] - 100.0) < 1e-6)


def json_samples(text: str) -> list:
    import json

    return json.loads(text)["samples"]


def test_ctrl_z_before_pressing_hands_over_to_blenders_undo_of_the_last_stroke(hb):
    from tests.blender.helpers import call, undo_step

    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806
    st = setup_scene(bpy)
    undo_step(bpy, "set up")
    _stroke(st, (40.0, 60.0), (120.0, 60.0))
    undo_step(bpy, "Paint")  # as Blender pushes after the operator
    one, text_one = pixels(st.paper_image), st.recording.as_string()
    _stroke(st, (40.0, 140.0), (120.0, 140.0))
    undo_step(bpy, "Paint")
    assert np.abs(pixels(st.paper_image) - one).max() > 0.3
    # painting again, Ctrl+Z before the button goes down: painting ends, the key goes on
    sim, _ = ext().operators.paint.start_simulation(bpy.context.scene, (60.0, 100.0))
    op = _paint_operator()
    op.start(bpy.context, st.paper_image, ext().sim.engine.live.LiveBrush(sim, 4.0, 2.0, None))
    z = LiveEvent("Z", "PRESS", time=op._live._t0 + 0.1, ctrl=True)
    assert op.step(bpy.context, z) == {"CANCELLED", "PASS_THROUGH"}
    call(bpy, "undo")  # Blender's Ctrl+Z: the last stroke goes
    st = bpy.context.scene.hairy_brush
    assert st.recording.as_string() == text_one
    np.testing.assert_array_equal(pixels(st.paper_image), one)
