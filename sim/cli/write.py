# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim write`` and ``write-set``: characters from stroke data written with the
brush, one, or many to a folder on this machine's processes or a Dask cluster."""

from __future__ import annotations

import os
import time

from ..core.params import ParameterError
from .render import paper_pixels
from .shared import _chars, _progress, _response, _template, _writable, sized


def cmd_write(args) -> int:
    from ..image.png import write_png
    from ..writing.writer import check_sheet, write_character

    _writable(args.output)
    if args.recording:
        _writable(args.recording)
    (char,) = _chars([args.char], args.data)
    if args.size_mm is not None:  # refused before the brush is calibrated
        check_sheet(float(args.size_mm), args.size / float(args.size_mm))
    t0 = time.perf_counter()
    template = _template(args)
    template, response = sized(args, template, _response(template), char)
    rec, resp, sim = write_character(
        char,
        args.size,
        template,
        size_mm=args.size_mm,
        response=response,
        passes=args.passes,
        progress=None if args.quiet else _progress,
    )
    write_png(args.output, paper_pixels(sim, args.matte))
    if args.recording:
        rec.save(args.recording)
    if not args.quiet:
        print(
            f"{args.output}: {args.size} x {args.size} px, {len(char['medians'])} strokes, "
            f"{len(rec.samples)} samples, {len(rec.dips)} dips, character {rec.width_mm:.1f} mm, "
            f"{time.perf_counter() - t0:.1f} s"
        )
    return 0


def cmd_write_set(args) -> int:
    """Many characters to a folder of PNGs and recordings, on this machine's processes or a
    Dask cluster (the executor of ``fit --scheduler``)."""
    from ..core.files import write_json_atomic
    from ..fitting.cluster import map_tasks
    from ..image.png import write_png

    if not os.path.isdir(args.out_dir):
        raise ParameterError(f"--out-dir {args.out_dir}: no such folder")
    chars = _chars(args.chars, args.data)
    template = _template(args)
    response = _response(template)
    tasks = [
        (c, f"{k:03d}", args.size, template, args.passes, response) for k, c in enumerate(chars)
    ]
    t0 = time.perf_counter()
    workers = args.workers or os.cpu_count() or 1
    done = None if args.quiet else (lambda n, total: _progress(n / total))
    for name, rgb, rec in map_tasks(write_task, tasks, workers, args.scheduler, done):
        write_png(os.path.join(args.out_dir, name + ".png"), rgb)
        write_json_atomic(os.path.join(args.out_dir, name + ".json"), rec)
    print(f"{args.out_dir}: {len(tasks)} characters, {time.perf_counter() - t0:.1f} s")
    return 0


def write_task(task):
    """One character of a batch (``sim write-set``), written in a worker: (name, RGB image,
    recording dict) - returned, not saved, as a cluster's workers may not share our disk."""
    from ..writing.writer import write_character

    char, name, size, template, passes, response = task
    rec, _resp, sim = write_character(char, size, template, response=response, passes=passes)
    return name, sim.image8(), rec.to_dict()
