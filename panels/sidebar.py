# SPDX-License-Identifier: GPL-3.0-or-later
"""View3D > Sidebar > Brush, in the order of the work: paper, brush, ink, write and paint,
animation (with the recording), quality. Each setting sits beside the button that uses it.
Nothing here reads a file or parses the recording: a draw runs on every redraw."""

from __future__ import annotations

import bpy

from ..blender import checks, primitives, recordings, surfaces, transforms
from ..blender.presets import HAIR_LENGTH_MM, QUALITY_GROUPS, preset_label


class _Panel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Brush"


def _preset_menu(layout, st, kind: str, text: str):
    row = layout.row(align=True)
    row.label(text=text)
    row.menu(
        f"HAIRY_BRUSH_MT_{kind}_presets", text=preset_label(kind, getattr(st, f"{kind}_preset"))
    )


class HAIRY_BRUSH_PT_paper(_Panel, bpy.types.Panel):
    bl_label = "Paper"
    bl_order = 0

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        _preset_menu(layout, st, "paper", "Paper")
        col = layout.column(align=True)
        col.prop(st, "paper_width_mm")
        col.prop(st, "paper_height_mm")
        col.prop(st, "px_per_mm")
        w, h = checks.paper_pixels(st)
        layout.label(text=f"Image {w} x {h} px", icon="IMAGE_DATA")
        if surfaces.is_surface(st):  # Width and Height are the texture's, in the mesh's mm
            layout.label(
                text=f"Writing on the surface of '{st.paper_object.name}'", icon="MESH_DATA"
            )
        col = layout.column(align=True)
        col.prop(st, "paper_color")
        col.prop(st, "paper_capacity")
        col.prop(st, "paper_fibre")
        col.prop(st, "paper_texture")
        layout.operator("hairy_brush.setup", icon="ADD")
        layout.operator(
            "hairy_brush.setup", text="Write on Selected Mesh", icon="MESH_UVSPHERE"
        ).surface = True
        col = layout.column(align=True)
        col.prop(st, "paper_object")
        col.prop(st, "paper_image")


class HAIRY_BRUSH_PT_brush(_Panel, bpy.types.Panel):
    bl_label = "Brush"
    bl_order = 1

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        _preset_menu(layout, st, "brush", "Brush")
        layout.prop(st, "brush_object")
        hair = HAIR_LENGTH_MM.get(st.brush_preset, st.touch_height_mm)
        layout.label(
            text=f"Touches the paper at z = {hair:g} mm (hair length)", icon="EMPTY_SINGLE_ARROW"
        )
        z = _brush_height(st)
        if z is not None:
            where = "above" if z >= hair else "pressed into"
            layout.label(text=f"Base now at z = {z:.1f} mm: {abs(z - hair):.1f} mm {where} it")


def _brush_height(st):
    """The brush base's height above the paper (mm), or None without brush and paper."""
    if st.brush_object is None or st.paper_object is None:
        return None
    try:
        s = transforms.sample_from_matrices(
            st, st.brush_object.matrix_world, st.paper_object.matrix_world
        )
    except checks.USER_ERRORS:
        return None
    return float(s[2])


class HAIRY_BRUSH_PT_ink(_Panel, bpy.types.Panel):
    bl_label = "Ink"
    bl_order = 2

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        _preset_menu(layout, st, "ink", "Ink")
        col = layout.column(align=True)
        col.prop(st, "ink_color")
        col.prop(st, "dip_wetness", slider=True)
        col.prop(st, "dip_depth", slider=True)
        col = layout.column(align=True)
        col.operator("hairy_brush.dip", text="Dip Brush at Current Frame", icon="MOD_FLUIDSIM")
        op = col.operator("hairy_brush.dip", text="Dip in Own Colour...", icon="COLOR")
        op.own_color = True
        text = st.recording
        if text is None:
            return
        # dips stored before dips could follow the ink kept the colour they were recorded with
        own = text.get(recordings.OWN_COLOR_TAG, text.get(recordings.DIPS_TAG))
        if own:
            layout.label(text=f"{own} dip(s) keep their own colour;", icon="INFO")
            layout.label(text="Ink Colour recolours the others")
            layout.operator("hairy_brush.follow_ink", icon="COLOR")
        elif own == 0:
            layout.label(text="Ink Colour recolours the whole recording", icon="INFO")


