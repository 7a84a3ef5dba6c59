# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.ink_matte: the ink alone as an image datablock (issue 29.4), for compositing over
any material or footage: straight-alpha RGBA whose alpha is the ink's density and RGB its colour
(sim.image.matte). It follows the paper image from then on (a new simulation, a frame change,
undo), so a compositor or a material reading it renders the writing as it is at every frame."""

from __future__ import annotations

import bpy

from ..blender import checks, images
from . import shown


class HAIRY_BRUSH_OT_ink_matte(bpy.types.Operator):
    """Make the ink matte image: the ink alone, alpha = its density, colour = the ink's colour
    (straight alpha), following the paper image from now on"""

    bl_idname = "hairy_brush.ink_matte"
    bl_label = "Ink Matte Image"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return shown.can_export(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        try:
            paper = shown.shown_paper(context.scene)
        except (*checks.USER_ERRORS, MemoryError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        matte = images.matte_image(st.paper_image, create=True)
        images.show_matte(st.paper_image, paper.ink)
        self.report(
            {"INFO"},
            f"Ink matte '{matte.name}' (straight alpha: alpha = ink density) follows the paper",
        )
        return {"FINISHED"}
