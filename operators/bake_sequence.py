# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.bake_sequence: the paper image of every frame, as an image sequence on disk, and
or instead the ink matte of every frame (``content``: straight-alpha RGBA ink_####.png, alpha the
ink's density, issue 29.4); from the sidebar a modal job, a frame or part of one a slice (Esc
stops it)."""

from __future__ import annotations

import os

import bpy

from ..blender import checks, frames, playback, runtime
from ..blender.jobs import Job, JobOperator, deadline
from ..sim.image.matte import paper_matte8
from ..sim.image.png import write_png
from . import polls


def sequence_folder(path: str) -> str:
    """The folder as an absolute path; UserError for one relative to an unsaved .blend (it
    would land wherever Blender was started from)."""
    if not path.strip():
        raise checks.UserError("Choose a Sequence Folder first")
    if path.startswith("//") and not bpy.data.filepath:
        raise checks.UserError(
            f"Sequence Folder '{path}' is relative to the .blend, which is not saved yet: "
            "save the file first or choose an absolute folder"
        )
    folder = bpy.path.abspath(path)
    if not os.path.isabs(folder):
        raise checks.UserError(f"Sequence Folder '{path}' is not an absolute path")
    return folder


class SequenceJob(Job):
    """One PNG per frame of the scene's range (the paper, its ink matte or both); the scene
    itself is not changed (the paper image keeps what it showed)."""

    title = "Baking image sequence"

    def __init__(self, scene, folder: str, content: str = "PAPER"):
        self.scene = scene
        self.folder = folder
        self.content = content
        self.pb = playback.playback_for(scene)
        self.frames = list(range(scene.frame_start, scene.frame_end + 1))
        self.k = 0
        self.written = []

    def step(self, budget_s: float) -> bool:
        stop = deadline(budget_s)
        os.makedirs(self.folder, exist_ok=True)
        with runtime.get().frames_suspended():
            while self.k < len(self.frames):
                f = self.frames[self.k]
                target = frames.samples_at_frame(self.pb.rec, self.scene, f)
                sim = self.pb.seek(target, should_stop=stop)
                if sim.index < target:
                    break  # the slice's time is up inside a frame
                if self.content in ("PAPER", "BOTH"):
                    path = os.path.join(self.folder, f"paper_{f:04d}.png")
                    write_png(path, self.pb.image8(sim))  # a work's grid and seal as sim render's
                    self.written.append(path)
                if self.content in ("MATTE", "BOTH"):
                    path = os.path.join(self.folder, f"ink_{f:04d}.png")
                    write_png(path, paper_matte8(sim.paper))
                    self.written.append(path)
                self.k += 1
                if stop is not None and stop():
                    break
        self.fraction = self.k / max(len(self.frames), 1)
        self.status = f"frame {self.k} of {len(self.frames)}"
        return self.k >= len(self.frames)

    def finish(self, context):
        return "INFO", f"Wrote {len(self.written)} images to {self.folder}"


class HAIRY_BRUSH_OT_bake_sequence(JobOperator, bpy.types.Operator):
    """Write the paper image (or the ink matte, or both) of every frame of the scene's range as
    PNG files (for render farms and compositing: an Image Texture set to Image Sequence plays
    them back)"""

    bl_idname = "hairy_brush.bake_sequence"
    bl_label = "Bake Image Sequence"
    bl_options = {"REGISTER"}

    content: bpy.props.EnumProperty(
        name="Content",
        items=(
            ("PAPER", "Paper", "paper_####.png: the paper as it shows"),
            (
                "MATTE",
                "Ink Matte",
                "ink_####.png: the ink alone, RGBA with alpha = the ink's density and RGB its "
                "colour, unpremultiplied (straight alpha), for compositing",
            ),
            ("BOTH", "Both", "paper_####.png and ink_####.png"),
        ),
        default="PAPER",
    )

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context)

    def execute(self, context):
        scene = context.scene
        try:
            folder = sequence_folder(checks.settings(scene).sequence_dir)
            job = SequenceJob(scene, folder, self.content)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return self.run_job(context, job)
