# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.write_character: write a character from stroke data (hanzi-writer-data files or
Make Me a Hanzi's graphics.txt) with the brush, and keyframe the brush empty along the
trajectory: press from the outline's width through the brush's calibrated response. From the
sidebar the writing runs as a modal job (Esc stops it; the scene changes only at the end).

On a surface paper (issue 17) the writing is laid on the surface around the point under the
brush empty (bridge.SurfaceWriting): the brush is keyframed over the surface, the recording keeps
its frames, the texture keeps its size and shows the writing simulated on the surface."""

from __future__ import annotations

import math

import bpy
import numpy as np
from bpy_extras.io_utils import ImportHelper

from .. import bridge, playback
from ..sim.writing.hanzi import find_char
from ..sim.writing.response import calibrate
from ..sim.writing.writer import DEFAULT_PASSES, auto_size_mm, write_character
from . import polls
from .jobs import JobOperator, WorkerJob

WRITE_SHARE = 0.6  # of the progress bar on a surface: the flat writing (then laying it)


def _share(progress, lo: float, hi: float):
    """progress(fraction, *details) reported on the part [lo, hi] of the bar."""
    return lambda f, *details: progress(lo + (hi - lo) * f, *details)


class WriteJob(WorkerJob):
    """The writing itself (calibration, practice passes) in a worker; ``finish`` sizes the
    paper, keyframes the brush, stores the recording and shows the writing. On a surface the
    worker also lays the writing on it and simulates it there."""

    title = "Writing character"
    on_surface = None  # bridge.SurfaceWriting when the paper is a surface (set by ``step``)

    def step(self, budget_s: float) -> bool:
        if self._thread is None and not self.finished:  # first, on Blender's thread
            st = bridge.settings(self.scene)
            self.on_surface = bridge.SurfaceWriting(self.scene) if bridge.is_surface(st) else None
        return super().step(budget_s)

    def __init__(self, scene, char: dict, size_mm: float, passes: int):
        st = bridge.settings(scene)
        self.scene, self.char = scene, char
        self.template = bridge.settings_recording(scene)
        self.ppm = float(st.px_per_mm)
        if size_mm:
            self._check(size_mm)
        super().__init__(lambda progress: self._write(size_mm, passes, progress))

    def _check(self, size_mm: float) -> float:
        """The size as the settings will hold it (single precision), checked for memory."""
        size = float(np.float32(size_mm))
        w = max(1, round(size * self.ppm))
        bridge.check_paper_pixels(w, w)
        return size

    def _write(self, size_mm: float, passes: int, progress):
        if not size_mm:  # the size follows from the brush's response
            progress(0.0, "calibrating the brush")
            size_mm = auto_size_mm(self.char, calibrate(self.template))
        size = self._check(size_mm)
        flat = progress if self.on_surface is None else _share(progress, 0.0, WRITE_SHARE)
        rec, _, sim = write_character(
            self.char,
            0,
            self.template,
            size_mm=size,
            passes=passes,
            progress=flat,
            px_per_mm=self.ppm,
        )
        if self.on_surface is not None:
            del sim  # the flat paper, before the surface's is simulated
            rec, sim = self.on_surface.lay(rec, size, _share(progress, WRITE_SHARE, 1.0))
        return size, rec, sim

    def describe(self, details) -> str:
        return details[0] if details else "practising the strokes"

    def finish(self, context):
        size, rec, sim = self.result
        scene = self.scene
        st = bridge.settings(scene)
        if self.on_surface is None:
            st.paper_width_mm = st.paper_height_mm = size  # the paper plane follows
            rec = bridge.new_recording(scene, rec.samples, dips=rec.dips)
            last = bridge.keyframe_samples(
                scene, st, rec.samples, rec.sample_rate_hz, scene.frame_start
            )
        else:  # laid on the surface (the texture keeps its size)
            mats = self.on_surface.matrices(st, rec)
            last = bridge.keyframe_matrices(scene, st, mats, rec.sample_rate_hz, scene.frame_start)
            bridge.keep_surface_paper(self.on_surface.digest, self.on_surface.paper)
        scene.frame_end = math.ceil(last)
        bridge.store_recording(st, rec)
        playback.clear()
        bridge.show_paper(bridge.ensure_paper_image(st), sim.paper, len(rec.samples))
        return "INFO", (
            f"{len(self.char['medians'])} strokes, {len(rec.samples)} samples, "
            f"{len(rec.dips)} dips, {size:.0f} mm"
        )


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

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def invoke(self, context, event):
        self.in_background = True
        return ImportHelper.invoke(self, context, event)

    def execute(self, context):
        scene = context.scene
        try:
            bridge.require_brush_and_paper(bridge.settings(scene))
            if self.character:
                char = find_char(self.character, self.filepath or None)
            else:
                char = find_char(self.filepath)
            job = WriteJob(scene, char, self.size_mm, self.passes)
        except (*bridge.USER_ERRORS, ValueError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return self.run_job(context, job)
