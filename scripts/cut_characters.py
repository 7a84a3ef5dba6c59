# SPDX-License-Identifier: GPL-3.0-or-later
"""Cut single characters out of pages of real writing, for ``scripts/imitate_scans.py``
(issue 26, point 4): the ink of each page (darker than ``--dark`` in every channel: a red grid
or seal reads as paper), grown by a 60th of the page's side so that a character's strokes
join, and every joined piece about one character in size (between ``SIZE`` of the page's side,
not much longer one way than the other, inked at least ``INKED``) cut out with a margin. The
pages and the cut pictures carry no licence: keep them outside the repository.

    python scripts/cut_characters.py PAGE [PAGE ...] --out DIR [--per-page 5]

Writes DIR/<page>_NN.png; prints how many each page gave. Characters that touch their
neighbours, or a title in a larger hand, are left out or come out whole: look at the cut
pictures before measuring with them.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image
from scipy import ndimage as ndi

SIZE = (0.08, 0.45)  # a character's longer side, as a share of the page's longer side
ASPECT = (0.55, 1.8)  # its height over its width
INKED = 0.08  # share of its box that is ink, at least
MARGIN = 0.08  # of its longer side, round it


def cut(page: Path, out: Path, per_page: int, dark: int) -> int:
    """Cut up to ``per_page`` characters out of ``page`` into ``out``; how many it cut."""
    im = np.asarray(Image.open(page).convert("RGB"))
    side = max(im.shape[:2])
    ink = ndi.binary_opening(im.max(axis=-1) < dark)
    grow = max(side // 60, 2)
    lab, _ = ndi.label(ndi.binary_dilation(ink, iterations=grow))
    made = 0
    for box in ndi.find_objects(lab):
        h, w = box[0].stop - box[0].start, box[1].stop - box[1].start
        if not SIZE[0] * side < max(h, w) < SIZE[1] * side or not ASPECT[0] < h / w < ASPECT[1]:
            continue
        if ink[box].mean() < INKED:
            continue
        pad = int(MARGIN * max(h, w)) - grow
        y0, y1 = max(box[0].start - pad, 0), min(box[0].stop + pad, im.shape[0])
        x0, x1 = max(box[1].start - pad, 0), min(box[1].stop + pad, im.shape[1])
        Image.fromarray(im[y0:y1, x0:x1]).save(out / f"{page.stem}_{made:02d}.png")
        made += 1
        if made == per_page:
            break
    return made


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pages", type=Path, nargs="+")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--per-page", type=int, default=5)
    ap.add_argument("--dark", type=int, default=110, help="ink is darker than this (0-255)")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for page in args.pages:
        print(f"{page.name}: {cut(page, args.out, args.per_page, args.dark)} characters")
    return 0


if __name__ == "__main__":
    sys.exit(main())
