# SPDX-License-Identifier: GPL-3.0-or-later
"""Settings kept in the .blend: ``scene.hairy_brush`` (a PropertyGroup) with the brush empty,
paper plane, paper image and recording text it acts on, the paper, brush and ink choices and the
eleven quality parameters of Sec. 7.1 (Fig. 8(a))."""

from __future__ import annotations

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)

from .sim.params import (
    QUALITY_DOC,
    QualityParams,
    ink_from_preset,
    load_preset,
    preset_names,
    quality_from_presets,
)
from .sim.recording import DEFAULT_BRUSH, DEFAULT_INK, DEFAULT_PAPER

QUALITY_LABELS = {
    "e": "Elasticity",
    "tre": "Split Threshold",
    "nu": "Relocation",
    "re": "Rotation",
    "ie": "Elongation",
    "sm": "Paper Grip",
    "ren": "Dry Brush",
    "eta": "Diffusion Distance",
    "ab": "Absorbency",
    "pw": "Diffusion",
    "dry": "Drying Speed",
}


def _preset_items(kind):
    items = []
    for i, name in enumerate(preset_names(kind)):
        p = load_preset(kind, name)
        items.append((name, p.label, p.description, i))
    return items


# EnumProperty items must stay referenced from Python (Blender keeps no copy of the strings).
_ITEMS = {kind: _preset_items(kind) for kind in ("brush", "paper", "ink")}


def apply_quality_presets(st, brush: bool = True, paper: bool = True):
    """Copy the quality values that the chosen brush/paper presets define into the settings."""
    values = quality_from_presets(
        load_preset("brush", st.brush_preset) if brush else None,
        load_preset("paper", st.paper_preset) if paper else None,
    )
    for k, v in values.items():
        setattr(st.quality, k, v)


def apply_ink_preset(st):
    ink = ink_from_preset(load_preset("ink", st.ink_preset))
    st.ink_color = ink.color
    st.dip_wetness = ink.wetness
    st.dip_depth = ink.depth


def _brush_changed(self, _context):
    apply_quality_presets(self, brush=True, paper=False)


def _paper_changed(self, _context):
    apply_quality_presets(self, brush=False, paper=True)


def _ink_changed(self, _context):
    apply_ink_preset(self)


def _quality_annotations():
    # the defaults are those of the default presets, as in a recording that names none
    defaults = QualityParams().with_values(
        quality_from_presets(
            load_preset("brush", DEFAULT_BRUSH), load_preset("paper", DEFAULT_PAPER)
        )
    )
    ann = {}
    for name in QualityParams.names():
        doc, group = QUALITY_DOC[name]
        ann[name] = FloatProperty(
            name=QUALITY_LABELS[name],
            description=f"{doc} (Qp{group}, '{name}')",
            default=getattr(defaults, name),
            min=0.0,
            max=1.0,
            subtype="FACTOR",
        )
    return ann


class HAIRY_BRUSH_PG_quality(bpy.types.PropertyGroup):
    """Qp = (Qp1, Qp2), Eq. 1: every value in [0, 1]."""

    __annotations__ = _quality_annotations()

    def as_dict(self) -> dict:
        return {n: float(getattr(self, n)) for n in QualityParams.names()}


def _is_empty(_self, obj):
    return obj.type == "EMPTY"


def _is_mesh(_self, obj):
    return obj.type == "MESH"


class HAIRY_BRUSH_PG_settings(bpy.types.PropertyGroup):
    brush_object: PointerProperty(
        name="Brush",
        type=bpy.types.Object,
        poll=_is_empty,
        description="Empty whose location is the brush base and whose rotation (Euler ZYX: "
        "X = forward deflection q, Y = sideways deflection d, Z = rotation r) tilts the brush",
    )
    paper_object: PointerProperty(
        name="Paper", type=bpy.types.Object, poll=_is_mesh, description="The paper plane"
    )
    paper_image: PointerProperty(
        name="Paper Image", type=bpy.types.Image, description="Image the ink is simulated into"
    )
    recording: PointerProperty(
        name="Recording",
        type=bpy.types.Text,
        description="The 6-DOF recording (JSON text block) that rebuilds the artwork",
    )
    paper_width_mm: FloatProperty(
        name="Width", default=200.0, min=1.0, max=5000.0, description="Paper width in mm"
    )
    paper_height_mm: FloatProperty(
        name="Height", default=200.0, min=1.0, max=5000.0, description="Paper height in mm"
    )
    px_per_mm: FloatProperty(
        name="Resolution",
        default=5.0,
        min=0.1,
        max=200.0,
        description="Paper pixels per millimetre (image size = paper size x resolution)",
    )
    brush_preset: EnumProperty(
        name="Brush",
        items=_ITEMS["brush"],
        default=DEFAULT_BRUSH,
        update=_brush_changed,
        description="Brush preset",
    )
    paper_preset: EnumProperty(
        name="Paper",
        items=_ITEMS["paper"],
        default=DEFAULT_PAPER,
        update=_paper_changed,
        description="Paper preset",
    )
    ink_preset: EnumProperty(
        name="Ink",
        items=_ITEMS["ink"],
        default=DEFAULT_INK,
        update=_ink_changed,
        description="Ink preset",
    )
    quality: PointerProperty(type=HAIRY_BRUSH_PG_quality)
    ink_color: FloatVectorProperty(
        name="Ink Colour",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=(0.03, 0.03, 0.04),
        description="Colour of the ink the next dip loads",
    )
    dip_wetness: FloatProperty(
        name="Wetness", default=0.9, min=0.0, max=1.0, description="Wetness the dip loads"
    )
    dip_depth: FloatProperty(
        name="Dip Depth",
        default=0.7,
        min=0.0,
        max=1.0,
        subtype="FACTOR",
        description="How much of the hair, from the tip, goes into the ink (Eq. 7-8)",
    )
    sample_rate_hz: FloatProperty(
        name="Sample Rate",
        default=120.0,
        min=1.0,
        max=1000.0,
        description="6-DOF samples per second taken from the animated brush",
    )
    seed: IntProperty(name="Seed", default=0, min=0, description="Seed of the one random generator")
    sync_frames: BoolProperty(
        name="Follow Frames",
        default=True,
        description="Update the paper image and the primitive objects on every frame change, "
        "so a render of frame N shows the artwork as it was at frame N",
    )
    paint_press_mm: FloatProperty(
        name="Press",
        default=4.0,
        min=0.0,
        max=60.0,
        description="Live painting: how far the brush base goes below the hair length while "
        "the button is held (mouse wheel changes it)",
    )
    paint_angle_step: FloatProperty(
        name="Angle Step",
        default=2.0,
        min=0.1,
        max=30.0,
        description="Live painting: degrees per key press of q/w, e/r, c/v",
    )
    sequence_dir: StringProperty(
        name="Sequence Folder",
        default="//hairy_brush_frames/",
        subtype="DIR_PATH",
        description="Where Bake Sequence writes one paper image per frame",
    )


CLASSES = (HAIRY_BRUSH_PG_quality, HAIRY_BRUSH_PG_settings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.hairy_brush = PointerProperty(type=HAIRY_BRUSH_PG_settings)


def unregister():
    del bpy.types.Scene.hairy_brush
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
