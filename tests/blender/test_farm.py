# SPDX-License-Identifier: GPL-3.0-or-later
"""A farm-ready .blend (issue 18): checkpoints next to the saved file let a fresh process show
any frame from the nearest one, exactly as sequential playback does, in any order."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from tests.paths import ADDON, ROOT

bpy = pytest.importorskip("bpy")

from sim.engine.simulation import Simulation  # noqa: E402
from sim.paper.display import linear_to_srgb  # noqa: E402
from tests.blender.helpers import (  # noqa: E402
    ext,
    keyframe_stroke,
    mesh_without_uv,
    pixels,
    select_only,
    setup_scene,
)


def farm_scene(tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=(1, 8, 70, 80))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    path = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return st, path


@pytest.mark.slow
def test_bake_cache_needs_a_saved_file_and_writes_checkpoints_next_to_it(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    with pytest.raises(RuntimeError, match="Save the file first"):
        bpy.ops.hairy_brush.bake_cache()
    st, path = farm_scene(tmp_path)
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    folder = tmp_path / "hairy_brush_cache_shot" / "Scene"
    n = len(json.loads(st.recording.as_string())["samples"])
    every = ext().blender.playback.CACHE_EVERY
    assert len(list(folder.glob("checkpoint_*.npz"))) == n // every + 1
    # a fresh start (as after opening the file) seeks from the nearest checkpoint
    ext().blender.runtime.get().forget_playbacks()
    sc = bpy.context.scene
    pb = ext().blender.playback.playback_for(sc)
    assert sorted(k for k in pb.timeline.snaps if k % every == 0)[-1] == (n // every) * every
    sc.frame_set(75)
    rec = ext().blender.recordings.recording_from_scene(sc)
    want = Simulation(rec).run(ext().blender.frames.samples_at_frame(rec, sc, 75)).paper.rgb()
    assert np.abs(pixels(st.paper_image)[..., :3] - want).max() <= 0.5 / 4095 + 1e-6
    # a changed setting makes the cache stale: it is not used
    st.quality.ren = 0.123 if st.quality.ren != 0.123 else 0.321
    ext().blender.runtime.get().forget_playbacks()
    assert len(ext().blender.playback.playback_for(sc).timeline.snaps) == 1


WORKER = textwrap.dedent(
    """
    import bpy
    import addon_utils
    import numpy as np
    addon_utils.enable({addon!r}, default_set=True)
    bpy.ops.wm.open_mainfile(filepath={path!r})
    sc = bpy.context.scene
    img = sc.hairy_brush.paper_image
    for f in {frames!r}:
        sc.frame_set(f)
        a = np.empty(len(img.pixels), np.float32)
        img.pixels.foreach_get(a)
        np.save({out!r} + f"/frame_{{f}}.npy", a)
    """
)


@pytest.mark.slow
def test_frames_rendered_in_shuffled_order_by_separate_processes_equal_sequential(hb, tmp_path):
    st, path = farm_scene(tmp_path)
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    bpy.ops.wm.save_mainfile()
    frames = [5, 30, 55, 72, 80]
    sequential = {}
    sc = bpy.context.scene
    for f in frames:
        sc.frame_set(f)
        a = np.empty(len(st.paper_image.pixels), np.float32)
        st.paper_image.pixels.foreach_get(a)
        sequential[f] = a
    out = tmp_path / "frames"
    out.mkdir()
    env = dict(os.environ)
    procs = []
    for part in ([72, 5, 55], [80, 30]):
        script = WORKER.format(addon=ADDON, path=str(path), frames=part, out=str(out))
        procs.append(subprocess.Popen([sys.executable, "-c", script], env=env, cwd=ROOT))
    assert all(p.wait(timeout=300) == 0 for p in procs)
    for f in frames:
        np.testing.assert_array_equal(np.load(out / f"frame_{f}.npy"), sequential[f])


# ----------------------------------------------------------------------------- relief (Sec. 9)
def _grid_over_paper(n=120):
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=n, y_subdivisions=n, size=0.2)
    return bpy.context.active_object  # UVs 0..1 over the 200 mm paper, as the paper image


@pytest.mark.parametrize("mode,sign", [("CARVE", -1.0), ("EMBOSS", 1.0)])
def test_relief_moves_the_surface_under_the_ink_only_by_the_depth(hb, mode, sign):
    st = setup_scene(bpy, ppm=2.0)
    keyframe_stroke(bpy, st, press=8.0)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    grid = _grid_over_paper()
    for ob in bpy.context.scene.objects:
        ob.select_set(ob == grid)
    assert bpy.ops.hairy_brush.relief(mode=mode, depth_mm=2.0) == {"FINISHED"}
    dg = bpy.context.evaluated_depsgraph_get()
    me = grid.evaluated_get(dg).to_mesh()
    z = np.array([v.co.z for v in me.vertices])
    xy = np.array([v.co[:2] for v in me.vertices])
    grid.evaluated_get(dg).to_mesh_clear()
    # by default the depth follows the ink's density (issue 17.3): the modifier reads the
    # Non-Color density image that follows the paper, which must show the ink the paper shows
    dens_img = bpy.data.images[st.paper_image["hairy_brush_density"]]
    raw = np.empty(len(dens_img.pixels), np.float32)
    dens_img.pixels.foreach_get(raw)
    depth = raw.reshape(400, 400, 4)[..., :3].mean(axis=2)  # 0 on bare paper, 1 under full ink
    img = np.empty(len(st.paper_image.pixels), np.float32)
    st.paper_image.pixels.foreach_get(img)
    img = linear_to_srgb(img.reshape(400, 400, 4)[..., :3])  # as the engine's Paper.rgb
    sheet = ext().blender.images.blank_sheet(st, st.paper_texture)  # the blank paper, textured
    shown = np.clip(1.0 - img / sheet, 0.0, 1.0).mean(axis=2)  # the density it shows
    np.testing.assert_allclose(depth, shown, atol=0.01)
    px = np.clip(((xy + 0.1) * 1000 * 2.0).astype(int), 0, 399)
    win = np.stack(
        [
            depth[np.clip(px[:, 1] + dy, 0, 399), np.clip(px[:, 0] + dx, 0, 399)]
            for dy in (-1, 0, 1)
            for dx in (-1, 0, 1)
        ]
    )
    # each vertex reads the density between its texels (linear filtering): between the
    # least and the most of its 3 x 3 neighbourhood, times the depth
    moved = sign * z / 0.002
    assert (moved >= win.min(axis=0) - 2e-3).all() and (moved <= win.max(axis=0) + 2e-3).all()
    inked, bare = win.min(axis=0) > 0.2, win.max(axis=0) < 1e-4
    assert inked.sum() > 20 and bare.sum() > 1000
    np.testing.assert_allclose(z[bare], 0.0, atol=1e-6)
    assert -sign * z.min() < 0.0021 and sign * z.max() < 0.0021  # never beyond the depth


def test_relief_needs_a_uv_map(hb):
    st = setup_scene(bpy)
    select_only(mesh_without_uv(bpy))
    assert st.paper_image is not None
    with pytest.raises(RuntimeError, match="has a UV map"):
        bpy.ops.hairy_brush.relief()


@pytest.mark.slow
def test_a_density_relief_leaves_nothing_when_it_fails_and_its_image_is_refreshed_only_while_read(
    hb, monkeypatch
):
    st = setup_scene(bpy, ppm=2.0)
    keyframe_stroke(bpy, st, press=8.0)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    img, tag = st.paper_image, "hairy_brush_density"
    grid = _grid_over_paper(n=8)
    select_only(grid)

    def fails(*_args, **_kw):
        raise RuntimeError("the re-simulation failed")

    with monkeypatch.context() as m:
        m.setattr(ext().blender.playback, "show", fails)
        with pytest.raises(RuntimeError, match="the re-simulation failed"):
            bpy.ops.hairy_brush.relief(follow="DENSITY")
    assert tag not in img and not [i for i in bpy.data.images if "Ink Density" in i.name]
    assert not [m for m in grid.modifiers if m.type == "DISPLACE"]
    assert bpy.ops.hairy_brush.relief(follow="DENSITY") == {"FINISHED"}
    dens = bpy.data.images[img[tag]]
    n = int(img[ext().blender.images.SHOWN_TAG])

    def density():
        a = np.empty(len(dens.pixels), np.float32)
        dens.pixels.foreach_get(a)
        return a.reshape(dens.size[1], dens.size[0], 4)[..., 0]

    full = density()
    assert full.max() > 0.2
    marker = np.full(len(dens.pixels), 0.5, np.float32)
    dens.pixels.foreach_set(marker)
    ext().blender.runtime.get().forget_playbacks()
    ext().blender.playback.show(bpy.context.scene, n)  # read by the relief: refreshed
    np.testing.assert_array_equal(density(), full)
    for mod in [m for m in grid.modifiers if m.type == "DISPLACE"]:
        grid.modifiers.remove(mod)
    dens.pixels.foreach_set(marker)
    ext().blender.runtime.get().forget_playbacks()
    ext().blender.playback.show(bpy.context.scene, n)  # no relief reads it: left as it is
    assert (density() == 0.5).all()
