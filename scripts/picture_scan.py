# SPDX-License-Identifier: GPL-3.0-or-later
"""Test pictures for imitating a picture, made here (nothing to license): a "scan" - the
brush's own writing of a character on raw xuan (bleeding, flying white) on tinted paper with
uneven light, stains, a red seal, fibres and scan noise - and a font-like render of a
character's outlines.

    python scripts/picture_scan.py CHAR.json OUT.png [--size N] [--seed S]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.image.filters import _gaussian  # noqa: E402
from sim.writing.outline import rasterise  # noqa: E402

PAPER_TINT = np.array([0.93, 0.87, 0.74])  # old xuan
STAIN_TINT = np.array([0.80, 0.66, 0.45])
SEAL_RED = np.array([0.70, 0.13, 0.10])


def font_picture(char: dict, n: int = 512) -> np.ndarray:
    """The character's outlines filled, black on white, (n, n) grey in [0, 1]."""
    return np.where(rasterise(char, n), 0.05, 0.95)


def piece_picture(columns: list[list[dict]], h: int = 200, gap: int = 40) -> np.ndarray:
    """A piece of characters (font-like renders) in columns, ``columns`` listed right to left,
    each top to bottom, as a piece is read: (H, W) grey in [0, 1]."""
    rows = max(len(c) for c in columns)
    pic = np.full((rows * (h + gap) + gap, len(columns) * (h + gap) + gap), 0.95)
    for k, col in enumerate(columns):
        x = gap + (len(columns) - 1 - k) * (h + gap)
        for r, char in enumerate(col):
            y = gap + r * (h + gap)
            pic[y : y + h, x : x + h] = np.where(rasterise(char, h), 0.05, 0.95)
    return pic


def _template(seed: int = 0, paper: str = "raw_xuan"):
    from sim.core.recording import Recording

    return Recording(
        np.zeros((1, 6)),
        seed=seed,
        brush={"preset": "wolf_stiff"},
        paper_preset=paper,
        ink={"preset": "sumi_black"},
    )


def written(char: dict, n: int = 512, seed: int = 0, paper: str = "raw_xuan"):
    """The brush's own writing of ``char`` (one pass, so it keeps the brush's texture): the
    RGB image and its ink (coverage above half), top row first."""
    from sim.writing.writer import coverage_mask, write_character

    _, _, sim = write_character(char, n, _template(seed, paper), passes=1)
    return sim.image(), coverage_mask(sim)


def written_size_mm(char: dict, seed: int = 0, paper: str = "raw_xuan") -> float:
    """The size (mm) the scan's piece was written at (the writer's own size for ``char``): a
    scan of a real piece has a size too, which ``--size-mm`` gives the imitation."""
    from sim.writing.response import calibrate
    from sim.writing.writer import auto_size_mm

    return auto_size_mm(char, calibrate(_template(seed, paper)))


def age(rgb: np.ndarray, seed: int = 0) -> np.ndarray:
    """A scan of old paper: the ink's darkness laid on tinted paper, light falling off across
    the sheet, a few tea stains, a red seal, paper fibres and sensor noise, blurred a little as
    a scanner's optics do. RGB in [0, 1]."""
    rng = np.random.default_rng(seed)
    n = rgb.shape[0]
    dark = 1.0 - rgb.mean(axis=2)
    yy, xx = np.mgrid[0:n, 0:n] / n
    light = 0.72 + 0.28 * (1 - 0.6 * xx) * (1 - 0.5 * (yy - 0.3) ** 2)
    paper = light[..., None] * PAPER_TINT
    for _ in range(4):  # stains: soft blobs, ring-edged as dried tea
        cy, cx = rng.uniform(0.1, 0.9, 2) * n
        r = rng.uniform(0.06, 0.16) * n
        d = np.hypot(yy * n - cy, xx * n - cx) / r
        blob = np.clip(1 - d, 0, 1) ** 0.5 * 0.35 + np.exp(-(((d - 1) / 0.06) ** 2)) * 0.25
        paper = paper * (1 - blob[..., None] * (1 - STAIN_TINT))
    fibres = _gaussian(rng.standard_normal((n, n)), 0.8)
    fibres = fibres / max(float(np.abs(fibres).max()), 1e-9)
    paper = paper * (1 + 0.05 * fibres[..., None])
    img = paper * (1 - 0.92 * dark[..., None])
    img = _seal(img, n)
    img = np.stack([_gaussian(img[..., c], 0.7) for c in range(3)], axis=2)
    img = img + rng.normal(0, 0.025, img.shape)
    return np.clip(img, 0, 1)


def _seal(img: np.ndarray, n: int) -> np.ndarray:
    """A red seal in the lower right corner: a square of cinnabar with its characters carved
    out as white lines."""
    s = max(n // 9, 8)
    y0, x0 = n - s - n // 25, n - s - n // 25
    yy, xx = np.mgrid[0:s, 0:s] / s
    carved = (
        (np.abs(xx - 0.35) < 0.05) & (yy > 0.15) & (yy < 0.85)
        | (np.abs(yy - 0.3) < 0.05) & (xx > 0.15) & (xx < 0.85)
        | (np.abs(xx - 0.7) < 0.05) & (yy > 0.45) & (yy < 0.85)
    )
    frame = (np.minimum(np.minimum(xx, 1 - xx), np.minimum(yy, 1 - yy)) < 0.06) | ~carved
    out = img.copy()
    out[y0 : y0 + s, x0 : x0 + s][frame] = SEAL_RED
    return out


def scan_picture(char: dict, n: int = 512, seed: int = 0):
    """The scan-like picture of ``char`` and the ink that made it."""
    rgb, ink = written(char, n, seed)
    return age(rgb, seed), ink


def main(argv=None) -> int:
    from sim.image.png import write_png
    from sim.writing.hanzi import find_char

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("char", help="hanzi-writer JSON file or a character of data/hanzi")
    ap.add_argument("output")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--font", action="store_true", help="the font-like render instead")
    args = ap.parse_args(argv)
    char = find_char(args.char)
    img = font_picture(char, args.size) if args.font else scan_picture(char, args.size)[0]
    write_png(args.output, img)
    return 0


if __name__ == "__main__":
    sys.exit(main())
