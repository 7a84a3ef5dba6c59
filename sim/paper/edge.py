# SPDX-License-Identifier: GPL-3.0-or-later
"""The hair's edge on an unevenly sized sheet (model addition, not in the paper; issue 26).

The paper's mark is the primitive's cut by the paper (Sec. 6), so a stroke's edge is the edge
of the swept solid: a smooth curve, where real ink on xuan ends in a finely ragged line (at a
few times a zoom a copybook's edges are serrated, never ruled). At a mark's edge the hair only
grazes the sheet: few hairs, little pressure, little liquid. Whether the sheet takes it there
depends on the sheet: its sizing (alum and glue) and pulp lie unevenly, so some places take
the grazing hair's ink and some hold it off. Here a pixel of a mark in the outer band of the
mark is not inked by it (nor wetted: it is left out of the mark, as if the hair did not reach
it) where

    e > 1 - EDGE_BITE * fibre * s,

``e`` the pixel's place between the mark's middle and its edge (Eq. 23's f, the distance from
the primitive's axis in its section, taken between the mark's least f, 0, and its edge, 1, so
that a light touch, whose every pixel lies near the surface, is bitten only at its edge, not
all over), ``s`` in [0, 1] how strongly the sheet holds off the hair there (``sizing``: smooth
value noise in millimetres, EDGE_MM, from the sheet's seed: the same sheet under every mark,
in every window, at any resolution), ``fibre`` the paper's; a pixel the new edge passes
through keeps the share of its colour inside it (over a pixel, as the mark's own edge is
smoothed, ``sim.brush.mark.section_cover``: ragged, not a staircase). As the brush moves, a
pixel near the stroke's edge lies under many marks; it is inked if one of them reaches it
deeply enough: the stroke's edge is its swept outline moved in by up to EDGE_BITE fibre of the
marks' half width, by the sheet's own pattern. Its bumps are as large against the stroke as
the brush is (the band of sparse hair at its edge), a thin hairline as ragged against its width
as a pressed stroke, and no speck stands free (pixels are only taken away, from the edge in).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .texture import _value_noise

EDGE_BITE = 0.2  # at most this share of a mark's half width, times the paper's fibre
EDGE_MM = (0.8, 0.3)  # the sizing's pattern: value noise at these scales (mm), ...
EDGE_SHARE = (0.65, 0.35)  # ... with these weights
EDGE_MIN_PX = 1.5  # no finer than this many pixels (finer than the pixels it would be a stipple)
EDGE_TILE = 64  # pixels a side of the tiles of sizing made once and kept (``_tile``)
EDGE_TILES = 1024  # tiles kept (16 KB each)
_SALT = 64  # the sizing's noises, apart from the paper tone's (``texture``: salts below 16)


def sizing(rows, cols, ppm: float, seed: int) -> np.ndarray:
    """How strongly the sheet holds off a grazing hair at the paper pixels (rows, cols) (arrays
    of one shape, bottom row first), in [0, 1] (float32): each pixel's value is its own, the
    same whatever else is asked with it."""
    y = (np.asarray(rows, dtype=np.float64) + 0.5) / ppm
    x = (np.asarray(cols, dtype=np.float64) + 0.5) / ppm
    n = sum(
        share * _value_noise(x / size, y / size, _SALT + k, seed)
        for k, (size, share) in enumerate(zip(_sizes(ppm), EDGE_SHARE, strict=True))
    )
    return np.clip(0.5 + 0.75 * n, 0.0, 1.0).astype(np.float32)


def _sizes(ppm: float) -> list[float]:
    """The pattern's scales (mm) at ``ppm`` pixels a mm: EDGE_MM, none finer than EDGE_MIN_PX."""
    return [max(mm, EDGE_MIN_PX / ppm) for mm in EDGE_MM]


@lru_cache(maxsize=EDGE_TILES)
def _tile(ty: int, tx: int, ppm: float, seed: int) -> np.ndarray:
    """``sizing`` of the tile (ty, tx) of EDGE_TILE pixels a side, kept (read-only)."""
    r = np.arange(ty * EDGE_TILE, (ty + 1) * EDGE_TILE)[:, None]
    c = np.arange(tx * EDGE_TILE, (tx + 1) * EDGE_TILE)[None, :]
    out = sizing(
        np.broadcast_to(r, (EDGE_TILE, EDGE_TILE)),
        np.broadcast_to(c, (EDGE_TILE, EDGE_TILE)),
        ppm,
        seed,
    )
    out.flags.writeable = False
    return out


def sizing_at(rows, cols, ppm: float, seed: int) -> np.ndarray:
    """``sizing`` at the paper pixels (rows, cols) (1-d integer arrays), read from the kept
    tiles: the same values, each tile of the pattern made once."""
    ty, tx = rows // EDGE_TILE, cols // EDGE_TILE
    ty0, tx0 = int(ty.min()), int(tx.min())
    span = int(tx.max()) - tx0 + 1
    at = (ty - ty0) * span + (tx - tx0)  # the pixel's tile in the pixels' box of tiles
    used = np.flatnonzero(np.bincount(at))
    which = np.zeros(used[-1] + 1, dtype=np.intp)
    which[used] = np.arange(used.size)
    stack = np.stack([_tile(ty0 + int(u) // span, tx0 + int(u) % span, ppm, seed) for u in used])
    return stack[which[at], rows % EDGE_TILE, cols % EDGE_TILE]


def bitten(sizes, depth, rows, cols, ppm: float, seed: int, bite: float):
    """Which pixels of marks the sheet holds off, and the share of the others' colour they
    keep (see the module's note): ``sizes`` the marks' pixel counts (none 0), ``depth`` their
    pixels' Eq. 23 f (all the marks' in a row), ``rows``, ``cols`` the pixels in the paper;
    ``bite`` EDGE_BITE times the paper's fibre. Returns (keep: the indices of the pixels
    kept, None: all, band: the pixels whose colour changes, share: the share each of those
    keeps), or None when none changes. Each mark keeps its middle pixel (its least f)."""
    if bite <= 0.0 or depth.size == 0:
        return None
    starts = np.cumsum(sizes) - sizes
    least = np.minimum.reduceat(depth, starts)
    reach = np.maximum(1.0 - least, 1e-6)
    one = len(sizes) == 1
    # the band: e > 1 - bite, e = (f - least) / reach the pixel's place between the mark's
    # middle (0) and its edge (1), found without e for every pixel
    low = least + (1.0 - bite) * reach
    band = np.flatnonzero(depth > (low[0] if one else np.repeat(low, sizes)))
    if band.size == 0:
        return None
    mark = 0 if one else np.searchsorted(starts, band, side="right") - 1
    e = (depth[band] - least[mark]) / reach[mark]
    s = sizing_at(rows[band], cols[band], ppm, seed)
    # the share of each band pixel inside the bitten edge, over a pixel (``cover``'s
    # smoothing: the edge as smooth as the sheet's pattern, not a staircase of pixels); a
    # mark's half width in pixels that of a disc of its area
    half = np.sqrt(sizes / np.pi)[mark]
    share = np.clip((1.0 - bite * s - e) * half + 0.5, 0.0, 1.0)
    part = share < 1.0
    if not part.any():
        return None
    lost = band[share <= 0.0]
    keep = None
    if lost.size:
        keep = np.ones(depth.size, dtype=bool)
        keep[lost] = False
        keep = np.flatnonzero(keep)
    return keep, band[part], share[part].astype(np.float32)
