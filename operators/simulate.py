# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.simulate: run the recording into the paper image (packed into the .blend when
the file is saved); from the sidebar a modal job in slices (Esc puts the paper back)."""

from __future__ import annotations

import time

import bpy

from ..blender import checks, frames, images, playback, surfaces
from ..blender.jobs import Job, JobOperator, deadline
from . import polls

SHOW_EVERY_S = 1.0  # the paper image shows the ink so far this often while simulating


class SimulateJob(Job):
    """Seek the scene's playback to ``target`` samples a slice at a time; the paper image
    shows the ink so far now and then and at the end."""

    title = "Simulating ink"

    def __init__(self, scene, target: int | None = None, to_current_frame: bool = False):
        self.scene = scene
        self.pb = playback.playback_for(scene)
        n = len(self.pb.rec.samples)
        if to_current_frame:
            n = frames.samples_at_frame(self.pb.rec, scene, scene.frame_current)
        self.target = n if target is None else target
        img = checks.settings(scene).paper_image
        self.shown_before = int(img[images.SHOWN_TAG]) if img and images.SHOWN_TAG in img else None
        self._last_show = time.perf_counter()

    def step(self, budget_s: float) -> bool:
        sim = self.pb.seek(self.target, should_stop=deadline(budget_s))
        self.fraction = sim.index / max(self.target, 1)
        self.status = f"sample {sim.index} of {self.target}"
        done = sim.index >= self.target
        if not done and time.perf_counter() - self._last_show > SHOW_EVERY_S:
            self._show(sim)
        return done

    def _show(self, sim):
        img = images.ensure_paper_image(checks.settings(self.scene))
        images.show_paper(img, sim.paper, sim.index, self.pb.overlay)
        self._last_show = time.perf_counter()

    def cancel(self):
        if self.shown_before is not None:
            playback.show(self.scene, self.shown_before)
        elif checks.settings(self.scene).paper_image is not None:
            st = checks.settings(self.scene)
            images.show_blank(st, surfaces.paper_texture(st))

    def finish(self, context):
        playback.show(self.scene, self.target)
        img = checks.settings(self.scene).paper_image
        return "INFO", f"Simulated {self.target} samples into '{img.name}'"


class HAIRY_BRUSH_OT_simulate(JobOperator, bpy.types.Operator):
    """Simulate the whole recording (or up to the current frame) into the paper image"""

    bl_idname = "hairy_brush.simulate"
    bl_label = "Simulate Ink"
    bl_options = {"REGISTER", "UNDO"}

    to_current_frame: bpy.props.BoolProperty(
        name="Up to Current Frame",
        default=False,
        description="Stop at the current frame instead of the end of the recording",
    )

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def execute(self, context):
        try:
            job = SimulateJob(context.scene, to_current_frame=self.to_current_frame)
        except (*checks.USER_ERRORS, MemoryError) as exc:
            return self._failed(exc)
        return self.run_job(context, job)
