# SPDX-License-Identifier: GPL-3.0-or-later
"""The paper image datablock: made and sized to the paper, shown from the engine's paper (only
the tiles that changed), its ink density image for reliefs, and packed into the .blend."""

from __future__ import annotations

import bpy
import numpy as np

from ..sim.image.matte import ink_matte
from ..sim.paper import display
from ..sim.paper.texture import paper_tone
from . import checks, runtime

PAPER_IMAGE = "HairyBrush Paper"
PAPER_TAG = "hairy_brush_paper"
SHOWN_TAG = "hairy_brush_shown"  # on the paper image: how many samples it shows
DENSITY_TAG = "hairy_brush_density"  # on the paper image: its ink density image (relief)
MATTE_TAG = "hairy_brush_matte"  # on the paper image: its ink matte image (issue 29.4)


def ensure_paper_image(st, color=(1.0, 1.0, 1.0)) -> bpy.types.Image:
    """The paper image, made (a float image: see sim.display) or resized to the paper."""
    w, h = checks.check_paper_size(st)
    img = st.paper_image
    if img is None:
        img = bpy.data.images.new(PAPER_IMAGE, w, h, alpha=True, float_buffer=True)
        img.generated_color = (*display.encode(color, linear=True), 1.0)
        img[PAPER_TAG] = 1
        st.paper_image = img
    elif tuple(img.size) != (w, h):
        img.scale(w, h)
    return img


def show_paper(img, paper, index: int, overlay=None, whole: bool = False):
    """Show ``paper`` in the image: only the tiles changed since the image was last shown from
    the same paper are converted, then the kept pixels go to Blender in one call. ``index`` (the
    samples simulated) is kept on the image, so undo can show exactly what was seen.
    ``overlay``: a work's grid and seal (sim.writing.work.overlay.Overlay), drawn as ``sim
    render`` draws them (see WorkView). ``whole``: a paper that was not simulated in place (a
    work put together from its cells keeps no record of its changed tiles): every pixel is
    converted."""
    key = img.as_pointer()
    views = runtime.get().views  # paper image (as_pointer) -> the pixels it shows
    view = views.get(key)
    kind = WorkView if overlay is not None or whole else display.PaperView
    if (
        whole
        or type(view) is not kind
        or view.linear != img.is_float
        or getattr(view, "overlay", None) is not overlay
    ):
        linear = img.is_float
        view = display.PaperView(linear) if kind is display.PaperView else WorkView(linear, overlay)
        views[key] = view
    view.refresh(paper)
    if tuple(img.size) != (paper.W, paper.H):
        img.scale(paper.W, paper.H)
    img.pixels.foreach_set(view.flat())
    img.update()
    keep_packed(img)
    img[SHOWN_TAG] = int(index)
    if density_read(img, tag_reliefs(img)):
        show_density(img, paper.ink)
    show_matte(img, paper.ink)


class WorkView:
    """The pixels of a paper with a work's grid under the ink and its seal over it, as
    ``sim.writing.work.overlay.work_image8`` draws them before rounding to 8 bits (the same
    ``Overlay.apply`` on the same visible colour; no overlay: the paper alone): brought up to
    date a band of whole rows at a time, the rows of the tiles that changed (the overlay is
    drawn across whole rows). A new paper (another playback, a work put together from its
    cells) is converted whole, every pixel (not only the tiles it records as changed)."""

    def __init__(self, linear: bool, overlay):
        self.linear, self.overlay = bool(linear), overlay
        self.pixels = None  # (H, W, 4) float32, bottom row first
        self._paper, self._version = None, -1

    def refresh(self, paper) -> int:
        if self._paper is not paper or self.pixels is None or self.pixels.shape[:2] != paper.shape:
            self.pixels = np.ones(paper.shape + (4,), dtype=np.float32)
            rows = [(0, paper.H)]
        else:
            tiles = paper.tiles_since(self._version)
            rows = [paper.tile_box(int(ty), 0)[0] for ty in np.unique(tiles[:, 0])]
            rows = [(r.start, r.stop) for r in rows]
        self._paper, self._version = paper, paper.version
        for y0, y1 in rows:
            for a in range(y0, y1, WORK_BAND_ROWS):
                self._band(paper, a, min(a + WORK_BAND_ROWS, y1))
        return sum(y1 - y0 for y0, y1 in rows) * paper.W

    def _band(self, paper, y0: int, y1: int):
        """Paper rows y0:y1 (bottom first) converted, the overlay drawn on them (top first)."""
        top = paper.H - y1  # the band's first row counted from the top
        band = paper.visible(paper.ink[y0:y1], slice(y0, y1), slice(0, paper.W))
        vis = np.ascontiguousarray(band[::-1], dtype=np.float32)
        if self.overlay is not None:
            vis = self.overlay.apply(vis, top)
        self.pixels[y0:y1, :, :3] = display.encode(np.clip(vis[::-1], 0.0, 1.0), self.linear)

    def flat(self) -> np.ndarray:
        return self.pixels.reshape(-1)


