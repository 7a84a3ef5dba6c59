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

from ..sim.core.params import (
    PAPER_CAPACITY_RANGE,
    PAPER_TEXTURE_MAX,
    QUALITY_DOC,
    QualityParams,
    load_preset,
    paper_from_preset,
    quality_from_presets,
)
from ..sim.core.recording import (
    DEFAULT_BRUSH,
    DEFAULT_INK,
    DEFAULT_PAPER,
    PAPER_MM_RANGE,
    PX_PER_MM_RANGE,
)
from ..sim.writing.work.compose import WORK_PASSES
from . import presets, scene_setup


def _brush_changed(self, _context):
    presets.apply_quality_presets(self, brush=True, paper=False)
    scene_setup.follow_hair_length(self)


def _paper_changed(self, _context):
    presets.apply_quality_presets(self, brush=False, paper=True)
    presets.apply_paper_preset(self)


def _seed_changed(self, _context):
    self.seed_of_recording = ""  # the artist's own seed replaces an imported large one


def _ink_changed(self, _context):
    presets.apply_ink_preset(self)


def _paper_size_changed(self, _context):
    scene_setup.resize_paper(self)


def _quality_annotations():
    # the defaults are those of the default presets, as in a recording that names none
    defaults = QualityParams().with_values(
        quality_from_presets(
            load_preset("brush", DEFAULT_BRUSH), load_preset("paper", DEFAULT_PAPER)
        )
    )
    ann = {}
    for name in QualityParams.names():
        label, effect = presets.QUALITY_UI[name]
        group = QUALITY_DOC[name][1]
        ann[name] = FloatProperty(
            name=label,
            description=f"{effect} (the paper's '{name}', Qp{group})",
            default=getattr(defaults, name),
            min=0.0,
            max=1.0,
            subtype="FACTOR",
        )
    return ann


class HAIRY_BRUSH_PG_quality(bpy.types.PropertyGroup):
    """Qp = (Qp1, Qp2), Eq. 1: every value in [0, 1]. Read them with checks.quality_values: a
    PropertyGroup holds properties only (Blender 4.2 crashes at exit when one has methods)."""

    __annotations__ = _quality_annotations()


class HAIRY_BRUSH_PG_work(bpy.types.PropertyGroup):
    """Write Text (issue 27, sim.writing.work): the text, how a new work is laid out on the
    paper, the signature and seal, and how the characters are written."""

    text: StringProperty(
        name="Text",
        default="",
        description="The characters to write: on an empty recording a new work is laid out on "
        "the paper; on a work they go on after its last character",
    )
    direction: EnumProperty(
        name="Layout",
        items=[
            ("vertical", "Columns", "Columns from the top, read from right to left"),
            ("horizontal", "Rows", "Rows from the left, read from top to bottom"),
        ],
        default="vertical",
        description="How a new work is laid out (a work keeps its own)",
    )
    per_line: IntProperty(
        name="Characters per Column",
        default=0,
        min=0,
        max=1000,
        description="Characters a column (row) of a new work holds; 0: as many as the paper holds",
    )
    char_mm: FloatProperty(
        name="Size (mm)",
        default=0.0,
        min=0.0,
        max=1000.0,
        description="A new work's character size (its em box) in mm; 0: the brush's own size, "
        "smaller when the text would not fit the paper",
    )
    grid: EnumProperty(
        name="Grid",
        items=[
            ("none", "None", "Blank paper"),
            ("mi", "米字格", "A practice sheet: border, centre cross and diagonals, faint red"),
            ("tian", "田字格", "A practice sheet: border and centre cross, faint red"),
        ],
        default="none",
        description="A practice grid printed under each cell of a new work",
    )
    new_line: BoolProperty(
        name="New Column",
        default=False,
        description="Write Text on a work starts a new column (row) instead of going on in "
        "the last one",
    )
    signature: StringProperty(
        name="Signature",
        default="",
        description="The signature (落款): smaller characters after the text, in their own "
        "column (row)",
    )
    seal: StringProperty(
        name="Seal",
        default="",
        description="The characters of a vermilion name seal stamped after the signature",
    )
    seal_style: EnumProperty(
        name="Seal Style",
        items=[
            ("baiwen", "白文", "White characters cut into the red (intaglio)"),
            ("zhuwen", "朱文", "Red characters in a red border (relief)"),
        ],
        default="baiwen",
    )
    passes: IntProperty(
        name="Practice Passes",
        default=WORK_PASSES,
        min=1,
        max=8,
        description="How often each stroke is written and corrected before the best pass is "
        "kept (more: closer to the font's outline, slower)",
    )
    variation: FloatProperty(
        name="Variation",
        default=1.0,
        min=0.0,
        max=1.0,
        subtype="FACTOR",
        description="How much a character written twice varies in size, slant and pressure "
        "(1: a hand's usual, 0: none)",
    )
    fit_brush: BoolProperty(
        name="Brush for the Size",
        default=True,
        description="A work smaller or larger than the brush's own size is written with the "
        "brush made smaller or larger in proportion, as a calligrapher takes a small brush for "
        "small characters (off: the brush as it is)",
    )
    punctuation: EnumProperty(
        name="Punctuation",
        items=[
            ("omit", "Leave Out", "Punctuation is left out, as in classical works"),
            ("keep", "Keep", "Punctuation written as small marks in the cell's corner"),
        ],
        default="omit",
    )
    skip_missing: BoolProperty(
        name="Skip Missing",
        default=False,
        description="Leave out characters that have no stroke data instead of writing nothing",
    )
    data_path: StringProperty(
        name="Stroke Data",
        default="",
        subtype="FILE_PATH",
        description="Your own stroke data (Make Me a Hanzi graphics.txt or a folder of "
        "<char>.json), used before the bundled 9,574 characters; empty: the bundled set",
    )
    cell: IntProperty(
        name="Cell",
        default=1,
        min=1,
        description="The cell Write Cell Again writes anew (1: the first written)",
    )


