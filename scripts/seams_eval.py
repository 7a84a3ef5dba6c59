# SPDX-License-Identifier: GPL-3.0-or-later
"""Hard seams inside the ink (issue 26, point 1): thin lines of a step or a ridge of ink density
that no real ink shows, inside the strokes of characters written with the default brush and
seed. Per character, over the ink's core (density above ``INKED``, at least ``CORE_PX`` px from
the outline), the share of pixels on

- a ridge: a line 1-3 px wide darker than both sides by more than ``LINE`` (the pixel's density
  above the larger of the two at 2 px on either side, in one of four directions);
- a step: a jump of more than ``LINE`` between two neighbours with flat ink on both sides (each
  side changes by less than a third of that over the next pixel);

either running on for 3 px or more;

and, for a check that the streaks of flying white are kept, on a trough (a lighter line);
each split by the line's run against the stroke's local direction (the stroke's across-way is
the gradient of the smoothed distance to the outline): ``along`` (a bristle streak, 飞白: kept)
or ``across`` (a seam at the front of a mark, a grid: what real ink never shows). Statistics
only, nothing here is used by the simulator.

    python scripts/seams_eval.py 元也光国永村 [--size 512] [--save DIR]
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

INKED = 0.2  # density above which a pixel is ink
CORE_PX = 2.0  # px from the outline: the ink's core, where seams are counted
LINE = (
    0.02  # density (the visible grey, 5 of 255 levels): a ridge or step larger than this is a line
)
SMOOTH_PX = 2.0  # Gaussian of the distance to the outline whose gradient is the across-way
# the four directions a line's normal is tried in (rows, columns), unit steps
NORMALS = ((0, 1), (1, 0), (1, 1), (1, -1))


def _shift(d, dy: int, dx: int) -> np.ndarray:
    """d moved so that out[y, x] = d[y + dy, x + dx] (edge values beyond the border)."""
    p = np.pad(d, 3, mode="edge")
    h, w = d.shape
    return p[3 + dy : 3 + dy + h, 3 + dx : 3 + dx + w]


def lines(d: np.ndarray) -> tuple[np.ndarray, ...]:
    """(ridge, step, trough, and the index into NORMALS of each one's strongest direction):
    where density ``d`` has a thin ridge, a hard step or a thin trough (a lighter line: a
    streak of flying white) larger than LINE that runs on for at least 3 px (the pixels either
    side along the line have one too, in the same direction: a line, not a speck of the hair's
    texture)."""
    ridge_s, step_s, trough_s = [], [], []
    for dy, dx in NORMALS:
        a1, b1 = _shift(d, dy, dx), _shift(d, -dy, -dx)
        a2, b2 = _shift(d, 2 * dy, 2 * dx), _shift(d, -2 * dy, -2 * dx)
        jump = np.abs(a1 - d)
        flat = np.maximum(np.abs(a2 - a1), np.abs(d - b1)) < jump / 3.0
        for out, score in (
            (ridge_s, np.minimum(d - a2, d - b2)),
            (step_s, np.where(flat, jump, 0.0)),
            (trough_s, np.minimum(a2 - d, b2 - d)),
        ):
            on = score > LINE
            run = on & _shift(on, -dx, dy) & _shift(on, dx, -dy)  # along the line: (-dx, dy)
            out.append(np.where(run, score, 0.0))
    found = [np.stack(s) for s in (ridge_s, step_s, trough_s)]
    return tuple(f.max(0) > 0 for f in found) + tuple(f.argmax(0) for f in found)


def seam_stats(d: np.ndarray) -> dict:
    """The seam statistic of one character's ink density ``d`` (H, W, top row first)."""
    ink = d > INKED
    dist = ndimage.distance_transform_edt(ink)
    core = dist >= CORE_PX
    sm = ndimage.gaussian_filter(dist, SMOOTH_PX)
    gy, gx = np.gradient(sm)
    g = np.hypot(gy, gx)
    known = core & (g > 0.05)
    ridge, step, trough, rn, sn, tn = lines(d)
    nrm = np.array(NORMALS, dtype=float)
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    out = {"core_px": int(core.sum())}
    n = max(int(core.sum()), 1)
    for name, on, which in (("ridge", ridge, rn), ("step", step, sn), ("trough", trough, tn)):
        cos = np.abs(nrm[which, 0] * gy + nrm[which, 1] * gx) / np.maximum(g, 1e-9)
        # the line's normal along the across-way: the line runs along the stroke
        along = on & known & (cos >= np.sqrt(0.5))
        across = on & known & (cos < np.sqrt(0.5))
        out[name] = float((on & core).sum() / n)
        out[name + "_along"] = float(along.sum() / n)
        out[name + "_across"] = float(across.sum() / n)
    return out


def density(char: dict, size: int) -> np.ndarray:
    """The ink density (the darkest channel's) of ``char`` written at ``size`` px, top first."""
    from sim.cli.shared import _response
    from sim.writing.writer import write_character

    template = _template()
    _rec, _resp, sim = write_character(char, size, template, response=_response(template))
    return sim.paper.ink.max(axis=-1)[::-1].astype(np.float64)


def _template():
    from sim.cli.main import _parser
    from sim.cli.shared import _template as template

    return template(_parser().parse_args(["write", "x", "-o", "/dev/null"]))


def densities(args):
    """(name, density) per character of ``args.chars``: written with the defaults at
    ``args.size`` (stroke data from ``args.data``), or read from ``args.load``; each kept in
    ``args.save`` when given."""
    from sim.cli.shared import _chars

    names = list(args.chars)
    chars = [None] * len(names) if args.load else _chars(names, args.data)
    for name, ch in zip(names, chars, strict=True):
        if args.load:
            d = np.load(os.path.join(args.load, f"{name}.npy")).astype(np.float64)
        else:
            d = density(ch, args.size)
        if args.save:
            os.makedirs(args.save, exist_ok=True)
            np.save(os.path.join(args.save, f"{name}.npy"), d.astype(np.float32))
        yield name, d


def arguments(doc: str) -> argparse.ArgumentParser:
    """The options every script reading ``densities`` takes: characters, data, size, save, load."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("chars")
    ap.add_argument("--data", default="/tmp/chars/package")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--save", default=None, help="a folder for each character's density (.npy)")
    ap.add_argument("--load", default=None, help="read the densities --save wrote, not write")
    return ap


def main(argv=None) -> int:
    args = arguments(__doc__).parse_args(argv)
    keys = tuple(f"{k}{w}" for k in ("ridge", "step", "trough") for w in ("", "_along", "_across"))
    total = dict.fromkeys(keys, 0.0)
    print("char " + " ".join(f"{k:>10}" for k in keys))
    names = list(args.chars)
    for name, d in densities(args):
        s = seam_stats(d)
        for k in keys:
            total[k] += s[k] / len(names)
        print(f"{name}    " + " ".join(f"{s[k]:10.4f}" for k in keys))
    print("mean " + " ".join(f"{total[k]:10.4f}" for k in keys))
    return 0


if __name__ == "__main__":
    sys.exit(main())
