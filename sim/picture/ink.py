# SPDX-License-Identifier: GPL-3.0-or-later
"""The ink of a picture of writing (dark writing on a light ground), numpy only: the picture is
fitted into the em box (a square, the paper's colour round it), the paper's uneven level
(light, shading, stains) divided out, the ink's darkness thresholded by Otsu's method, specks
removed and pin-holes filled. A picture that holds no writing is refused with one message."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.params import ParameterError
from ..image import morph as M
from ..image.filters import _gaussian, otsu

MAX_PICTURE_SIDE = 8192
MAX_PICTURE_PIXELS = 32 * 2**20
MIN_PICTURE_SIDE = 16
TILES = 8  # the paper's level is read in tiles of 1/TILES of the picture's side
MIN_CONTRAST = 0.15  # darkness the darkest ink must reach over the paper
MIN_SEPARATION = 0.7  # Otsu's between-class share of the darkness's variance (a blurred photo of
# writing with toned ink: 0.75-0.85; a photo of a scene: 0.72, and far too much ink)
INK_SHARE = (0.002, 0.4)  # of the em box: less is no writing, more is not writing on paper
MAX_PIECES = 64  # separate pieces of ink (after specks are removed)
SPECK = 2e-4  # a piece of ink smaller than this share of the em box is a speck
SEAL_CHROMA = 0.3  # max - min of a pixel's RGB above which it is a colour, not ink or paper
FILL_MIN, FILL = 0.5, 0.8  # writing smaller than FILL_MIN of the picture is framed to fill FILL
FRAME = (0.03, 0.25)  # a piece of ink lying within the first share of the side from the em box's
# edges, and as long as the second along them, is a frame or the page's edge, not writing
PIN_HOLE = 4e-4  # a hole in the ink smaller than this share of the em box is filled
STREAK = 0.3  # flying white: paper narrower than twice this share of the strokes' typical
# half-width, inside one piece of ink (a streak along a stroke), or across one stroke broken
# in two pieces (``_across``), is ink
ACROSS_REACH = 3.0  # ... the pieces' ink within this many half-widths of the gap tells which
ACROSS_RATIO = 1.5  # ... and are about as wide across the line through the gap
LUMA = tuple(np.float32(w) for w in (0.2126, 0.7152, 0.0722))  # Rec. 709 luminance weights
ROWS = 256  # a picture is turned into luminance this many rows at a time (its float copies)


class PictureError(ParameterError):
    """The picture holds no writing this can imitate (blank, dark, a photo, ...)."""


@dataclass
class Ink:
    """The picture's ink on the em box's n x n grid (top row first)."""

    mask: np.ndarray  # (n, n) bool
    darkness: np.ndarray  # (n, n) float in [0, 1]: 0 paper, 1 black
    threshold: float
    separation: float  # Otsu's between-class variance over the total: how two-toned it is


def grey_of(img, name: str = "the picture") -> np.ndarray:
    """Luminance in [0, 1] (float32) of a picture (H, W[, C]) of uint8 or floats in [0, 1], C in
    1..4; an alpha channel is laid over white paper. The picture is converted ROWS rows at a
    time: a picture at the size limit is never copied whole as floats per channel."""
    a = np.asarray(img)
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3 or a.shape[2] not in (1, 2, 3, 4) or a.size == 0:
        raise PictureError(f"{name} is not an image (shape {tuple(np.shape(img))})")
    h, c = a.shape[0], a.shape[2]
    lum = np.empty(a.shape[:2], dtype=np.float32)
    coloured = np.zeros(a.shape[:2], dtype=bool) if c >= 3 else None
    neutral_dark = 0  # pixels of dark neutral ink (the writing, beside a coloured seal)
    for y in range(0, h, ROWS):
        part = _unit(a[y : y + ROWS, :, : 3 if c >= 3 else 1], name)
        if c >= 3:
            r, g, b = part[..., 0], part[..., 1], part[..., 2]
            lum[y : y + ROWS] = r * LUMA[0] + g * LUMA[1] + b * LUMA[2]
            chroma = np.maximum(np.maximum(r, g), b) - np.minimum(np.minimum(r, g), b)
            coloured[y : y + ROWS] = chroma > SEAL_CHROMA
            dark = (lum[y : y + ROWS] < 0.5) & (chroma < SEAL_CHROMA / 2)
            neutral_dark += int(np.count_nonzero(dark))
        else:
            lum[y : y + ROWS] = part[..., 0]
    if coloured is not None:
        _without_seals(lum, coloured, neutral_dark)
    if c in (2, 4):  # over white paper
        for y in range(0, h, ROWS):
            alpha = _unit(a[y : y + ROWS, :, c - 1], name)
            lum[y : y + ROWS] *= alpha
            lum[y : y + ROWS] += 1.0 - alpha
    return lum


def _unit(part: np.ndarray, name: str) -> np.ndarray:
    """Some of a picture's rows as float32 in [0, 1] (uint8 over 255; floats clipped)."""
    if part.dtype == np.uint8:
        out = part.astype(np.float32)
        out /= np.float32(255.0)
        return out
    src = part if np.issubdtype(part.dtype, np.floating) else part.astype(np.float64)
    if not np.isfinite(src).all():
        raise PictureError(f"{name} has pixels that are not numbers")
    return np.clip(src, 0.0, 1.0, out=np.empty(src.shape, dtype=np.float32))


