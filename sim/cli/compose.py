# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim compose TEXT -o sheet.png``: a whole work from text - a poem in columns (or
rows), signed and sealed, written with one brush into one recording (sim.writing.work), its
cells written and simulated on this machine's processes or a Dask cluster."""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

from ..core.params import ParameterError
from ..core.recording import DEFAULT_BRUSH, DEFAULT_PAPER
from .render import add_matte_option
from .shared import (
    _progress,
    _real,
    _response,
    _template,
    _whole,
    _writable,
    add_keep_brush,
    cache_dir,
)

DEFAULT_CHAR_PX = 256
DEFAULT_DPI = 150.0
CHAR_MM_RANGE = (5.0, 1000.0)


class Mapper:
    """``mapper(fn, tasks, done)`` for sim.writing.work: here (one worker), on a pool of this
    machine's processes, or on a Dask cluster (``--scheduler``, as ``sim fit``) - one pool or
    client for the whole command; results in the tasks' order."""

    def __init__(self, workers: int, scheduler: str | None):
        self.workers, self.scheduler = workers, scheduler
        self._pool = self._client = self._cluster = None
        if scheduler is not None:
            from ..fitting.cluster import connect

            self._client, self._cluster = connect(scheduler, workers)
        elif workers > 1:
            from concurrent.futures import ProcessPoolExecutor

            from ..fitting.cluster import exit_with_parent

            self._pool = ProcessPoolExecutor(  # its workers end with this process (issue 30)
                workers, initializer=exit_with_parent, initargs=(os.getpid(),)
            )

    def __call__(self, fn, tasks, done=None) -> list:
        tasks = list(tasks)
        out = [None] * len(tasks)
        if self._client is not None:
            from distributed import as_completed

            with warnings.catch_warnings():  # a long text's tasks are a few MB in all, ~10 kB each
                warnings.filterwarnings("ignore", "Sending large graph", UserWarning)
                futures = self._client.map(fn, tasks, pure=False)
            index = {f.key: k for k, f in enumerate(futures)}
            for n, fut in enumerate(as_completed(futures), 1):
                out[index[fut.key]] = fut.result()
                if done is not None:
                    done(n, len(tasks))
            return out
        if self._pool is not None:
            from concurrent.futures import as_completed

            futures = {self._pool.submit(fn, t): k for k, t in enumerate(tasks)}
            for n, fut in enumerate(as_completed(futures), 1):
                out[futures[fut]] = fut.result()
                if done is not None:
                    done(n, len(tasks))
            return out
        from ..writing.work.compose import local_map

        return local_map(fn, tasks, done)

    def close(self):
        if self._pool is not None:
            self._pool.shutdown()
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()


def _text(args) -> str:
    if (args.text is None) == (args.text_file is None):
        raise ParameterError("give the text, or --text-file (one of them)")
    if args.text is not None:
        return args.text
    from ..core.jsonio import decode_text

    try:
        with open(args.text_file, "rb") as fh:
            data = fh.read(4 * 2**20 + 1)
    except OSError as exc:
        raise ParameterError(f"cannot read --text-file {args.text_file}: {exc.strerror}") from None
    if len(data) > 4 * 2**20:
        raise ParameterError(f"--text-file {args.text_file} is larger than 4 MB")
    return decode_text(data, f"--text-file {args.text_file}", ParameterError)


def _settings(args):
    from ..writing.work.layout import Settings, paper_size

    paper = None
    if args.paper:
        landscape = args.orientation or ("portrait" if args.layout == "vertical" else "landscape")
        paper = paper_size(args.paper, landscape == "landscape")
    elif args.dpi is not None:
        raise ParameterError("--dpi goes with --paper (without it, give --char-size)")
    if args.paper and args.char_mm:
        raise ParameterError("--char-mm and --paper: give one (the characters fit the paper)")
    if args.paper and args.char_size and args.dpi:
        raise ParameterError("with --paper, give --char-size or --dpi, not both")
    style = {"白文": "baiwen", "朱文": "zhuwen"}.get(args.seal_style, args.seal_style)
    return Settings(
        direction=args.layout,
        per_line=args.per_column,
        signature=args.signature or "",
        seal=args.seal or "",
        seal_style=style,
        grid=args.grid,
        paper_mm=paper,
        char_mm=args.char_mm,
    )


