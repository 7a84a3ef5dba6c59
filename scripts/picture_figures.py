# SPDX-License-Identifier: GPL-3.0-or-later
"""README pictures of imitating a picture (docs/img/picture_*.png), with the engine alone:

- picture_font.png: a character the project has never seen, rendered from its outlines | the
  strokes read off the picture, numbered in the writing order found, each from where it starts
  | the brush's imitation;
- picture_scan.png: the same for a scan-like picture (the brush's 永 on raw xuan, aged: tinted
  paper, uneven light, stains, fibres, noise), imitated at the piece's own size (as
  ``--size-mm`` gives it: the auto size, read off the blots, is 30 % smaller);
- picture_replay.png: the imitation's recording replayed, at five moments of the writing;
- picture_piece.png: a piece of four characters in two columns (font-like renders of unseen
  characters) | the imitation with ``piece=True``: read right to left, top to bottom, each
  character written in its own square (the strokes numbered in the writing order).

    python scripts/picture_figures.py [--size 512]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scripts.picture_eval import template  # noqa: E402
from scripts.picture_scan import (  # noqa: E402
    font_picture,
    piece_picture,
    scan_picture,
    written_size_mm,
)
from sim.engine.simulation import Simulation  # noqa: E402
from sim.image.morph import resize  # noqa: E402
from sim.image.png import write_png  # noqa: E402
from sim.picture.imitate import imitate  # noqa: E402
from sim.writing.hanzi import find_char  # noqa: E402

OUT = ROOT / "docs" / "img"
COLOURS = np.array(
    [
        [0.85, 0.1, 0.1],
        [0.1, 0.55, 0.1],
        [0.1, 0.25, 0.85],
        [0.85, 0.5, 0.0],
        [0.6, 0.1, 0.7],
        [0.0, 0.6, 0.6],
        [0.5, 0.3, 0.1],
        [0.9, 0.2, 0.6],
        [0.3, 0.3, 0.3],
        [0.4, 0.6, 0.0],
    ]
)
DIGITS = {  # 3 x 5 bitmaps
    "0": "111101101101111",
    "1": "010110010010111",
    "2": "111001111100111",
    "3": "111001111001111",
    "4": "101101111001001",
    "5": "111100111001111",
    "6": "111100111101111",
    "7": "111001010010010",
    "8": "111101111101111",
    "9": "111101111001111",
}


def _stamp(img, text: str, x: int, y: int, colour, scale: int = 4) -> None:
    n = img.shape[0]
    for k, ch in enumerate(text):
        bits = np.array([int(b) for b in DIGITS[ch]], dtype=bool).reshape(5, 3)
        big = np.kron(bits, np.ones((scale, scale), dtype=bool))
        x0, y0 = x + k * 4 * scale, y
        h, w = big.shape
        if 0 <= x0 and x0 + w < n and 0 <= y0 and y0 + h < n:
            img[y0 : y0 + h, x0 : x0 + w][big] = colour


def strokes_figure(im, n: int) -> np.ndarray:
    """The strokes read: faint ink, each stroke's centre line in its colour, a square where it
    starts and its number in the writing order."""
    img = np.where(im.ink.mask[..., None], 0.85, 1.0) * np.ones(3)
    for i, s in enumerate(im.strokes):
        c = COLOURS[i % len(COLOURS)]
        for x, y in s.pts:
            xi, yi = int(round(x)), int(round(y))
            img[max(yi - 1, 0) : yi + 2, max(xi - 1, 0) : xi + 2] = c
        x, y = (int(round(v)) for v in s.pts[0])
        img[max(y - 5, 0) : y + 6, max(x - 5, 0) : x + 6] = c * 0.6
        _stamp(img, str(i + 1), x + 8, max(y - 24, 0), c * 0.8, scale=max(n // 128, 2))
    return img


def _rgb(a) -> np.ndarray:
    a = np.asarray(a, dtype=np.float64)
    a = a / 255.0 if a.max() > 1.0 else a
    return a if a.ndim == 3 else np.repeat(a[..., None], 3, axis=2)


def _row(*panels, gap: int = 8) -> np.ndarray:
    h = panels[0].shape[0]
    sep = np.full((h, gap, 3), 0.6)
    parts = []
    for p in panels:
        parts += [_rgb(p)[..., :3], sep]
    return np.concatenate(parts[:-1], axis=1)


def figure(picture, n: int, size_mm: float | None = None):
    rec, _, sim, im = imitate(picture, template(), n, size_mm=size_mm)
    return _row(picture, strokes_figure(im, n), sim.image()), rec


def replay(rec, moments: int = 5) -> np.ndarray:
    """The recording written again from the start, shown at ``moments`` points of its way."""
    sim = Simulation(rec)
    n = len(rec.samples)
    frames = []
    for k in range(1, moments + 1):
        sim.run(until=n * k // moments)
        img = sim.image()
        h, w = img.shape[0] // 2, img.shape[1] // 2  # half size: five fit a README's width
        frames.append(np.stack([resize(img[..., c], h, w) for c in range(3)], axis=2))
    return _row(*frames)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--char", default=str(ROOT / "tests" / "data" / "unseen" / "禾.json"))
    args = ap.parse_args(argv)
    n = args.size
    font, _ = figure(font_picture(find_char(args.char), n), n)
    write_png(OUT / "picture_font.png", font)
    scan, _ = scan_picture(find_char("永"), n)
    row, rec = figure(scan, n, written_size_mm(find_char("永")))  # the piece's own size
    write_png(OUT / "picture_scan.png", row)
    write_png(OUT / "picture_replay.png", replay(rec))
    unseen = ROOT / "tests" / "data" / "unseen"
    cols = [[find_char(str(unseen / f"{c}.json")) for c in col] for col in ("木王", "口禾")]
    piece = piece_picture(cols)
    rec, _, sim, im = imitate(piece, template(), n, piece=True)
    side = n * piece.shape[1] // piece.shape[0]
    shown = np.stack([resize(piece, n, side)] * 3, axis=2)
    write_png(OUT / "picture_piece.png", _row(shown, sim.image()))
    print(f"{OUT}/picture_font.png, picture_scan.png, picture_replay.png, picture_piece.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