def _without_seals(lum: np.ndarray, coloured: np.ndarray, neutral_dark: int) -> None:
    """Strongly coloured marks (a red seal, a coloured stamp) taken as paper, in place, when the
    picture also holds dark neutral ink (the writing); writing that is all in one colour
    (vermilion, indigo) is kept."""
    if coloured.any() and neutral_dark / lum.size > INK_SHARE[0]:
        lum[coloured] = np.quantile(lum[~coloured], 0.9, overwrite_input=True)  # the paper's


EXR_MAGIC = b"\x76\x2f\x31\x01"
PILLOW_HINT = "pip install pillow"


def load_picture(path) -> np.ndarray:
    """A picture file's luminance, read by Pillow when it is installed (the command line's
    optional dependency: PNG of any depth, palette, grey, alpha or interlace, JPEG, TIFF, BMP,
    WebP, ...); without it only an 8-bit non-interlaced PNG, by ``sim.image.png``, and anything
    else is refused naming ``pip install pillow``. A PNG's size is checked from its header
    before anything is decoded. (Inside Blender, Blender's own image loading reads pictures:
    operators/imitate_image.py.)"""
    from ..image.png import SIGNATURE, PNGKindError, png_header, read_png

    try:
        with open(path, "rb") as f:
            head = f.read(len(SIGNATURE))
    except OSError as exc:
        raise PictureError(f"cannot read {path}: {exc.strerror or exc}") from None
    if head.startswith(EXR_MAGIC):
        raise PictureError(
            f"{path} is OpenEXR: Imitate Picture in Blender reads it; for the command line save "
            "it as PNG or TIFF"
        )
    png = head == SIGNATURE
    if png:
        png_header(path, MAX_PICTURE_SIDE, MAX_PICTURE_PIXELS, any_kind=True)
    image = _pillow()
    if image is not None:
        return grey_of(_read_pillow(image, path), str(path))
    if not png:
        raise PictureError(
            f"{path} is not a PNG; other formats (JPEG, TIFF, ...) need Pillow ({PILLOW_HINT})"
        )
    try:
        return grey_of(read_png(path, MAX_PICTURE_SIDE, MAX_PICTURE_PIXELS), str(path))
    except PNGKindError as exc:
        raise PictureError(f"{exc}; Pillow reads it ({PILLOW_HINT})") from None


def _pillow():
    """Pillow's Image module, or None when Pillow is not installed."""
    try:
        from PIL import Image
    except ImportError:
        return None
    return Image


def _read_pillow(image, path) -> np.ndarray:
    """A picture through Pillow, its size checked before it is decoded: (H, W[, C]) uint8, or
    floats in [0, 1] for a 16-bit or float grey picture (Pillow keeps those in 32-bit modes)."""
    try:
        with image.open(path) as im:
            w, h = im.size
            if max(w, h) > MAX_PICTURE_SIDE or w * h > MAX_PICTURE_PIXELS:
                raise PictureError(
                    f"{path} is {w} x {h} px; at most {MAX_PICTURE_SIDE} a side and "
                    f"{MAX_PICTURE_PIXELS} pixels"
                )
            return _pillow_array(im)
    except (OSError, ValueError, SyntaxError, image.DecompressionBombError) as exc:
        if isinstance(exc, PictureError):
            raise
        raise PictureError(f"{path} is not a picture this can read: {exc}") from None


