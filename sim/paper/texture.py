# SPDX-License-Identifier: GPL-3.0-or-later
"""Model addition (not in the paper): the look of the sheet itself. Xuan paper is not an even
colour: its pulp lies thicker and thinner in soft clouds a few millimetres across, and its
fibres show as fine light and dark threads a millimetre or a few long, lying every way. A scan of
real calligraphy shows both under and between the ink; a flat colour is what gives a rendering
away. ``paper_tone`` gives, per pixel, the factor the sheet's colour is multiplied by there:

    tone = 1 + texture * (MOTTLE * clouds + THREADS * fibres)

``clouds`` is value noise at two scales in millimetres (CLOUD_MM), ``fibres`` thin ridges of
value noise stretched along a few directions (FIBRE_MM long, as thin as a pixel allows), each
in [-1, 1]. ``texture`` is the paper's (0: the flat colour, as before). Every value comes from
a hash of the pixel's place in millimetres and of the sheet's seed (``paper_grain``'s hash):
the same sheet at every step, in any window, tile or band it is asked for, and the same
threads in mm at any resolution. No generator is drawn, so the brush's draws are unchanged.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..core import exact
from .grain import paper_grain

CLOUD_MM = (6.0, 1.6)  # sizes of the pulp's clouds (value noise scales), mm
CLOUD_SHARE = (0.7, 0.3)  # their weights
FIBRE_MM = (2.5, 0.06)  # a fibre's length and thickness (before the pixel's limit), mm
FIBRE_WAYS = 6  # directions the fibres lie in (turned by the seed), each bent by the clouds
FIBRE_BEND_MM = 0.6  # how far the small clouds push a fibre sideways (they curl, not hatch)
FIBRE_SHARE = 0.12  # share of a fibre noise's range at either end that shows as a thread
MOTTLE = 0.6  # the clouds' and ...
THREADS = 0.4  # ... the fibres' share of the texture
TONE_TILES = 2048  # tiles of tone kept (``sheet_tone``; 16 KB each at 64 px: 32 MB at most)
# tiles a process writes to the folder of ``keep_tiles_in`` at most (32 MB at 64 px: a sheet
# rendered whole at 600 dpi does not fill the cache with its every tile)
DISK_TILES = 2048
# tiles kept in the cache folder at most, over every version's subfolder (256 MB at 64 px); the
# oldest go first when a command starts (a cache that only grows fills a user's disk)
KEPT_TILES = 16384
_OCTAVE = 1 << 40  # index offsets that keep the noises' lattices apart
_HALF = 1 << 19  # lattice indices are offset by this to stay positive (sheets < 2**19 cells)


def _lattice(ix, iy, salt: int, seed: int) -> np.ndarray:
    """A value in [0, 1) per lattice point (ix, iy) of noise number ``salt``."""
    index = (iy + _HALF).astype(np.uint64) * np.uint64(2 * _HALF) + (ix + _HALF).astype(np.uint64)
    return paper_grain(index + np.uint64(salt * _OCTAVE), seed)


def _value_noise(u, v, salt: int, seed: int) -> np.ndarray:
    """Smooth value noise in [-1, 1] at lattice coordinates (u, v) (arrays of one shape): the
    lattice values of the window's cells hashed once, then looked up per pixel."""
    iu, iv = np.floor(u), np.floor(v)
    fu, fv = u - iu, v - iv
    fu, fv = fu * fu * (3.0 - 2.0 * fu), fv * fv * (3.0 - 2.0 * fv)
    iu, iv = iu.astype(np.int64), iv.astype(np.int64)
    u0, v0 = int(iu.min()), int(iv.min())
    gu = np.arange(u0, int(iu.max()) + 2)[None, :]
    gv = np.arange(v0, int(iv.max()) + 2)[:, None]
    table = _lattice(
        np.broadcast_to(gu, (gv.size, gu.size)), np.broadcast_to(gv, (gv.size, gu.size)), salt, seed
    )
    flat, stride = table.ravel(), gu.size
    at = (iv - v0) * stride + (iu - u0)
    a, b = flat[at], flat[at + 1]
    c, d = flat[at + stride], flat[at + stride + 1]
    top = a + (b - a) * fu
    return 2.0 * (top + (c + (d - c) * fu - top) * fv) - 1.0


