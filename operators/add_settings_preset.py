# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.add_settings_preset: Blender's preset system for the user's own settings."""

from __future__ import annotations

import bpy
from bl_operators.presets import AddPresetBase

from ..sim.params import QualityParams

PRESET_SUBDIR = "hairy_brush/settings"


class HAIRY_BRUSH_OT_add_settings_preset(AddPresetBase, bpy.types.Operator):
    """Save the brush, paper, ink and quality settings as a preset of your own (or remove one)"""

    bl_idname = "hairy_brush.add_settings_preset"
    bl_label = "Add Hairy Brush Preset"
    preset_menu = "HAIRY_BRUSH_MT_settings_presets"
    preset_subdir = PRESET_SUBDIR
    preset_defines = ["st = bpy.context.scene.hairy_brush"]
    # the preset choices first: choosing one resets quality values, which follow
    preset_values = [
        "st.brush_preset",
        "st.paper_preset",
        "st.ink_preset",
        "st.ink_color",
        "st.dip_wetness",
        "st.dip_depth",
        *(f"st.quality.{name}" for name in QualityParams.names()),
    ]
