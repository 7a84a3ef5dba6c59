# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.add_settings_preset: Blender's preset system for the user's own settings.

A preset is a Python file Blender runs when it is chosen; it is written here from the settings
as data (issue 30): every value checked and turned into a literal by ``preset_literal`` (a NaN
setting is refused by name, never written as ``nan``, which fails when the preset is applied),
and the file written whole or not at all (``write_atomic``)."""

from __future__ import annotations

import json
import os

import bpy
from bl_operators.presets import AddPresetBase

from ..blender import checks
from ..sim.core.files import write_atomic
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
        "st.paper_texture",
        "st.ink_color",
        "st.dip_wetness",
        "st.dip_depth",
        *(f"st.quality.{name}" for name in QualityParams.names()),
    ]

    @classmethod
    def poll(cls, context):
        return polls.scene(cls, context)

    def add(self, context, filepath):
        """Called by AddPresetBase.execute in place of its own writer (which uses repr)."""
        write_settings_preset(checks.settings(context.scene), filepath)

    def execute(self, context):
        if not (self.remove_active or self.remove_name):
            try:
                checks.check_settings(checks.settings(context.scene))
            except checks.USER_ERRORS as exc:
                self.report({"ERROR"}, f"Preset not saved: {exc}")
                return {"CANCELLED"}
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


def preset_literal(value) -> str:
    """A Python literal for a setting's value: a number, a name or a colour, from data; a value
    that is not a finite number raises ValueError."""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, (int, float, str)):
        return json.dumps(value, allow_nan=False)  # a Python literal too, for these types
    return "(" + ", ".join(preset_literal(v) for v in value) + ",)"


def settings_preset_text(st) -> str:
    """The preset file for the settings ``st`` (the lines Blender's own writer would make)."""
    lines = ["import bpy", *HAIRY_BRUSH_OT_add_settings_preset.preset_defines, ""]
    for path in HAIRY_BRUSH_OT_add_settings_preset.preset_values:
        value = st
        for attr in path.split(".")[1:]:  # "st.quality.e" -> st.quality.e
            value = getattr(value, attr)
        if not isinstance(value, (bool, int, float, str)):
            value = tuple(value)
        lines.append(f"{path} = {preset_literal(value)}")
    return "\n".join(lines) + "\n"


def write_settings_preset(st, path) -> str:
    """Check the settings and write them as a preset file at ``path``, whole or not at all."""
    checks.check_settings(st)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    write_atomic(path, settings_preset_text(st))
    return path
