# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.write_text: write a text with the brush as a calligrapher writes a work (issue
27): on an empty recording the work is laid out on the paper from its corner (the sidebar's
layout, characters per column, size and grid); on a work the text goes on after its last
character (or in a new column), the earlier strokes, the paper and the brush's earlier keys
kept. The brush empty is keyed so playback writes the whole work in order. From the sidebar a
modal job (Esc stops it; the scene changes only at the end, so undo takes back one call)."""

from __future__ import annotations

import bpy

from ..blender import checks, work
from ..blender.jobs import JobOperator
from . import polls


class HAIRY_BRUSH_OT_write_text(JobOperator, bpy.types.Operator):
    """Write the text with the brush: a new work laid out on the paper, or more text after the
    last character of the work; the brush is keyframed so the work plays as animation"""

    bl_idname = "hairy_brush.write_text"
    bl_label = "Write Text"
    bl_options = {"REGISTER", "UNDO"}

    text: bpy.props.StringProperty(
        name="Text",
        default="",
        description="The characters to write (a line break starts a new column or row); "
        "empty: the sidebar's Text",
    )
    new_line: bpy.props.BoolProperty(
        name="New Column",
        default=False,
        description="On a work, start a new column (row) instead of going on in the last one",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def execute(self, context):
        scene = context.scene
        try:
            checks.require_brush_and_paper(checks.settings(scene))
            text = self.text or checks.settings(scene).work.text
            if not text.strip():
                raise checks.UserError("Type the text to write first (Write Text > Text)")
            job = work.write_job(scene, text, self.new_line)
        except (*checks.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(work.user_error(exc)))
            return {"CANCELLED"}
        return self.run_job(context, job)
