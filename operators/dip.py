# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.dip: record a dip (depth, ink colour, wetness; Eq. 7-8) in the recording."""

from __future__ import annotations

import bpy

from ..blender import checks, frames, recordings
from ..sim.core.recording import RecordingError, from_dict
from . import polls


class HAIRY_BRUSH_OT_dip(bpy.types.Operator):
    """Dip the brush: a dip event with the sidebar's depth, ink colour and wetness"""

    bl_idname = "hairy_brush.dip"
    bl_label = "Dip Brush"
    bl_options = {"REGISTER", "UNDO"}

    at: bpy.props.EnumProperty(
        name="When",
        items=(
            ("FRAME", "Current Frame", "Before the first sample at or after the current frame"),
            (
                "END",
                "Next Painted Stroke",
                "After the last sample: before the next stroke painted live",
            ),
        ),
        default="FRAME",
        description="Where in the recording the brush is dipped",
    )

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def execute(self, context):
        scene = context.scene
        st = checks.settings(scene)
        try:
            d = recordings.read_recording_dict(st)
            rec = from_dict(d)
        except checks.UserError:
            self.report({"ERROR"}, "No recording to dip in: bake samples or paint first")
            return {"CANCELLED"}
        except RecordingError as exc:
            self.report({"ERROR"}, f"Recording '{st.recording.name}': {exc}")
            return {"CANCELLED"}
        n = len(rec.samples)
        at = (
            n
            if self.at == "END"
            else frames.first_sample_from_frame(rec, scene, scene.frame_current)
        )
        if not rec.dips:
            rec.dips = list(rec.dips_or_default())
        rec.dips = [dp for dp in rec.dips if dp.before_sample != at]
        rec.dips.append(recordings.current_dip(st, at))
        rec.dips.sort(key=lambda dp: dp.before_sample)
        recordings.store_recording(st, rec)
        if at >= n:
            self.report(
                {"WARNING"},
                f"Dip after the last of the {n} samples: it loads the brush for the next stroke "
                "painted live, and changes nothing already recorded",
            )
        else:
            self.report({"INFO"}, f"Dip before sample {at} (frame {scene.frame_current})")
        return {"FINISHED"}
