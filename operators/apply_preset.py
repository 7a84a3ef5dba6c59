# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.apply_preset: choose one of the shipped JSON presets (presets/*/*.json); the
tooltip says what it overwrites, the report what it did."""

from __future__ import annotations

import bpy

from ..blender import checks, recordings
from ..blender.presets import (
    PRESET_INFO,
    QUALITY_LABELS,
    apply_ink_preset,
    apply_paper_preset,
    apply_quality_presets,
    preset_label,
)
from ..sim.core.params import ParameterError, QualityParams, load_preset
from . import polls

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

    @classmethod
    def description(cls, _context, properties):
        info = PRESET_INFO.get((properties.kind, properties.name))
        return info[1] if info else cls.__doc__.replace("\n", " ")

    @classmethod
    def poll(cls, context):
        return polls.scene(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        try:
            preset = load_preset(self.kind, self.name)
            if self.kind == "quality":
                values = QualityParams().with_values(preset.data.get("quality", {})).to_dict()
        except ParameterError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        label = preset_label(self.kind, self.name)
        if self.kind == "quality":  # only the values it names; brush and paper stay chosen
            for k in preset.data.get("quality", {}):
                setattr(st.quality, k, values[k])
            self.report({"INFO"}, f"{label}: set {_names(preset)}")
            return {"FINISHED"}
        hair_before = st.touch_height_mm
        setattr(st, PROPERTY[self.kind], self.name)
        # also when the preset was already chosen (no update then): restore its values
        if self.kind == "ink":
            apply_ink_preset(st)
            self.report({"INFO"}, f"Ink {label}: set Ink Colour, Ink Wetness and Dip Depth")
            return {"FINISHED"}
        apply_quality_presets(st, brush=self.kind == "brush", paper=self.kind == "paper")
        if self.kind == "paper":
            apply_paper_preset(st)
            self.report(
                {"INFO"}, f"Paper {label}: set colour, Ink Capacity, Fibre, {_names(preset)}"
            )
            return {"FINISHED"}
        change = _hair_change(st, hair_before) + _recording_change(context.scene)
        self.report({"INFO"}, f"Brush {label}: {change}; set {_names(preset)}")
        return {"FINISHED"}


def _names(preset) -> str:
    return ", ".join(QUALITY_LABELS[k] for k in preset.data.get("quality", {}))


def _hair_change(st, before: float) -> str:
    now = st.touch_height_mm
    text = f"hair length {now:g} mm (touches the paper at z = {now:g} mm)"
    if abs(now - before) > 1e-6 and st.brush_object is not None:
        way = "up" if now > before else "down"
        text += f", brush empty moved {way} {abs(now - before):g} mm to hover as before"
    return text


def _recording_change(scene) -> str:
    """What the new brush does to the stored recording's samples (recordings.hair_shift)."""
    st = checks.settings(scene)
    if st.recording is None:
        return ""
    try:
        stored = recordings.read_recording_dict(st)
        rec = recordings.recording_from_scene(scene)
    except checks.USER_ERRORS:
        return ""  # Simulate says what is wrong with it
    brush = stored.get("brush") if isinstance(stored.get("brush"), dict) else {}
    hair = recordings.hair_length_of(brush)
    if recordings.own_hair_length(brush):
        return f"; the recording keeps its own hair length ({hair:g} mm): its samples stay"
    shift = recordings.hair_shift(brush, rec)
    if hair is None or abs(shift) < 1e-9:
        return "; the recording's samples stay (recorded with this hair length)"
    way = "higher" if shift > 0 else "lower"
    return (
        f"; the recording's samples are placed {abs(shift):g} mm {way} than recorded (with a "
        f"{hair:g} mm brush), to press and hover as recorded"
    )
