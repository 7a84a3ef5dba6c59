# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.simulate: run the recording into the paper image (packed into the .blend when
the file is saved)."""

from __future__ import annotations

import bpy

from .. import bridge, playback


class HAIRY_BRUSH_OT_simulate(bpy.types.Operator):
    """Simulate the whole recording (or up to the current frame) into the paper image"""

    bl_idname = "hairy_brush.simulate"
    bl_label = "Simulate Ink"
    bl_options = {"REGISTER", "UNDO"}

    to_current_frame: bpy.props.BoolProperty(
        name="Up to Current Frame",
        default=False,
        description="Stop at the current frame instead of the end of the recording",
    )

    def execute(self, context):
        scene = context.scene
        st = bridge.settings(scene)
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            rec = playback.playback_for(scene).rec
            n = len(rec.samples)
            if self.to_current_frame:
                n = bridge.samples_at_frame(rec, scene, scene.frame_current)
            playback.show(scene, n, progress=lambda f: wm.progress_update(int(100 * f)))
        except bridge.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        except MemoryError:
            self.report({"ERROR"}, "Not enough memory for this paper: lower its resolution")
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        self.report({"INFO"}, f"Simulated {n} samples into '{st.paper_image.name}'")
        return {"FINISHED"}
