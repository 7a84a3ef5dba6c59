# SPDX-License-Identifier: GPL-3.0-or-later
"""How far back each practice pass must be written again (issue 28): for every stroke of the
characters given, written as ``python -m sim write`` writes them (512 px, the defaults), and
every pass after its first, the first sample of the stroke whose planned pose differs from the
pass before it (bitwise), how many of its samples differ at all and by more than 0.05 mm, and
the largest change; then the brush steps the practice ran against the character's samples.

A later pass can begin from a snapshot of the pass before only up to its first changed sample
(``practice._rewind``): where that is the stroke's start, every pass is the whole stroke again.

    python scripts/practice_rewinds.py 出 左 生 禾 --data tests/data/unseen
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from sim.cli.main import _parser  # noqa: E402
from sim.cli.shared import _chars, _response, _template  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from sim.writing import writer  # noqa: E402
from sim.writing.practice import _practise_stroke  # noqa: E402

BIG_MM = 0.05  # a change of a sample's pose (mm, or the angles' units) counted as large


def _watch(rows: list):
    """``_practise_stroke`` that notes every later pass's change of the stroke's samples in
    rows (not the best pass's samples filled in again once the simulation is taken back to it)."""

    def practise(sim, a, b, passes, fill, *rest):
        fills = []
        restore = sim.restore

        def restored(state):
            fills.append("restored")
            return restore(state)

        def noted(a_, b_, *args):
            before = sim.rec.samples[a_:b_].copy()
            body = fill(a_, b_, *args)
            after = sim.rec.samples[a_:b_]
            if fills and fills[-1] != "restored":
                diff = np.abs(after - before).max(axis=1)
                changed = np.flatnonzero(np.any(after != before, axis=1))
                first = int(changed[0]) if changed.size else -1
                big = int(np.count_nonzero(diff > BIG_MM))
                head = int(body[0]) - a_  # the stroke's first body sample
                rows.append((a, b - a, head, first, changed.size, big, float(diff.max())))
            fills.append("pass")
            return body

        sim.restore = restored
        try:
            return _practise_stroke(sim, a, b, passes, noted, *rest)
        finally:
            del sim.restore

    return practise


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("chars", nargs="+")
    ap.add_argument("--data", default=str(ROOT / "data" / "hanzi"))
    ap.add_argument("--size", type=int, default=512)
    args = ap.parse_args(argv)
    template = _template(_parser().parse_args(["write", "永", "-o", "unused.png"]))
    response = _response(template)
    steps = [0]
    advance = Simulation._advance

    def counted(self):
        steps[0] += 1
        return advance(self)

    Simulation._advance = counted
    for name, char in zip(args.chars, _chars(args.chars, args.data), strict=True):
        rows: list = []
        writer._practise_stroke = _watch(rows)
        steps[0] = 0
        rec, _, _ = writer.write_character(char, args.size, template, response=response)
        print(f"{name}: {len(rec.samples)} samples, {steps[0]} brush steps")
        print("  stroke at  samples  body from  first changed  changed  > 0.05 mm  largest (mm)")
        for a, n, head, first, changed, big, top in rows:
            print(f"  {a:8d}  {n:7d}  {head:9d}  {first:13d}  {changed:7d}  {big:9d}  {top:12.3f}")
        at_head = sum(1 for r in rows if 0 <= r[3] <= r[2])
        share = sum(r[4] for r in rows) / max(sum(r[1] for r in rows), 1)
        print(f"  later passes changed from the head (to the first body sample): {at_head}", end="")
        print(f"/{len(rows)}")
        print(f"  share of a later pass's samples that change: {share:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