def _is_empty(_self, obj):
    return obj.type == "EMPTY"


def _is_mesh(_self, obj):
    return obj.type == "MESH"


_DEFAULT_PAPER_SPEC = paper_from_preset(load_preset("paper", DEFAULT_PAPER))


class HAIRY_BRUSH_PG_settings(bpy.types.PropertyGroup):
    brush_object: PointerProperty(
        name="Brush Empty",
        type=bpy.types.Object,
        poll=_is_empty,
        description="Empty whose location is the brush base and whose rotation (Euler ZYX: "
        "X = forward deflection q, Y = sideways deflection d, Z = rotation r) tilts the brush",
    )
    paper_object: PointerProperty(
        name="Paper Plane", type=bpy.types.Object, poll=_is_mesh, description="The paper plane"
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
        name="Width (mm)",
        default=200.0,
        min=PAPER_MM_RANGE[0],
        max=PAPER_MM_RANGE[1],
        update=_paper_size_changed,
        description="Paper width in millimetres; the paper plane follows (200 mm = 0.2 m)",
    )
    paper_height_mm: FloatProperty(
        name="Height (mm)",
        default=200.0,
        min=PAPER_MM_RANGE[0],
        max=PAPER_MM_RANGE[1],
        update=_paper_size_changed,
        description="Paper height in millimetres; the paper plane follows (200 mm = 0.2 m)",
    )
    px_per_mm: FloatProperty(
        name="Resolution (px/mm)",
        default=5.0,
        min=PX_PER_MM_RANGE[0],
        max=PX_PER_MM_RANGE[1],
        description="Paper pixels per millimetre (image size = paper size x resolution)",
    )
    brush_preset: EnumProperty(
        name="Brush Preset",
        items=presets.ITEMS["brush"],
        default=DEFAULT_BRUSH,
        update=_brush_changed,
        description="The kind of brush: its hair length (where it touches the paper) and its "
        "brush quality values",
    )
    paper_preset: EnumProperty(
        name="Paper Preset",
        items=presets.ITEMS["paper"],
        default=DEFAULT_PAPER,
        update=_paper_changed,
        description="The kind of paper: its colour, ink capacity, fibre and paper quality values",
    )
    ink_preset: EnumProperty(
        name="Ink Preset",
        items=presets.ITEMS["ink"],
        default=DEFAULT_INK,
        update=_ink_changed,
        description="The kind of ink: its colour, wetness and dip depth",
    )
    paper_color: FloatVectorProperty(
        name="Paper Colour",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=_DEFAULT_PAPER_SPEC.color,
        description="Colour of the blank paper (set by the paper preset)",
    )
    paper_capacity: FloatProperty(
        name="Ink Capacity",
        default=_DEFAULT_PAPER_SPEC.capacity,
        min=PAPER_CAPACITY_RANGE[0],
        max=PAPER_CAPACITY_RANGE[1],
        soft_max=10.0,
        description="How much ink a pixel of paper holds before the rest spreads to its "
        "neighbours: lower bleeds more (raw xuan 0.55, sized xuan 1, smooth paper 1000)",
    )
    paper_fibre: FloatProperty(
        name="Fibre",
        default=_DEFAULT_PAPER_SPEC.fibre,
        min=0.0,
        max=1.0,
        subtype="FACTOR",
        description="How much the sheet's grain shows where the hair offers little ink: higher "
        "gives a more mottled grey in dry and fast strokes; 0 = an even grey "
        "(raw xuan 0.4, sized xuan 0.62, smooth paper 0.3)",
    )
    paper_texture: FloatProperty(
        name="Texture",
        default=_DEFAULT_PAPER_SPEC.texture,
        min=0.0,
        max=PAPER_TEXTURE_MAX,
        description="How much the sheet itself shows: the pulp's soft clouds and its fibres, "
        "under and between the ink; 0 = an even colour (raw xuan 0.06, sized xuan 0.05, "
        "smooth paper 0)",
    )
    touch_height_mm: FloatProperty(
        name="Touching Height (mm)",
        default=presets.HAIR_LENGTH_MM[DEFAULT_BRUSH],
        min=0.0,
        options={"HIDDEN"},
        description="The hair length of the brush the scene was last set up for: the brush "
        "touches the paper when its base is this high above it",
    )
    quality: PointerProperty(type=HAIRY_BRUSH_PG_quality)
    ink_color: FloatVectorProperty(
        name="Ink Colour",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=(0.03, 0.03, 0.04),
        description="Colour of the ink: every dip loads it, so a new colour recolours the "
        "recording (except dips given their own colour with Dip in Own Colour)",
    )
    dip_wetness: FloatProperty(
        name="Ink Wetness",
        default=0.9,
        min=0.0,
        max=1.0,
        subtype="FACTOR",
        description="How wet the brush is after the dip: wetter strokes are darker and longer",
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
        name="Sample Rate (Hz)",
        default=120.0,
        min=1.0,
        max=1000.0,
        description="Poses a second that Bake Brush Samples takes from the animated brush",
    )
    seed: IntProperty(
        name="Seed",
        default=0,
        min=0,
        update=_seed_changed,
        description="Seed of the simulation's one random generator: the same seed, the same "
        "artwork",
    )
    seed_of_recording: StringProperty(
        name="Seed of the Recording",
        default="",
        options={"HIDDEN"},
        description="An imported recording's seed too large for Seed (up to 2**64 - 1), used "
        "until Seed is changed",
    )
    sync_frames: BoolProperty(
        name="Follow Frames",
        default=True,
        description="Update the paper image and the primitive objects on every frame change, "
        "so a render of frame N shows the artwork as it was at frame N",
    )
    paint_press_mm: FloatProperty(
        name="Press (mm)",
        default=4.0,
        min=0.0,
        max=60.0,
        description="Live painting: how far the brush base goes below the touching height "
        "while the button is held (mouse wheel changes it)",
    )
    paint_angle_step: FloatProperty(
        name="Angle Step (°)",
        default=2.0,
        min=0.1,
        max=30.0,
        description="Live painting: degrees the brush tilts or turns per press of Q/W, E/R, C/V",
    )
    sequence_dir: StringProperty(
        name="Sequence Folder",
        default="//hairy_brush_frames/",
        subtype="DIR_PATH",
        description="Where Bake Image Sequence writes one paper image per frame (// is the "
        ".blend's folder: save the file first)",
    )
    work: PointerProperty(type=HAIRY_BRUSH_PG_work, name="Write Text")


CLASSES = (HAIRY_BRUSH_PG_quality, HAIRY_BRUSH_PG_work, HAIRY_BRUSH_PG_settings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.hairy_brush = PointerProperty(type=HAIRY_BRUSH_PG_settings)


def unregister():
    del bpy.types.Scene.hairy_brush
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
