# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.export_image: the paper, or its ink matte, at a chosen print size and DPI, as PNG
or TIFF with the DPI in the file (issue 29.4; sim.image.prints: the ink's density resampled
with a Mitchell filter, then the picture made from it)."""

from __future__ import annotations

import os

import bpy
from bpy_extras.io_utils import ExportHelper

from ..blender import checks
from ..sim.image.prints import PrintError, write_print
from . import shown


class HAIRY_BRUSH_OT_export_image(bpy.types.Operator, ExportHelper):
    """Save the paper (or the ink alone, as a straight-alpha matte) at a print size and DPI, as
    PNG or TIFF with the DPI in the file"""

    bl_idname = "hairy_brush.export_image"
    bl_label = "Export Print Image"
    bl_options = {"REGISTER"}

    filename_ext = ".png"
    check_extension = None  # .png, .tif and .tiff are all taken as they are
    filter_glob: bpy.props.StringProperty(default="*.png;*.tif;*.tiff", options={"HIDDEN"})
    content: bpy.props.EnumProperty(
        name="Content",
        items=(
            ("PAPER", "Paper", "The paper as the paper image shows it (RGB)"),
            (
                "MATTE",
                "Ink Matte",
                "The ink alone (RGBA): alpha = the ink's density, colour = the ink's colour, "
                "unpremultiplied (straight alpha)",
            ),
        ),
        default="PAPER",
    )
    width_mm: bpy.props.FloatProperty(
        name="Print Width (mm)",
        default=0.0,
        min=0.0,
        max=10000.0,
        description="Width of the print; the height follows the paper's shape (0: the paper's "
        "own width, a print at 1:1)",
    )
    dpi: bpy.props.FloatProperty(
        name="DPI", default=300.0, min=1.0, max=10000.0, description="Pixels per inch of the print"
    )
    depth: bpy.props.EnumProperty(
        name="Bits",
        items=(("8", "8 bit", "8 bits a channel"), ("16", "16 bit", "16 bits a channel")),
        default="8",
    )

    @classmethod
    def poll(cls, context):
        return shown.can_export(cls, context)

    def execute(self, context):
        st = checks.settings(context.scene)
        path = bpy.path.abspath(self.filepath)
        if not os.path.splitext(path)[1]:
            path += self.filename_ext
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            paper = shown.shown_paper(context.scene)
            width = self.width_mm or float(st.paper_width_mm)
            w, h = write_print(
                path,
                paper,
                width,
                self.dpi,
                matte=self.content == "MATTE",
                bits=int(self.depth),
                progress=lambda f: wm.progress_update(int(100 * f)),
            )
        except (*checks.USER_ERRORS, PrintError, OSError, MemoryError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        what = "Ink matte" if self.content == "MATTE" else "Paper"
        self.report(
            {"INFO"}, f"{what}: {w} x {h} px, {width:g} mm wide at {self.dpi:g} dpi, {path}"
        )
        return {"FINISHED"}
