# SPDX-License-Identifier: GPL-3.0-or-later
"""Measure ``sim imitate`` on real-style pictures (issue 26, point 4): characters rendered in
system fonts (``picture_real``: Kaiti and others, never the simulator's own output) and
degraded as photographs and scans are (blurred, small, unevenly lit, paper texture, JPEG),
each saved to a file and imitated with the command line's defaults (brush, paper, ink, seed,
passes, 512 px). For each the table gives the box-normalised IoU of the imitation's ink with
the picture's true ink (``picture_real.box_iou``), the holes and pieces of both, the width
error and the seconds; then the summary (mean and lowest IoU, hole and piece agreement, the
median width error and ratio) and one JSON line.

The characters are not those the reading was tuned on (TUNE); --tune measures those instead.

    python scripts/imitate_eval.py [--fonts ukai,cwkai] [--kinds scan,photo] [--chars 国何]
        [--only 品高] [--read-only] [--overlay] [--out /tmp/picture/eval]

(``--only``: of the cases, those of the characters given, each in the font and kind it has
among all the characters: one bad case measured again alone. ``--overlay``: beside each case's
picture, ``-overlay.png``: the true ink against the ink read (left) and the ink written
(right), both in their boxes as the IoU sees them: black both, red the truth's alone, blue
ours alone: a stroke's ink missed or added, or the whole shifted by an end that moved the box.)
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scripts.picture_real import (  # noqa: E402
    KINDS,
    available_fonts,
    box_iou,
    has_glyph,
    holes,
    pieces,
    real_style,
    width_error,
)
from sim.picture.ink import PictureError  # noqa: E402

TUNE = "宫般永心回明字书风"  # the reading may be tuned on these
CHARS = "国何品高语鹤墨剑虎飞必家端福雨龙帆船兴为学点然京"  # measured: never tuned on
DEFAULT_FONTS = ("ukai", "cwkai", "gkai")
DEFAULT_KINDS = ("clean", "blurred", "small", "uneven", "scan", "photo")


def cases(chars: str, fonts, kinds, per_char: int) -> list[tuple[str, str, str]]:
    """(char, font, kind): every character in one of the fonts in turn (the next that draws
    it) and ``per_char`` of the kinds in turn (so every font and every kind meets many
    characters without the full product)."""
    out = []
    per_char = min(per_char, len(kinds))
    for i, ch in enumerate(chars):
        for j in range(per_char):
            kind = kinds[(i + j * len(kinds) // per_char) % len(kinds)]
            drawn = [
                f for t in range(len(fonts)) if has_glyph(ch, f := fonts[(i + t) % len(fonts)])
            ]
            if drawn:
                out.append((ch, drawn[0], kind))
    return out


def evaluate(ch, font, kind, out: Path, read_only: bool, ctx, overlay: bool = False) -> dict:
    seed = sum(map(ord, ch + font + kind)) % 1000
    _, data, truth = real_style(ch, font, kind, seed)
    path = out / f"{ord(ch):x}-{font}-{kind}.{'png' if KINDS[kind]['jpeg'] is None else 'jpg'}"
    path.write_bytes(data)
    row = {"char": ch, "font": font, "kind": kind, "px": KINDS[kind]["px"]}
    t0 = time.perf_counter()
    try:
        ink, im = _imitated(path, read_only, ctx)
    except PictureError as exc:  # refused: a failure of the reading, scored as no ink
        print(f"refused: {exc}", flush=True)
        row.update(s=round(time.perf_counter() - t0, 1), strokes=0, read_iou=0.0, iou=0.0)
        row.update(holes=holes(truth), holes_got=-1, pieces=pieces(truth), pieces_got=-1)
        row.update(width_err=1.0, width_ratio=0.0)
        return row
    row["s"] = round(time.perf_counter() - t0, 1)
    from sim.image.png import write_png

    write_png(path.with_name(path.stem + "-ink.png"), np.where(ink, 0.0, 1.0))  # measured again
    if overlay:
        write_png(path.with_name(path.stem + "-overlay.png"), overlaid(truth, im.ink.mask, ink))
    row["strokes"] = len(im.strokes)
    row["read_iou"] = round(box_iou(im.ink.mask, truth), 4)  # the ink read off the picture
    row["iou"] = round(box_iou(ink, truth), 4)
    row["holes"] = holes(truth)
    row["holes_got"] = holes(ink)
    row["pieces"] = pieces(truth)
    row["pieces_got"] = pieces(ink)
    err, ratio = width_error(truth, ink)
    row["width_err"] = round(err, 3)
    row["width_ratio"] = round(ratio, 3)
    return row


OVERLAY_SIDE = 256  # px a side of each of the overlay's squares (the IoU's own square)


def overlaid(truth: np.ndarray, read: np.ndarray, written: np.ndarray) -> np.ndarray:
    """The true ink against the ink read and against the ink written, side by side, each in
    its box (``box_shape``, as ``box_iou`` compares them): black where both are ink, red the
    truth's alone, blue ours alone, white paper."""
    from sim.picture.correct import box_shape

    t = box_shape(truth, OVERLAY_SIDE)
    halves = []
    for ours in (read, written):
        o = box_shape(ours, OVERLAY_SIDE)
        rgb = np.ones((*t.shape, 3))
        rgb[t & o] = 0.0
        rgb[t & ~o] = (1.0, 0.2, 0.2)
        rgb[~t & o] = (0.2, 0.4, 1.0)
        halves.append(rgb)
    gap = np.ones((OVERLAY_SIDE, 8, 3))
    return np.concatenate([halves[0], gap, halves[1]], axis=1)


