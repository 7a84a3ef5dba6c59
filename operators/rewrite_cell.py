# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.rewrite_cell: write one cell of a work again with another seed (issue 27), for
an artist who dislikes one character: its strokes and the brush's keys there are replaced,
every other cell's ink and keys stay (later keys move only when the new writing takes longer).
The cell is chosen by its number or by the 3D cursor on it. A modal job from the sidebar."""

from __future__ import annotations

import bpy

from ..blender import checks, work
from ..blender.jobs import JobOperator
from . import polls


class HAIRY_BRUSH_OT_rewrite_cell(JobOperator, bpy.types.Operator):
    """Write one character of the work again (another seed: its own variation and brush),
    leaving every other character as it is"""

    bl_idname = "hairy_brush.rewrite_cell"
    bl_label = "Write Cell Again"
    bl_options = {"REGISTER", "UNDO"}

    index: bpy.props.IntProperty(
        name="Cell",
        default=-1,
        min=-1,
        description="The cell to write again, in writing order from 0; -1: the cell under the "
        "3D cursor",
    )
    seed: bpy.props.IntProperty(
        name="Seed",
        default=-1,
        min=-1,
        description="The cell's new seed; -1: one no cell of the work has",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context) and polls.recording(cls, context)

    def execute(self, context):
        scene = context.scene
        try:
            checks.require_brush_and_paper(checks.settings(scene))
            index = self.index
            if index < 0:
                _, lay = work.scene_work(scene)
                index = work.cell_at(scene, lay, scene.cursor.location) if lay else None
                if index is None:
                    raise checks.UserError(
                        "The 3D cursor is not on a cell of the work: place it on the character "
                        "to write again (or give the cell's number)"
                    )
            job = work.rewrite_job(scene, index, None if self.seed < 0 else self.seed)
        except (*checks.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(work.user_error(exc)))
            return {"CANCELLED"}
        return self.run_job(context, job)
