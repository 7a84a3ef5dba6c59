# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.dip: record a dip (depth, ink colour, wetness; Eq. 7-8) in the recording. The
dip loads the scene's Ink Colour, now and after any change of it, or keeps its own colour (a
second ink: a seal's vermilion, a signature in another ink)."""

from __future__ import annotations

import bpy

from ..blender import checks, frames, recordings
from ..sim.core.recording import RecordingError, from_dict
from . import polls


class HAIRY_BRUSH_OT_dip(bpy.types.Operator):
    """Dip the brush: a dip event with the sidebar's depth and wetness that loads the Ink
    Colour (or, with Own Colour, a colour of its own that a new Ink Colour leaves alone)"""

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
    own_color: bpy.props.BoolProperty(
        name="Own Colour",
        default=False,
        description="A second ink: the dip keeps Colour whatever Ink Colour becomes; off: it "
        "loads the Ink Colour, and a new Ink Colour recolours it",
    )
    color: bpy.props.FloatVectorProperty(
        name="Colour",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=(0.82, 0.16, 0.09),
        description="The dip's own colour (with Own Colour)",
    )

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def invoke(self, context, _event):
        if self.own_color:  # choose the colour first
            return context.window_manager.invoke_props_dialog(self)
        return self.execute(context)

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
        rec.dips.append(recordings.current_dip(st, at, self.color if self.own_color else None))
        rec.dips.sort(key=lambda dp: dp.before_sample)
        recordings.store_recording(st, rec)
        ink = "its own colour" if self.own_color else "the Ink Colour"
        if at >= n:
            self.report(
                {"WARNING"},
                f"Dip in {ink} after the last of the {n} samples: it loads the brush for the "
                "next stroke painted live, and changes nothing already recorded",
            )
        else:
            self.report({"INFO"}, f"Dip in {ink} before sample {at} (frame {scene.frame_current})")
        return {"FINISHED"}
