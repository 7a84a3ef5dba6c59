# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.setup: a brush empty, a paper plane textured with the paper image, the settings."""

from __future__ import annotations

import math

import bpy
import numpy as np
from mathutils import Vector

from .. import bridge
from ..sim.params import HOVER_MM

PAPER_MATERIAL = "HairyBrush Paper"
HAIR_TAG = "hairy_brush_hair"


def paper_material(img) -> bpy.types.Material:
    mat = bpy.data.materials.get(PAPER_MATERIAL)
    if mat is None:
        mat = bpy.data.materials.new(PAPER_MATERIAL)
    if mat.node_tree is None:  # Blender < 5 creates materials without nodes
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    tex = next((n for n in nodes if n.type == "TEX_IMAGE"), None)
    if tex is None:
        tex = nodes.new("ShaderNodeTexImage")
        tex.location = (-400, 300)
    tex.image = img
    bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is not None:
        mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        bsdf.inputs["Roughness"].default_value = 0.9
    return mat


def paper_mesh(name: str, width_m: float, height_m: float) -> bpy.types.Mesh:
    """A plane of the paper's size, UV (0, 0) at its lower-left corner."""
    w, h = width_m / 2, height_m / 2
    me = bpy.data.meshes.new(name)
    me.from_pydata([(-w, -h, 0), (w, -h, 0), (w, h, 0), (-w, h, 0)], [], [(0, 1, 2, 3)])
    uv = me.uv_layers.new(name="UVMap")
    for loop, co in zip(me.loops, ((0, 0), (1, 0), (1, 1), (0, 1)), strict=True):
        uv.data[loop.index].uv = co
    me.update()
    return me


def resize_paper(st):
    """Make the paper plane match the paper size in the settings (the property update of Width
    and Height calls this, so the plane follows every change and every import)."""
    obj = st.paper_object
    if obj is None or obj.type != "MESH":
        return
    w, h = st.paper_width_mm / bridge.MM, st.paper_height_mm / bridge.MM
    if not (math.isfinite(w) and math.isfinite(h)):
        return
    me = obj.data
    xs = [v.co.x for v in me.vertices]
    ys = [v.co.y for v in me.vertices]
    if xs and abs((max(xs) - min(xs)) - w) <= 1e-7 and abs((max(ys) - min(ys)) - h) <= 1e-7:
        return
    if len(me.vertices) == 4 and me.users == 1:  # the plane Setup made: move its corners
        for v in me.vertices:
            v.co.x = w / 2 if v.co.x > (max(xs) + min(xs)) / 2 else -w / 2
            v.co.y = h / 2 if v.co.y > (max(ys) + min(ys)) / 2 else -h / 2
        me.update()
        return
    obj.data = paper_mesh(me.name, w, h)
    for m in me.materials:
        obj.data.materials.append(m)
    if me.users == 0:
        bpy.data.meshes.remove(me)


def hair_marker(brush):
    """The brush's hair marker (a child empty drawn as an arrow from the base down to the
    tip of the unbent hair: where the arrow's point meets the paper, the brush touches)."""
    return next((c for c in brush.children if HAIR_TAG in c), None)


def show_hair_length(st, hair_mm: float):
    """Make or update the hair marker of the settings' brush."""
    brush = st.brush_object
    if brush is None:
        return
    marker = hair_marker(brush)
    if marker is None:
        marker = bpy.data.objects.new("HairyBrush Hair", None)
        marker[HAIR_TAG] = 1
        marker.empty_display_type = "SINGLE_ARROW"
        marker.rotation_euler = (math.pi, 0.0, 0.0)  # the arrow points down the hair
        marker.hide_render = True
        marker.hide_select = True
        for coll in brush.users_collection:
            coll.objects.link(marker)
        marker.parent = brush
    marker.empty_display_size = hair_mm / bridge.MM


def follow_hair_length(st):
    """After the brush preset changed: the marker shows the new hair length and the brush
    empty (with its location keyframes) moves by the change, so it hovers or presses as far
    above or into its touching height as before. Returns the change in mm."""
    new = bridge.hair_length(st)
    delta = new - st.touch_height_mm
    st.touch_height_mm = new
    brush, paper = st.brush_object, st.paper_object
    if brush is None:
        return delta
    show_hair_length(st, new)
    if abs(delta) < 1e-9 or paper is None:
        return delta
    move = _basis_offset(brush, paper, delta)
    brush.location = brush.location + Vector(move)
    ad = brush.animation_data
    if ad is not None and ad.action is not None:
        for fc in bridge.fcurves(ad):
            if fc.data_path != "location" or abs(move[fc.array_index]) < 1e-12:
                continue
            d = move[fc.array_index]
            for kp in fc.keyframe_points:
                kp.co.y += d
                kp.handle_left.y += d
                kp.handle_right.y += d
            fc.update()
    return delta


def _basis_offset(brush, paper, delta_mm: float) -> np.ndarray:
    """The change of the brush's location that moves it ``delta_mm`` along the paper's
    normal (in the engine's millimetres, as a sample's z)."""
    world = np.array(paper.matrix_world)[:3, :3] @ np.array([0.0, 0.0, delta_mm / bridge.MM])
    if brush.parent is None:
        return world
    parent = np.array(brush.parent.matrix_world) @ np.array(brush.matrix_parent_inverse)
    return np.linalg.solve(parent[:3, :3], world)


class HAIRY_BRUSH_OT_setup(bpy.types.Operator):
    """Add a brush empty and a paper plane whose material shows the paper image"""

    bl_idname = "hairy_brush.setup"
    bl_label = "Set Up Brush and Paper"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to set up the brush and paper")
            return False
        return True

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        try:
            bridge.check_paper_size(st)
            color = bridge.blank_color(st)
            geom_len = bridge.hair_length(st)
        except bridge.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        coll = scene.collection
        if st.paper_object is None:
            me = paper_mesh("HairyBrush Paper", st.paper_width_mm / 1000, st.paper_height_mm / 1000)
            paper = bpy.data.objects.new("HairyBrush Paper", me)
            coll.objects.link(paper)
            st.paper_object = paper
        else:
            resize_paper(st)
        img = bridge.ensure_paper_image(st, color)
        if bridge.SHOWN_TAG not in img:
            img = bridge.show_blank(st)
        mat = paper_material(img)
        if mat.name not in st.paper_object.data.materials:
            st.paper_object.data.materials.append(mat)
        if st.brush_object is None:
            brush = bpy.data.objects.new("HairyBrush Brush", None)
            brush.empty_display_type = "SINGLE_ARROW"
            brush.empty_display_size = 0.03
            brush.rotation_mode = "ZYX"  # Rx(q) Ry(d) Rz(r): X = q, Y = d, Z = r
            brush.rotation_euler = (0.0, 0.0, 0.0)  # upright: the hair hangs down -Z
            brush.parent = st.paper_object
            brush.location = (0.0, 0.0, (geom_len + HOVER_MM) / bridge.MM)
            coll.objects.link(brush)
            st.brush_object = brush
        st.touch_height_mm = geom_len
        show_hair_length(st, geom_len)
        self.report({"INFO"}, f"Paper {st.paper_object.name}, brush {st.brush_object.name}")
        return {"FINISHED"}
