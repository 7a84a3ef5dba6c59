# SPDX-License-Identifier: GPL-3.0-or-later
"""Carve/Emboss on any mesh (issue 29.7): a coarse mesh is cut where the ink is as finely as the
ink's texels need (it showed nothing, and said nothing, with the old default), the carving
along a stroke is even (a few uniform subdivisions showed it in blocks and streaks), and a mesh
that would need too many vertices gets the relief in its material, with a message."""

from __future__ import annotations

import numpy as np
import pytest

from tests.blender.helpers import ext, keyframe_stroke, select_only, setup_scene

bpy = pytest.importorskip("bpy")
pytestmark = pytest.mark.slow  # each writes and simulates a stroke first (over a second)


def stroke_and_plane():
    """A horizontal stroke across the paper's middle (200 mm paper at 2 px/mm), and a separate
    200 mm square of 4 vertices whose UVs cover the paper image."""
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    bpy.ops.mesh.primitive_plane_add(size=0.2, location=(0.5, 0.0, 0.0))
    plane = bpy.context.active_object
    select_only(plane)
    return st, plane


def heights(obj) -> np.ndarray:
    """(N, 3) the evaluated mesh's vertices in mm, in the object's space."""
    dg = bpy.context.evaluated_depsgraph_get()
    me = obj.evaluated_get(dg).to_mesh()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    obj.evaluated_get(dg).to_mesh_clear()
    return co.reshape(-1, 3) * 1000


def density_at(xy_mm) -> np.ndarray:
    """The engine's ink density at points of the plane (mm from its centre)."""
    paper = ext().blender.playback.playback_for(bpy.context.scene).sim.paper
    dens = paper.ink.mean(axis=2)
    col = np.clip(((xy_mm[:, 0] + 100) * paper.ppm).astype(int), 0, paper.W - 1)
    row = np.clip(((xy_mm[:, 1] + 100) * paper.ppm).astype(int), 0, paper.H - 1)
    return dens[row, col]


def test_a_coarse_mesh_is_cut_where_the_ink_is_and_carved_evenly_along_the_stroke(hb, capfd):
    st, plane = stroke_and_plane()
    capfd.readouterr()
    assert bpy.ops.hairy_brush.relief(mode="CARVE", depth_mm=1.5) == {"FINISHED"}
    said = capfd.readouterr().out
    assert "faces under the ink cut" in said  # it says what it did
    co = heights(plane)
    assert len(co) > 50_000  # 4 vertices before
    plan_says = int(said.split("about ")[1].split(" vertices")[0].replace(",", ""))
    assert len(co) == pytest.approx(plan_says, rel=0.02)
    depth = -co[:, 2]
    # as deep as the ink is dense where it is darkest (a loaded stroke's film levels across it:
    # about 0.9 here, at 2 px/mm)
    darkest = float(
        ext().blender.playback.playback_for(bpy.context.scene).sim.paper.ink.mean(2).max()
    )
    assert darkest > 0.85
    assert depth.max() == pytest.approx(1.5 * darkest, abs=0.1)
    # along the stroke's middle, every vertex carved as deep as the ink is dense: no blocks,
    # no streaks
    mid = (np.abs(co[:, 1]) < 0.5) & (np.abs(co[:, 0]) < 30.0)
    assert mid.sum() > 100
    want = 1.5 * density_at(co[mid, :2])
    np.testing.assert_allclose(depth[mid], want, atol=0.1)  # (texels read bilinearly)
    assert depth[mid].min() > 0.5 * depth[mid].max()
    # and bare paper does not move
    assert np.abs(depth[np.abs(co[:, 1]) > 20.0]).max() < 1e-6


def test_a_few_uniform_subdivisions_warn_that_the_relief_is_coarse(hb, capfd):
    st, plane = stroke_and_plane()
    capfd.readouterr()
    assert bpy.ops.hairy_brush.relief(mode="CARVE", depth_mm=1.5, detail=4) == {"FINISHED"}
    assert "the relief shows in blocks" in capfd.readouterr().out
    assert plane.modifiers[ext().operators.relief.DETAIL].type == "SUBSURF"


def test_a_mesh_too_coarse_for_its_vertices_gets_the_relief_in_its_material(hb, capfd, monkeypatch):
    st, plane = stroke_and_plane()
    relief = ext().operators.relief
    monkeypatch.setattr(ext().sim.surface.relief, "MAX_RELIEF_VERTICES", 1000)
    capfd.readouterr()
    assert bpy.ops.hairy_brush.relief(mode="EMBOSS", depth_mm=1.0) == {"FINISHED"}
    assert "it is in the material instead" in capfd.readouterr().out
    assert relief.RELIEF not in plane.modifiers and relief.DETAIL not in plane.modifiers
    nodes = plane.active_material.node_tree.nodes
    bump = nodes[ext().blender.materials.BUMP_NODE]
    assert bump.invert  # emboss: ink (dark) comes out
    assert nodes[ext().blender.materials.BUMP_NODE + " Height"].image == st.paper_image
    bsdf = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    assert bsdf.inputs["Normal"].links[0].from_node == bump
    monkeypatch.undo()  # with room for the vertices: the shape again, the bump gone
    assert bpy.ops.hairy_brush.relief(mode="EMBOSS", depth_mm=1.0) == {"FINISHED"}
    assert relief.RELIEF in plane.modifiers
    assert ext().blender.materials.BUMP_NODE not in plane.active_material.node_tree.nodes
    assert heights(plane)[:, 2].max() == pytest.approx(1.0, abs=0.1)
