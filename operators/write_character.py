# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.write_character: keyframe the brush along a character's strokes (hanzi-writer
data: a JSON file with 'strokes' and 'medians')."""

from __future__ import annotations

import math

import bpy
from bpy_extras.io_utils import ImportHelper

from .. import bridge
from ..sim.hanzi import load_char, simple_samples
from ..sim.recording import RecordingError
from .setup import resize_paper


class HAIRY_BRUSH_OT_write_character(bpy.types.Operator, ImportHelper):
    """Keyframe the brush empty along a character's strokes (pressing, travelling, lifting
    between strokes) and store the matching recording, ready to simulate, play or edit"""

    bl_idname = "hairy_brush.write_character"
    bl_label = "Write Character"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})
    size_mm: bpy.props.FloatProperty(
        name="Size", default=160.0, min=10.0, max=2000.0, description="Character size in mm"
    )
    press: bpy.props.FloatProperty(
        name="Press",
        default=0.4,
        min=0.05,
        max=0.9,
        subtype="FACTOR",
        description="How far the brush is pressed, as a fraction of the hair length",
    )
    speed_mm_s: bpy.props.FloatProperty(name="Speed", default=70.0, min=5.0, max=1000.0)

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        try:
            bridge.require_brush_and_paper(st)
            char = load_char(self.filepath)
        except (bridge.UserError, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        st.paper_width_mm = st.paper_height_mm = self.size_mm
        resize_paper(st)
        hair = bridge.hair_length(st)
        samples = simple_samples(
            char,
            self.size_mm,
            hair_length_mm=hair,
            press_mm=self.press * hair,
            speed_mm_s=self.speed_mm_s,
            rate_hz=st.sample_rate_hz,
        )
        try:
            rec = bridge.new_recording(scene, samples)
        except (RecordingError, bridge.UserError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        last = bridge.keyframe_samples(
            scene, st, rec.samples, rec.sample_rate_hz, scene.frame_start
        )
        scene.frame_end = math.ceil(last)
        bridge.store_recording(st, rec)
        bridge.ensure_paper_image(st)
        self.report({"INFO"}, f"{len(char['medians'])} strokes, {len(samples)} samples")
        return {"FINISHED"}
