# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.apply_to_mesh: map the paper texture onto selected meshes through their UVs."""

from __future__ import annotations

import bpy

from ..blender import checks, materials
from . import polls


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
        st = checks.settings(context.scene)
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
                    o.data.materials.append(materials.new_material(f"{o.name} Material"))
                for slot in o.material_slots:
                    if slot.material is None:
                        slot.material = materials.new_material(f"{o.name} Material")
                    done += materials.add_ink(slot.material, img, uv)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Ink applied to {len(meshes)} mesh(es), {done} material(s)")
        return {"FINISHED"}