class HAIRY_BRUSH_PT_write(_Panel, bpy.types.Panel):
    bl_label = "Write and Paint"
    bl_order = 3

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        col = layout.column(align=True)
        col.prop(st, "paint_press_mm")
        col.prop(st, "paint_angle_step")
        col.operator("hairy_brush.paint", icon="GREASEPENCIL")
        layout.operator("hairy_brush.write_character", icon="FONT_DATA")
        layout.operator("hairy_brush.imitate_image", icon="IMAGE_DATA")


class HAIRY_BRUSH_PT_write_text(_Panel, bpy.types.Panel):
    """Write Text (issue 27): the text, a new work's layout, the signature and seal, one cell
    written again. What it shows of the work comes from tags on the recording text."""

    bl_label = "Write Text"
    bl_parent_id = "HAIRY_BRUSH_PT_write"

    def draw(self, context):
        st = context.scene.hairy_brush
        w = st.work
        layout = self.layout
        layout.prop(w, "text", text="")
        text = st.recording
        chars = text.get(recordings.WORK_TAG) if text is not None else None
        signed = bool(text.get(recordings.SIGNED_TAG)) if text is not None else False
        if chars is None:  # a new work: how it is laid out
            if text is not None:
                layout.label(text="The recording is not a work: clear it to start one", icon="INFO")
            layout.row(align=True).prop(w, "direction", expand=True)
            col = layout.column(align=True)
            per = "Per Column" if w.direction == "vertical" else "Per Row"
            col.prop(w, "per_line", text=f"Characters {per}")
            col.prop(w, "char_mm")
            layout.prop(w, "grid")
        elif signed:
            layout.label(text=f"A signed work of {len(chars)} cells", icon="INFO")
        else:
            layout.label(text=f"Goes on after {chars[-1:]} ({len(chars)} cells)", icon="INFO")
            layout.prop(w, "new_line")
        op = layout.operator("hairy_brush.write_text", icon="FONT_DATA")
        op.text = w.text
        op.new_line = bool(chars) and w.new_line
        col = layout.column(align=True)
        col.prop(w, "signature")
        row = col.row(align=True)
        row.prop(w, "seal")
        row.prop(w, "seal_style", text="")
        col.operator("hairy_brush.sign_work", icon="OUTLINER_OB_FONT")
        if chars:
            row = layout.row(align=True)
            row.prop(w, "cell")
            row.label(text=chars[min(w.cell, len(chars)) - 1])
            row.operator("hairy_brush.rewrite_cell", text="Write Again").index = (
                min(w.cell, len(chars)) - 1
            )
            op = layout.operator(
                "hairy_brush.rewrite_cell", text="Write Cell under 3D Cursor", icon="PIVOT_CURSOR"
            )
            op.index = -1


class HAIRY_BRUSH_PT_write_text_options(_Panel, bpy.types.Panel):
    bl_label = "How the Characters Are Written"
    bl_parent_id = "HAIRY_BRUSH_PT_write_text"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        w = context.scene.hairy_brush.work
        layout = self.layout
        col = layout.column(align=True)
        col.prop(w, "passes")
        col.prop(w, "variation", slider=True)
        layout.prop(w, "fit_brush")
        layout.prop(w, "punctuation")
        layout.prop(w, "skip_missing")
        layout.prop(w, "data_path")


class HAIRY_BRUSH_PT_animation(_Panel, bpy.types.Panel):
    bl_label = "Animation"
    bl_order = 4

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        col = layout.column(align=True)
        col.prop(st, "sample_rate_hz")
        col.prop(st, "seed")
        if st.seed_of_recording:
            col.label(text=f"Recording's seed {st.seed_of_recording} (change Seed to replace)")
        col.operator("hairy_brush.bake_samples", icon="KEYINGSET")
        layout.operator("hairy_brush.simulate", icon="BRUSH_DATA")
        layout.prop(st, "sync_frames")
        layout.operator("hairy_brush.build_primitives", icon="SURFACE_NSURFACE")
        coll = primitives.primitive_collection()
        if coll is not None:  # a viewport aid, hidden from final renders unless asked
            layout.prop(coll, "hide_render", text="Primitives in Renders", invert_checkbox=True)
        col = layout.column(align=True)
        col.prop(st, "sequence_dir")
        col.operator("hairy_brush.bake_sequence", icon="RENDER_ANIMATION")
        col.operator("hairy_brush.bake_cache", icon="DISK_DRIVE")
        layout.operator("hairy_brush.apply_to_mesh", icon="MATERIAL")
        row = layout.row(align=True)
        op = row.operator("hairy_brush.relief", text="Carve", icon="MOD_DISPLACE")
        op.mode = "CARVE"
        op = row.operator("hairy_brush.relief", text="Emboss")
        op.mode = "EMBOSS"


