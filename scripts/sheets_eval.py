# SPDX-License-Identifier: GPL-3.0-or-later
"""Pale hard-edged sheets in the ink (issue 26, points 1 and 2): flat mid-grey areas with a hard
outline, such as a brush late on its load laid as translucent sheets over and beside its darker
ink, the most "computer-made" thing in our writing; real ink stays dark where it lies and a dry
brush breaks into white streaks along the stroke (飞白) instead. Per character written with the
default brush and seed (the ink density, the darkest channel's, as ``seams_eval`` reads it):

- ``sheet``: the pixels of mid-grey (density in ``PALE``) that belong to a mid-grey area at
  least ``WIDE_PX`` px across (an opening of it: not the one-pixel rim of a dark stroke nor the
  edge of a streak) and lie within ``NEAR_PX`` px of a hard edge (a density gradient above
  ``HARD`` a pixel), per thousand pixels of ink (density above ``INKED``);
- ``pale``: all the mid-grey area at least ``WIDE_PX`` across, hard-edged or not, per thousand
  of the ink (for a check that the sheets are not just made soft);
- ``ink``: the ink's pixels.

Statistics only, nothing here is used by the simulator.

    python scripts/sheets_eval.py 剑虎鹤 [--size 512] [--save DIR] [--load DIR]
"""

from __future__ import annotations

import os
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

PALE = (0.35, 0.75)  # density of a pale grey (between paper and the ink's full colour)
HARD = 0.2  # density a pixel: a gradient steeper than this is a hard edge
NEAR_PX = 3  # px from a hard edge
WIDE_PX = 3  # px: a pale area at least this wide is a sheet, not a rim
INKED = 0.2  # density above which a pixel is ink


def sheet_masks(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(sheet, pale) masks of the density image ``d`` (see the module's docstring)."""
    mid = (d >= PALE[0]) & (d <= PALE[1])
    pale = ndimage.binary_opening(mid, np.ones((WIDE_PX, WIDE_PX), bool))
    gy, gx = np.gradient(d)
    edge = np.hypot(gy, gx) > HARD
    yy, xx = np.mgrid[-NEAR_PX : NEAR_PX + 1, -NEAR_PX : NEAR_PX + 1]
    near = ndimage.binary_dilation(edge, yy**2 + xx**2 <= NEAR_PX**2)
    return pale & near, pale


def sheet_stats(d: np.ndarray) -> dict:
    """``sheet``, ``pale`` (per thousand of the ink) and ``ink`` (px) of the density ``d``."""
    sheet, pale = sheet_masks(d)
    ink = max(int((d > INKED).sum()), 1)
    return {
        "sheet": 1000.0 * sheet.sum() / ink,
        "pale": 1000.0 * pale.sum() / ink,
        "ink": float(ink),
    }


def main(argv=None) -> int:
    from scripts.seams_eval import arguments, densities

    ap = arguments(__doc__)
    ap.add_argument("--masks", default=None, help="a folder for each character's sheet mask (png)")
    args = ap.parse_args(argv)

    keys = ("sheet", "pale", "ink")
    total = dict.fromkeys(keys, 0.0)
    print("char " + " ".join(f"{k:>9}" for k in keys))
    names = list(args.chars)
    for name, d in densities(args):
        if args.masks:
            _save_mask(d, os.path.join(args.masks, f"{name}.png"))
        s = sheet_stats(d)
        for k in keys:
            total[k] += s[k] / len(names)
        print(f"{name}    " + " ".join(f"{s[k]:9.2f}" for k in keys))
    print("mean " + " ".join(f"{total[k]:9.2f}" for k in keys))
    return 0


def _save_mask(d: np.ndarray, path: str):
    """The density in grey with the sheets in red, for a look."""
    from PIL import Image

    sheet, _ = sheet_masks(d)
    grey = (255 * (1.0 - np.clip(d, 0, 1))).astype(np.uint8)
    rgb = np.stack([grey, grey, grey], axis=-1)
    rgb[sheet] = (255, 0, 0)
    Image.fromarray(rgb).save(path)


if __name__ == "__main__":
    sys.exit(main())
