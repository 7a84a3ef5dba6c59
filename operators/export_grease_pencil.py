# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.export_grease_pencil: the recording as Grease Pencil strokes (issue 29.4), for
artists who edit strokes there: a stroke for each touch of the brush, a point per sample where
the brush's axis meets the paper, its pressure from the press depth (sim.engine.pen).

Blender has two Grease Pencils: the legacy one up to 4.2 (``bpy.data.grease_pencils``, points
with a pressure and strokes with a line width) and v3 from 4.3 (``bpy.data.grease_pencils_v3``
in 4.3 to 4.5, ``bpy.data.grease_pencils`` from 5.0; points with a radius, no pressure). The
running Blender's is used: with v3 the pressure goes into each point's radius and is kept as
the point attribute ``pressure`` too."""

from __future__ import annotations

import bpy
import numpy as np

from ..blender import checks, recordings, surfaces, transforms
from ..sim import surface as surf
from ..sim.engine.pen import pen_strokes
from . import polls

OBJECT = "HairyBrush Strokes"
MATERIAL = "HairyBrush Ink Stroke"
LIFT_MM = 0.1  # the strokes lie this far above a flat paper (no z-fighting with it)
LEGACY_RADIUS_PER_WIDTH = 1.0 / 2000.0  # metres of radius per legacy line width at pressure 1


def grease_pencil_v3_data():
    """The collection of v3 Grease Pencil data, or None when this Blender has only legacy."""
    coll = getattr(bpy.data, "grease_pencils_v3", None)  # Blender 4.3 to 4.5
    if coll is not None:
        return coll
    if "layer_groups" in bpy.types.GreasePencil.bl_rna.properties:  # 5.0 on
        return bpy.data.grease_pencils
    return None


def world_strokes(scene, rec):
    """The pen strokes with their points in world coordinates (metres)."""
    st = checks.settings(scene)
    if surfaces.is_surface(st):
        frames = surf.frames_from_dict(rec.extra.get(recordings.SURFACE_KEY), len(rec.samples))
        if frames is None:
            raise checks.UserError(
                "The recording has no surface frames (it was made on flat paper): there is no "
                f"place for its strokes on '{st.paper_object.name}'"
            )
        to_world = surfaces.surface_space(st.paper_object)
        strokes = pen_strokes(rec, frames)
    else:
        to_world = transforms.engine_to_world(st, st.paper_object)
        strokes = pen_strokes(rec)
        for s in strokes:
            s.points[:, 2] = LIFT_MM
    m = np.asarray(to_world, dtype=float)
    scale = 1.0 / transforms.MM if surfaces.is_surface(st) else 1.0
    out = []
    for s in strokes:
        p = s.points * scale
        out.append((p @ m[:3, :3].T + m[:3, 3], s))
    return out


def stroke_material(color) -> bpy.types.Material:
    mat = bpy.data.materials.get(MATERIAL)
    if mat is None or not mat.is_grease_pencil:
        mat = bpy.data.materials.new(MATERIAL)
        bpy.data.materials.create_gpencil_data(mat)
    mat.grease_pencil.color = (*color, 1.0)
    return mat


def fill_v3(gp, frame: int, strokes, rate_hz: float):
    """Points with a radius (the pressure's), and each point's time from its sample."""
    layer = gp.layers.new("Strokes")
    drawing = layer.frames.new(frame).drawing
    drawing.add_strokes([len(s.pressure) for _p, s in strokes])
    for stroke, (pts, s) in zip(drawing.strokes, strokes, strict=True):
        radius = s.radius_mm / transforms.MM
        times = (s.samples - s.samples[0]) / rate_hz
        for pt, p, r, t in zip(stroke.points, pts, radius, times, strict=True):
            pt.position = p
            pt.radius = r
            pt.delta_time = t
    pressure = drawing.attributes.new("pressure", "FLOAT", "POINT")
    pressure.data.foreach_set("value", np.concatenate([s.pressure for _p, s in strokes]))


def fill_legacy(gp, frame: int, strokes, _rate_hz: float):
    """Points with a pressure; a stroke's line width is its full pressure's radius."""
    layer = gp.layers.new("Strokes")
    gframe = layer.frames.new(frame)
    for pts, s in strokes:
        stroke = gframe.strokes.new()
        stroke.display_mode = "3DSPACE"
        full = float(s.radius_mm.max() / s.pressure.max()) / transforms.MM
        stroke.line_width = max(1, round(full / LEGACY_RADIUS_PER_WIDTH))
        stroke.points.add(len(pts))
        stroke.points.foreach_set("co", pts.astype(np.float32).ravel())
        stroke.points.foreach_set("pressure", s.pressure.astype(np.float32))
        stroke.points.foreach_set("strength", np.ones(len(pts), np.float32))


class HAIRY_BRUSH_OT_export_grease_pencil(bpy.types.Operator):
    """Make the recording Grease Pencil strokes: a stroke for each touch of the brush, its
    pressure from how deep the brush presses (the object 'HairyBrush Strokes', on the paper)"""

    bl_idname = "hairy_brush.export_grease_pencil"
    bl_label = "Recording to Grease Pencil"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.recording(cls, context) and polls.object_mode(cls, context)

    def execute(self, context):
        scene = context.scene
        st = checks.settings(scene)
        try:
            checks.require_brush_and_paper(st)
            rec = recordings.recording_from_scene(scene)
            strokes = world_strokes(scene, rec)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        if not strokes:
            self.report({"ERROR"}, "The brush never touches the paper: no strokes to make")
            return {"CANCELLED"}
        old = bpy.data.objects.get(OBJECT)
        if old is not None:
            bpy.data.objects.remove(old)
        v3 = grease_pencil_v3_data()
        gp = (v3 if v3 is not None else bpy.data.grease_pencils).new(OBJECT)
        fill = fill_v3 if v3 is not None else fill_legacy
        fill(gp, scene.frame_start, strokes, rec.sample_rate_hz)
        gp.materials.append(stroke_material(tuple(st.ink_color)))
        obj = bpy.data.objects.new(OBJECT, gp)
        scene.collection.objects.link(obj)
        obj.parent = st.paper_object  # it moves with the paper
        obj.matrix_parent_inverse = st.paper_object.matrix_world.inverted()
        kind = "v3" if v3 is not None else "legacy"
        self.report(
            {"INFO"},
            f"{len(strokes)} Grease Pencil ({kind}) strokes, "
            f"{sum(len(s.pressure) for _p, s in strokes)} points, in '{obj.name}'",
        )
        return {"FINISHED"}
