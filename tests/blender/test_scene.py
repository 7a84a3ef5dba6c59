# SPDX-License-Identifier: GPL-3.0-or-later
"""Setting up the scene: the brush empty and paper plane in metres, the brush's pose read as the
paper's 6-DOF, presets, and the ink put on other meshes."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tests.blender.helpers import (
    HAIR,
    ext,
    mesh_without_uv,
    pixels,
    select_only,
    setup_scene,
)

bpy = pytest.importorskip("bpy")


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
    # the blank sheet: the preset's colour with its texture (clouds and fibres, a few per cent)
    sheet = ext().blender.images.blank_sheet(st, st.paper_texture)
    np.testing.assert_allclose(pixels(img)[..., :3], sheet, atol=1e-3)
    np.testing.assert_allclose(sheet.reshape(-1, 3).mean(axis=0), color, rtol=0.02)
    assert st.paper_texture > 0 and sheet[..., 1].std() > 0.002
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


# ----------------------------------------------------------------------------- 3D surfaces
def test_apply_to_mesh_puts_the_ink_over_the_meshs_own_material(hb):
    st = setup_scene(bpy)
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    mat = ext().blender.materials.new_material("Clay")  # with nodes before 5.0 too
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
