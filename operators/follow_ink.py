# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.follow_ink: every dip of the recording loads the scene's Ink Colour (dips given
their own colour, and those of a recording made before dips could follow the ink, keep the
colour they were recorded with until then)."""

from __future__ import annotations

import bpy

from ..blender import checks, recordings
from ..sim.core.recording import from_dict
from . import polls


class HAIRY_BRUSH_OT_follow_ink(bpy.types.Operator):
    """Make every dip of the recording load the Ink Colour (dips with their own colour, e.g. a
    second ink or an imported recording's, take it too)"""

    bl_idname = "hairy_brush.follow_ink"
    bl_label = "Use Ink Colour for All Dips"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        try:
            rec = from_dict(recordings.read_recording_dict(st))  # as stored
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, f"Recording '{st.recording.name}': {exc}")
            return {"CANCELLED"}
        own = sum(not dp.follows_ink for dp in rec.dips)
        rec.dips = recordings.following_ink(rec.dips_or_default())
        recordings.store_recording(st, rec)
        self.report({"INFO"}, f"{own} dip(s) now load the Ink Colour")
        return {"FINISHED"}
