# SPDX-License-Identifier: GPL-3.0-or-later
"""Does glibc's malloc slow the engine down in a long session (issue 17's report)? Time per sample
of a 2 s stroke stepped one sample at a time (as live painting steps it) and run in batches (as
playback and Simulate run it), on a flat paper of the given size, in a fresh process, and in a
process that first simulated and freed a large paper (what re-simulating or setting up again
leaves behind in Blender), each with glibc's default trimming and with a fixed trim threshold.
Every case runs in its own process.

    .venv/bin/python scripts/surface_malloc.py [--px 2048 4096] [--freed-px 4096]
"""

from __future__ import annotations

import argparse
import gc
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.core.recording import Recording  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402

L = 30.0  # the default brush's hair length, mm
N = 240  # 2 s at 120 Hz
PPM = 10.0


def stroke(side_mm: float) -> Recording:
    x = side_mm / 2 + np.linspace(-100.0, 100.0, N) * 0.99
    press = np.full(N, -5.0)
    press[12:-12] = 4.0
    samples = np.c_[x, np.full(N, side_mm / 2), L - press, np.tile([0.0, -8.0, 0.0], (N, 1))]
    return Recording(samples, width_mm=side_mm, height_mm=side_mm, px_per_mm=PPM)


def case(px: int, freed_px: int, trim: bool) -> dict:
    if trim:
        import ctypes

        ctypes.CDLL("libc.so.6").mallopt(-1, 1 << 30)  # M_TRIM_THRESHOLD
    if freed_px:  # a large paper simulated, then freed
        big = Simulation(stroke(freed_px / PPM))
        big.run()
        del big
        gc.collect()
    rec = stroke(px / PPM)
    out = {}
    for mode in ("live", "batch"):
        best = None
        for _ in range(3):
            sim = Simulation(rec)
            t0 = time.perf_counter()
            if mode == "live":
                while not sim.done:
                    sim.step()
            else:
                sim.run()
            ms = (time.perf_counter() - t0) / N * 1000
            best = ms if best is None else min(best, ms)
        out[mode] = best
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--px", type=int, nargs="+", default=[2048, 4096])
    ap.add_argument("--freed-px", type=int, default=4096)
    ap.add_argument("--case", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.case:
        px, freed, trim = json.loads(args.case)
        print(json.dumps(case(px, freed, trim)))
        return 0
    print("| paper | process | malloc | live ms / sample | batch ms / sample |")
    print("|---|---|---|---|---|")
    for px in args.px:
        for freed in (0, args.freed_px):
            for trim in (False, True):
                arg = json.dumps([px, freed, trim])
                res = subprocess.run(
                    [sys.executable, __file__, "--case", arg],
                    capture_output=True,
                    text=True,
                    check=True,
                )
                r = json.loads(res.stdout.strip().splitlines()[-1])
                proc = f"after a {freed} px paper was freed" if freed else "fresh"
                how = "fixed trim threshold" if trim else "glibc default"
                print(f"| {px} px | {proc} | {how} | {r['live']:.2f} | {r['batch']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
