# SPDX-License-Identifier: GPL-3.0-or-later
"""Command line: ``python -m sim render REC.json -o OUT.png`` (from the repository root)."""

from __future__ import annotations

import argparse
import sys
import time

from .params import ParameterError
from .recording import RecordingError


def _progress(frac: float) -> None:
    bar = int(frac * 30)
    sys.stderr.write(f"\r[{'#' * bar}{'.' * (30 - bar)}] {frac * 100:5.1f}%")
    if frac >= 1.0:
        sys.stderr.write("\n")
    sys.stderr.flush()


def cmd_render(args) -> int:
    from .engine import Simulation
    from .png import write_png
    from .recording import load

    rec = load(args.recording)
    if args.px_per_mm is not None:
        from .recording import from_dict

        d = rec.to_dict()
        d["paper"]["px_per_mm"] = args.px_per_mm
        rec = from_dict(d)
    if args.seed is not None:
        rec.seed = args.seed
    t0 = time.perf_counter()
    sim = Simulation(rec).run(progress=None if args.quiet else _progress)
    write_png(args.output, sim.image8())
    if not args.quiet:
        dt = time.perf_counter() - t0
        print(
            f"{args.output}: {rec.width_px} x {rec.height_px} px, {len(rec.samples)} samples in "
            f"{dt:.2f} s, {sim.brush.m} writing primitive(s) at the end"
        )
    return 0


def cmd_bench(args) -> int:
    from .bench import main as bench

    bench(quick=args.quick)
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m sim", description="Virtual Hairy Brush engine")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render", help="render a recording to a PNG")
    r.add_argument("recording")
    r.add_argument("-o", "--output", required=True)
    r.add_argument("--px-per-mm", type=float, default=None, help="override the resolution")
    r.add_argument("--seed", type=int, default=None, help="override the seed")
    r.add_argument("-q", "--quiet", action="store_true")
    r.set_defaults(func=cmd_render)
    b = sub.add_parser("bench", help="speed benchmark: a table, then one JSON line")
    b.add_argument("--quick", action="store_true", help="one repetition instead of three")
    b.set_defaults(func=cmd_bench)
    args = ap.parse_args(argv)
    try:
        return args.func(args)
    except (RecordingError, ParameterError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
