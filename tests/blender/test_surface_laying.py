# SPDX-License-Identifier: GPL-3.0-or-later
"""Write Character on Suzanne's brow (issue 29.7): the strokes of a character laid on a curved,
creased mesh land where they lie on flat paper relative to each other, whatever their order
(they came out in broken fragments: each stroke was laid by following the ones before it over
the surface, and the place a path over a curved surface ends at depends on the path)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.blender.helpers import HAIR, ext
from tests.paths import ROOT

bpy = pytest.importorskip("bpy")


def suzanne_paper():
    bpy.ops.mesh.primitive_monkey_add(size=0.2)  # 273 mm wide
    obj = bpy.context.active_object
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project()  # islands cut at its creases: many UV seams
    bpy.ops.object.mode_set(mode="OBJECT")
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = 2.0
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    return st, obj


@pytest.mark.slow
def test_a_character_written_on_suzannes_brow_lands_the_same_whatever_its_strokes_order(hb):
    from mathutils import Matrix

    st, obj = suzanne_paper()
    # the brush upright over the brow, above the eyes (0, -58, 50 mm; normal mostly -y)
    centre, n = np.array([0.0, -58.37, 50.0]), np.array([-0.1616, -0.9694, 0.1847])
    x = np.cross([0.0, 0.0, 1.0], n)
    x /= np.linalg.norm(x)
    m = np.eye(4)
    m[:3, :3] = np.stack([x, np.cross(n, x), n], axis=1)
    m[:3, 3] = (centre + n * (HAIR + 5)) / 1000
    st.brush_object.rotation_mode = "QUATERNION"
    st.brush_object.matrix_world = Matrix(m.tolist())
    bpy.context.view_layer.update()
    writing = ext().blender.surfaces.SurfaceWriting(bpy.context.scene)  # where it is laid
    path = ROOT / "data" / "hanzi" / "永.json"
    res = bpy.ops.hairy_brush.write_character(filepath=str(path), size_mm=30.0, passes=1)
    assert res == {"FINISHED"}
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    frames = np.asarray(rec.extra["surface"]["frames"])
    # laid again with its strokes the other way round, every sample lands where it did
    surf = ext().sim.surface
    down = np.flatnonzero(np.diff((rec.samples[:, 2] < HAIR).astype(int)) == 1) + 1
    order = np.concatenate(np.split(np.arange(len(rec.samples)), down)[::-1])
    again = np.empty_like(frames)
    again[order] = surf.lay_on(
        writing.surface, writing.start, rec.samples[order], surf.TriangleGrid(writing.surface)
    )
    touch = rec.samples[:, 2] < HAIR
    moved = np.linalg.norm(again[touch, 2:5] - frames[touch, 2:5], axis=1)
    assert moved.max() < 0.01, f"strokes land {moved.max():.1f} mm elsewhere in another order"
    # and the writing is on the brow, under the brush, about its size
    P = frames[touch, 2:5]
    assert np.linalg.norm(P - centre, axis=1).max() < 30.0
    assert np.ptp(P[:, 0]) > 15.0 and np.ptp(P[:, 2]) > 15.0
