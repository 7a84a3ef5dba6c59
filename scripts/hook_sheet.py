# SPDX-License-Identifier: GPL-3.0-or-later
"""Before/after sheet of hooks (issue 26.2, a dry hook leaves as a point): for every hook of
each character (``hooks_eval.hooks``: 竖钩, 横折钩, 乚), the box round its corner and its tip cut
from two writings of the character at the same size (``--before`` and ``--after``: folders of
``<char>.png`` as ``sim write`` makes them) and zoomed ``--zoom`` times, side by side, a row a
hook. Pictures only, nothing here is used by the simulator.

    python scripts/hook_sheet.py 孔乱司 --before DIR --after DIR -o sheet.png [--size 512]
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

MARGIN = 0.35  # the box reaches this share of the hook's length past its corner and tip
CELL = 360  # px: the side of a zoomed crop on the sheet (at most)


def hook_boxes(ch: str, n: int, data) -> list[tuple[int, int, int, int]]:
    """The image box (x0, y0, x1, y1) of every hook of ``ch`` written at ``n`` px."""
    from scripts.hooks_eval import hooks
    from sim.writing.hanzi import find_char
    from sim.writing.outline import to_image

    out = []
    for _si, corner, tip, _median, _kind in hooks(find_char(ch, data)):
        c, t = to_image(np.stack([corner, tip]), n)
        reach = MARGIN * float(np.linalg.norm(t - c)) + 6.0
        lo, hi = np.minimum(c, t) - reach, np.maximum(c, t) + reach
        x0, y0 = np.clip(np.floor(lo), 0, n - 1).astype(int)
        x1, y1 = np.clip(np.ceil(hi), 1, n).astype(int)
        out.append((int(x0), int(y0), int(x1), int(y1)))
    return out


def main(argv=None) -> int:
    from PIL import Image, ImageDraw

    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("chars")
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", required=True)
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--zoom", type=int, default=4)
    ap.add_argument("--data", default="/tmp/chars/package")
    a = ap.parse_args(argv)
    rows = []
    dirs = (a.before, a.after)
    for ch in a.chars:
        pics = [Image.open(os.path.join(d, f"{ch}.png")).convert("RGB") for d in dirs]
        for box in hook_boxes(ch, a.size, a.data):
            w, h = box[2] - box[0], box[3] - box[1]
            z = min(a.zoom, CELL / max(w, h))
            size = (int(w * z), int(h * z))
            rows.append([p.crop(box).resize(size, Image.LANCZOS) for p in pics] + [ch])
    width = max(r[0].width for r in rows) * 2 + 30
    sheet = Image.new("RGB", (width, sum(r[0].height + 20 for r in rows)), "white")
    draw = ImageDraw.Draw(sheet)
    y = 0
    for before, after, ch in rows:
        draw.text((4, y + 2), f"{ch}: before | after", fill="black")
        sheet.paste(before, (0, y + 18))
        sheet.paste(after, (before.width + 30, y + 18))
        y += before.height + 20
    sheet.save(a.out)
    print(f"{a.out}: {len(rows)} hooks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