def cmd_compose(args) -> int:
    from ..core.files import write_json_atomic
    from ..image.png import write_png
    from ..writing.work import compose as work

    for out in (args.output, args.layout_out, args.save_recording):
        if out:
            _writable(out)
    text = _text(args)
    settings = _settings(args)
    template = _template(
        argparse.Namespace(
            **{**vars(args), "paper": args.paper_preset or DEFAULT_PAPER, "brush": args.brush}
        )
    )
    if args.paper and not args.char_size:
        res = {"px_per_mm": (args.dpi or DEFAULT_DPI) / 25.4}
    else:
        res = {"char_px": float(args.char_size or DEFAULT_CHAR_PX)}
    options = work.Options(args.passes, args.dip_every, args.variation, not args.keep_brush)
    t0 = time.perf_counter()
    workers = args.workers or os.cpu_count() or 1
    quiet = args.quiet

    def stage(lo, hi):
        return None if quiet else (lambda f: _progress(lo + (hi - lo) * f))

    # the text, signature and seal checked (every character without stroke data named) before
    # the brush is calibrated or a cluster is reached
    work.prepare(
        text,
        settings,
        data=args.data,
        punctuation=args.punctuation,
        skip_missing=args.skip_missing,
    )
    response = _response(template)
    mapper = Mapper(workers, args.scheduler)
    try:
        rec, lay, skipped = work.compose(
            text,
            settings,
            template,
            data=args.data,
            punctuation=args.punctuation,
            skip_missing=args.skip_missing,
            options=options,
            mapper=mapper,
            progress=stage(0.0, 0.85),
            response=response,
            cache_dir=cache_dir(),
            **res,
        )
        paper, inks = work.render(rec, mapper=mapper, progress=stage(0.85, 1.0))
    finally:
        mapper.close()
    if args.matte:  # the ink alone (sim.image.matte): no grid, no seal
        from ..image.matte import paper_matte8

        write_png(args.output, paper_matte8(paper))
    else:
        write_png(args.output, work.image8(paper, rec))
    if args.save_recording:
        rec.save(args.save_recording)
    if args.layout_out:
        items = work.layout_items(rec, inks)
        write_json_atomic(args.layout_out, items, ensure_ascii=False, indent=1, separators=None)
    if skipped:
        from ..writing.work.text import describe

        print(
            f"skipped (no stroke data): {', '.join(describe(c) for c in skipped)}", file=sys.stderr
        )
    if not quiet:
        text_cells = sum(c.role == "text" for c in lay.cells)
        print(
            f"{args.output}: {rec.width_px} x {rec.height_px} px, {text_cells} characters "
            f"+ {len(lay.cells) - text_cells} signed, em box {lay.char_mm:.1f} mm, "
            f"{sum(c.dip for c in lay.cells)} dips, {len(rec.samples)} samples, "
            f"{time.perf_counter() - t0:.1f} s"
        )
    return 0


