# SPDX-License-Identifier: GPL-3.0-or-later
"""Write Text in Blender (issue 27, points 5 and 7): a short text at a small size through the
operator - the layout against the ink, the paper image against the engine's render of the
stored recording (grid and seal as ``sim render`` draws them), the append behaviour (earlier
strokes, keys and paper kept; undo takes back one call), the unsupported-character message,
one cell written again, sign and seal, Esc, and a work laid in a surface's UV space."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import pytest

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

from sim.core.recording import load  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from sim.image.png import read_png  # noqa: E402
from sim.writing.work import compose  # noqa: E402
from sim.writing.work.layout import Layout  # noqa: E402

PPM = 1.5  # px/mm: a 200 mm paper is 300 px
SIZE = 24.0  # mm, the em box


def small_work(bpy, **work):
    st = setup_scene(bpy, ppm=PPM)
    w = st.work
    w.char_mm, w.passes = SIZE, 1
    for k, v in work.items():
        setattr(w, k, v)
    return st


def scene_rec():
    return ext().blender.recordings.recording_from_scene(bpy.context.scene)


def layout_of(rec) -> Layout:
    return Layout.from_dict(rec.extra["work"]["layout"])


def keys(st) -> dict:
    """(path, index) -> (frames, values) of the brush empty's location and rotation keys."""
    return ext().blender.keyframes.read_channels(st.brush_object)


def engine_image(rec) -> np.ndarray:
    """What ``sim render`` writes for the recording: its whole run, the work's grid and seal."""
    return compose.image8(Simulation(rec).run().paper, rec)


def shown(st) -> np.ndarray:
    """The paper image as 8-bit RGB, top row first (as a PNG of it holds)."""
    return np.floor(pixels(st.paper_image)[::-1, :, :3] * 255 + 0.5).astype(np.uint8)


def assert_shows(st, rec):
    """The paper image is the engine's render of the recording (to the image's float precision:
    at most one 8-bit step, in a few per cent of the pixels: the paper's texture puts many of
    them near a rounding step)."""
    want = engine_image(rec).astype(int)
    got = shown(st).astype(int)
    assert got.shape == want.shape
    diff = np.abs(got - want)
    assert diff.max() <= 1 and (diff > 0).mean() < 0.05


def ink_in_territory(rec, lay):
    """Each cell's own ink (simulated alone, compose.render) lies inside its place on the paper
    (its em box and half the gap to its neighbours)."""
    _, inks = compose.render(rec)
    H = rec.height_px
    for cell, ci in zip(lay.cells, inks, strict=True):
        rows, cols = np.nonzero(ci.mask & (ci.ink.max(axis=-1) > compose.INK_SEEN))
        assert rows.size > 20, cell.char
        r0, _, c0, _ = ci.window
        x0, y0, x1, y1 = (np.array(cell.territory(lay.vertical)) * rec.px_per_mm).tolist()
        assert x0 - 1 <= c0 + cols.min() and c0 + cols.max() < x1 + 1, cell.char
        assert y0 - 1 <= r0 + rows.min() and r0 + rows.max() < y1 + 1, cell.char
    assert H == rec.height_px


# ----------------------------------------------------------------------------- messages
def test_text_without_stroke_data_is_named_and_nothing_is_written(hb):
    """Every character without stroke data is named in one message before anything is
    written; a recording that is not a work, a size that does not fit and an empty text are
    refused with their reason, the scene unchanged."""
    st = small_work(bpy)
    paper = (st.paper_width_mm, st.paper_height_mm)
    with pytest.raises(RuntimeError, match=r"No stroke data for 2 character\(s\): 'A'.*'😀'"):
        bpy.ops.hairy_brush.write_text(text="十A一😀")
    assert st.recording is None and st.brush_object.animation_data is None
    with pytest.raises(RuntimeError, match="Type the text"):
        bpy.ops.hairy_brush.write_text(text="  ")
    st.work.char_mm = float("nan")  # a hand-edited file
    with pytest.raises(RuntimeError, match="Size is not a number"):
        bpy.ops.hairy_brush.write_text(text="十")
    st.work.char_mm = 150.0  # five 150 mm characters on a 200 mm paper
    with pytest.raises(RuntimeError, match="does not fit the paper"):
        bpy.ops.hairy_brush.write_text(text="十一二三四")
    assert (st.paper_width_mm, st.paper_height_mm) == paper and st.recording is None
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    with pytest.raises(RuntimeError, match="not a work written with Write Text"):
        bpy.ops.hairy_brush.write_text(text="十")
    with pytest.raises(RuntimeError, match="No recording yet|not a work"):
        bpy.ops.hairy_brush.rewrite_cell(index=0)


