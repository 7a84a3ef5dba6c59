# SPDX-License-Identifier: GPL-3.0-or-later
"""The preset menu: the shipped JSON presets, then the user's own (Blender's preset system)."""

from __future__ import annotations

import bpy

from ..operators.add_settings_preset import PRESET_SUBDIR
from ..sim.params import load_preset, preset_names


class HAIRY_BRUSH_MT_settings_presets(bpy.types.Menu):
    bl_label = "Hairy Brush Presets"
    preset_subdir = PRESET_SUBDIR
    preset_operator = "script.execute_preset"

    def draw(self, context):
        layout = self.layout
        for kind, title in (
            ("brush", "Brushes"),
            ("paper", "Papers"),
            ("ink", "Inks"),
            ("quality", "Fitted Quality"),
        ):
            layout.label(text=title)
            for name in preset_names(kind):
                op = layout.operator("hairy_brush.apply_preset", text=load_preset(kind, name).label)
                op.kind, op.name = kind, name
            layout.separator()
        layout.label(text="Your Presets")
        bpy.types.Menu.draw_preset(self, context)


CLASSES = (HAIRY_BRUSH_MT_settings_presets,)