class HAIRY_BRUSH_PT_recording(_Panel, bpy.types.Panel):
    bl_label = "Recording"
    bl_parent_id = "HAIRY_BRUSH_PT_animation"

    def draw(self, context):
        st = context.scene.hairy_brush
        layout = self.layout
        layout.prop(st, "recording")
        text = st.recording
        if text is not None:
            n = text.get(recordings.SAMPLES_TAG)
            if n is None:
                layout.label(text="Not counted: stored outside the extension", icon="INFO")
            else:
                layout.label(text=f"{n} samples, {text.get(recordings.DIPS_TAG, 0)} dips")
            scale = text.get(recordings.SCALE_TAG)
            if scale is not None:
                layout.label(text=f"Brush {scale:g} times its size, for the writing's")
            hair, now = text.get(recordings.HAIR_TAG), HAIR_LENGTH_MM.get(st.brush_preset)
            if now is not None and scale is not None:  # the brush chosen, as large
                now *= scale
            if hair is not None and now is not None and abs(now - hair) > 1e-6:
                layout.label(
                    text=f"Recorded with {hair:g} mm hair: placed {now - hair:+g} mm", icon="INFO"
                )
        row = layout.row(align=True)
        row.operator("hairy_brush.import_recording", icon="IMPORT")
        row.operator("hairy_brush.export_recording", icon="EXPORT")
        layout.operator("hairy_brush.open_example", icon="FILE_BLEND")


class HAIRY_BRUSH_PT_export(_Panel, bpy.types.Panel):
    """The writing out of Blender (issue 29.4): the ink matte, prints, the outline as SVG, the
    recording as Grease Pencil strokes."""

    bl_label = "Export"
    bl_parent_id = "HAIRY_BRUSH_PT_animation"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        col = layout.column(align=True)
        col.operator("hairy_brush.ink_matte", icon="IMAGE_RGB_ALPHA")
        op = col.operator(
            "hairy_brush.bake_sequence", text="Bake Paper and Ink Matte", icon="RENDER_ANIMATION"
        )
        op.content = "BOTH"
        col = layout.column(align=True)
        col.operator("hairy_brush.export_image", icon="IMAGE_DATA")
        col.operator("hairy_brush.export_svg", icon="OUTLINER_OB_CURVE")
        layout.operator("hairy_brush.export_grease_pencil", icon="OUTLINER_OB_GREASEPENCIL")


class HAIRY_BRUSH_PT_quality(_Panel, bpy.types.Panel):
    bl_label = "Quality"
    bl_order = 5

    def draw(self, context):
        st = context.scene.hairy_brush
        q = st.quality
        layout = self.layout
        row = layout.row(align=True)
        row.menu(
            "HAIRY_BRUSH_MT_settings_presets",
            text=bpy.types.HAIRY_BRUSH_MT_settings_presets.bl_label,
        )
        row.operator("hairy_brush.add_settings_preset", text="", icon="ADD")
        op = row.operator("hairy_brush.add_settings_preset", text="", icon="REMOVE")
        op.remove_active = True
        layout.menu("HAIRY_BRUSH_MT_quality_presets", icon="PRESET")
        for title, icon, names in QUALITY_GROUPS:
            col = layout.column(align=True)
            col.label(text=title, icon=icon)
            for name in names:
                col.prop(q, name, slider=True)
        layout.operator("hairy_brush.fit_parameters", icon="DRIVER_DISTANCE")


CLASSES = (
    HAIRY_BRUSH_PT_paper,
    HAIRY_BRUSH_PT_brush,
    HAIRY_BRUSH_PT_ink,
    HAIRY_BRUSH_PT_write,
    HAIRY_BRUSH_PT_write_text,
    HAIRY_BRUSH_PT_write_text_options,
    HAIRY_BRUSH_PT_animation,
    HAIRY_BRUSH_PT_recording,
    HAIRY_BRUSH_PT_quality,
    HAIRY_BRUSH_PT_export,
)
