# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.write_character: write a character from stroke data (hanzi-writer-data files or
Make Me a Hanzi's graphics.txt) with the brush, and keyframe the brush empty along the
trajectory: press from the outline's width through the brush's calibrated response. From the
sidebar the writing runs as a modal job (Esc stops it; the scene changes only at the end).

On a surface paper (issue 17) the writing is laid on the surface around the point under the
brush empty (surfaces.SurfaceWriting): the brush is keyframed over the surface, the recording keeps
its frames, the texture keeps its size and shows the writing simulated on the surface."""

from __future__ import annotations

import bpy
from bpy_extras.io_utils import ImportHelper

from ..blender import checks
from ..blender.jobs import JobOperator
from ..blender.writing import WriteJob
from ..sim.writing.hanzi import find_char
from ..sim.writing.writer import DEFAULT_PASSES
from . import polls


class HAIRY_BRUSH_OT_write_character(JobOperator, bpy.types.Operator, ImportHelper):
    """Write a character with the brush from stroke data: the brush follows each stroke's
    median, pressing as wide as the font's outline, and is keyframed so the writing plays,
    edits and renders as animation"""

    bl_idname = "hairy_brush.write_character"
    bl_label = "Write Character"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json;*.txt", options={"HIDDEN"})
    character: bpy.props.StringProperty(
        name="Character",
        default="",
        description="A character to look up in the chosen data file or folder (graphics.txt or "
        "a folder of <char>.json); leave empty to write the chosen .json file itself",
    )
    size_mm: bpy.props.FloatProperty(
        name="Size (mm)",
        default=0.0,
        min=0.0,
        max=2000.0,
        description="Character size in mm (a flat paper becomes this square; on a surface the "
        "character is laid at this size under the brush); 0 sizes the character to the brush",
    )
    passes: bpy.props.IntProperty(
        name="Practice Passes",
        default=DEFAULT_PASSES,
        min=1,
        max=8,
        description="How often each stroke is written, measured against the outline and "
        "corrected before the best pass is kept (1: the calibrated response alone)",
    )
    fit_brush: bpy.props.BoolProperty(
        name="Brush for the Size",
        default=True,
        description="A size other than the brush's own is written with the brush made smaller "
        "or larger in proportion, as a calligrapher takes a small brush for small characters "
        "(off: the brush as it is)",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def invoke(self, context, event):
        self.in_background = True
        return ImportHelper.invoke(self, context, event)

    def execute(self, context):
        scene = context.scene
        try:
            checks.require_brush_and_paper(checks.settings(scene))
            if self.character:
                char = find_char(self.character, self.filepath or None)
            else:
                char = find_char(self.filepath)
            job = WriteJob(scene, char, self.size_mm, self.passes, self.fit_brush)
        except (*checks.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return self.run_job(context, job)
