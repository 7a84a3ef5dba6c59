# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.build_primitives: the writing primitives as NURBS surface objects."""

from __future__ import annotations

import bpy

from ..blender import checks, frames, playback, primitives, recordings, transforms
from ..sim.engine.simulation import Simulation
from . import polls


class HAIRY_BRUSH_OT_build_primitives(bpy.types.Operator):
    """Show each writing primitive of the brush, at the current frame, as a NURBS surface
    object on the paper (the engine's own control points, weights and knots); a viewport aid,
    hidden from final renders unless Primitives in Renders is on"""

    bl_idname = "hairy_brush.build_primitives"
    bl_label = "Build Primitive Surfaces"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def execute(self, context):
        scene = context.scene
        st = checks.settings(scene)
        try:
            checks.require_brush_and_paper(st)
            if st.recording is not None:
                pb = playback.playback_for(scene)
                sim = pb.seek(frames.samples_at_frame(pb.rec, scene, scene.frame_current))
            else:  # no recording yet: the free brush where the empty is
                s = transforms.sample_from_matrices(
                    st, st.brush_object.matrix_world, st.paper_object.matrix_world
                )
                sim = Simulation(recordings.new_recording(scene, [s]))
                sim.brush.place(s)
            n = primitives.sync_primitives(scene, sim, create=True)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"{n} writing primitive(s)")
        return {"FINISHED"}