def paper_tone(rows: slice, cols: slice, ppm: float, texture: float, seed: int = 0):
    """The factor (len(rows), len(cols)) float32 the paper's colour takes at the pixels of the
    window (paper array indices, bottom row first; pixel centres at (index + 1/2) / ppm mm).
    1 everywhere for ``texture`` 0."""
    h, w = rows.stop - rows.start, cols.stop - cols.start
    if texture <= 0.0 or h <= 0 or w <= 0:
        return np.ones((max(h, 0), max(w, 0)), dtype=np.float32)
    y = np.broadcast_to(((np.arange(rows.start, rows.stop) + 0.5) / ppm)[:, None], (h, w))
    x = np.broadcast_to(((np.arange(cols.start, cols.stop) + 0.5) / ppm)[None, :], (h, w))
    layers = [_value_noise(x / size, y / size, k, seed) for k, size in enumerate(CLOUD_MM)]
    clouds = sum(share * n for share, n in zip(CLOUD_SHARE, layers, strict=True))
    fibres = np.zeros((h, w))
    length, thick = FIBRE_MM[0], max(FIBRE_MM[1], 0.7 / ppm)
    turn = np.pi * float(paper_grain(np.array([7]), seed)[0])
    bend = FIBRE_BEND_MM * layers[-1]
    for k in range(FIBRE_WAYS):
        a = turn + np.pi * k / FIBRE_WAYS
        sin_a, cos_a = exact.sin_cos(a)
        along = x * cos_a + y * sin_a
        across = -x * sin_a + y * cos_a + bend
        n = _value_noise(along / length, across / thick, len(CLOUD_MM) + k, seed)
        fibres += np.clip((np.abs(n) - (1.0 - FIBRE_SHARE)) / FIBRE_SHARE, 0.0, 1.0) * np.sign(n)
    fibres = np.clip(fibres, -1.0, 1.0)
    return (1.0 + texture * (MOTTLE * clouds + THREADS * fibres)).astype(np.float32)


# where tiles of tone are kept between processes (``keep_tiles_in``), or None: only in memory
_tile_folder: Path | None = None
_tiles_written = [0]  # by this process, up to DISK_TILES


def keep_tiles_in(cache_dir) -> None:
    """Keep the tiles of tone in ``cache_dir`` too (None: stop), so that a new process reads
    them instead of making them again (issue 28: 0.2-0.4 s a process). They are regenerable:
    a subfolder named after a hash of this module's and the grain's source, so a changed
    texture makes new tiles; a missing or unreadable file is made again."""
    global _tile_folder
    _tiles_written[0] = 0  # DISK_TILES for each command (a test runs many in one process)
    if cache_dir is None:
        _tile_folder = None
        return
    here = Path(__file__).resolve().parent
    digest = hashlib.sha256()
    for name in ("texture.py", "grain.py"):
        digest.update((here / name).read_bytes())
    _tile_folder = Path(cache_dir) / f"paper-tone-{digest.hexdigest()[:16]}"
    _prune_kept_tiles(Path(cache_dir), KEPT_TILES - DISK_TILES)


def _prune_kept_tiles(cache_dir: Path, keep: int) -> None:
    """Remove the oldest kept tiles (by when they were written) of every ``paper-tone-*``
    subfolder of ``cache_dir`` down to ``keep``, and the subfolders left empty; a file another
    process removes first, or a folder that cannot be read, is passed over."""
    try:
        folders = [f for f in cache_dir.glob("paper-tone-*") if f.is_dir()]
        entries = [e for f in folders for e in os.scandir(f) if e.name.endswith(".npy")]
    except OSError:
        return
    if len(entries) <= keep:
        return
    dated = []
    for entry in entries:
        try:
            dated.append((entry.stat().st_mtime_ns, entry.path))
        except OSError:
            continue
    dated.sort()
    for _, path in dated[: max(len(dated) - keep, 0)]:
        with contextlib.suppress(OSError):
            os.remove(path)
    for folder in folders:
        with contextlib.suppress(OSError):
            folder.rmdir()  # only when empty


def _tile_file(ty: int, tx: int, tile: int, ppm: float, texture: float, seed: int):
    """The file of a tile in ``_tile_folder`` (the floats by their exact hex)."""
    key = f"{tile}_{float(ppm).hex()}_{float(texture).hex()}_{int(seed)}_{ty}_{tx}"
    return _tile_folder / f"{key}.npy"


def _read_tile(path, tile: int):
    """A kept tile, or None when it is missing or not a whole tile."""
    try:
        tone = np.load(path, allow_pickle=False)
    except (OSError, ValueError):
        return None
    if tone.shape != (tile, tile) or tone.dtype != np.float32:
        return None
    return tone


def _write_tile(path, tone) -> None:
    """Keep a tile (written whole, then renamed: a reader never sees half a file); a folder
    that cannot be written only costs the time of making the tile again next time."""
    if _tiles_written[0] >= DISK_TILES:
        return
    _tiles_written[0] += 1
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "wb") as f:
            np.save(f, tone, allow_pickle=False)
        os.replace(tmp, path)
    except OSError:
        return


