# SPDX-License-Identifier: GPL-3.0-or-later
"""Preset menus: one for each kind of shipped preset (brush, paper, ink, fitted quality; its
button in the sidebar names the active one), and the user's own presets (Blender's preset
system: the menu's label is the preset last applied)."""

from __future__ import annotations

import bpy

from ..blender.presets import ITEMS
from ..operators.add_settings_preset import NO_PRESET_LABEL, PRESET_SUBDIR


class _ShippedPresets:
    kind = ""
    active_property = ""

    def draw(self, context):
        st = context.scene.hairy_brush
        active = getattr(st, self.active_property) if self.active_property else None
        for name, label, _tip, _i in ITEMS[self.kind]:
            icon = "CHECKMARK" if name == active else "BLANK1"
            op = self.layout.operator("hairy_brush.apply_preset", text=label, icon=icon)
            op.kind, op.name = self.kind, name


class HAIRY_BRUSH_MT_brush_presets(_ShippedPresets, bpy.types.Menu):
    bl_label = "Brush Presets"
    kind, active_property = "brush", "brush_preset"


class HAIRY_BRUSH_MT_paper_presets(_ShippedPresets, bpy.types.Menu):
    bl_label = "Paper Presets"
    kind, active_property = "paper", "paper_preset"


class HAIRY_BRUSH_MT_ink_presets(_ShippedPresets, bpy.types.Menu):
    bl_label = "Ink Presets"
    kind, active_property = "ink", "ink_preset"


class HAIRY_BRUSH_MT_quality_presets(_ShippedPresets, bpy.types.Menu):
    bl_label = "Fitted Quality"
    kind = "quality"


class HAIRY_BRUSH_MT_settings_presets(bpy.types.Menu):
    """Your own presets: brush, paper and ink choices, colours and all quality values."""

    bl_label = NO_PRESET_LABEL
    preset_subdir = PRESET_SUBDIR
    preset_operator = "script.execute_preset"
    draw = bpy.types.Menu.draw_preset


CLASSES = (
    HAIRY_BRUSH_MT_brush_presets,
    HAIRY_BRUSH_MT_paper_presets,
    HAIRY_BRUSH_MT_ink_presets,
    HAIRY_BRUSH_MT_quality_presets,
    HAIRY_BRUSH_MT_settings_presets,
)
