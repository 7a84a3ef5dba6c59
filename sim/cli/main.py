# SPDX-License-Identifier: GPL-3.0-or-later
"""Command line: ``python -m sim render REC.json -o OUT.png`` (from the repository root). The
parser and the dispatch; each command group is in its own module of ``sim.cli``."""

from __future__ import annotations

import argparse
import sys

from ..core.files import WriteError
from ..core.params import MAX_PAPER_SIDE_PX, ParameterError
from ..core.recording import (
    DEFAULT_BRUSH,
    DEFAULT_PAPER,
    MAX_SEED,
    PAPER_MM_RANGE,
    PX_PER_MM_RANGE,
    RecordingError,
)
from ..paper.texture import keep_tiles_in
from .compose import _add_compose
from .evaluate import cmd_iou
from .fit import _add_fit
from .imitate import _add_imitate
from .memory import EXIT_CODE, NotEnoughMemory, out_of_memory, reserve_workspace
from .render import add_matte_option, cmd_render
from .shared import _named, _real, _whole, add_keep_brush, cache_dir
from .write import cmd_write, cmd_write_set


def cmd_bench(args) -> int:
    from .bench import main as bench

    bench(quick=args.quick, work_only=args.work)
    return 0


def cmd_speed(args) -> int:
    from .speed import main as speed

    speed(args.repeats, baseline=args.baseline, against=args.against)
    return 0


def _parser() -> argparse.ArgumentParser:
    from ..writing.writer import DEFAULT_PASSES, MAX_PASSES, MIN_SHEET_PX

    seed = _whole(0, MAX_SEED)
    size = _whole(MIN_SHEET_PX, MAX_PAPER_SIDE_PX)
    ap = argparse.ArgumentParser(prog="python -m sim", description="Virtual Hairy Brush engine")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render", help="render a recording to a PNG")
    r.add_argument("recording", type=_named)
    r.add_argument("-o", "--output", type=_named, required=True)
    r.add_argument(
        "--px-per-mm", type=_real(*PX_PER_MM_RANGE), default=None, help="override the resolution"
    )
    r.add_argument("--seed", type=seed, default=None, help="override the seed")
    r.add_argument("-q", "--quiet", action="store_true")
    add_matte_option(r)
    r.set_defaults(func=cmd_render)

    def common(p):
        p.add_argument(
            "--data", type=_named, default=None, help="folder of <char>.json or graphics.txt"
        )
        p.add_argument("--brush", type=_named, default=DEFAULT_BRUSH, help="brush preset")
        p.add_argument("--paper", type=_named, default=DEFAULT_PAPER, help="paper preset")
        p.add_argument("--ink", type=_named, default="sumi_black", help="ink preset")
        p.add_argument(
            "--quality", type=_named, default=None, help="quality JSON (e.g. from sim fit)"
        )
        p.add_argument("--seed", type=seed, default=0)
        p.add_argument(
            "--size-mm", type=_real(*PAPER_MM_RANGE), default=None, help="character size (auto)"
        )
        p.add_argument(
            "--passes",
            type=_whole(1, MAX_PASSES),
            default=DEFAULT_PASSES,
            help="practice passes per stroke",
        )

    w = sub.add_parser("write", help="write a character from stroke data with the brush")
    w.add_argument("char", help="hanzi-writer JSON file, or one character (with --data)")
    w.add_argument("-o", "--output", type=_named, required=True)
    w.add_argument("--size", type=size, default=512, help="image size N (the em box)")
    w.add_argument("--recording", type=_named, default=None, help="also save the recording it made")
    w.add_argument("-q", "--quiet", action="store_true")
    add_matte_option(w)
    common(w)
    add_keep_brush(w)
    w.set_defaults(func=cmd_write)
    _add_imitate(sub, size, common)
    ws = sub.add_parser("write-set", help="write many characters to a folder (PNG + recording)")
    ws.add_argument("chars", nargs="+", help="hanzi-writer JSON files, or characters")
    ws.add_argument("--out-dir", type=_named, required=True, help="folder for NNN.png and NNN.json")
    ws.add_argument("--size", type=size, default=512, help="image size N (the em box)")
    ws.add_argument("--workers", type=_whole(0, 256), default=0, help="processes (0: all)")
    ws.add_argument("--scheduler", type=_named, default=None, help="a Dask cluster, as for fit")
    ws.add_argument("-q", "--quiet", action="store_true")
    common(ws)
    ws.set_defaults(func=cmd_write_set)
    m = sub.add_parser("iou", help="IoU of written characters against the font outlines")
    m.add_argument("chars", nargs="+")
    m.add_argument("--size", type=size, default=512)
    common(m)
    add_keep_brush(m)
    m.set_defaults(func=cmd_iou)
    _add_fit(sub, size, common)
    _add_compose(sub, seed)
    b = sub.add_parser("bench", help="speed benchmark: a table, then one JSON line")
    b.add_argument("--quick", action="store_true", help="one repetition instead of five")
    b.add_argument("--work", action="store_true", help="only the composed work's line")
    b.set_defaults(func=cmd_bench)
    sp = sub.add_parser(
        "speed", help="what users wait for, beside the previous version measured in the same run"
    )
    sp.add_argument("--repeats", type=_whole(1, 50), default=3, help="runs of each version")
    sp.add_argument("--against", default=None, help="the previous version: a git revision")
    sp.add_argument("--baseline", default=None, help="the previous version: a checkout")
    sp.set_defaults(func=cmd_speed)
    return ap


def main(argv=None) -> int:
    """Run a command; any bad input ends in one 'error:' line and exit code 2, too little
    memory in one line saying how much was needed and exit code 3."""
    args = _parser().parse_args(argv)
    try:
        reserve_workspace()
        keep_tiles_in(cache_dir())  # the paper's tiles of tone, made once (issue 28)
        return args.func(args)
    except NotEnoughMemory as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_CODE
    except MemoryError as exc:
        print(f"error: {out_of_memory(exc)}", file=sys.stderr)
        return EXIT_CODE
    except (RecordingError, ParameterError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"error: {os_message(exc)}", file=sys.stderr)
        return 2


def os_message(exc: OSError) -> str:
    """A system error in plain words: what failed on which file, no error numbers."""
    if isinstance(exc, WriteError) or not exc.strerror:
        return str(exc)
    return f"{exc.filename}: {exc.strerror}" if exc.filename else exc.strerror