def _add_compose(sub, seed):
    """The ``compose`` command's options."""
    from ..writing.work.compose import WORK_PASSES
    from ..writing.work.layout import DIRECTIONS, GRIDS, PAPER_SIZES_MM
    from ..writing.work.seal import STYLES
    from ..writing.work.text import PUNCTUATION_MODES
    from ..writing.writer import DEFAULT_PASSES, MAX_PASSES

    c = sub.add_parser(
        "compose",
        help="write a whole work from text: columns or rows, signature, seal, one recording",
        description="Write a work from text with one brush. Characters without stroke data "
        "(Latin letters, emoji, characters outside the set) stop the command with one message "
        "naming each of them, before anything is written; --skip-missing leaves them out.",
    )
    c.add_argument("text", nargs="?", default=None, help="the text (a newline starts a column)")
    c.add_argument("--text-file", default=None, help="read the text from a UTF-8 file")
    c.add_argument("-o", "--output", required=True, help="the sheet (PNG)")
    c.add_argument("--layout", choices=DIRECTIONS, default="vertical", help="columns or rows")
    c.add_argument(
        "--per-column",
        type=_whole(1, 1000),
        default=None,
        help="characters a column (row); default: the text's lines, or a balanced block",
    )
    c.add_argument(
        "--char-size",
        type=_real(8, 4096),
        default=None,
        help=f"pixels an em box (default {DEFAULT_CHAR_PX}; with --paper: from --dpi)",
    )
    c.add_argument(
        "--char-mm",
        type=_real(*CHAR_MM_RANGE),
        default=None,
        help="the em box in mm (default: the size the brush writes best)",
    )
    c.add_argument(
        "--paper",
        default=None,
        help=f"the sheet: {', '.join(PAPER_SIZES_MM)} or WxH (mm); the characters fit it",
    )
    c.add_argument("--orientation", choices=("portrait", "landscape"), default=None)
    c.add_argument(
        "--dpi", type=_real(5, 5000), default=None, help=f"with --paper (default {DEFAULT_DPI:g})"
    )
    c.add_argument(
        "--signature", default=None, help="the signature (落款), smaller, after the text"
    )
    c.add_argument("--seal", default=None, help="the seal's characters, stamped by the signature")
    c.add_argument(
        "--seal-style", default="baiwen", choices=(*STYLES, "白文", "朱文"), help="白文 or 朱文"
    )
    c.add_argument("--grid", choices=GRIDS, default="none", help="米字格 (mi) or 田字格 (tian)")
    c.add_argument(
        "--punctuation",
        choices=PUNCTUATION_MODES,
        default="omit",
        help="leave punctuation out (classical) or keep it as small marks",
    )
    c.add_argument(
        "--skip-missing",
        action="store_true",
        help="leave out characters without stroke data (default: stop and name them)",
    )
    c.add_argument(
        "--dip-every",
        type=_whole(1, 100000),
        default=None,
        help="dip every N characters (default: when the brush's ink runs low)",
    )
    c.add_argument("--variation", type=_real(0, 3), default=1.0, help="how much repeats vary")
    c.add_argument("--layout-out", default=None, help="write the characters' boxes (JSON)")
    c.add_argument("--save-recording", default=None, help="save the one recording of the sheet")
    c.add_argument("--data", default=None, help="your own graphics.txt or folder of <char>.json")
    c.add_argument("--brush", default=DEFAULT_BRUSH, help="brush preset")
    add_keep_brush(c)
    c.add_argument("--paper-preset", default=None, help="paper preset (kind of paper)")
    c.add_argument("--ink", default="sumi_black", help="ink preset")
    c.add_argument("--quality", default=None, help="quality JSON (e.g. from sim fit)")
    c.add_argument("--seed", type=seed, default=0)
    c.add_argument(
        "--passes",
        type=_whole(1, MAX_PASSES),
        default=WORK_PASSES,
        help=f"practice passes per stroke (default {WORK_PASSES}; {DEFAULT_PASSES}: the finest)",
    )
    c.add_argument("--workers", type=_whole(0, 256), default=0, help="processes (0: all cores)")
    c.add_argument(
        "--scheduler",
        default=None,
        help="write on a Dask cluster: 'local' or a scheduler's address (tcp://host:8786)",
    )
    c.add_argument("-q", "--quiet", action="store_true")
    add_matte_option(c)
    c.set_defaults(func=cmd_compose)
