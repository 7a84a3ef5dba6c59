# SPDX-License-Identifier: GPL-3.0-or-later
"""The name seal (印章) stamped near the signature: a square stone whose characters are fitted
into it (one filling it; two side by side, read from the right; three as one tall column and
two; four in two columns), printed in vermilion seal paste. 白文 (``baiwen``, intaglio): the
characters are carved away and show the paper in a red square. 朱文 (``zhuwen``, relief): the
characters and a frame print red.

A stamp is never a flat red square (model addition, nothing of it is in the paper): the paste
lies unevenly (a slow field of density), leaves small specks where it did not take (more toward
the edges, where the pressure falls off), the stone's edges and the carving are not ruler
straight (the shapes' edges wander by a noise field), and the stamp is set down a little
askew. Everything is drawn from the outline polygons of the stroke data (no brush) and seeded,
so the recording rebuilds it exactly."""

from __future__ import annotations

import math

import numpy as np

from ..outline import fill, stroke_polygons

STYLES = ("baiwen", "zhuwen")
VERMILION = (0.78, 0.15, 0.11)  # seal paste (朱砂印泥), linear RGB reflectance
MAX_SEAL_CHARS = 9
BORDER = 0.07  # 白文: red margin round the characters; 朱文: the frame's inner edge
FRAME = 0.055  # 朱文: the frame's width (shares of the side)
GAP = 0.1  # between the characters' boxes
TILT_SD_DEG = 1.2  # how askew the stamp is set down
EDGE_WANDER = 0.006  # shares of the side the edges wander by
STROKE_GROW = 0.010  # the carved strokes made bolder (a seal's strokes are even and strong)
SUPERSAMPLE = 2


def char_boxes(n: int) -> list[tuple[float, float, float, float]]:
    """The boxes (u0, v0, u1, v1), u right and v down in [0, 1], of n characters in reading
    order: columns from the right, each from the top."""
    if n <= 0:
        return []
    if n == 3:  # one tall column on the right, two on the left
        return [(0.5, 0.0, 1.0, 1.0), (0.0, 0.0, 0.5, 0.5), (0.0, 0.5, 0.5, 1.0)]
    cols = 1 if n == 1 else 2 if n <= 4 else math.ceil(math.sqrt(n))
    rows = math.ceil(n / cols)
    out = []
    for k in range(n):
        c, r = divmod(k, rows)
        u1 = 1.0 - c / cols
        out.append((u1 - 1.0 / cols, r / rows, u1, (r + 1) / rows))
    return out


def _noise(shape, cell_px: float, rng) -> np.ndarray:
    """Value noise in [0, 1] varying over ``cell_px`` pixels (smoothstep between lattice
    values)."""
    h, w = shape
    gh, gw = int(h / cell_px) + 3, int(w / cell_px) + 3
    lat = rng.random((gh, gw))
    y = np.arange(h) / cell_px
    x = np.arange(w) / cell_px
    iy, ix = np.floor(y).astype(int), np.floor(x).astype(int)
    fy, fx = y - iy, x - ix
    fy, fx = fy * fy * (3 - 2 * fy), fx * fx * (3 - 2 * fx)
    a = lat[iy][:, ix] * (1 - fx) + lat[iy][:, ix + 1] * fx
    b = lat[iy + 1][:, ix] * (1 - fx) + lat[iy + 1][:, ix + 1] * fx
    return a * (1 - fy)[:, None] + b * fy[:, None]


def _glyph_polys(char: dict, box, to_px) -> list[list[np.ndarray]]:
    """The character's strokes (polygons in pixels of the stamp) fitted into ``box``: its own
    extent stretched to fill the box, as a seal carver fills the stone."""
    polys = stroke_polygons(char)
    pts = np.concatenate([p for s in polys for p in s])
    lo, hi = pts.min(axis=0), np.maximum(pts.max(axis=0), pts.min(axis=0) + 1.0)
    u0, v0, u1, v1 = box
    out = []
    for stroke in polys:
        mapped = []
        for p in stroke:
            t = (p - lo) / (hi - lo)  # data units, y up -> [0, 1] in the box, v down
            u = u0 + t[:, 0] * (u1 - u0)
            v = v0 + (1.0 - t[:, 1]) * (v1 - v0)
            mapped.append(to_px(np.stack([u, v], axis=1)))
        out.append(mapped)
    return out


def _grow(mask: np.ndarray, r: float) -> np.ndarray:
    """The mask dilated by a disc of radius r pixels."""
    k = int(math.floor(r))
    if k < 1:
        return mask
    out = mask.copy()
    h, w = mask.shape
    for dy in range(-k, k + 1):
        for dx in range(-k, k + 1):
            if dx * dx + dy * dy > r * r or (dx == 0 and dy == 0):
                continue
            out[max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] |= mask[
                max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
            ]
    return out