def _pillow_array(im) -> np.ndarray:
    """A Pillow image's pixels in a form ``grey_of`` reads."""
    if im.mode.startswith("I;16") or im.mode == "I":  # 16-bit grey (PNG, TIFF)
        return np.asarray(im, dtype=np.float32) / np.float32(65535.0)
    if im.mode == "F":  # float grey (TIFF)
        return np.asarray(im, dtype=np.float32)
    if im.mode in ("1", "L"):
        return np.asarray(im.convert("L"))
    if im.mode in ("LA", "La"):
        return np.asarray(im.convert("LA"))
    alpha = "A" in im.getbands() or "transparency" in im.info
    return np.asarray(im.convert("RGBA" if alpha else "RGB"))


def _paper(grey: np.ndarray) -> float:
    return float(np.quantile(grey, 0.9))


def _shrunk(grey: np.ndarray, n: int) -> tuple[np.ndarray, int]:
    """The picture block-averaged by halves while its longer side is 2n or more (``M.resize``
    would average those blocks of the square anyway), and the factor it shrank by: a picture
    at the size limit is read without a full-size square of it."""
    f = 1
    while max(grey.shape) >= 2 * n and min(grey.shape) >= 2:
        hh, ww = grey.shape[0] // 2 * 2, grey.shape[1] // 2 * 2
        grey = grey[:hh, :ww].reshape(hh // 2, 2, ww // 2, 2).mean(axis=(1, 3))
        f *= 2
    return grey, f


def _square(grey: np.ndarray, n: int) -> np.ndarray:
    """The picture centred in a square of its paper's colour, resampled to n x n."""
    h, w = grey.shape
    s = max(h, w)
    out = np.full((s, s), _paper(grey), dtype=grey.dtype)
    out[(s - h) // 2 : (s - h) // 2 + h, (s - w) // 2 : (s - w) // 2 + w] = grey
    return M.resize(out, n, n)


def _check_ground(grey: np.ndarray, name: str) -> None:
    h, w = grey.shape
    if min(h, w) < MIN_PICTURE_SIDE:
        raise PictureError(f"{name} is {w} x {h} px; at least {MIN_PICTURE_SIDE} px a side")
    if float(np.median(grey)) < 0.3:
        raise PictureError(
            f"{name} is mostly dark (median brightness {np.median(grey):.2f}); it needs dark "
            "writing on a light ground"
        )


def _clean(mask: np.ndarray) -> np.ndarray:
    """Specks and frames (``_frames``) removed, flying white inside a stroke closed
    (``_streaks_closed``), pin-holes (flying white inside a stroke, scan dust) filled."""
    n2 = mask.size
    mask = _without_grid_lines(mask)
    lab, k = M.label(mask)
    if k:
        area = np.bincount(lab.ravel(), minlength=k + 1)
        keep = area >= max(SPECK * n2, 0.02 * area[1:].max())
        keep[0] = False
        keep[_frames(lab, k)] = False
        mask = keep[lab]
    mask = _without_ruled_lines(_streaks_closed(mask))
    holes, k = M.label(~mask)
    if k:
        area = np.bincount(holes.ravel(), minlength=k + 1)
        border = np.unique(np.concatenate([holes[0], holes[-1], holes[:, 0], holes[:, -1]]))
        fill = area < PIN_HOLE * n2
        fill[0] = False
        fill[border] = False
        mask = mask | fill[holes]
    return mask


def _frames(lab: np.ndarray, k: int) -> np.ndarray:
    """The labels (of ``k`` in ``lab``) of the pieces of ink that lie wholly in a band
    FRAME[0] of the side wide round the em box's edges and run FRAME[1] of the side or more
    along them: the ruled frame of a copybook's square (红格, 米字格) or the page's edge that a
    photograph or a scan cut tight round one character shows. Writing crosses the band, it does
    not lie in it (read as strokes, a frame's lines set the imitation's box, and every stroke
    was measured against it: a copybook scan's 居 at box IoU 0.10). (Beyond the paper's Sec. 9.)
    """
    n = lab.shape[0]
    band = max(int(FRAME[0] * n), 1)
    ring = np.ones(lab.shape, dtype=bool)
    ring[band:-band, band:-band] = False
    inside = np.bincount(lab[~ring].ravel(), minlength=k + 1) == 0
    out = inside & (_lengths(lab, k) >= FRAME[1] * n)
    out[0] = False
    return np.flatnonzero(out)


def _lengths(lab: np.ndarray, k: int) -> np.ndarray:
    """The longer side of each piece's box (pixels; index 0, the paper, 0 or less)."""
    n = max(lab.shape)
    ys, xs = np.nonzero(lab)
    ids = lab[ys, xs]
    lo_y, hi_y = np.full(k + 1, n), np.zeros(k + 1, dtype=np.int64)
    lo_x, hi_x = np.full(k + 1, n), np.zeros(k + 1, dtype=np.int64)
    np.minimum.at(lo_y, ids, ys)
    np.maximum.at(hi_y, ids, ys)
    np.minimum.at(lo_x, ids, xs)
    np.maximum.at(hi_x, ids, xs)
    return np.maximum(hi_y - lo_y, hi_x - lo_x) + 1


RULED = (0.25, 0.4)  # a piece of ink as long as the first share of the side or more, and
# on average thinner than the second share of the strokes' typical width, is a ruled line (0.15
# left a copybook square's double top line, 2 px lines 2 px apart, as a stroke)


def _without_ruled_lines(mask: np.ndarray) -> np.ndarray:
    """The ink without the pieces that are ruled lines anywhere in the picture: at least
    RULED[0] of the side long (their box's longer side) and on average (area over length)
    thinner than RULED[1] of the strokes' typical width (twice ``_half_width`` of the largest
    piece, which is writing: thin lines and ribbons would take the typical width down). A copybook's
    grid (米字格, a 田字格's middle lines, a square's side a little inside the crop) printed grey
    or black, not red, reads as ink; a brush's stroke as long is about as wide as the others,
    a grid's line a pixel or two (a scan of 冰 cut from its page: a grid line 175 px long and
    1 px wide beside it, read as two strokes, set the imitation's box). Looked for once a dry
    stroke's ribbons are closed into one (``_streaks_closed``). (Beyond the paper's Sec. 9, as
    ``_frames``.)"""
    lab, k = M.label(mask)
    if not k:
        return mask
    area = np.bincount(lab.ravel(), minlength=k + 1)
    area[0] = 0
    width = 2.0 * _half_width(lab == int(area.argmax()))  # the largest piece's: writing
    length = np.maximum(_lengths(lab, k), 1)
    ruled = (length >= RULED[0] * lab.shape[0]) & (area / length < RULED[1] * width)
    ruled[0] = False
    return mask & ~ruled[lab] if ruled.any() else mask


GRID_LINE = (0.3, 0.15, 2.0, 0.5)  # a copybook grid's line crossing the writing: ink at most
# the first share of the strokes' typical width thick across a row (or column), with the fourth
# share of paper clear on both sides, in runs at least the third times that width long,
# together the second share of the side or more along the row (or out to the picture's edge)
WIDTH_QUANTILE = 0.8  # ... the strokes' typical width read at this quantile of the ink's depth


def _run_lengths(mask: np.ndarray, clear: float = 0.0) -> np.ndarray:
    """Each pixel's run of ink along its row (0 on paper); with ``clear``, 0 as well where the
    paper on either side of its run is shorter than that (the picture's edge is clear)."""
    rows, starts, ends = M._runs(mask)
    length = ends - starts
    value = length
    if clear:
        same = np.r_[False, rows[1:] == rows[:-1]]  # a run before it on its row
        before = np.where(same, starts - np.r_[0, ends[:-1]], np.inf)
        after = np.where(np.r_[same[1:], False], np.r_[starts[1:], 0] - ends, np.inf)
        value = np.where((before >= clear) & (after >= clear), length, 0)
    first = np.cumsum(length) - length  # each run's first pixel in the runs' pixels
    cols = np.arange(int(length.sum())) - np.repeat(first - starts, length)
    out = np.zeros(mask.shape, dtype=np.int64)
    out[np.repeat(rows, length), cols] = np.repeat(value, length)
    return out


def _grid_lines(mask: np.ndarray, width: float) -> np.ndarray:
    """The pixels of level lines (rows): ink thinner than GRID_LINE[0] of ``width`` across,
    with paper GRID_LINE[3] of it clear on either side (a dry stroke's ribbons lie close
    together: they are a stroke); on every row whose such ink runs, in runs of GRID_LINE[2]
    widths or more, together GRID_LINE[1] of the side or out to the picture's edge (a grid's
    line past the writing), all its such ink (the short pieces between a stroke and another
    line too)."""
    across = _run_lengths(mask.T, clear=GRID_LINE[3] * width).T
    thin = mask & (across > 0) & (across <= max(GRID_LINE[0] * width, 1.0))
    long_runs = thin & (_run_lengths(thin) >= GRID_LINE[2] * width)
    lined = long_runs.sum(axis=1) >= GRID_LINE[1] * mask.shape[1]
    lined |= long_runs[:, 0] | long_runs[:, -1]  # a long run out to the picture's edge
    return thin & lined[:, None]


def _without_grid_lines(mask: np.ndarray) -> np.ndarray:
    """The ink without the lines of a copybook's grid that cross or touch the writing (a
    田字格's or 米字格's middle lines, a square's frame that a stroke's foot rests on): level
    and upright lines as thin as a pen's across and running along a sixth of the side or out
    to the picture's edge (GRID_LINE); where a stroke crosses the line the stroke's ink stays.
    Joined to the writing, a line is no piece of its own (``_without_ruled_lines``): a
    copybook 學 in a black square whose foot touched the frame was read with the frame as
    strokes, and its box was the square's (box IoU 0.49 -> 0.81 with the lines dropped).
    (Beyond the paper's Sec. 9, as ``_frames``.)"""
    if not mask.any():
        return mask
    # the strokes' typical width from the depth of the ink (a band's depths spread evenly up
    # to its half-width): the lines, long and a pixel or two deep, would take the outline's
    # length up and ``_half_width`` down
    width = 2.0 * float(np.quantile(M.edt(mask)[mask], WIDTH_QUANTILE)) / WIDTH_QUANTILE
    for _ in range(2):  # where lines cross, each is thick across the other: once more
        mask = mask & ~_grid_lines(mask, width)
        mask = mask & ~_grid_lines(mask.T, width).T
    return mask


def _streaks_closed(mask: np.ndarray) -> np.ndarray:
    """The ink with its flying white closed: a brush running dry or fast leaves white streaks
    along a stroke and gaps across it, narrower than the stroke; read as paper they split the
    stroke into ribbons, whose skeletons become strokes of their own (the brush's own 木 on raw
    xuan, its vertical read as two). The ink is closed (grown and shrunk again) by STREAK of the
    strokes' typical half-width (``_half_width``), and the paper
    so filled kept where it lies within one piece of ink, or across one stroke that a dry gap
    broke in two (``_across``): paper between two separate strokes (a dot that stops short of
    a stroke) stays paper. (Beyond the paper's Sec. 9: its dry-brush
    texture, Sec. 6, is what a picture of brush writing shows; reading it back is not described.)
    """
    if not mask.any():
        return mask
    r = _half_width(mask)
    rho = STREAK * r
    if rho < 1.0:
        return mask
    mask, across = _closed_within(mask, rho)
    if across:  # the streaks within pieces closed first: a gap across is then one of its own
        lab = M.label(mask)[0]
        parts, keep = _closing(mask, rho, lab)
        for b in np.flatnonzero(keep < 0):
            keep[b] = _across(parts == b, lab, *_pair(parts == b, lab), r)
        mask = mask | (keep > 0)[parts]
    return mask


def _closing(mask: np.ndarray, rho: float, lab: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The paper the closing by ``rho`` fills, as labelled parts, and for each part 1 when it
    touches one piece of ink (``lab``), -1 when it touches two or more, 0 when none."""
    near = _grown(mask, rho, False)
    filled = ~_grown(~near, rho, True) & ~mask
    parts, k = M.label(filled)
    lo = np.full(k + 1, np.iinfo(np.int64).max)
    hi = np.zeros(k + 1, dtype=np.int64)
    ids = parts[filled]
    for dy, dx in M.NEIGHBOURS_8:
        nb = M._shift(lab, dy, dx, 0)[filled]
        touch = nb > 0
        np.minimum.at(lo, ids[touch], nb[touch])
        np.maximum.at(hi, ids[touch], nb[touch])
    keep = np.where(lo == hi, 1, np.where(hi > 0, -1, 0))
    keep[0] = 0
    return parts, keep


def _half_width(mask: np.ndarray) -> float:
    """The strokes' typical half-width: the ink's area over its outline's length (pixels of
    ink beside paper), as for a long band of that half-width."""
    edge = np.zeros_like(mask)
    for dy, dx in ((0, 1), (0, -1), (1, 0), (-1, 0)):
        edge |= ~M._shift(mask, dy, dx, False)
    return float(np.count_nonzero(mask)) / max(int(np.count_nonzero(edge & mask)), 1)


def _grown(mask: np.ndarray, rho: float, fill: bool) -> np.ndarray:
    """The mask grown by a disc of radius ``rho`` (``fill``: beyond the picture's edge)."""
    k = int(np.floor(rho))
    out = mask.copy()
    for dy in range(-k, k + 1):
        for dx in range(-k, k + 1):
            if (dy or dx) and dy * dy + dx * dx <= rho * rho:
                out |= M._shift(mask, dy, dx, fill)
    return out


def _closed_within(mask: np.ndarray, rho: float) -> tuple[np.ndarray, bool]:
    """The ink with the paper its closing fills within one piece made ink, and whether the
    closing also filled paper between pieces."""
    parts, keep = _closing(mask, rho, M.label(mask)[0])
    return mask | (keep > 0)[parts], bool((keep < 0).any())


def _pair(bridge: np.ndarray, lab: np.ndarray) -> tuple[int, int]:
    """The two pieces of ink a bridge touches most (0 for a missing one)."""
    grown = bridge.copy()
    for dy, dx in M.NEIGHBOURS_8:
        grown |= M._shift(bridge, dy, dx, False)
    ids, counts = np.unique(lab[grown & (lab > 0)], return_counts=True)
    top = ids[np.argsort(counts)[::-1][:2]]
    return (int(top[0]), int(top[1])) if len(top) == 2 else (0, 0)


def _chord(lab: np.ndarray, piece: int, y: float, x: float, way: np.ndarray, limit: float) -> float:
    """The length of the line through (y, x) along ``way`` (unit x, y) inside ``piece`` of
    ``lab`` (at most ``limit`` either side)."""
    h, w = lab.shape
    out = 0.0
    for sign in (1.0, -1.0):
        s = 0.0
        while s < limit:
            yy = int(round(y + sign * (s + 1) * way[1]))
            xx = int(round(x + sign * (s + 1) * way[0]))
            if not (0 <= yy < h and 0 <= xx < w) or lab[yy, xx] != piece:
                break
            s += 1.0
        out += s
    return out + 1.0


def _across(bridge: np.ndarray, lab: np.ndarray, a: int, b: int, r: float) -> bool:
    """Whether paper ``bridge`` filled between pieces ``a`` and ``b`` of the ink (labels of
    ``lab``) is a dry gap across one stroke: the pieces' ink near it (within ACROSS_REACH of
    the half-width ``r``) lies on either side of it, and across the line between them both are
    about as wide (within ACROSS_RATIO of each other, and a stroke's width, not a stroke's
    length: a dot that stops short of a horizontal faces the horizontal's length)."""
    if not a or not b:
        return False
    ys, xs = np.nonzero(bridge)
    cy, cx = ys.mean(), xs.mean()
    reach = ACROSS_REACH * r
    h, w = lab.shape
    y0, y1 = max(int(cy - reach), 0), min(int(cy + reach) + 1, h)
    x0, x1 = max(int(cx - reach), 0), min(int(cx + reach) + 1, w)
    win = lab[y0:y1, x0:x1]
    yy, xx = np.mgrid[y0:y1, x0:x1]
    near = (yy - cy) ** 2 + (xx - cx) ** 2 <= reach * reach
    mids = []
    for piece in (a, b):
        sel = near & (win == piece)
        if np.count_nonzero(sel) < 4:
            return False
        mids.append((float(yy[sel].mean()), float(xx[sel].mean())))
    join = np.array([mids[1][1] - mids[0][1], mids[1][0] - mids[0][0]])
    join /= max(float(np.linalg.norm(join, axis=-1)), 1e-9)
    across = np.array([-join[1], join[0]])
    limit = 2.0 * reach
    wide = [_chord(lab, p, y, x, across, limit) for p, (y, x) in zip((a, b), mids, strict=True)]
    return max(wide) <= ACROSS_RATIO * min(wide) and max(wide) < 2.0 * limit


def _separation(d: np.ndarray, t: float) -> float:
    lo, hi = d[d <= t], d[d > t]
    if lo.size == 0 or hi.size == 0 or d.var() <= 0:
        return 0.0
    w0 = lo.size / d.size
    return float(w0 * (1 - w0) * (hi.mean() - lo.mean()) ** 2 / d.var())


def _read_ink(grey: np.ndarray, n: int, name: str) -> Ink:
    """Darkness over the paper's level on the em box, Otsu's threshold, cleaned."""
    sq = _square(grey, n)
    paper = M.paper_level(sq, max(n // TILES, 4))
    dark = np.clip(1.0 - sq / paper, 0.0, 1.0)
    dark = _gaussian(dark, max(n / 512.0, 0.5))  # scan noise
    if float(np.quantile(dark, 0.9999)) < MIN_CONTRAST:
        raise PictureError(f"{name} shows no writing: nothing is darker than the paper")
    t = max(otsu(dark), MIN_CONTRAST / 2)
    return Ink(_clean(dark > t), dark, float(t), _separation(dark, t))


def _framed(grey: np.ndarray, small: np.ndarray, f: int, ink: Ink) -> np.ndarray | None:
    """When the writing fills less than FILL_MIN of the picture's side: the picture cut to a
    square round it in which it fills FILL (as a font's character fills its em box), the paper's
    colour beyond the picture's edges. None when it fills the picture already. ``ink`` was read
    off ``small``, the picture shrunk by ``f`` (``_shrunk``); the cut is the full picture's."""
    n = ink.mask.shape[0]
    ys, xs = np.nonzero(ink.mask)
    if ys.size == 0:
        return None
    side = max(np.ptp(ys), np.ptp(xs)) + 1
    if side >= FILL_MIN * n:
        return None
    h, w = grey.shape
    hs, ws = small.shape
    s = max(hs, ws)
    k = s / n  # shrunk picture pixels per em-box pixel
    cy = ((ys.min() + ys.max() + 1) / 2 * k - (s - hs) // 2) * f
    cx = ((xs.min() + xs.max() + 1) / 2 * k - (s - ws) // 2) * f
    size = max(int(round(side * k * f / FILL)), MIN_PICTURE_SIDE)
    y0, x0 = int(round(cy - size / 2)), int(round(cx - size / 2))
    out = np.full((size, size), _paper(small), dtype=grey.dtype)
    ya, yb, xa, xb = max(y0, 0), min(y0 + size, h), max(x0, 0), min(x0 + size, w)
    out[ya - y0 : yb - y0, xa - x0 : xb - x0] = grey[ya:yb, xa:xb]
    return out


def find_ink(grey: np.ndarray, n: int, name: str = "the picture") -> Ink:
    """The ink of a picture's luminance on the em box's n x n grid (the picture cut round the
    writing first when the writing is small in it, ``_framed``); PictureError when it holds no
    writing (blank, mostly dark, no two tones, ink everywhere, too many pieces)."""
    _check_ground(grey, name)
    small, f = _shrunk(grey, n)
    ink = _read_ink(small, n, name)
    framed = _framed(grey, small, f, ink)
    del small
    if framed is not None:
        ink = _read_ink(_shrunk(framed, n)[0], n, name)
    share = ink.mask.mean()
    if ink.separation < MIN_SEPARATION or not INK_SHARE[0] <= share <= INK_SHARE[1]:
        raise PictureError(
            f"{name} does not look like dark writing on paper (ink {100 * share:.1f}% of the "
            f"picture, two-tone {ink.separation:.2f}; writing is {100 * INK_SHARE[0]:g}-"
            f"{100 * INK_SHARE[1]:g}% ink and two-tone above {MIN_SEPARATION})"
        )
    pieces = M.label(ink.mask)[1]
    if pieces > MAX_PIECES:
        raise PictureError(
            f"{name} breaks into {pieces} separate pieces of ink; writing has at most "
            f"{MAX_PIECES} (is it a photo or a page of text?)"
        )
    return ink
