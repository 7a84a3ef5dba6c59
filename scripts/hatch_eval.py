# SPDX-License-Identifier: GPL-3.0-or-later
"""Cross-hatched hook ends (issue 26, points 1 and 2): at a 竖弯钩's 乚 end (``hooks_eval``'s
``curl`` hooks) the brush turns at the toe and flicks up; if every pass over the toe lays its
own crisp hair lines in its own direction of travel the lines of all directions add up to a
broom. A real 乚 is one dark pointed hook whose dry streaks, when any, run along the flick.
Per hook, written with the default brush and seed, over the hook's box (the stroke's own font,
dilated by ``PAD_PX``, from ``BACK`` hook lengths before the corner to past the tip):

- ``visits``: the mean number of steps that darkened an inked pixel (by more than ``EPS`` of
  density, the darkest channel's);
- ``cross``: the share of the inked pixels (density above ``INKED``) darkened by steps whose
  directions of travel (as lines: modulo 180 deg) differ by more than ``CROSS_DEG``;
- ``spread``: the median over the inked pixels of that largest difference (deg); both
  also for the direction of the lines of hair each step laid (``_line``) besides its travel.

Statistics only, nothing here is used by the simulator.

    python scripts/hatch_eval.py 虎九元 [--size 512]
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

EPS = 0.005  # density a step must add to a pixel to count as a visit that inked it
INKED = 0.2  # density above which a pixel is ink
CROSS_DEG = 45.0  # visits whose lines differ by more than this cross
PAD_PX = 3  # px the hook's own font is dilated by
BACK = 0.0  # hook lengths before the corner that the box takes in (the toe)


def _boxes(char, n: int) -> list[tuple[int, np.ndarray]]:
    """(stroke, mask of the hook's box) per 乚 (``curl``) hook of ``char`` at ``n`` px."""
    from scipy.ndimage import binary_dilation

    from scripts.hooks_eval import hooks
    from sim.writing.outline import fill, stroke_polygons, to_image

    polys = stroke_polygons(char)
    out = []
    yy, xx = np.mgrid[0:n, 0:n]
    for si, corner, tip, _median, kind in hooks(char):
        if kind != "curl":
            continue
        c, t = to_image(corner[None], n)[0], to_image(tip[None], n)[0]
        length = float(np.linalg.norm(t - c))
        u = (t - c) / length
        along = (xx - c[0]) * u[0] + (yy - c[1]) * u[1]
        own = fill([to_image(q, n) for q in polys[si]], n)
        box = binary_dilation(own, iterations=PAD_PX) & (along > -BACK * length)
        out.append((si, box & (along < 1.2 * length)))
    return out


def _spread(angles: np.ndarray) -> float:
    """The largest difference (deg) between lines at ``angles`` (deg, modulo 180)."""
    a = np.sort(np.mod(angles, 180.0))
    if a.size < 2:
        return 0.0
    gaps = np.diff(np.r_[a, a[0] + 180.0])
    return float(180.0 - gaps.max())


def measure(ch: str, n: int, data) -> list[tuple]:
    """Per 乚 hook of ``ch`` written at ``n`` px: (char, stroke, visits, cross, spread)."""
    from scripts.shoulders_eval import written
    from sim.core.recording import DEFAULT_BRUSH
    from sim.engine import simulation
    from sim.writing.hanzi import find_char

    boxes = _boxes(find_char(ch, data), n)
    if not boxes:
        return []
    mask = np.logical_or.reduce([b for _, b in boxes])
    ys, xs = np.nonzero(mask)
    rs = n - 1 - ys  # the paper's rows are bottom first
    visits: dict[int, tuple] = {}  # by step: a practice taken back is redone
    take = simulation.Simulation._deposit_flat

    def watched(self, pending, filled):
        if self.paper.ink.shape[:2] != (n, n):  # another writing (the response's)
            take(self, pending, filled)
            return
        for p, f in zip(pending, filled, strict=True):
            before = self.paper.ink[rs, xs].max(axis=1)
            take(self, [p], [f])
            gain = self.paper.ink[rs, xs].max(axis=1) - before
            hit = np.flatnonzero(gain > EPS)
            if hit.size:
                visits[p.step] = (hit, _angle(p.bristles.travel), _line(p.bristles))
            else:
                visits.pop(p.step, None)

    simulation.Simulation._deposit_flat = watched
    try:
        _char, sim = written(ch, DEFAULT_BRUSH, n, data)
    finally:
        simulation.Simulation._deposit_flat = take
    dens = sim.paper.ink[rs, xs].max(axis=1)
    per = [[] for _ in range(ys.size)]
    for hit, travel, line in visits.values():
        for i in hit.tolist():
            per[i].append((travel, line))
    rows = []
    for si, box in boxes:
        sel = np.flatnonzero(box[ys, xs] & (dens > INKED))
        count = np.array([len(per[i]) for i in sel])
        figures = [float(count.mean())]
        for k in (0, 1):
            spreads = np.array([_spread(np.array([v[k] for v in per[i]])) for i in sel])
            figures += [float(np.mean(spreads > CROSS_DEG)), float(np.median(spreads))]
        rows.append((ch, si, *figures))
    return rows


def _angle(v) -> float:
    """The direction (deg) of the vector ``v``."""
    return float(np.degrees(np.arctan2(v[1], v[0])))


def _line(st) -> float:
    """The direction (deg) of the lines of hair a step lays by the contact: the newest segment
    of the path they are measured from (``sim.brush.bristles._trail_path``)."""
    from sim.brush.bristles import _trail_path

    path = _trail_path(st)
    path = path[np.isfinite(path[:, 0])]
    return _angle(path[-1] - path[-2]) if len(path) >= 2 else _angle(st.travel)


def main(argv=None) -> int:
    from scripts.flick_eval import hook_rows

    rows = hook_rows(__doc__, measure, argv)
    print("char st  visits  cross spread (travel)  cross spread (lines)")
    for ch, si, *f in rows:
        print(f"{ch}   {si:3d} {f[0]:7.1f} {f[1]:6.3f} {f[2]:7.1f} {f[3]:14.3f} {f[4]:7.1f}")
    if rows:
        m = np.mean([r[2:] for r in rows], axis=0)
        print(f"mean {len(rows):2d}   {m[0]:7.1f} {m[1]:6.3f} {m[2]:7.1f} {m[3]:14.3f} {m[4]:7.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
