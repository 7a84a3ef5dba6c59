# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.bake_sequence: the paper image of every frame, as an image sequence on disk."""

from __future__ import annotations

import os

import bpy

from .. import bridge, handlers, playback
from ..sim.png import write_png


class HAIRY_BRUSH_OT_bake_sequence(bpy.types.Operator):
    """Write the paper image of every frame of the scene's range as PNG files (for render
    farms: an Image Texture set to Image Sequence plays them back)"""

    bl_idname = "hairy_brush.bake_sequence"
    bl_label = "Bake Image Sequence"
    bl_options = {"REGISTER"}

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        folder = bpy.path.abspath(st.sequence_dir)
        if folder.startswith("//") or not folder:
            self.report({"ERROR"}, "Save the .blend first or choose an absolute Sequence Folder")
            return {"CANCELLED"}
        wm = context.window_manager
        frames = range(scene.frame_start, scene.frame_end + 1)
        wm.progress_begin(0, len(frames))
        try:
            os.makedirs(folder, exist_ok=True)
            pb = playback.playback_for(scene)
            with handlers.suspended():
                for k, f in enumerate(frames):
                    sim = pb.seek(bridge.samples_at_frame(pb.rec, scene, f))
                    write_png(os.path.join(folder, f"paper_{f:04d}.png"), sim.image8())
                    wm.progress_update(k)
        except (*bridge.USER_ERRORS, OSError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        self.report({"INFO"}, f"Wrote {len(frames)} images to {folder}")
        return {"FINISHED"}