def test_the_sidebar_shows_the_work_from_the_texts_tags(hb):
    """The Write Text panel reads the work's cells from tags on the recording text (no JSON
    parsed while drawing); another recording stored over it drops them."""
    from tests.blender.test_sidebar import drawn, names

    st = small_work(bpy)
    log = drawn(bpy.types.HAIRY_BRUSH_PT_write_text)
    assert {"text", "direction", "per_line", "char_mm", "grid", "signature", "seal"} <= set(
        names(log, "prop")
    )
    assert "hairy_brush.write_text" in names(log, "op")
    assert "hairy_brush.sign_work" in names(log, "op")
    rec_mod = ext().blender.recordings
    from sim.core.recording import Recording

    rec = Recording(np.zeros((3, 6)))
    rec.extra["work"] = {"layout": {"cells": [{"char": "十", "role": "text"}]}}
    rec_mod.store_recording(st, rec)
    assert st.recording[rec_mod.WORK_TAG] == "十"
    log = drawn(bpy.types.HAIRY_BRUSH_PT_write_text)
    assert "new_line" in names(log, "prop") and "hairy_brush.rewrite_cell" in names(log, "op")
    assert "direction" not in names(log, "prop")  # a work keeps its layout
    rec_mod.store_recording(st, Recording(np.zeros((3, 6))))
    assert rec_mod.WORK_TAG not in st.recording


