# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.dip: record a dip (depth, ink colour, wetness; Eq. 7-8) in the recording."""

from __future__ import annotations

import bpy

from .. import bridge
from ..sim.recording import RecordingError, from_dict


class HAIRY_BRUSH_OT_dip(bpy.types.Operator):
    """Dip the brush: a dip event with the sidebar's depth, ink colour and wetness"""

    bl_idname = "hairy_brush.dip"
    bl_label = "Dip Brush"
    bl_options = {"REGISTER", "UNDO"}

    at: bpy.props.EnumProperty(
        name="When",
        items=(
            ("END", "Next Stroke", "Before the next sample painted or appended"),
            ("FRAME", "Current Frame", "Before the first sample at or after the current frame"),
        ),
        default="END",
    )

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        try:
            d = bridge.read_recording_dict(st)
            rec = from_dict(d)
        except bridge.UserError:
            self.report({"ERROR"}, "No recording to dip in: bake samples or paint first")
            return {"CANCELLED"}
        except RecordingError as exc:
            self.report({"ERROR"}, f"Recording '{st.recording.name}': {exc}")
            return {"CANCELLED"}
        n = len(rec.samples)
        at = (
            n
            if self.at == "END"
            else bridge.first_sample_from_frame(rec, scene, scene.frame_current)
        )
        if not rec.dips:
            rec.dips = list(rec.dips_or_default())
        rec.dips = [dp for dp in rec.dips if dp.before_sample != at]
        rec.dips.append(bridge.current_dip(st, at))
        rec.dips.sort(key=lambda dp: dp.before_sample)
        bridge.store_recording(st, rec)
        self.report({"INFO"}, f"Dip before sample {at}")
        return {"FINISHED"}
