# SPDX-License-Identifier: GPL-3.0-or-later
"""The 3D point of every texel (the design's part 3, see the package): each UV triangle
rasterised in the texture with a pad around it, a tile at a time when the marks first reach
it."""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np

from .mesh import Surface
from .query import BoxGrid

PAD_TEXELS = 1.5  # texels around each UV triangle that get its 3D points (filtering at seams)


# ------------------------------------------------------------------------------ texels
@dataclass(frozen=True)
class TexelPoints:
    """The 3D point (and face normal) of every texel a UV triangle (or its pad) covers."""

    index: np.ndarray  # (K,) flat texel index row * W + col, rows from the bottom (v = 0)
    xyz: np.ndarray  # (K, 3) mm
    normal: np.ndarray  # (K, 3)
    W: int
    H: int


def texel_points(surface: Surface, W: int, H: int) -> TexelPoints:
    """Every texel's 3D point in a W x H texture (see TexelTiles, which builds them only where
    the writing reaches)."""
    return TexelTiles(surface, W, H).all()


TEXEL_TILE = 16  # texels a side of the tiles in which texel points are built on first use
BUILD_CHUNK = 1 << 20  # candidate texels rasterised together at most (bounds the memory)


class TexelTiles:
    """The 3D point of every texel a UV triangle (or its pad of PAD_TEXELS) covers, built a
    TEXEL_TILE tile at a time when a splat first reaches it and kept: so no frame change or
    first stroke pays for the whole texture, only for the tiles its marks touch. A texel's
    point comes from the triangle it lies deepest in (its signed distance in texels to the
    nearest edge, the largest; the later triangle on a tie), whatever the order in which the
    tiles are built.

    Made at once, in time proportional to the triangles: each triangle's part in each tile it
    covers (a "piece": its texel rectangle there) and that piece's 3D box (the affine image of
    the rectangle holds every point the triangle gives its texels there), binned in a BoxGrid.
    A query's 3D box finds the pieces, hence the tiles, that may hold texels in it."""

    def __init__(self, surface: Surface, W: int, H: int):
        self.surface, self.W, self.H = surface, int(W), int(H)
        uvp = surface.uvs * np.array([W, H]) - 0.5  # texel centres at integers
        lo = np.maximum(np.floor(uvp.min(axis=1) - PAD_TEXELS).astype(np.int64) + 1, 0)
        hi = np.minimum(np.ceil(uvp.max(axis=1) + PAD_TEXELS).astype(np.int64), [W, H])
        self.coef = _edge_functions(uvp)
        # each edge function over its gradient's length: the signed distance (texels) to it
        with np.errstate(invalid="ignore"):
            norm = np.hypot(self.coef[:, :, 0], self.coef[:, :, 1])[:, :, None]
            self.dist = (self.coef / norm).astype(np.float32)
        tri = np.flatnonzero(np.isfinite(self.coef).all(axis=(1, 2)) & (hi > lo).all(axis=1))
        self.tiles_x = -(-self.W // TEXEL_TILE)
        n_tiles = self.tiles_x * -(-self.H // TEXEL_TILE)
        key, ptri, rect = self._pieces(tri, lo, hi)
        order = np.lexsort((ptri, key))  # by tile, then triangle
        self.key, self.tri, self.rect = key[order], ptri[order], rect[order]
        plo, phi = self._piece_boxes()
        self.box_lo, self.box_hi = plo, phi
        cell = float(np.clip(np.median((phi - plo).max(axis=1)), 1.0, 50.0)) if len(plo) else 1.0
        self.grid = BoxGrid(plo, phi, cell)
        self.owner = np.full(self.W * self.H, -1, np.int32)  # the triangle that gives its point
        self.xyz = np.zeros((self.W * self.H, 3), np.float32)  # pages touched when built only
        self.built = np.zeros(n_tiles, bool)
        self._lock = threading.Lock()

    def _pieces(self, tri, lo, hi):
        """(tile key, triangle, texel rectangle x0, x1, y0, y1) of each triangle in each tile
        its padded rectangle covers."""
        T = TEXEL_TILE
        t0, t1 = lo[tri] // T, (hi[tri] - 1) // T
        ext = t1 - t0 + 1
        n = ext[:, 0] * ext[:, 1]
        j = np.repeat(np.arange(len(tri)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        tx, ty = t0[j, 0] + k % ext[j, 0], t0[j, 1] + k // ext[j, 0]
        ptri = tri[j]
        rect = np.stack(
            [
                np.maximum(lo[ptri, 0], tx * T),
                np.minimum(hi[ptri, 0], tx * T + T),
                np.maximum(lo[ptri, 1], ty * T),
                np.minimum(hi[ptri, 1], ty * T + T),
            ],
            axis=1,
        )
        return ty * self.tiles_x + tx, ptri, rect

    def _piece_boxes(self):
        """Each piece's 3D box: its texel rectangle's corners through the triangle's map."""
        corners = self.surface.corners[self.tri]
        pts = []
        for x, y in ((0, 2), (0, 3), (1, 2), (1, 3)):
            xs = self.rect[:, x] - (x == 1)  # the last texel of [x0, x1)
            ys = self.rect[:, y] - (y == 3)
            bary = _bary(self.coef[self.tri], xs.astype(float), ys.astype(float))
            pts.append(np.einsum("kj,kjd->kd", bary, corners))
        pts = np.stack(pts)
        return pts.min(axis=0) - 1e-3, pts.max(axis=0) + 1e-3  # float32 points: a margin

    def query_box(self, lo, hi) -> np.ndarray:
        """The texels (flat indices, by tile then row) whose points lie in the box [lo, hi],
        looked for in the tiles that may hold them; those tiles are built first if they are
        not yet."""
        lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
        p = self.grid.query_box(lo, hi)
        p = p[((self.box_lo[p] <= hi) & (self.box_hi[p] >= lo)).all(axis=1)]
        tiles = np.unique(self.key[p])
        with self._lock:  # a kept paper is shared by a worker (writing) and Blender's thread
            self.build(tiles[~self.built[tiles]])
        idx = self._tile_texels(tiles)
        idx = idx[self.owner[idx] >= 0]
        xyz = self.xyz[idx]
        return idx[((xyz >= lo) & (xyz <= hi)).all(axis=1)]

    def _tile_texels(self, tiles) -> np.ndarray:
        T = TEXEL_TILE
        r = np.arange(T)
        ys = (tiles // self.tiles_x)[:, None, None] * T + r[None, :, None]
        xs = (tiles % self.tiles_x)[:, None, None] * T + r[None, None, :]
        ys, xs = np.broadcast_arrays(ys, xs)
        inside = (ys < self.H) & (xs < self.W)
        return (ys * self.W + xs)[inside]

    def normal(self, idx) -> np.ndarray:
        return self.surface.face_normals[self.owner[idx]].astype(np.float32)

    def build(self, tiles):
        """Rasterise the triangles' pieces in these tiles (a chunk of tiles at a time)."""
        if len(tiles) == 0:
            return
        s = np.searchsorted(self.key, tiles, "left")
        e = np.searchsorted(self.key, tiles, "right")
        self.built[tiles[e == s]] = True  # no triangle there: no texel
        tiles, s, e = tiles[e > s], s[e > s], e[e > s]
        if len(tiles) == 0:
            return
        r = self.rect
        size = (r[:, 1] - r[:, 0]) * (r[:, 3] - r[:, 2])
        per_tile = np.add.reduceat(size, s)
        start = 0
        while start < len(tiles):
            cum = np.cumsum(per_tile[start:])
            stop = start + max(int(np.searchsorted(cum, BUILD_CHUNK)), 1)
            n = e[start:stop] - s[start:stop]
            pos = np.repeat(s[start:stop] - (np.cumsum(n) - n), n) + np.arange(int(n.sum()))
            self._rasterise(pos)
            self.built[tiles[start:stop]] = True
            start = stop

    def _rasterise(self, pieces):
        """Each texel of these pieces goes to its deepest triangle; its point is made."""
        r = self.rect[pieces]
        nx = r[:, 1] - r[:, 0]
        n = nx * (r[:, 3] - r[:, 2])
        j = np.repeat(np.arange(len(pieces)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        x, y = r[j, 0] + k % nx[j], r[j, 2] + k // nx[j]
        tri = self.tri[pieces][j]
        c = self.dist[tri]  # float32: the pad's edge needs no more
        xf, yf = x.astype(np.float32), y.astype(np.float32)
        depth = c[:, 0, 0] * xf + c[:, 0, 1] * yf + c[:, 0, 2]
        for i in (1, 2):
            np.minimum(depth, c[:, i, 0] * xf + c[:, i, 1] * yf + c[:, i, 2], out=depth)
        keep = depth >= -PAD_TEXELS
        flat, depth, tri, x, y = (y * self.W + x)[keep], depth[keep], tri[keep], x[keep], y[keep]
        order = np.lexsort((tri, depth, flat))  # the last of each texel: deepest, then latest
        flat, tri, x, y = flat[order], tri[order], x[order], y[order]
        last = np.r_[flat[1:] != flat[:-1], True] if flat.size else np.zeros(0, bool)
        flat, tri, x, y = flat[last], tri[last], x[last], y[last]
        bary = _bary(self.coef[tri], x.astype(float), y.astype(float))
        self.xyz[flat] = np.einsum("kj,kjd->kd", bary, self.surface.corners[tri])
        self.owner[flat] = tri

    def all(self) -> TexelPoints:
        """Every texel's point (all tiles built): tests, pictures."""
        with self._lock:
            self.build(np.flatnonzero(~self.built))
        idx = np.flatnonzero(self.owner >= 0).astype(np.int32)
        return TexelPoints(idx, self.xyz[idx], self.normal(idx), self.W, self.H)


def _edge_functions(uvp) -> np.ndarray:
    """(T, 3, 3): for each triangle and corner i, (A, B, C) with A x + B y + C its barycentric
    coordinate at texel (x, y); NaN for a triangle of no area."""
    a, b, c = uvp[:, 0], uvp[:, 1], uvp[:, 2]
    den = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(np.abs(den) > 1e-14, 1.0 / den, np.nan)
    out = np.empty((len(uvp), 3, 3))
    for i, (p, q) in enumerate(((b, c), (c, a), (a, b))):  # corner i: the edge opposite it
        out[:, i, 0] = (p[:, 1] - q[:, 1]) * inv
        out[:, i, 1] = (q[:, 0] - p[:, 0]) * inv
        out[:, i, 2] = (p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]) * inv
    return out


def _bary(coef, x, y) -> np.ndarray:
    return coef[:, :, 0] * x[:, None] + coef[:, :, 1] * y[:, None] + coef[:, :, 2]
