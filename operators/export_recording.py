# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.export_recording: the scene's recording, with its current settings, to JSON."""

from __future__ import annotations

import bpy
from bpy_extras.io_utils import ExportHelper

from ..blender import checks, recordings
from . import polls


class HAIRY_BRUSH_OT_export_recording(bpy.types.Operator, ExportHelper):
    """Save the recording with the scene's settings as JSON (``python -m sim render`` reads it)"""

    bl_idname = "hairy_brush.export_recording"
    bl_label = "Export Recording"
    bl_options = {"REGISTER"}

    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def execute(self, context):
        try:
            rec = recordings.recording_from_scene(context.scene)
            rec.save(self.filepath)
        except (*checks.USER_ERRORS, OSError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Wrote {len(rec.samples)} samples to {self.filepath}")
        return {"FINISHED"}
