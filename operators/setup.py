# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.setup: a brush empty, a paper plane textured with the paper image, the settings."""

from __future__ import annotations

import bpy

from .. import bridge
from ..sim.live import HOVER_MM
from ..sim.params import load_preset, paper_from_preset

PAPER_MATERIAL = "HairyBrush Paper"


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
    """Make the paper plane match the paper size in the settings."""
    obj = st.paper_object
    if obj is None:
        return
    w, h = st.paper_width_mm / bridge.MM, st.paper_height_mm / bridge.MM
    xs = [v.co.x for v in obj.data.vertices]
    ys = [v.co.y for v in obj.data.vertices]
    if abs((max(xs) - min(xs)) - w) > 1e-6 or abs((max(ys) - min(ys)) - h) > 1e-6:
        old = obj.data
        obj.data = paper_mesh(old.name, w, h)
        for m in old.materials:
            obj.data.materials.append(m)
        if old.users == 0:
            bpy.data.meshes.remove(old)


class HAIRY_BRUSH_OT_setup(bpy.types.Operator):
    """Add a brush empty and a paper plane whose material shows the paper image"""

    bl_idname = "hairy_brush.setup"
    bl_label = "Set Up Brush and Paper"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        try:
            bridge.check_paper_size(st)
            color = paper_from_preset(load_preset("paper", st.paper_preset)).color
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
        self.report({"INFO"}, f"Paper {st.paper_object.name}, brush {st.brush_object.name}")
        return {"FINISHED"}
