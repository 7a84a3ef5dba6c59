# SPDX-License-Identifier: GPL-3.0-or-later
"""A hook flicked out in one movement (issue 26, points 1-2): per hook of a character
(``Plan.hooks``: a 竖钩, a 横折钩, a 斜钩, a 竖弯钩's 乚), the written path of the brush's base
(the recording, after practice) over the hook's body and the last width of the movement into its
foot (where the base rests on the foot):

- ``swing``: the mean absolute change of direction (deg) between consecutive steps of the base
  longer than ``MOVING`` mm (at rest its direction means nothing);
- ``zigs``: how many times that change of direction reverses its sign (each by more than
  ``TURN`` deg): the zigzags of the path.

Written with the default brush and seed, as shoulders_eval does. Statistics only, nothing here
is used by the simulator.

    python scripts/flick_eval.py 也龙兄先 [--size 512]
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

MOVING = 0.02  # mm a step of the base must be long for its direction to count
TURN = 1.0  # deg a change of direction must be to count as a zig or a zag


def _headings(path) -> np.ndarray:
    """The changes of direction (deg) between consecutive moving steps of ``path`` (mm)."""
    step = np.diff(path, axis=0)
    size = np.linalg.norm(step, axis=1)
    moving = step[size > MOVING]
    ang = np.degrees(np.arctan2(moving[:, 1], moving[:, 0]))
    return (np.diff(ang) + 180.0) % 360.0 - 180.0


def path_figures(path) -> tuple[float, int]:
    """(swing, zigs) of a base's ``path`` (mm, (n, 2))."""
    turn = _headings(path)
    swing = float(np.mean(np.abs(turn))) if turn.size else 0.0
    big = np.sign(turn[np.abs(turn) > TURN])
    zigs = int(np.count_nonzero(big[1:] != big[:-1])) if big.size else 0
    return swing, zigs


def hook_spans(pl) -> list[tuple[int, int, int]]:
    """Per hook of plan ``pl``: (first sample of the foot's rest, first sample of the hook's
    body, its end), the rest being the last width of the body before the hook's foot."""
    from sim.writing.feet import _along
    from sim.writing.planner import WRITING

    body = pl.phase == WRITING
    out = []
    for h in pl.hooks:
        e = h
        while e < len(body) and body[e]:
            e += 1
        f = h - 1
        while f > 0 and not body[f]:
            f -= 1
        g = f
        while g > 0 and body[g - 1]:
            g -= 1
        s = _along(pl.target[g : f + 1])
        wide = float(pl.width[g : f + 1].max())
        out.append((g + int(np.searchsorted(s, s[-1] - wide)), h, e))
    return out


def measure(ch: str, n: int, data) -> list[tuple]:
    """Per hook of ``ch`` written at ``n`` px: (char, first body sample, swing, zigs)."""
    from scripts.shoulders_eval import written
    from sim.core.recording import DEFAULT_BRUSH
    from sim.writing import writer

    plans = []
    practise = writer._practise_stroke

    def spy(sim, a, b, passes, fill, own, ctx, *args):
        plans.append((ctx[0], sim))
        return practise(sim, a, b, passes, fill, own, ctx, *args)

    writer._practise_stroke = spy
    try:
        written(ch, DEFAULT_BRUSH, n, data)
    finally:
        writer._practise_stroke = practise
    pl, sim = plans[-1]
    rows = []
    for rest, h, e in hook_spans(pl):
        rows.append((ch, h, *path_figures(sim.rec.samples[rest:e, :2])))
    return rows


def hook_rows(doc: str, measure, argv=None) -> list:
    """The rows ``measure(char, size, data)`` gives for the characters on the command line."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("chars")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--data", default="/tmp/chars/package")
    a = ap.parse_args(argv)
    return [r for ch in a.chars for r in measure(ch, a.size, a.data)]


def main(argv=None) -> int:
    rows = hook_rows(__doc__, measure, argv)
    print("char  hook  swing(deg) zigs")
    for ch, h, swing, zigs in rows:
        print(f"{ch}  {h:5d} {swing:10.2f} {zigs:4d}")
    if rows:
        m = np.mean([r[2:] for r in rows], axis=0)
        print(f"mean {len(rows):2d}   {m[0]:10.2f} {m[1]:4.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
