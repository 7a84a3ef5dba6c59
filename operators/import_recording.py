# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.import_recording: a recording JSON file into the .blend."""

from __future__ import annotations

import bpy
from bpy_extras.io_utils import ImportHelper

from ..blender import checks, recordings
from ..sim.core.recording import load
from . import polls


class HAIRY_BRUSH_OT_import_recording(bpy.types.Operator, ImportHelper):
    """Load a 6-DOF recording (the engine's JSON) into the scene; its settings fill the
    sidebar, where another preset or resolution can re-render it"""

    bl_idname = "hairy_brush.import_recording"
    bl_label = "Import Recording"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        return polls.object_mode(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        try:
            rec = load(self.filepath)
            recordings.copy_settings_from_recording(st, rec)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, f"{bpy.path.basename(self.filepath)}: {exc}")
            return {"CANCELLED"}
        st.recording = None  # a new text block: the previous recording stays in the file
        text = recordings.store_recording(st, rec)
        self.report(
            {"INFO"},
            f"Imported {len(rec.samples)} samples into '{text.name}'; paper "
            f"{rec.width_mm:g} x {rec.height_mm:g} mm, brush {st.brush_preset}",
        )
        return {"FINISHED"}