WORK_BAND_ROWS = 256  # rows a work's overlay is drawn on at a time


def tag_reliefs(img) -> set:
    """Objects whose Displace modifier reads the paper image (or its density image) are
    evaluated again: new pixels alone do not move a relief's vertices. Returns the names of
    those of the two images that a relief reads."""
    images = {img.name, img.get(DENSITY_TAG)}
    read = set()
    for obj in bpy.data.objects:
        for mod in obj.modifiers if obj.type == "MESH" else ():
            tex = getattr(mod, "texture", None) if mod.type == "DISPLACE" else None
            if tex is not None and getattr(tex, "image", None) is not None:
                if tex.image.name in images:
                    obj.update_tag()
                    read.add(tex.image.name)
    return read


def density_read(img, read: set) -> bool:
    """Whether the paper image's density image is among the images reliefs read (``read``, from
    tag_reliefs): only then is it refreshed (a whole second image)."""
    name = img.get(DENSITY_TAG)
    return isinstance(name, str) and name in read


def density_image(img, create: bool = False):
    """The paper image's ink density image (a relief that follows the density reads it;
    None when there is none and ``create`` is False)."""
    name = img.get(DENSITY_TAG)
    dens = bpy.data.images.get(name) if isinstance(name, str) else None
    if dens is None and create:
        w, h = img.size
        dens = bpy.data.images.new(f"{img.name} Ink Density", w, h, float_buffer=True)
        dens.colorspace_settings.name = "Non-Color"  # read as it is: the density
        dens[PAPER_TAG] = 1  # packed on save with the paper
        img[DENSITY_TAG] = dens.name
    return dens


def density_of(ink) -> np.ndarray:
    """(H, W) the grey density an image shows of the engine's ``Paper.ink``."""
    return np.clip(ink.mean(axis=2, dtype=np.float32), 0.0, 1.0)


def show_density(img, ink=None):
    """Fill the paper image's density image: the mean of the ink's density (the engine's
    ``Paper.ink``, bottom row first; None: the blank paper), grey. Costs a whole image, so
    only a paper with a density relief has one."""
    dens = density_image(img)
    if dens is None:
        return
    w, h = img.size
    if ink is None:
        write_density(dens, np.zeros((h, w), np.float32))
    else:
        write_density(dens, density_of(ink))


def write_density(dens, density):
    """A density (H, W), bottom row first, into the density image, grey."""
    h, w = density.shape
    if tuple(dens.size) != (w, h):
        dens.scale(w, h)
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = density[..., None]
    dens.pixels.foreach_set(rgba.ravel())
    dens.update()
    keep_packed(dens)


def density_from_image(st, img, texture: float) -> np.ndarray:
    """The ink density (H, W) the paper image shows: 1 - visible / the blank sheet's colour
    (with its ``texture``, for an image of the paper's size), the channels' mean (the inverse
    of ``Paper.rgb``, to the image's precision)."""
    rgb = image_rgb(img)
    if rgb.shape[:2] == checks.paper_pixels(st)[::-1]:
        paper = np.maximum(blank_sheet(st, texture), 1e-6)
    else:
        paper = np.maximum(np.asarray(blank_color(st), np.float32), 1e-6)
    return np.clip(1.0 - rgb / paper, 0.0, 1.0).mean(axis=2)


