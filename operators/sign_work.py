# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.sign_work: sign and seal a work written with Write Text (issue 27): the
signature (落款) after its text, in its own column (row), and the seal stamped after it, as
``sim compose`` places them; the earlier strokes and keys kept. A modal job from the sidebar."""

from __future__ import annotations

import bpy

from ..blender import checks, work
from ..blender.jobs import JobOperator
from . import polls


class HAIRY_BRUSH_OT_sign_work(JobOperator, bpy.types.Operator):
    """Sign the work with the sidebar's signature and stamp its seal after it (no text goes
    after them)"""

    bl_idname = "hairy_brush.sign_work"
    bl_label = "Sign and Seal"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context) and polls.recording(cls, context)

    def execute(self, context):
        scene = context.scene
        w = checks.settings(scene).work
        try:
            checks.require_brush_and_paper(checks.settings(scene))
            job = work.sign_job(scene, w.signature, w.seal, w.seal_style)
        except (*checks.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(work.user_error(exc)))
            return {"CANCELLED"}
        return self.run_job(context, job)
