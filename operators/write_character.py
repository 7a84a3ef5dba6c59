# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.write_character: write a character from stroke data (hanzi-writer-data files or
Make Me a Hanzi's graphics.txt) with the brush, and keyframe the brush empty along the
trajectory: press from the outline's width through the brush's calibrated response."""

from __future__ import annotations

import math

import bpy
from bpy_extras.io_utils import ImportHelper

from .. import bridge, playback
from ..sim.hanzi import find_char
from ..sim.imitate import write_character
from .setup import resize_paper


class HAIRY_BRUSH_OT_write_character(bpy.types.Operator, ImportHelper):
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
        name="Size",
        default=0.0,
        min=0.0,
        max=2000.0,
        description="Character size in mm (the paper becomes this square); 0 sizes the "
        "character to the brush",
    )
    passes: bpy.props.IntProperty(
        name="Practice Passes",
        default=3,
        min=1,
        max=8,
        description="How often each stroke is written, measured against the outline and "
        "corrected before the best pass is kept (1: the calibrated response alone)",
    )

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        wm = context.window_manager
        try:
            bridge.require_brush_and_paper(st)
            if self.character:
                char = find_char(self.character, self.filepath or None)
            else:
                char = find_char(self.filepath)
            template = bridge.settings_recording(scene)
        except (*bridge.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        old_size = (st.paper_width_mm, st.paper_height_mm)
        wm.progress_begin(0, 100)
        try:
            size = self.size_mm
            if not size:  # the size follows from the brush's response
                from ..sim.imitate import auto_size_mm, calibrate

                size = auto_size_mm(char, calibrate(template))
            # the paper becomes the em box; the values read back are the ones the stored
            # recording will carry (Blender keeps single precision)
            st.paper_width_mm = st.paper_height_mm = size
            size, ppm = float(st.paper_width_mm), float(st.px_per_mm)
            bridge.check_paper_size(st)
            rec, _, sim = write_character(
                char,
                0,
                template,
                size_mm=size,
                passes=self.passes,
                progress=lambda f: wm.progress_update(int(100 * f)),
                px_per_mm=ppm,
            )
            rec = bridge.new_recording(scene, rec.samples, dips=rec.dips)
        except (*bridge.USER_ERRORS, ValueError) as exc:
            st.paper_width_mm, st.paper_height_mm = old_size  # a cancelled operator leaves no trace
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        resize_paper(st)
        last = bridge.keyframe_samples(
            scene, st, rec.samples, rec.sample_rate_hz, scene.frame_start
        )
        scene.frame_end = math.ceil(last)
        bridge.store_recording(st, rec)
        playback.clear()
        bridge.show_paper(bridge.ensure_paper_image(st), sim.paper, len(rec.samples))
        self.report(
            {"INFO"},
            f"{len(char['medians'])} strokes, {len(rec.samples)} samples, "
            f"{len(rec.dips)} dips, {size:.0f} mm",
        )
        return {"FINISHED"}
