# SPDX-License-Identifier: GPL-3.0-or-later
"""Measure ``sim imitate`` on scans or photographs of real brush writing (issue 26, point 4):
every picture in a folder (one character each: cut them out of a copybook page with any image
tool; the scans carry no licence, so they stay outside the repository) imitated with the
command line's defaults at 512 px, and its box-normalised IoU with the picture's own ink
(``picture_real.box_iou``). The picture's ink, the truth here, is read independently of the
imitation's reader: the pixels whose largest of R, G, B is below ``--dark`` (a red grid or seal
reads as paper), pieces under ``SPECK`` of the ink left out (dust, a printed label).

    python scripts/imitate_scans.py DIR [--dark 140] [--level] [--out /tmp/scans] [--keep]
    python scripts/imitate_scans.py DIR --scored /tmp/scans [--level]

Prints one line per picture and the mean; ``--keep`` keeps the written PNGs in ``--out``;
``--scored`` scores PNGs kept before instead of writing again. With ``--level`` the truth is
read against the paper's own level round each pixel (``level_ink``): a photograph on grey
paper with a shadow along its foot, read against a fixed ``--dark``, counts the shadow as ink
(a crop of 压 on a 150-grey page: a band below the character in the truth, and its box).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from PIL import Image
from scipy import ndimage as ndi

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scripts.picture_real import box_iou  # noqa: E402

SPECK = 0.01  # of the picture's ink: a smaller piece is not writing
GRID_LONG, GRID_THIN = 0.2, 2.5  # a printed grid's line: this share of the side long, px wide
PICTURES = (".png", ".jpg", ".jpeg", ".tif", ".tiff")


def scan_ink(path: Path, dark: int) -> np.ndarray:
    """The picture's ink: darker than ``dark`` in every channel, pieces under SPECK dropped,
    and lines of a printed grid (a piece at least GRID_LONG of the picture's side long and on
    average under GRID_THIN px wide: a scan cut from a 米字格 page shows them beside the
    character)."""
    return _writing(np.asarray(Image.open(path).convert("RGB")).max(axis=-1) < dark)


LEVEL_BLOCKS = 8  # the paper's level is read in blocks of 1/LEVEL_BLOCKS of the picture's side
LEVEL_QUANTILE = 0.9  # ... as this quantile of each block's brightness (mostly paper)


def level_ink(path: Path, dark: int) -> np.ndarray:
    """The picture's ink read against the paper's level round each pixel: the largest of R,
    G, B over the level (each block's LEVEL_QUANTILE, smoothed across blocks) darker than
    ``dark`` / 255 of it: ``dark`` 140 on white paper is ``scan_ink``'s; on a grey or unevenly
    lit page it follows the page. Specks and grid lines dropped as ``scan_ink``'s."""
    v = np.asarray(Image.open(path).convert("RGB")).max(axis=-1).astype(np.float64)
    h, w = v.shape
    b = max(max(h, w) // LEVEL_BLOCKS, 4)
    ny, nx = -(-h // b), -(-w // b)
    pad = np.pad(v, ((0, ny * b - h), (0, nx * b - w)), mode="edge")
    blocks = pad.reshape(ny, b, nx, b).transpose(0, 2, 1, 3).reshape(ny, nx, -1)
    level = ndi.maximum_filter(np.quantile(blocks, LEVEL_QUANTILE, axis=-1), size=3)
    level = ndi.zoom(ndi.uniform_filter(level, 3, mode="nearest"), b, order=1)[:h, :w]
    ink = v < np.maximum(level, 1.0) * (dark / 255.0)
    return _writing(ink)


def _thin_lines(ink: np.ndarray) -> np.ndarray:
    """The pixels of level lines: on every row whose ink no more than GRID_THIN px tall
    (its run down its column) spans GRID_LONG of the picture's width or more, that ink."""
    lab, _ = ndi.label(ink, structure=[[0, 1, 0], [0, 1, 0], [0, 1, 0]])  # runs down columns
    tall = np.bincount(lab.ravel())[lab]
    thin = ink & (tall <= GRID_THIN)
    return thin & (thin.sum(axis=1) >= GRID_LONG * ink.shape[1])[:, None]


def _writing(ink: np.ndarray) -> np.ndarray:
    """The writing of the ink: without a grid's lines (level and upright, ``_thin_lines``,
    twice: where two cross each is tall across the other), specks and pieces that are lines."""
    for _ in range(2):
        ink = ink & ~_thin_lines(ink)
        ink = ink & ~_thin_lines(ink.T).T
    lab, _ = ndi.label(ink)
    area = np.bincount(lab.ravel())
    area[0] = 0
    boxes = ndi.find_objects(lab)
    length = np.array([1] + [max(b[0].stop - b[0].start, b[1].stop - b[1].start) for b in boxes])
    grid = (length >= GRID_LONG * max(ink.shape)) & (area < GRID_THIN * length)
    return ((area >= SPECK * area.sum()) & ~grid)[lab]


def imitated(path: Path, out: Path) -> np.ndarray:
    """The ink ``python -m sim imitate`` writes for the picture (its PNG saved at ``out``)."""
    cmd = [sys.executable, "-m", "sim", "imitate", str(path), "-o", str(out), "-q"]
    subprocess.run(cmd, cwd=ROOT, check=True)
    return np.asarray(Image.open(out).convert("L")) < 128


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=Path)
    ap.add_argument("--dark", type=int, default=140, help="ink is darker than this (0-255)")
    ap.add_argument("--out", type=Path, help="folder for the written PNGs (with --keep)")
    ap.add_argument("--keep", action="store_true")
    ap.add_argument("--level", action="store_true", help="the truth against the paper's level")
    ap.add_argument("--scored", type=Path, help="score the written PNGs kept in this folder")
    args = ap.parse_args(argv)
    pictures = sorted(p for p in args.folder.iterdir() if p.suffix.lower() in PICTURES)
    if not pictures:
        ap.error(f"no pictures in {args.folder}")
    out = args.scored or args.out or Path(tempfile.mkdtemp(prefix="scans-"))
    out.mkdir(parents=True, exist_ok=True)
    truth = level_ink if args.level else scan_ink
    rows = {}
    for path in pictures:
        png = out / f"{path.stem}-written.png"
        if args.scored:
            written = np.asarray(Image.open(png).convert("L")) < 128
        else:
            written = imitated(path, png)
        rows[path.name] = round(box_iou(truth(path, args.dark), written), 4)
        print(f"{path.name:<24} box IoU {rows[path.name]:.3f}", flush=True)
        if not args.keep and not args.scored:
            (out / f"{path.stem}-written.png").unlink()
    values = list(rows.values())
    print(f"mean {np.mean(values):.4f}  lowest {min(values):.3f}  pictures {len(values)}")
    print(json.dumps({"mean": round(float(np.mean(values)), 4), "rows": rows}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