@lru_cache(maxsize=TONE_TILES)
def _tile_tone(ty: int, tx: int, tile: int, ppm: float, texture: float, seed: int):
    """``paper_tone`` of the tile (ty, tx), ``tile`` pixels a side, kept (read-only), and in
    ``_tile_folder`` when one is set."""
    path = None if _tile_folder is None else _tile_file(ty, tx, tile, ppm, texture, seed)
    tone = None if path is None else _read_tile(path, tile)
    if tone is None:
        tone = paper_tone(
            slice(ty * tile, (ty + 1) * tile), slice(tx * tile, (tx + 1) * tile), ppm, texture, seed
        )
        if path is not None:
            _write_tile(path, tone)
    tone.flags.writeable = False
    return tone


def _from_tiles(rows: slice, cols: slice, tile: int, tile_of) -> np.ndarray:
    """The window (rows, cols) put together from the tiles ``tile_of(ty, tx)``."""
    out = np.empty((rows.stop - rows.start, cols.stop - cols.start), dtype=np.float32)
    for ty in range(rows.start // tile, (rows.stop - 1) // tile + 1):
        r0, r1 = max(rows.start, ty * tile), min(rows.stop, (ty + 1) * tile)
        for tx in range(cols.start // tile, (cols.stop - 1) // tile + 1):
            c0, c1 = max(cols.start, tx * tile), min(cols.stop, (tx + 1) * tile)
            out[r0 - rows.start : r1 - rows.start, c0 - cols.start : c1 - cols.start] = tile_of(
                ty, tx
            )[r0 - ty * tile : r1 - ty * tile, c0 - tx * tile : c1 - tx * tile]
    return out


def sheet_tone(rows: slice, cols: slice, ppm: float, texture: float, seed: int, tile: int):
    """``paper_tone`` of the window, put together from tiles of ``tile`` pixels that are made
    once and kept (the same values: each pixel's tone is its own): a display refreshing the
    tiles the brush changed, or going back to an earlier frame, makes none of them again."""
    h, w = rows.stop - rows.start, cols.stop - cols.start
    if texture <= 0.0 or h <= 0 or w <= 0:
        return paper_tone(rows, cols, ppm, texture, seed)
    return _from_tiles(
        rows, cols, tile, lambda ty, tx: _tile_tone(ty, tx, tile, ppm, texture, seed)
    )


DRAW_BASE = 0.7  # how well the sheet draws liquid where its tone is even, ...
DRAW_SPREAD = 4.0  # ... and how much its fibres and pulp change that (per unit of tone and of
# the paper's fibre: sized xuan's 0.62 gives 2.5)
DRAW_MIN = 0.05


def sheet_draw(rows: slice, cols: slice, ppm: float, seed: int, tile: int, fibre: float):
    """How well each pixel of the window draws liquid along the sheet (capillary wicking,
    ``sim.paper.wick._wick``), in [DRAW_MIN, 1]: more on a fibre and where the pulp lies thick,
    less between them, as much as the paper's ``fibre`` says (0: evenly); the sheet's own
    clouds and fibres (``paper_tone`` at full texture), so the same in every window and at any
    resolution in mm. Put together from tiles of draw made once and kept (``_tile_draw``: each
    pixel's draw is its own, so the same values as from the window's tone)."""
    if fibre <= 0.0:
        return np.full((rows.stop - rows.start, cols.stop - cols.start), DRAW_BASE, np.float32)
    if rows.stop <= rows.start or cols.stop <= cols.start:
        return _draw_of(sheet_tone(rows, cols, ppm, 1.0, seed, tile), fibre)
    return _from_tiles(rows, cols, tile, lambda ty, tx: _tile_draw(ty, tx, tile, ppm, seed, fibre))


@lru_cache(maxsize=TONE_TILES)
def _tile_draw(ty: int, tx: int, tile: int, ppm: float, seed: int, fibre: float):
    """``sheet_draw`` of the tile (ty, tx), kept (read-only)."""
    draw = _draw_of(_tile_tone(ty, tx, tile, ppm, 1.0, seed), fibre)
    draw.flags.writeable = False
    return draw


def _draw_of(tone, fibre: float) -> np.ndarray:
    """The draw of pixels of tone ``tone`` (full texture) on a paper of ``fibre``."""
    spread = DRAW_SPREAD * fibre
    return np.clip(DRAW_BASE + spread * (tone - 1.0), DRAW_MIN, 1.0).astype(np.float32)