def stamp(chars: list[dict], style: str, side_px: float, seed: int) -> np.ndarray:
    """The stamp's paste cover (alpha in [0, 1], float32, top row first) on a square patch of
    ``ceil(side_px * 1.1) + 4`` pixels whose centre is the seal's centre (drawn at twice the
    resolution and averaged down, so its edges are smooth)."""
    if style not in STYLES:
        raise ValueError(f"seal style must be one of {STYLES}, got {style!r}")
    rng = np.random.Generator(np.random.PCG64([int(seed), 0x5EA1]))
    n = int(math.ceil(side_px * 1.1)) + 4
    big, side = SUPERSAMPLE * n, SUPERSAMPLE * side_px
    tilt = math.radians(float(np.clip(rng.standard_normal(), -2, 2)) * TILT_SD_DEG)
    c, s = math.cos(tilt), math.sin(tilt)

    def to_px(uv):  # stamp's unit square (v down) -> patch pixels, turned by the tilt
        d = (np.asarray(uv, dtype=float) - 0.5) * side
        return np.stack(
            [big / 2 + c * d[:, 0] - s * d[:, 1], big / 2 + s * d[:, 0] + c * d[:, 1]], 1
        )

    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    inner = BORDER + (FRAME if style == "zhuwen" else 0.0)
    glyphs = np.zeros((big, big), dtype=bool)
    for char, (u0, v0, u1, v1) in zip(chars, char_boxes(len(chars)), strict=True):
        g = GAP / 2
        box = tuple(inner + (1 - 2 * inner) * np.array([u0 + g, v0 + g, u1 - g, v1 - g]))
        for stroke in _glyph_polys(char, box, to_px):
            glyphs |= fill(stroke, big)
    glyphs = _grow(glyphs, STROKE_GROW * side)
    stone = fill([to_px(square)], big)
    if style == "baiwen":
        paste = stone & ~glyphs
    else:
        frame = stone & ~fill([to_px(FRAME + (1 - 2 * FRAME) * square)], big)
        paste = frame | glyphs
    alpha = _print(paste, side, rng)
    return alpha.reshape(n, SUPERSAMPLE, n, SUPERSAMPLE).mean(axis=(1, 3)).astype(np.float32)


def _box(a: np.ndarray, r: int) -> np.ndarray:
    """The mean of a over (2r + 1)^2 pixels around each (edges held)."""
    for axis in (0, 1):
        p = np.pad(a, [(r + 1, r) if k == axis else (0, 0) for k in (0, 1)], mode="edge")
        c = np.cumsum(p, axis=axis, dtype=np.float64)
        hi = np.take(c, np.arange(2 * r + 1, c.shape[axis]), axis=axis)
        lo = np.take(c, np.arange(0, c.shape[axis] - 2 * r - 1), axis=axis)
        a = ((hi - lo) / (2 * r + 1)).astype(np.float32)
    return a


def _print(paste: np.ndarray, side_px: float, rng) -> np.ndarray:
    """The uneven print of the paste: wandering edges, density, specks, falling pressure
    toward the stone's edges."""
    n = paste.shape[0]
    # edges wander: the shape box-blurred over the wander's reach, cut at a level the noise
    # moves (the 0.5 level is the edge; the noise moves it by up to about the reach)
    reach = max(int(round(EDGE_WANDER * side_px)), 1)
    soft = _box(paste.astype(np.float32), reach)
    wander = _noise((n, n), max(side_px * 0.03, 2.0), rng) - 0.5
    cover = soft + 0.7 * wander > 0.5
    # pressure: full in the middle, less toward the edges and corners of the stone
    yy, xx = np.mgrid[0:n, 0:n]
    r = np.maximum(np.abs(xx - n / 2), np.abs(yy - n / 2)) / (side_px / 2)
    pressure = 1.0 - 0.5 * np.clip((r - 0.7) / 0.3, 0, 1) ** 2
    pressure *= 0.85 + 0.3 * _noise((n, n), max(side_px * 0.35, 3.0), rng)
    # specks where the paste did not take: clustered (a speck noise only where a slower field
    # lets it), more where the pressure is low
    cluster = _noise((n, n), max(side_px * 0.08, 2.0), rng)
    fine = _noise((n, n), max(side_px * 0.015, 1.5 * SUPERSAMPLE), rng)
    speck = fine * cluster > 0.48 * np.clip(pressure, 0.3, 1.0) + 0.08
    density = 0.86 + 0.14 * _noise((n, n), max(side_px * 0.12, 2.0), rng)
    grain = 0.93 + 0.07 * rng.random((n, n))
    alpha = np.where(cover & ~speck, np.clip(density * grain * np.minimum(pressure, 1.0), 0, 1), 0)
    return alpha.astype(np.float32)


def seal_chars_in_box(text: str) -> list[str]:
    return [c for c in text if not c.isspace()][:MAX_SEAL_CHARS]
