# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the ink lands (the design's part 3, see the package): SurfacePaper gives the engine
the frames of the samples and the chart's origin, and splats a sample's chart marks into the
texels under them, in groups of texture tiles that do not touch."""

from __future__ import annotations

import copy
import math
from dataclasses import replace

import numpy as np

from ..core.exact import matmul
from .chart import frame_parts, step_to
from .mesh import Surface, SurfaceError
from .query import TriangleGrid
from .texels import TexelPoints, TexelTiles

CHART_SIDES = 11.0  # the chart's origin, in paper sides from its own 0 (samples reach 10)
CHART_SHAPE = (1 << 30, 1 << 30)  # the chart's pixel grid is unbounded for the marks
NORMAL_DOT_MIN = 0.0  # a texel whose normal faces away from the frame's is on another side
DEPTH_TOL_MM = 0.5  # plus half the mark's radius: how far off the tangent plane a texel may be
GROUP_TILE = 64  # texture tiles by which one sample's texels are grouped for the paper


# ------------------------------------------------------------------------------ the paper
class SurfacePaper:
    """What the engine needs to write on a surface: the frames of the recording's samples,
    the chart's origin, and the splat of a sample's chart marks into the texture."""

    def __init__(self, surface: Surface, frames, W: int, H: int, ppm: float, side_mm: float):
        self.surface = surface
        self.ppm = float(ppm)
        self.tiles = TexelTiles(surface, W, H)  # texel points, built where the marks reach
        self.W, self.H, self.side_mm = W, H, float(side_mm)
        # the chart is offset so that its pixels are never negative (samples reach 10 sides)
        self.offset = math.ceil(CHART_SIDES * side_mm * self.ppm) / self.ppm
        self.near = TriangleGrid(surface)  # the frames of live samples
        self._set_frames(frames)

    @property
    def texels(self) -> TexelPoints:
        """Every texel's point (builds them all: for tests and pictures, not the splat)."""
        return self.tiles.all()

    def _set_frames(self, frames):
        self.frames = list(np.asarray(frames, dtype=float)) if frames is not None else []
        self.given = len(self.frames)  # the recording's; the rest follow live samples
        self._followed = {}  # frame index -> the chart position it was made for

    def with_frames(self, frames) -> SurfacePaper:
        """The same surface and texels (the costly part) for another recording's frames."""
        other = copy.copy(self)
        other._set_frames(frames)
        return other

    def frame(self, i: int, sample) -> np.ndarray:
        """Sample i's frame. A sample painted live (beyond the recording's frames) gets one that
        follows the previous frame to its chart position; a stroke taken back and painted again
        gets new ones."""
        xy = (float(sample[0]), float(sample[1]))
        if i >= self.given and i < len(self.frames) and self._followed.get(i) != xy:
            del self.frames[i:]
        while len(self.frames) <= i:
            if not self.frames:
                raise SurfaceError("a surface recording's first sample has no frame")
            k = len(self.frames)
            self.frames.append(step_to(self.surface, self.frames[-1], xy, self.near))
            self._followed[k] = xy
        return self.frames[i]

    def engine_sample(self, i: int, sample) -> np.ndarray:
        """Sample i on the offset chart the marks are rasterised in."""
        self.frame(i, sample)
        s = np.array(sample, dtype=float)
        s[:2] += self.offset
        return s

    def splat(self, marks, i: int) -> list[list]:
        """Sample i's chart marks as texture marks, in groups of texels far enough apart (a
        mark straddling a seam lands in two places of the texture) that the paper takes each
        group as its own window; [] when no texel is under the marks."""
        marks = [mk for mk in marks if mk.rows.size]
        if not marks:
            return []
        c, p, t, b, n = frame_parts(self.frames[i])
        c = c + self.offset
        ppm = self.ppm
        x0 = min(mk.ix0 for mk in marks) / ppm
        y0 = min(mk.iy0 for mk in marks) / ppm
        x1 = max(mk.ix0 + mk.shape[1] for mk in marks) / ppm
        y1 = max(mk.iy0 + mk.shape[0] for mk in marks) / ppm
        tol = DEPTH_TOL_MM + math.hypot(x1 - x0, y1 - y0) / 4
        # the box in 3D around the marks' rectangle on the tangent plane, tol off it
        corners = np.array(
            [
                p + (x - c[0]) * t + (y - c[1]) * b + h * n
                for x in (x0, x1)
                for y in (y0, y1)
                for h in (-tol, tol)
            ]
        )
        tiles = self.tiles
        cand = tiles.query_box(corners.min(axis=0), corners.max(axis=0))
        d = tiles.xyz[cand] - p
        ok = (np.abs(matmul(d, n)) <= tol) & (matmul(tiles.normal(cand), n) > NORMAL_DOT_MIN)
        cand, d = cand[ok], d[ok]
        col = np.floor((c[0] + matmul(d, t)) * ppm).astype(np.int64)
        row = np.floor((c[1] + matmul(d, b)) * ppm).astype(np.int64)
        out = []
        for mk in marks:
            tm = self._texture_mark(mk, row, col, cand)
            if tm is not None:
                out.append(tm)
        return group_marks(out)

    def _texture_mark(self, mk, row, col, texel):
        """One chart mark as the texels that fall in its inked pixels (None: none do)."""
        h, w = mk.shape
        r, cc = row - mk.iy0, col - mk.ix0
        inwin = (r >= 0) & (r < h) & (cc >= 0) & (cc < w)
        if not inwin.any():
            return None
        lut = np.full(h * w, -1, dtype=np.int64)
        lut[mk.rows * w + mk.cols] = np.arange(mk.rows.size)
        k = lut[r[inwin] * w + cc[inwin]]
        hit = k >= 0
        if not hit.any():
            return None
        k = k[hit]
        tex = texel[inwin][hit].astype(np.int64)
        ty, tx = tex // self.W, tex % self.W
        iy0, ix0 = int(ty.min()), int(tx.min())
        return _replace_pixels(
            mk, iy0, ix0, ty - iy0, tx - ix0, k, (int(ty.max()) - iy0 + 1, int(tx.max()) - ix0 + 1)
        )