# ----------------------------------------------------------------------------- writing
@pytest.mark.slow
def test_write_text_lays_a_work_goes_on_after_it_and_undo_takes_back_one_call(hb):
    """On an empty recording the work is laid on the paper from its corner (the paper keeps its
    size), each character's ink in its cell, the brush keyed a key a sample, the paper image
    the engine's render of the stored recording with its 米字格. A further call goes on in a
    new column: the earlier samples, dips and keys stay as they were. Undo takes back that
    call alone."""
    sc = bpy.context.scene
    st = small_work(bpy, per_line=2, grid="mi")
    paper = (st.paper_width_mm, st.paper_height_mm, tuple(st.paper_image.size))
    t0 = time.perf_counter()
    assert bpy.ops.hairy_brush.write_text(text="十一") == {"FINISHED"}
    print(f"\nwrite_text 十一 at {SIZE} mm, {PPM} px/mm: {time.perf_counter() - t0:.1f} s")
    assert (st.paper_width_mm, st.paper_height_mm, tuple(st.paper_image.size)) == paper
    rec = scene_rec()
    lay = layout_of(rec)
    assert [(c.char, c.line, c.index) for c in lay.cells] == [("十", 0, 0), ("一", 0, 1)]
    assert (lay.width_mm, lay.height_mm) == paper[:2] and lay.char_mm == SIZE
    # a vertical work starts at the paper's top right, the second character under the first
    first, second = lay.cells
    assert first.x > st.paper_width_mm / 2 and first.y > st.paper_height_mm / 2
    assert second.x == pytest.approx(first.x) and second.y < first.y
    ink_in_territory(rec, lay)
    assert_shows(st, rec)
    # the grid is printed: faint red lines where the paper has no ink
    img = shown(st).astype(int)
    red = (img[..., 0] - img[..., 2] > 25) & (img[..., 1] < img[..., 0])
    assert red.sum() > 100
    k = keys(st)
    assert len(k[("location", 0)][0]) == len(rec.samples)
    assert sc.frame_end >= k[("location", 0)][0][-1]
    before = (rec.samples.copy(), list(rec.dips), k, sc.frame_end)
    undo_step(bpy, "Write Text")
    # a further call: a new column, nothing earlier moved
    assert bpy.ops.hairy_brush.write_text(text="人", new_line=True) == {"FINISHED"}
    rec2 = scene_rec()
    lay2 = layout_of(rec2)
    assert [(c.char, c.line, c.index) for c in lay2.cells][-1] == ("人", 1, 0)
    n = len(before[0])
    np.testing.assert_array_equal(rec2.samples[:n], before[0])
    assert rec2.dips[: len(before[1])] == before[1] and len(rec2.samples) > n
    k2 = keys(st)
    for key, (frames, values) in before[2].items():
        np.testing.assert_array_equal(k2[key][0][:n], frames)
        np.testing.assert_array_equal(k2[key][1][:n], values)
        assert len(k2[key][0]) == len(rec2.samples)
    assert sc.frame_end > before[3]
    assert (st.paper_width_mm, st.paper_height_mm, tuple(st.paper_image.size)) == paper
    assert_shows(st, rec2)
    # the keys put the brush where the samples say
    paper_mw = st.paper_object.matrix_world
    fps = sc.render.fps / sc.render.fps_base
    for i in (n // 2, n + (len(rec2.samples) - n) // 2):
        f = sc.frame_start + i * fps / rec2.sample_rate_hz
        sc.frame_set(math.floor(f), subframe=f - math.floor(f))
        want = ext().blender.transforms.matrix_from_sample(st, paper_mw, rec2.samples[i])
        np.testing.assert_allclose(np.array(st.brush_object.matrix_world), want, atol=1e-4)
    undo_step(bpy, "Write Text")
    call(bpy, "undo")  # one call taken back: the work of two characters again
    st = bpy.context.scene.hairy_brush
    back = scene_rec()
    assert [c.char for c in layout_of(back).cells] == ["十", "一"]
    np.testing.assert_array_equal(back.samples, before[0])
    assert len(keys(st)[("location", 0)][0]) == n
    assert bpy.context.scene.frame_end == before[3]


@pytest.mark.slow
def test_playback_and_image_sequences_draw_the_work_as_sim_render_does(hb, tmp_path):
    """Following frames, the paper image of a work with a grid is the engine's image at that
    frame; the image sequence's last frame is byte for byte what ``sim render`` writes for the
    exported recording."""
    from sim.cli.main import main

    sc = bpy.context.scene
    st = small_work(bpy, grid="tian", direction="horizontal")
    assert bpy.ops.hairy_brush.write_text(text="口") == {"FINISHED"}
    rec = scene_rec()
    ext().blender.runtime.get().forget_playbacks()
    sc.frame_set(sc.frame_end)
    assert_shows(st, rec)
    mid = sc.frame_start + (sc.frame_end - sc.frame_start) // 2
    sc.frame_set(mid)
    n = ext().blender.frames.samples_at_frame(rec, sc, mid)
    part = Simulation(rec).run(until=n).paper
    want = compose.image8(part, rec).astype(int)
    assert np.abs(shown(st).astype(int) - want).max() <= 1
    st.sequence_dir = str(tmp_path / "seq")
    sc.frame_start = sc.frame_end  # the last frame only
    assert bpy.ops.hairy_brush.bake_sequence() == {"FINISHED"}
    (png,) = sorted((tmp_path / "seq").iterdir())
    path = tmp_path / "rec.json"
    assert bpy.ops.hairy_brush.export_recording(filepath=str(path)) == {"FINISHED"}
    assert main(["render", str(path), "-o", str(tmp_path / "cli.png"), "-q"]) == 0
    np.testing.assert_array_equal(read_png(png), read_png(tmp_path / "cli.png"))
    assert json.loads(path.read_text("utf-8"))["work"]["layout"]["grid"] == "tian"


@pytest.mark.slow
def test_a_cell_written_again_leaves_the_others_and_the_work_signs_and_seals(hb):
    """Write Cell Again (the cell under the 3D cursor) replaces that cell's strokes and keys;
    the other cell's samples, keys and ink stay bit for bit. Sign and Seal adds the signature
    and a red seal after the text, as the engine renders them; no text goes after them."""
    sc = bpy.context.scene
    st = small_work(bpy, per_line=2)
    assert bpy.ops.hairy_brush.write_text(text="大人") == {"FINISHED"}
    rec = scene_rec()
    assert_shows(st, rec)  # a work without grid or seal: the paper alone
    lay = layout_of(rec)
    _, inks = compose.render(rec)
    k = keys(st)
    (a0, b0), (a1, b1) = (c.samples for c in lay.cells)
    # the 3D cursor on the second character
    cell = lay.cells[1]
    xy = np.array([cell.x + cell.size / 2, cell.y + cell.size / 2, 0.0, 1.0])
    world = ext().blender.transforms.engine_to_world(st, st.paper_object) @ xy
    sc.cursor.location = world[:3]
    assert bpy.ops.hairy_brush.rewrite_cell(index=-1) == {"FINISHED"}
    rec2 = scene_rec()
    lay2 = layout_of(rec2)
    assert lay2.cells[1].seed != cell.seed and lay2.cells[0].seed == lay.cells[0].seed
    np.testing.assert_array_equal(rec2.samples[a0:b0], rec.samples[a0:b0])
    a2, b2 = lay2.cells[1].samples
    assert a2 == a1 and not np.array_equal(rec2.samples[a2 : a2 + 50], rec.samples[a1 : a1 + 50])
    k2 = keys(st)
    for key in k:
        np.testing.assert_array_equal(k2[key][1][:b0], k[key][1][:b0])
        assert len(k2[key][0]) == len(rec2.samples)
    _, inks2 = compose.render(rec2)
    for name in ("mask", "ink", "wet", "last"):  # the first character's ink, bit for bit
        np.testing.assert_array_equal(getattr(inks2[0], name), getattr(inks[0], name))
    assert not np.array_equal(inks2[1].ink, inks[1].ink)
    assert_shows(st, rec2)
    with pytest.raises(RuntimeError, match="not on a cell"):
        sc.cursor.location = (5.0, 5.0, 0.0)
        bpy.ops.hairy_brush.rewrite_cell(index=-1)
    st.work.signature, st.work.seal, st.work.seal_style = "一", "口", "zhuwen"
    assert bpy.ops.hairy_brush.sign_work() == {"FINISHED"}
    rec3 = scene_rec()
    lay3 = layout_of(rec3)
    assert [c.role for c in lay3.cells] == ["text", "text", "signature"]
    assert lay3.seal["text"] == "口" and lay3.seal["style"] == "zhuwen"
    np.testing.assert_array_equal(rec3.samples[: len(rec2.samples)], rec2.samples)
    assert_shows(st, rec3)
    img = shown(st).astype(int)
    x0, y0, x1, y1 = lay3.seal["box"]
    H = rec3.height_px
    box = img[int(H - y1 * PPM) : int(H - y0 * PPM), int(x0 * PPM) : int(x1 * PPM)]
    assert ((box[..., 0] - box[..., 2] > 60) & (box[..., 1] < 150)).mean() > 0.1  # vermilion
    assert st.recording[ext().blender.recordings.SIGNED_TAG] == 1
    with pytest.raises(RuntimeError, match="signed"):
        bpy.ops.hairy_brush.write_text(text="十")


@pytest.mark.slow
def test_esc_leaves_nothing_of_the_call_and_the_job_reports_progress(hb):
    """The job writes in a worker (Blender's thread free); Esc stops it between cells and the
    scene is as it was; run to the end its progress only goes forward."""
    from tests.blender.test_sidebar import run_slices

    sc = bpy.context.scene
    st = small_work(bpy)
    work = ext().blender.work
    job = work.write_job(sc, "十一", False)
    assert job.step(0.01) is False
    time.sleep(0.2)
    job.cancel()
    job._thread.join(120.0)
    assert not job._thread.is_alive() and job.result is None and job.error is None
    assert st.recording is None and st.brush_object.animation_data is None
    job = work.write_job(sc, "十", False)
    fractions = run_slices(job, budget=0.05, limit=300.0)
    assert fractions == sorted(fractions) and 0 <= fractions[0] and fractions[-1] <= 1
    level, message = job.finish(bpy.context)
    assert level == "INFO" and "十" in message
    assert st.recording is not None and len(layout_of(scene_rec()).cells) == 1
    # a stroke painted after the work (samples no cell holds): the next call's paper is the
    # whole run of the recording, still the engine's render of it
    rec = scene_rec()
    x, y = layout_of(rec).cells[0].x - 10.0, layout_of(rec).cells[0].y
    stroke = np.array(
        [[x, y - 5 * k, HAIR - (3.0 if 2 < k < 8 else -5.0), 0, 0, 0] for k in range(10)]
    )
    rec.samples = np.concatenate([rec.samples, stroke])
    ext().blender.recordings.store_recording(st, rec)
    assert bpy.ops.hairy_brush.write_text(text="一") == {"FINISHED"}
    rec2 = scene_rec()
    np.testing.assert_array_equal(rec2.samples[: len(rec.samples)], rec.samples)
    assert not ext().blender.work.cells_cover(rec2, layout_of(rec2))
    assert_shows(st, rec2)


@pytest.mark.slow
def test_write_text_on_a_cylinder_lays_the_work_in_its_uv_space(hb):
    """On a surface paper each cell is laid on the surface around the point whose UV is its
    centre, upright along the texture's x; the texture keeps its size; a further call goes on
    with the earlier frames kept; a new simulation of the stored recording shows the same
    image bit for bit."""
    from tests.blender.test_surface import R_MM, cylinder, surface_scene

    sc = bpy.context.scene
    st = surface_scene(cylinder(), ppm=2.0)
    st.work.char_mm, st.work.passes, st.work.per_line = 16.0, 1, 1
    side, size_px = (st.paper_width_mm, st.paper_height_mm), tuple(st.paper_image.size)
    assert bpy.ops.hairy_brush.write_text(text="十") == {"FINISHED"}
    old = scene_rec()
    assert bpy.ops.hairy_brush.write_text(text="一", new_line=True) == {"FINISHED"}
    assert (st.paper_width_mm, st.paper_height_mm) == side
    assert tuple(st.paper_image.size) == size_px
    rec = scene_rec()
    frames = np.asarray(rec.extra["surface"]["frames"])
    assert frames.shape == (len(rec.samples), 11)
    n = len(old.samples)
    np.testing.assert_array_equal(frames[:n], np.asarray(old.extra["surface"]["frames"]))
    P = frames[:, 2:5]
    assert np.abs(np.hypot(P[:, 0], P[:, 1]) - R_MM).max() < 0.5  # on the cylinder
    surface = ext().blender.surfaces.mesh_surface(st.paper_object)[0]
    hair = rec.resolve()[1].hair_length_mm  # a brush made smaller for 16 mm (brush_size)
    assert hair < HAIR
    for cell in layout_of(rec).cells:
        a, b = cell.samples
        touch = rec.samples[a:b, 2] < hair
        centre = ((cell.x + cell.size / 2) / rec.width_mm, (cell.y + cell.size / 2) / rec.height_mm)
        want = ext().sim.surface.uv_hit(surface, centre).point
        mid = (P[a:b][touch].max(axis=0) + P[a:b][touch].min(axis=0)) / 2
        assert np.linalg.norm(mid - want) < 0.35 * cell.size, cell.char
    shown_px = np.empty(len(st.paper_image.pixels), np.float32)
    st.paper_image.pixels.foreach_get(shown_px)
    assert (pixels(st.paper_image)[..., :3].mean(axis=2) < 0.5).sum() > 20
    sc.frame_set(sc.frame_end)
    ext().blender.runtime.get().forget_playbacks()
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    again = np.empty(len(st.paper_image.pixels), np.float32)
    st.paper_image.pixels.foreach_get(again)
    np.testing.assert_array_equal(shown_px, again)


def test_a_saved_recording_of_a_work_renders_bit_for_bit(hb, tmp_path):
    """Import of a composed recording (the command line's) keeps its work: the playback draws
    its grid as sim render does, exactly."""
    path = tmp_path / "w.json"
    rec = _tiny_work()
    rec.save(path)
    st = setup_scene(bpy, ppm=rec.px_per_mm)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(path)) == {"FINISHED"}
    assert st.recording[ext().blender.recordings.WORK_TAG] == "一"
    sc = bpy.context.scene
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    rec = scene_rec()
    assert rec.extra["work"] == load(path).extra["work"]
    assert_shows(st, rec)
    assert sc.frame_end >= sc.frame_start


def _tiny_work():
    """A one-cell work with a grid built straight from the layout (no writing): a short
    stroke in its cell, a restarting dip."""
    from sim.core.recording import Dip, Recording
    from sim.writing.strokes import stroke
    from sim.writing.work.layout import Settings, lay_out
    from sim.writing.work.text import parse_text

    lay = lay_out(parse_text("一"), Settings(char_mm=20.0, grid="mi"))
    cell = lay.cells[0]
    s = stroke(
        [[cell.x + 4, cell.y + 10], [cell.x + 16, cell.y + 10]],
        press_mm=3.0,
        speed_mm_s=60.0,
        hair_length_mm=HAIR,
    )
    cell.samples = (0, len(s))
    rec = Recording(
        s,
        width_mm=lay.width_mm,
        height_mm=lay.height_mm,
        px_per_mm=2.0,
        dips=[Dip(0, 0.7, (0.03, 0.03, 0.04), 0.9, follows_ink=True, restart=0)],
    )
    rec.extra["work"] = {"version": 1, "layout": lay.to_dict(), "seal_glyphs": []}
    return rec
