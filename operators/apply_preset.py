# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.apply_preset: choose one of the shipped JSON presets (presets/*/*.json)."""

from __future__ import annotations

import bpy

from .. import bridge
from ..properties import apply_ink_preset, apply_quality_presets
from ..sim.params import ParameterError, load_preset

PROPERTY = {"brush": "brush_preset", "paper": "paper_preset", "ink": "ink_preset"}


class HAIRY_BRUSH_OT_apply_preset(bpy.types.Operator):
    """Use a shipped brush, paper or ink preset (its quality parameters and colours)"""

    bl_idname = "hairy_brush.apply_preset"
    bl_label = "Apply Preset"
    bl_options = {"REGISTER", "UNDO"}

    kind: bpy.props.EnumProperty(
        items=(("brush", "Brush", ""), ("paper", "Paper", ""), ("ink", "Ink", ""))
    )
    name: bpy.props.StringProperty()

    def execute(self, context):
        st = bridge.settings(context.scene)
        try:
            load_preset(self.kind, self.name)
        except ParameterError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        setattr(st, PROPERTY[self.kind], self.name)
        # also when the preset was already chosen (no update then): restore its values
        if self.kind == "ink":
            apply_ink_preset(st)
        else:
            apply_quality_presets(st, brush=self.kind == "brush", paper=self.kind == "paper")
        return {"FINISHED"}