def show_blank(st, texture: float):
    """The paper image as the blank paper of the scene's paper preset (``texture``: how much
    its sheet shows, ``surfaces.paper_texture``)."""
    color = blank_color(st)
    img = ensure_paper_image(st, color)
    write_image(img, blank_sheet(st, texture))
    img[SHOWN_TAG] = 0
    if density_read(img, tag_reliefs(img)):
        show_density(img)
    show_matte(img)
    return img


def blank_color(st) -> tuple:
    """The blank paper's colour as the engine will simulate it."""
    return tuple(float(c) for c in st.paper_color)


def blank_sheet(st, texture: float) -> np.ndarray:
    """The blank paper (H, W, 3), bottom row first, as the engine will show it: its colour
    with its texture (``sim.paper.texture``: ``texture``, the scene's px/mm and seed)."""
    from .recordings import scene_seed

    w, h = checks.paper_pixels(st)
    color = np.asarray(blank_color(st), np.float32)
    tone = paper_tone(slice(0, h), slice(0, w), float(st.px_per_mm), texture, scene_seed(st))
    return np.clip(color * tone[..., None], 0.0, 1.0)


def write_image(img, rgb_bottom_up: np.ndarray):
    """Engine RGB (H, W, 3), bottom row first (Blender's order) -> image pixels."""
    runtime.get().views.pop(img.as_pointer(), None)
    h, w, _ = rgb_bottom_up.shape
    if tuple(img.size) != (w, h):
        img.scale(w, h)
    rgba = np.empty((h, w, 4), np.float32)
    rgba[..., :3] = display.encode(rgb_bottom_up, linear=img.is_float)
    rgba[..., 3] = 1.0
    img.pixels.foreach_set(rgba.ravel())
    img.update()
    keep_packed(img)


def image_rgb(img) -> np.ndarray:
    """The image's visible colour (H, W, 3), bottom row first, as the engine's ``Paper.rgb``."""
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    rgb = a.reshape(img.size[1], img.size[0], 4)[..., :3]
    return display.linear_to_srgb(rgb).astype(np.float32) if img.is_float else rgb


def keep_packed(img):
    """Pack the image again when it lost its packing: Image > Save As points the datablock at
    the file it wrote and unpacks it, and Cycles reads an unpacked file image from its file, not
    from the pixels the paper shows. Costs one encoding, once after such a save."""
    if img.packed_file is None and img.source == "FILE":
        pack_image(img)


def pack_image(img):
    """Keep the pixels inside the .blend (nothing in side files the user can lose): float
    images as OpenEXR (lossless), byte images as PNG. Done when the file is saved."""
    ext, fmt = (".exr", "OPEN_EXR") if img.is_float else (".png", "PNG")
    if not img.filepath_raw or not img.filepath_raw.endswith(ext):
        img.filepath_raw = f"//{img.name}{ext}"
    img.file_format = fmt
    img.pack()


def matte_image(img, create: bool = False):
    """The paper image's ink matte image (straight-alpha RGBA: alpha the ink's density, RGB its
    colour; sim.image.matte), which follows the paper image from then on; None when there is
    none and ``create`` is False."""
    name = img.get(MATTE_TAG)
    matte = bpy.data.images.get(name) if isinstance(name, str) else None
    if matte is None and create:
        w, h = img.size
        matte = bpy.data.images.new(f"{img.name} Ink Matte", w, h, alpha=True, float_buffer=True)
        matte.alpha_mode = "STRAIGHT"
        matte[PAPER_TAG] = 1  # packed on save with the paper
        img[MATTE_TAG] = matte.name
    return matte


def show_matte(img, ink=None):
    """Fill the paper image's matte image (if it has one) from the engine's ``Paper.ink``
    (bottom row first, Blender's order; None: the blank paper): the matte's colour is
    sRGB-encoded like the paper's, so a float image holds it decoded to linear light."""
    matte = matte_image(img)
    if matte is None:
        return
    if ink is None:
        ink = np.zeros((img.size[1], img.size[0], 3), np.float32)
    h, w = ink.shape[:2]
    if tuple(matte.size) != (w, h):
        matte.scale(w, h)
    rgba = ink_matte(ink)
    rgba[..., :3] = display.encode(rgba[..., :3], linear=matte.is_float)
    matte.pixels.foreach_set(rgba.ravel())
    matte.update()
