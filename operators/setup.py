# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.setup: a brush empty, a paper plane textured with the paper image, the settings;
with ``surface=True`` the selected mesh is the paper instead (the scene is built by
``blender.scene``)."""

from __future__ import annotations

import bpy

from ..blender import checks, scene_setup


class HAIRY_BRUSH_OT_setup(bpy.types.Operator):
    """Add a brush empty and a paper plane whose material shows the paper image"""

    bl_idname = "hairy_brush.setup"
    bl_label = "Set Up Brush and Paper"
    bl_options = {"REGISTER", "UNDO"}

    surface: bpy.props.BoolProperty(
        name="On the Selected Mesh",
        default=False,
        description="Make the selected mesh the paper: the brush writes on its surface and the "
        "ink goes into an image read through its active UV map (its size follows the mesh's "
        "area and Resolution)",
    )

    @classmethod
    def poll(cls, context):
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to set up the brush and paper")
            return False
        return True

    def execute(self, context):
        try:
            if not self.surface:
                message = scene_setup.set_up_flat(context.scene)
            else:
                obj = scene_setup.surface_target(context)
                if obj is None:
                    self.report({"ERROR"}, "Select a mesh to write on (one with a UV map)")
                    return {"CANCELLED"}
                message = scene_setup.set_up_surface(context.scene, obj)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, message)
        return {"FINISHED"}
