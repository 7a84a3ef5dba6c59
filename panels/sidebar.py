# SPDX-License-Identifier: GPL-3.0-or-later
"""View3D > Sidebar > Brush: set-up, brush, ink, paper, quality parameters, recording,
animation."""

from __future__ import annotations

import json

import bpy

from ..sim.params import QP1, QP2


class _Panel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Brush"


class HAIRY_BRUSH_PT_main(_Panel, bpy.types.Panel):
    bl_label = "Virtual Hairy Brush"

    def draw(self, context):
        st = context.scene.hairy_brush
        col = self.layout.column(align=True)
        col.operator("hairy_brush.setup", icon="ADD")
        col.prop(st, "brush_object")
        col.prop(st, "paper_object")
        col.prop(st, "paper_image")
        col = self.layout.column(align=True)
        col.operator("hairy_brush.bake_samples", icon="KEYINGSET")
        col.operator("hairy_brush.simulate", icon="BRUSH_DATA")
        col.operator("hairy_brush.paint", icon="GREASEPENCIL")
        col.operator("hairy_brush.dip", icon="MOD_FLUIDSIM")
        col.operator("hairy_brush.build_primitives", icon="SURFACE_NSURFACE")
        col.operator("hairy_brush.write_character", icon="FONT_DATA")


class HAIRY_BRUSH_PT_brush(_Panel, bpy.types.Panel):
    bl_label = "Brush"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "brush_preset")
        layout.prop(st, "sample_rate_hz")
        layout.prop(st, "seed")
        box = layout.box()
        box.label(text="Live Painting")
        box.prop(st, "paint_press_mm")
        box.prop(st, "paint_angle_step")


class HAIRY_BRUSH_PT_ink(_Panel, bpy.types.Panel):
    bl_label = "Ink"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "ink_preset")
        layout.prop(st, "ink_color")
        layout.prop(st, "dip_wetness")
        layout.prop(st, "dip_depth")


class HAIRY_BRUSH_PT_paper(_Panel, bpy.types.Panel):
    bl_label = "Paper"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "paper_preset")
        col = layout.column(align=True)
        col.prop(st, "paper_width_mm")
        col.prop(st, "paper_height_mm")
        col.prop(st, "px_per_mm")
        w = round(st.paper_width_mm * st.px_per_mm)
        h = round(st.paper_height_mm * st.px_per_mm)
        layout.label(text=f"{w} x {h} px", icon="IMAGE_DATA")


class HAIRY_BRUSH_PT_quality(_Panel, bpy.types.Panel):
    bl_label = "Quality Parameters"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        q = context.scene.hairy_brush.quality
        layout = self.layout
        row = layout.row(align=True)
        row.menu("HAIRY_BRUSH_MT_settings_presets", text="Presets")
        row.operator("hairy_brush.add_settings_preset", text="", icon="ADD")
        op = row.operator("hairy_brush.add_settings_preset", text="", icon="REMOVE")
        op.remove_active = True
        for title, names in (("Shape (Qp1)", QP1), ("Texture (Qp2)", QP2)):
            col = layout.column(align=True)
            col.label(text=title)
            for name in names:
                col.prop(q, name, slider=True)
        layout.operator("hairy_brush.fit_parameters", icon="DRIVER_DISTANCE")


class HAIRY_BRUSH_PT_recording(_Panel, bpy.types.Panel):
    bl_label = "Recording"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "recording")
        if st.recording is not None:
            try:
                d = json.loads(st.recording.as_string())
                layout.label(
                    text=f"{len(d.get('samples', []))} samples, {len(d.get('dips', []))} dips"
                )
            except (json.JSONDecodeError, AttributeError):
                layout.label(text="Not a valid recording", icon="ERROR")
        row = layout.row(align=True)
        row.operator("hairy_brush.import_recording", icon="IMPORT")
        row.operator("hairy_brush.export_recording", icon="EXPORT")


class HAIRY_BRUSH_PT_animation(_Panel, bpy.types.Panel):
    bl_label = "Animation and Surfaces"
    bl_parent_id = "HAIRY_BRUSH_PT_main"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "sync_frames")
        layout.prop(st, "sequence_dir")
        layout.operator("hairy_brush.bake_sequence", icon="RENDER_ANIMATION")
        layout.operator("hairy_brush.apply_to_mesh", icon="MATERIAL")


CLASSES = (
    HAIRY_BRUSH_PT_main,
    HAIRY_BRUSH_PT_brush,
    HAIRY_BRUSH_PT_ink,
    HAIRY_BRUSH_PT_paper,
    HAIRY_BRUSH_PT_quality,
    HAIRY_BRUSH_PT_recording,
    HAIRY_BRUSH_PT_animation,
)
