# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim imitate``: a picture of writing read and written with the brush."""

from __future__ import annotations

import time

from .shared import (
    _named,
    _progress,
    _response,
    _template,
    _writable,
    add_keep_brush,
    cache_dir,
)


def _progress_after_reading(frac: float, *_details) -> None:
    """The bar from the first progress past reading the picture (a refused picture leaves
    only its error line)."""
    if frac > 0.0:
        _progress(frac)


def cmd_imitate(args) -> int:
    """Read a picture of writing, write it with the brush, report how close the ink is."""
    from ..core.files import write_json_atomic
    from ..fitting.texture import score, texture_stats
    from ..image.png import write_png
    from ..picture.imitate import imitate, ink_on
    from ..writing.outline import iou
    from ..writing.writer import coverage_mask

    for path in (args.output, args.recording, args.char_data):
        if path:
            _writable(path)
    t0 = time.perf_counter()
    template = _template(args)
    rec, _, sim, im = imitate(
        args.image,
        template,
        response=_response(template),
        n_px=args.size,
        size_mm=args.size_mm,
        passes=args.passes,
        progress=None if args.quiet else _progress_after_reading,
        piece=args.piece,
        fit_brush=not args.keep_brush,
        cache_dir=cache_dir(),
    )
    write_png(args.output, sim.image8())
    if args.recording:
        rec.save(args.recording)
    if args.char_data:
        write_json_atomic(args.char_data, im.char)
    if not args.quiet:
        ink = ink_on(im.ink.mask, args.size)  # read at most MAX_DETAIL a side
        print(
            f"{args.output}: {len(im.strokes)} strokes read in {im.seconds:.1f} s, "
            f"{len(rec.samples)} samples, character {rec.width_mm:.1f} mm, IoU with the "
            f"picture's ink {iou(coverage_mask(sim), ink):.3f}, texture score "
            f"{score(texture_stats(sim.image())):.2f}, {time.perf_counter() - t0:.1f} s"
        )
    return 0


def _add_imitate(sub, size, common):
    """The ``imitate`` command's options."""
    from ..picture.imitate import MAX_DETAIL, PASSES

    im = sub.add_parser("imitate", help="read a picture of writing and write it with the brush")
    im.add_argument(
        "image",
        type=_named,
        help="dark writing on a light ground: any PNG, JPEG, TIFF, ... with Pillow installed "
        "(pip install pillow); without it an 8-bit PNG",
    )
    im.add_argument("-o", "--output", type=_named, required=True)
    im.add_argument(
        "--size",
        type=size,
        default=512,
        help=f"image size N (the em box) written; the picture is read at N, at most {MAX_DETAIL}",
    )
    im.add_argument(
        "--recording", type=_named, default=None, help="also save the recording it made"
    )
    im.add_argument(
        "--char-data", type=_named, default=None, help="also save the strokes read (JSON)"
    )
    im.add_argument(
        "--piece",
        action="store_true",
        help="a piece of several characters: columns right to left, each top to bottom, each "
        "character written in its own square of the sheet",
    )
    im.add_argument("-q", "--quiet", action="store_true")
    common(im)
    add_keep_brush(im)
    im.set_defaults(func=cmd_imitate, passes=PASSES)
