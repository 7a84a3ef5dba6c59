# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim render``: a recording to a PNG (``--matte``: the ink alone, RGBA)."""

from __future__ import annotations

import time

from .memory import RENDER_BYTES_PER_PIXEL, check_room
from .shared import _progress, _writable

MATTE_HELP = (
    "write the ink alone as RGBA instead of the paper: alpha = the ink's density, RGB = the "
    "ink's colour, unpremultiplied (straight alpha), for compositing"
)


def add_matte_option(parser) -> None:
    """``--matte`` on a command that writes a paper (render, write, compose)."""
    parser.add_argument("--matte", action="store_true", help=MATTE_HELP)


def paper_pixels(sim, matte: bool, rec=None):
    """What a command writes of a finished simulation: the paper as it shows (RGB; with
    ``rec``, a work's grid and seal with the ink) or its ink matte (RGBA, sim.image.matte: the
    ink alone, no grid or seal), top row first, uint8."""
    if matte:
        from ..image.matte import paper_matte8

        return paper_matte8(sim.paper)
    if rec is not None:
        from ..writing.work.compose import image8

        return image8(sim.paper, rec)
    return sim.image8()


def cmd_render(args) -> int:
    from ..core.recording import load
    from ..engine.simulation import Simulation
    from ..image.png import write_png
    from ..writing.work.compose import check_work

    _writable(args.output)
    rec = load(args.recording)
    check_work(rec)  # a work's layout and seal, before any simulation
    if args.px_per_mm is not None:
        from ..core.recording import from_dict

        d = rec.to_dict()
        d["paper"]["px_per_mm"] = args.px_per_mm
        rec = from_dict(d)
    if args.seed is not None:
        rec.seed = args.seed
    w, h = rec.width_px, rec.height_px
    check_room(w * h * RENDER_BYTES_PER_PIXEL, f"a paper of {w} x {h} px")
    t0 = time.perf_counter()
    sim = Simulation(rec).run(progress=None if args.quiet else _progress)
    write_png(args.output, paper_pixels(sim, args.matte, rec))  # a work: grid and seal too
    if not args.quiet:
        dt = time.perf_counter() - t0
        print(
            f"{args.output}: {rec.width_px} x {rec.height_px} px, {len(rec.samples)} samples in "
            f"{dt:.2f} s, {sim.brush.m} writing primitive(s) at the end"
        )
    return 0
