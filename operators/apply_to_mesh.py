# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.apply_to_mesh: map the paper texture onto selected meshes through their UVs."""

from __future__ import annotations

import bpy

from .. import bridge
from . import polls

INK_NODE = "HairyBrush Ink"


def add_ink(mat, img, uv_name: str):
    """Multiply the material's base colour by the paper image read through ``uv_name``: white
    paper leaves the mesh's own shading as it was, ink darkens or tints it."""
    if mat.node_tree is None:
        mat.use_nodes = True
    nt = mat.node_tree
    if INK_NODE in nt.nodes:
        nt.nodes[INK_NODE].image = img
        return False
    bsdf = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        raise bridge.UserError(f"Material '{mat.name}' has no Principled BSDF to put ink on")
    base = bsdf.inputs["Base Color"]
    uv = nt.nodes.new("ShaderNodeUVMap")
    uv.uv_map = uv_name
    uv.location = bsdf.location.x - 900, bsdf.location.y - 200
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.name = tex.label = INK_NODE
    tex.image = img
    tex.location = bsdf.location.x - 700, bsdf.location.y - 200
    mix = nt.nodes.new("ShaderNodeMix")
    mix.data_type = "RGBA"
    mix.blend_type = "MULTIPLY"
    mix.name = mix.label = INK_NODE + " Multiply"
    mix.inputs["Factor"].default_value = 1.0
    mix.location = bsdf.location.x - 300, bsdf.location.y
    a = _socket(mix.inputs, "A_Color")
    b = _socket(mix.inputs, "B_Color")
    if base.is_linked:
        nt.links.new(base.links[0].from_socket, a)
    else:
        a.default_value = base.default_value
    nt.links.new(uv.outputs["UV"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], b)
    nt.links.new(_socket(mix.outputs, "Result_Color"), base)
    return True


def _socket(sockets, identifier):
    return next(s for s in sockets if s.identifier == identifier)


class HAIRY_BRUSH_OT_apply_to_mesh(bpy.types.Operator):
    """Put the paper's ink on the selected meshes through their active UV map, keeping each
    mesh's own material under the ink"""

    bl_idname = "hairy_brush.apply_to_mesh"
    bl_label = "Apply Ink to Selected Meshes"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.paper_image_and_meshes(cls, context)

    def execute(self, context):
        st = bridge.settings(context.scene)
        img = st.paper_image
        if img is None:
            self.report({"ERROR"}, "No paper image yet: run Setup and Simulate first")
            return {"CANCELLED"}
        meshes = polls.selected_meshes(context)
        if not meshes:
            self.report({"ERROR"}, "Select one or more meshes (other than the paper)")
            return {"CANCELLED"}
        no_uv = [o.name for o in meshes if not o.data.uv_layers]
        meshes = [o for o in meshes if o.data.uv_layers]
        if not meshes:
            names = ", ".join(f"'{n}'" for n in no_uv)
            self.report({"ERROR"}, f"{names} has no UV map: unwrap it first")
            return {"CANCELLED"}
        if no_uv:
            names = ", ".join(f"'{n}'" for n in no_uv)
            self.report({"WARNING"}, f"Skipped {names}: no UV map (unwrap it, then apply again)")
        done = 0
        try:
            for o in meshes:
                uv = o.data.uv_layers.active.name
                if not o.data.materials:
                    o.data.materials.append(bpy.data.materials.new(f"{o.name} Material"))
                for slot in o.material_slots:
                    if slot.material is None:
                        slot.material = bpy.data.materials.new(f"{o.name} Material")
                    done += add_ink(slot.material, img, uv)
        except bridge.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Ink applied to {len(meshes)} mesh(es), {done} material(s)")
        return {"FINISHED"}
