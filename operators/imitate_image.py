# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.imitate_image: read a picture of writing (an image datablock or a picture file
Blender can load: PNG of any kind, JPEG, TIFF, OpenEXR, ...),
recover its strokes, their order and widths (``sim.picture``), write it with the brush as Write
Character does and keyframe the brush empty along the writing, so it plays back and renders.
From the sidebar it runs as a modal job (progress bar, Esc stops it; the scene changes only at
the end)."""

from __future__ import annotations

import bpy
import numpy as np
from bpy_extras.io_utils import ImportHelper

from ..blender import checks
from ..blender.jobs import JobOperator
from ..blender.writing import ImitateJob
from ..sim.image.png import SIGNATURE, PNGError, png_header
from ..sim.paper.display import linear_to_srgb
from ..sim.picture.imitate import MAX_DETAIL, PASSES
from ..sim.picture.ink import MAX_PICTURE_PIXELS, MAX_PICTURE_SIDE, ROWS, PictureError
from . import polls


def image_grey(image: bpy.types.Image) -> np.ndarray:
    """An image datablock's pixels as a picture (H, W, C) floats, top row first, as they look:
    a float image (16-bit PNG, OpenEXR, a render) holds linear light, encoded to sRGB here as a
    byte image's pixels already are (an image of data, Non-Color, is read as it is)."""
    w, h = (int(v) for v in image.size)
    if w == 0 or h == 0 or not image.has_data and not _loads(image):
        raise PictureError(f"image '{image.name}' has no pixels (is its file missing?)")
    if w * h > MAX_PICTURE_PIXELS:
        raise PictureError(
            f"image '{image.name}' is {w} x {h} px; at most {MAX_PICTURE_PIXELS} pixels"
        )
    c = image.channels
    buf = np.empty(w * h * c, dtype=np.float32)
    image.pixels.foreach_get(buf)
    pic = buf.reshape(h, w, c)[::-1]
    if image.is_float and not image.colorspace_settings.is_data:
        colour = slice(0, 3 if c >= 3 else 1)  # alpha stays as it is
        for y in range(0, h, ROWS):  # a few rows at a time: no full-size float64 copy
            pic[y : y + ROWS, :, colour] = linear_to_srgb(pic[y : y + ROWS, :, colour])
    return pic


def _loads(image) -> bool:
    try:
        image.pixels[0]  # noqa: B018 - touching the pixels loads a packed or file image
    except (IndexError, RuntimeError):
        return False
    return bool(image.has_data)


def file_picture(path: str) -> np.ndarray:
    """A picture file read through Blender's own image loading (any PNG, JPEG, TIFF, OpenEXR,
    ... Blender reads), in a temporary image datablock removed once its pixels are read. A
    PNG's size is checked from its header first (a huge one is refused before Blender
    decodes it)."""
    try:
        with open(path, "rb") as f:
            png = f.read(len(SIGNATURE)) == SIGNATURE
        if png:
            png_header(path, MAX_PICTURE_SIDE, MAX_PICTURE_PIXELS, any_kind=True)
    except OSError as exc:
        raise PictureError(f"cannot read {path}: {exc.strerror or exc}") from None
    except PNGError as exc:
        raise PictureError(str(exc)) from None
    try:
        img = bpy.data.images.load(path, check_existing=False)
    except RuntimeError as exc:
        raise PictureError(f"{path} is not a picture Blender can read ({exc})") from None
    try:
        if not _loads(img):
            raise PictureError(f"{path} is not a picture Blender can read")
        return image_grey(img)
    finally:
        bpy.data.images.remove(img)


class HAIRY_BRUSH_OT_imitate_image(JobOperator, bpy.types.Operator, ImportHelper):
    """Imitate a picture of writing (dark on a light ground): read its strokes, their order
    and widths, write it with the brush and keyframe the brush empty along the writing"""

    bl_idname = "hairy_brush.imitate_image"
    bl_label = "Imitate Picture"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".png"
    filter_glob: bpy.props.StringProperty(
        default="*.png;*.jpg;*.jpeg;*.tif;*.tiff;*.exr;*.bmp;*.webp", options={"HIDDEN"}
    )
    image: bpy.props.StringProperty(
        name="Image",
        default="",
        description="An image datablock to imitate (its name); empty: the chosen picture file",
    )
    size_mm: bpy.props.FloatProperty(
        name="Size (mm)",
        default=0.0,
        min=0.0,
        max=2000.0,
        description="The picture's size in mm (a flat paper becomes this square; on a surface "
        "the picture is laid at this size under the brush); 0 sizes the writing to the brush",
    )
    passes: bpy.props.IntProperty(
        name="Practice Passes",
        default=PASSES,
        min=1,
        max=8,
        description="How often each stroke is written, measured against the picture's ink "
        "and corrected before the best pass is kept",
    )
    detail: bpy.props.IntProperty(
        name="Detail (px)",
        default=512,
        min=64,
        max=MAX_DETAIL,
        description="The picture is read at this many pixels a side (its strokes, widths "
        "and ink); the writing itself is at the paper's resolution",
    )

    fit_brush: bpy.props.BoolProperty(
        name="Brush for the Size",
        default=True,
        description="A size other than the brush's own for the picture's strokes is written "
        "with the brush made smaller or larger in proportion (off: the brush as it is)",
    )
    piece: bpy.props.BoolProperty(
        name="Several Characters",
        default=False,
        description="The picture is a piece of several characters in columns: read them right "
        "to left, top to bottom, and write each in its own square of the paper",
    )

    @classmethod
    def poll(cls, context):
        return polls.brush_and_paper(cls, context)

    def invoke(self, context, event):
        self.in_background = True
        if self.image:
            return self.execute(context)
        return ImportHelper.invoke(self, context, event)

    def execute(self, context):
        scene = context.scene
        try:
            checks.require_brush_and_paper(checks.settings(scene))
            if self.image:
                img = bpy.data.images.get(self.image)
                if img is None:
                    raise PictureError(f"no image named '{self.image}'")
                picture, name = image_grey(img), img.name
            else:
                picture, name = file_picture(self.filepath), bpy.path.basename(self.filepath)
            job = ImitateJob(
                scene,
                picture,
                name,
                self.size_mm,
                self.passes,
                self.detail,
                self.piece,
                self.fit_brush,
            )
        except (*checks.USER_ERRORS, ValueError, OSError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return self.run_job(context, job)
