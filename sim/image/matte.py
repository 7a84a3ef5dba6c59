# SPDX-License-Identifier: GPL-3.0-or-later
"""The ink alone, as a matte for compositing (issue 29.4): RGBA whose alpha is the ink's
density and whose RGB is the ink's colour, *unpremultiplied* (straight alpha).

The paper keeps its ink as a density per channel, d (``sim.paper.Paper.ink``: 0 the paper's
own colour, 1 all its light taken; the visible colour is paper x (1 - d)). The matte takes

    alpha = max over the channels of d,     colour = 1 - d / alpha     (alpha > 0),

so black ink (d equal in all channels) is black with alpha = d, and a coloured ink keeps its hue
at any density: vermilion at half density is vermilion with alpha 0.5. Laid "over" white paper
in the same (display, sRGB-encoded) values the image holds, alpha x colour + (1 - alpha) gives
exactly the paper image's 1 - d; over any other background it is the usual straight-alpha
"over". Where there is no ink (alpha 0) the colour is the ink's mean colour over the sheet, so
a filter that mixes in unpremultiplied neighbours brings no dark or white fringe.

Functions take the paper's ink array (H, W, 3), so the matte plugs in wherever a paper is: the
command line's ``--matte``, composed works, the Blender image datablock and Bake Image
Sequence. numpy only."""

from __future__ import annotations

import numpy as np

from .png import to_uint8

BAND_ROWS = 256  # rows converted at a time (a large sheet needs no full-size float temporaries)


def mean_ink_colour(ink) -> np.ndarray:
    """(3,) the ink's colour weighted by its density over the sheet (black on a blank sheet)."""
    d = np.clip(np.asarray(ink, dtype=np.float32), 0.0, 1.0)
    alpha_sum = float(d.max(axis=-1).sum(dtype=np.float64))
    if alpha_sum <= 0.0:
        return np.zeros(3, np.float32)
    dsum = d.reshape(-1, 3).sum(axis=0, dtype=np.float64)
    return np.clip(1.0 - dsum / alpha_sum, 0.0, 1.0).astype(np.float32)


def ink_matte(ink, fill=None) -> np.ndarray:
    """(H, W, 4) float32 straight-alpha RGBA of an ink density array (H, W, 3), in its own row
    order; ``fill`` (3,) is the colour where there is no ink (default: ``mean_ink_colour``)."""
    d = np.clip(np.asarray(ink, dtype=np.float32), 0.0, 1.0)
    fill = mean_ink_colour(d) if fill is None else np.asarray(fill, np.float32)
    alpha = d.max(axis=-1)
    out = np.empty(d.shape[:-1] + (4,), np.float32)
    inked = alpha > 0.0
    safe = np.where(inked, alpha, 1.0)[..., None]
    out[..., :3] = np.where(inked[..., None], np.clip(1.0 - d / safe, 0.0, 1.0), fill)
    out[..., 3] = alpha
    return out


def paper_matte8(paper) -> np.ndarray:
    """The paper's ink matte as (H, W, 4) uint8, TOP row first (an image file's order), a band
    of rows at a time (``paper``: a sim.paper.Paper, or anything with its ``ink``)."""
    ink = paper.ink
    h = ink.shape[0]
    fill = mean_ink_colour(ink)
    out = np.empty(ink.shape[:-1] + (4,), np.uint8)
    for y0 in range(0, h, BAND_ROWS):
        y1 = min(y0 + BAND_ROWS, h)
        out[y0:y1] = to_uint8(ink_matte(ink[h - y1 : h - y0][::-1], fill))
    return out
