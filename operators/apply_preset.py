# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.apply_preset: choose one of the shipped JSON presets (presets/*/*.json)."""

from __future__ import annotations

import bpy

from .. import bridge
from ..properties import apply_ink_preset, apply_quality_presets
from ..sim.params import ParameterError, QualityParams, load_preset

PROPERTY = {"brush": "brush_preset", "paper": "paper_preset", "ink": "ink_preset"}


class HAIRY_BRUSH_OT_apply_preset(bpy.types.Operator):
    """Use a shipped brush, paper, ink or fitted-quality preset (its quality parameters and
    colours)"""

    bl_idname = "hairy_brush.apply_preset"
    bl_label = "Apply Preset"
    bl_options = {"REGISTER", "UNDO"}

    kind: bpy.props.EnumProperty(
        items=(
            ("brush", "Brush", ""),
            ("paper", "Paper", ""),
            ("ink", "Ink", ""),
            ("quality", "Quality", "Quality values fitted by sim fit (Sec. 7.2)"),
        )
    )
    name: bpy.props.StringProperty()

    def execute(self, context):
        st = bridge.settings(context.scene)
        try:
            preset = load_preset(self.kind, self.name)
            if self.kind == "quality":
                values = QualityParams().with_values(preset.data.get("quality", {})).to_dict()
        except ParameterError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        if self.kind == "quality":  # only the values it names; brush and paper stay chosen
            for k in preset.data.get("quality", {}):
                setattr(st.quality, k, values[k])
            return {"FINISHED"}
        setattr(st, PROPERTY[self.kind], self.name)
        # also when the preset was already chosen (no update then): restore its values
        if self.kind == "ink":
            apply_ink_preset(st)
        else:
            apply_quality_presets(st, brush=self.kind == "brush", paper=self.kind == "paper")
        return {"FINISHED"}