def _imitated(path, read_only: bool, ctx):
    """The imitation's ink (the strokes' outlines read, with ``read_only``) and what was read."""
    from sim.picture.imitate import imitate, read_picture
    from sim.writing.outline import rasterise
    from sim.writing.writer import coverage_mask

    if read_only:
        im = read_picture(str(path), 512)
        return rasterise(im.char, 512), im  # the strokes' own outlines, as the writer gets them
    template, response = ctx
    _, _, sim, im = imitate(str(path), template, 512, response=response)
    return coverage_mask(sim), im


def _evaluate(task) -> dict:
    return evaluate(*task)


def summary(rows: list) -> dict:
    iou = np.array([r["iou"] for r in rows])
    return {
        "cases": len(rows),
        "iou_mean": round(float(iou.mean()), 4),
        "iou_min": round(float(iou.min()), 4),
        "iou_p10": round(float(np.quantile(iou, 0.1)), 4),
        "read_iou_mean": round(float(np.mean([r["read_iou"] for r in rows])), 4),
        "holes_agree": round(float(np.mean([r["holes"] == r["holes_got"] for r in rows])), 3),
        "pieces_agree": round(float(np.mean([r["pieces"] == r["pieces_got"] for r in rows])), 3),
        "width_err": round(float(np.median([r["width_err"] for r in rows])), 3),
        "width_ratio": round(float(np.median([r["width_ratio"] for r in rows])), 3),
        "seconds_mean": round(float(np.mean([r["s"] for r in rows])), 1),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chars", default=None, help=f"characters (default: {CHARS})")
    ap.add_argument("--tune", action="store_true", help=f"the tuning characters {TUNE}")
    ap.add_argument("--fonts", default=",".join(DEFAULT_FONTS))
    ap.add_argument("--kinds", default=",".join(DEFAULT_KINDS))
    ap.add_argument("--per-char", type=int, default=2, help="kinds each character is shown in")
    ap.add_argument("--only", default="", help="of the cases, only those of these characters")
    ap.add_argument("--read-only", action="store_true", help="the outlines read, not written")
    ap.add_argument("--overlay", action="store_true", help="write each case's -overlay.png")
    ap.add_argument("--out", default="/tmp/picture/eval", help="folder for the pictures")
    ap.add_argument("--workers", type=int, default=1, help="processes (each case is one)")
    args = ap.parse_args(argv)
    kinds = args.kinds.split(",")
    fonts = [f for f in args.fonts.split(",") if f in available_fonts()]
    if not fonts:
        print(f"none of the fonts {args.fonts} is installed (see picture_real.FONTS)")
        return 1
    chars = TUNE if args.tune else (args.chars or CHARS)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ctx = None
    if not args.read_only:
        from sim.cli.shared import cache_dir
        from sim.core.recording import Recording
        from sim.writing.response import calibrate

        template = Recording(np.zeros((1, 6)))  # the command line's defaults
        ctx = (template, calibrate(template, cache_dir=cache_dir()))
    rows = []
    todo = [
        (*c, out, args.read_only, ctx, args.overlay)
        for c in cases(chars, fonts, kinds, args.per_char)
        if not args.only or c[0] in args.only
    ]
    if args.workers > 1:
        import multiprocessing

        pool = multiprocessing.get_context("fork").Pool(args.workers)
        results = pool.imap(_evaluate, todo)
    else:
        results = map(_evaluate, todo)
    for row in results:
        rows.append(row)
        print("  ".join(f"{k} {v}" for k, v in row.items()), flush=True)
    if args.workers > 1:
        pool.close()
        pool.join()
    s = summary(rows)
    for kind in kinds:
        part = [r for r in rows if r["kind"] == kind]
        if part:
            print(f"{kind:8s}", "  ".join(f"{k} {v}" for k, v in summary(part).items()))
    print("all     ", "  ".join(f"{k} {v}" for k, v in s.items()))
    print(json.dumps({"summary": s, "rows": rows, "pid": os.getpid()}, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
