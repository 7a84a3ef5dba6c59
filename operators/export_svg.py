# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.export_svg: the ink's outline as SVG for cutters and engravers (issue 29.4;
sim.image.svg): the ink traced at a density threshold, smooth closed curves with their holes,
in millimetres, filled even-odd."""

from __future__ import annotations

import bpy
from bpy_extras.io_utils import ExportHelper

from ..blender import checks
from ..sim.image import svg
from ..sim.image.prints import write_file
from . import shown


class HAIRY_BRUSH_OT_export_svg(bpy.types.Operator, ExportHelper):
    """Save the outline of the ink as SVG in millimetres (closed smooth curves, holes kept), for
    vinyl and laser cutters and engravers"""

    bl_idname = "hairy_brush.export_svg"
    bl_label = "Export Ink Outline (SVG)"
    bl_options = {"REGISTER"}

    filename_ext = ".svg"
    filter_glob: bpy.props.StringProperty(default="*.svg", options={"HIDDEN"})
    threshold: bpy.props.FloatProperty(
        name="Threshold",
        default=svg.DEFAULT_THRESHOLD,
        min=0.01,
        max=0.99,
        subtype="FACTOR",
        description="Ink density at which the outline is drawn: lower takes in thinner ink",
    )
    smooth_mm: bpy.props.FloatProperty(
        name="Smoothing (mm)",
        default=svg.DEFAULT_SMOOTH_MM,
        min=0.0,
        max=5.0,
        description="How much the ink's fibrous edge is smoothed before it is traced",
    )
    min_area_mm2: bpy.props.FloatProperty(
        name="Smallest Piece (mm²)",
        default=svg.DEFAULT_MIN_AREA_MM2,
        min=0.0,
        max=100.0,
        description="Specks of ink and holes smaller than this are left out",
    )
    width_mm: bpy.props.FloatProperty(
        name="Width (mm)",
        default=0.0,
        min=0.0,
        max=10000.0,
        description="Width of the drawing (0: the paper's own size, 1:1)",
    )

    @classmethod
    def poll(cls, context):
        return shown.can_export(cls, context)

    def execute(self, context):
        path = bpy.path.abspath(self.filepath)
        try:
            paper = shown.shown_paper(context.scene)
            doc = svg.ink_svg(
                paper, self.threshold, self.smooth_mm, self.min_area_mm2, self.width_mm or None
            )
            write_file(path, doc.encode("utf-8"))
        except (*checks.USER_ERRORS, ValueError, OSError, MemoryError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        curves = doc.split(' d="')[1].count("M")
        self.report({"INFO"}, f"Ink outline: {curves} closed curves, {path}")
        return {"FINISHED"}
