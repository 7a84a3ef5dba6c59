# SPDX-License-Identifier: GPL-3.0-or-later
"""What the commands share: the progress bar, the output check, the template recording and the
characters from the options, and the argparse types of numbers in a range."""

from __future__ import annotations

import argparse
import os
import sys

from ..core.params import ParameterError, number_within, short_repr


def _progress(frac: float) -> None:
    bar = int(frac * 30)
    sys.stderr.write(f"\r[{'#' * bar}{'.' * (30 - bar)}] {frac * 100:5.1f}%")
    if frac >= 1.0:
        sys.stderr.write("\n")
    sys.stderr.flush()


def _writable(path) -> None:
    """Refuse an output path whose folder does not exist before any long work."""
    if not str(path).strip():
        raise ParameterError("the output path is empty: name a file to write")
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path) or not os.path.isdir(folder):
        raise ParameterError(f"cannot write {path}: no such folder, or it is a folder")


def _template(args):
    """A recording carrying the chosen brush, paper, ink, quality and seed (no samples yet)."""
    import numpy as np

    from ..core.recording import Recording

    quality = {}
    if getattr(args, "quality", None):
        from ..fitting.search import load_quality

        quality = load_quality(args.quality)
    rec = Recording(
        np.zeros((1, 6)),
        seed=args.seed,
        brush={"preset": args.brush},
        paper_preset=args.paper,
        ink={"preset": args.ink},
        quality=quality,
    )
    rec.resolve()  # the presets exist and are sound
    return rec


def cache_dir() -> str:
    """Where the command line keeps what it can measure again (the brush's calibrated
    response): $HAIRY_BRUSH_CACHE, else the platform's cache folder ($XDG_CACHE_HOME or
    ~/.cache on Linux, ~/Library/Caches on macOS, %LOCALAPPDATA% on Windows)/hairy_brush."""
    if os.environ.get("HAIRY_BRUSH_CACHE"):
        return os.environ["HAIRY_BRUSH_CACHE"]
    home = os.path.expanduser("~")
    if sys.platform == "win32":
        root = os.environ.get("LOCALAPPDATA") or os.path.join(home, "AppData", "Local")
    elif sys.platform == "darwin":
        root = os.path.join(home, "Library", "Caches")
    else:
        root = os.environ.get("XDG_CACHE_HOME") or os.path.join(home, ".cache")
    return os.path.join(root, "hairy_brush")


def _response(template):
    """The brush's calibrated response for the template, kept in ``cache_dir()``."""
    from ..writing.response import calibrate

    return calibrate(template, cache_dir=cache_dir())


def add_keep_brush(p):
    """The option that keeps the chosen brush at any size (``sized``)."""
    p.add_argument(
        "--keep-brush",
        action="store_true",
        help="write with the brush as it is at any size (default: writing set smaller or "
        "larger than the brush's own size is written with the brush made smaller or larger "
        "in proportion, as a calligrapher takes a small brush for small characters)",
    )


def sized(args, template, response, char):
    """The template and response to write ``char`` with at ``--size-mm``: the brush made
    smaller or larger for that size (``sim.writing.brush_size``), or as it is (no size, or
    ``--keep-brush``)."""
    from ..writing.brush_size import brush_for_char

    if args.size_mm is None or args.keep_brush:
        return template, response
    return brush_for_char(template, response, char, args.size_mm, cache_dir())


def _chars(specs, data):
    from ..writing.hanzi import find_char

    return [find_char(spec, data) for spec in specs]


def _named(text: str) -> str:
    """An argparse type: a path or a name, which may not be empty ('' used to mean the
    default for --quality and --data, and an unreadable message for -o)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("is empty: give a file, folder or name")
    return text


def _whole(lo: int, hi: int):
    """An argparse type: a whole number in [lo, hi]."""

    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be a whole number, got {short_repr(text)}"
            ) from None
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"must lie in [{lo}, {hi}], got {short_repr(v)}")
        return v

    return parse


def _real(lo: float, hi: float):
    """An argparse type: a finite number in [lo, hi]."""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a number, got {short_repr(text)}") from None
        if not number_within(v, lo, hi):
            raise argparse.ArgumentTypeError(f"must lie in [{lo:g}, {hi:g}], got {text}")
        return v

    return parse