def _replace_pixels(mk, iy0, ix0, rows, cols, k, shape):
    """A copy of the mark at other pixels, each with the ink of the mark's pixel k."""
    return replace(
        mk,
        iy0=iy0,
        ix0=ix0,
        rows=rows,
        cols=cols,
        wet=mk.wet[k],
        col=mk.col[k],
        lateral=mk.lateral[k],
        depth=mk.depth[k],
        shape=shape,
    )


def group_marks(marks) -> list[list]:
    """Split texture marks into groups whose GROUP_TILE tiles do not touch (each mark cut at
    the gaps): the paper deposits each group in its own window, so a mark on both sides of a
    seam costs its texels, not the texture between them."""
    if not marks:
        return []
    keys = [_tile_keys(mk) for mk in marks]
    tiles = np.unique(np.concatenate(keys))
    if tiles.size == 1 or np.ptp(tiles // _KEY) <= 1 and np.ptp(tiles % _KEY) <= 1:
        return [marks]  # one tile or a block of touching ones: one window
    label = _tile_components([divmod(int(k), _KEY) for k in tiles])
    lab_of = np.array([label[divmod(int(k), _KEY)] for k in tiles])
    if np.unique(lab_of).size == 1:
        return [marks]
    groups: dict[int, list] = {}
    for mk, key in zip(marks, keys, strict=True):
        lab = lab_of[np.searchsorted(tiles, key)]
        for g in np.unique(lab).tolist():
            groups.setdefault(g, []).append(_subset(mk, lab == g))
    return [groups[g] for g in sorted(groups)]


_KEY = 1 << 20  # tile row * _KEY + tile column


def _tile_keys(mk) -> np.ndarray:
    return ((mk.rows + mk.iy0) // GROUP_TILE) * _KEY + (mk.cols + mk.ix0) // GROUP_TILE


def _tile_components(tiles: list) -> dict:
    """Connected components (8-neighbourhood, so groups are at least a tile apart)."""
    label, left = {}, set(tiles)
    comp = 0
    for t0 in tiles:
        if t0 in label:
            continue
        stack = [t0]
        label[t0] = comp
        left.discard(t0)
        while stack:
            y, x = stack.pop()
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    nb = (y + dy, x + dx)
                    if nb in left:
                        left.discard(nb)
                        label[nb] = comp
                        stack.append(nb)
        comp += 1
    return label


def _subset(mk, sel):
    rows, cols = mk.rows[sel] + mk.iy0, mk.cols[sel] + mk.ix0
    iy0, ix0 = int(rows.min()), int(cols.min())
    shape = (int(rows.max()) - iy0 + 1, int(cols.max()) - ix0 + 1)
    k = np.flatnonzero(sel)
    return _replace_pixels(mk, iy0, ix0, rows - iy0, cols - ix0, k, shape)
