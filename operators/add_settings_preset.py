# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.add_settings_preset: Blender's preset system for the user's own settings."""

from __future__ import annotations

import bpy
from bl_operators.presets import AddPresetBase

from ..sim.core.params import QualityParams
from . import polls

PRESET_SUBDIR = "hairy_brush/settings"
NO_PRESET_LABEL = "Your Presets"  # the menu's label while none of the user's presets is active


class HAIRY_BRUSH_OT_add_settings_preset(AddPresetBase, bpy.types.Operator):
    """Save the brush, paper, ink and quality settings as a preset of your own (or remove the
    active one of yours)"""

    bl_idname = "hairy_brush.add_settings_preset"
    bl_label = "Add Hairy Brush Preset"
    preset_menu = "HAIRY_BRUSH_MT_settings_presets"
    preset_subdir = PRESET_SUBDIR
    preset_defines = ["st = bpy.context.scene.hairy_brush"]
    # the preset choices first: choosing one resets quality values and colours, which follow
    preset_values = [
        "st.brush_preset",
        "st.paper_preset",
        "st.ink_preset",
        "st.paper_color",
        "st.paper_capacity",
        "st.paper_fibre",
        "st.ink_color",
        "st.dip_wetness",
        "st.dip_depth",
        *(f"st.quality.{name}" for name in QualityParams.names()),
    ]

    @classmethod
    def poll(cls, context):
        return polls.scene(cls, context)

    def execute(self, context):
        if self.remove_active:
            label = getattr(bpy.types, self.preset_menu).bl_label
            if not bpy.utils.preset_find(label, self.preset_subdir, display_name=True):
                self.report(
                    {"WARNING"},
                    f"'{label}' is not one of your presets: choose one of yours in the menu, "
                    "then remove it (shipped presets cannot be removed)",
                )
                return {"CANCELLED"}
        result = super().execute(context)
        menu = getattr(bpy.types, self.preset_menu)
        if self.remove_active or self.remove_name:  # Blender leaves "Presets": say whose
            if not bpy.utils.preset_find(menu.bl_label, self.preset_subdir, display_name=True):
                menu.bl_label = NO_PRESET_LABEL
        return result
