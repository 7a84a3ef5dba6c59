# SPDX-License-Identifier: GPL-3.0-or-later
"""Hooks flicked up to a point (issue 26.2), a 竖钩's, a 弯钩's, a 竖弯钩's 乚 (kind ``foot``: off
a sharp corner; ``curl``: off the curve the end curls from, ``hooks``): per hook, the ink's width
across it at 25, 50 and 75 % of the way from the median's corner to the font's tip, against the
font's (the stroke's own outline cut there, the ink counted 2 px either side of the cut), how
far the ink stops short of the font's tip (px), the ink outside the font round the hook (px),
and the hook's darkness (1 - grey / paper, bare pixels 0) over the font's hook past 50 % and
past 75 % of its length, against the body's (the stroke's own font nearest its median over
``BODY`` hook lengths back up from the corner, not the hook's): the hook's darkness over the
body's, and its pale share (the hook's font past 25 % darker than no more than half the body,
grey or streaked between the hair's bundles). Written with the default brush and seed, as
shoulders_eval does; the means are given per kind and over all.

    python scripts/hooks_eval.py 村时守寸 [--size 384 512] [--workers 2]
"""

from __future__ import annotations

import argparse
import os
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

STEP = 0.25  # px between the samples of a cut across the hook
PAD = 2.0  # px either side of the font's cut where the ink is counted too
BODY = 2.0  # hook lengths of the median back up from the corner whose font is the body


def _hook_corner(pts, polys, step: float) -> tuple[int, str] | None:
    """Where a hook leaves its stroke's median (``pts``: resampled every ``step``), as
    ``outline.median_movements`` cuts it, and its kind: at the last sharp corner (``"foot"``: a
    竖钩, a 横折钩, a 弯钩) if the movement after it is a hook, else where the end curls off a
    curve (``"curl"``: a 竖弯钩's 乚, 乙, 九; ``outline._curled_end``); None if neither."""
    from sim.writing import outline as ol

    edges = [0, *ol.corners(pts, step), len(pts) - 1]
    if len(edges) > 2 and ol._pieces(pts, polys, step, edges)[-1][2]:
        return edges[-2], "foot"
    k = ol._curled_end(pts, step, edges[-2])
    return None if k is None else (k, "curl")


def hooks(char: dict) -> list[tuple[int, np.ndarray, np.ndarray, np.ndarray, str]]:
    """Each hook that goes up from its foot or from the curve it curls off: (stroke, median
    corner, font tip, the median's points up to the corner, kind: ``_hook_corner``), data
    units. The tip is the stroke outline's point farthest along the hook near it. (The curled
    end's 乚 added in issue 26.2: only a corner's hooks were read, none of 元 光 也's.)"""
    from sim.writing import outline as ol

    out = []
    step = 4.0
    moves = ol.median_movements(char, step)
    polys_all = ol.stroke_polygons(char)
    for si, (med, polys, (_pieces, hook)) in enumerate(
        zip(char["medians"], polys_all, moves, strict=True)
    ):
        pts, _ = ol.resample(ol._to_the_tips(med, polys), step)
        at = _hook_corner(pts, polys, step) if hook else None
        if at is None:
            continue
        c = pts[at[0]]
        d = (pts[-1] - c) / np.linalg.norm(pts[-1] - c)
        edge = np.concatenate(polys)
        edge = edge[np.linalg.norm(edge - c, axis=1) < 1.5 * np.linalg.norm(pts[-1] - c)]
        tip = edge[int(np.argmax((edge - c) @ d))]
        if tip[1] > c[1]:  # y up: a hook flicked up
            out.append((si, c, tip, pts[: at[0] + 1], at[1]))
    return out


def _cut(own, ink, centre, across, reach) -> tuple[float, float]:
    """(ink, font) widths (px) across the hook at ``centre``: the run of the stroke's own font
    through the font sample nearest ``centre`` along ``across``, and the ink on it and ``PAD``
    either side."""
    n = own.shape[0]
    s = np.arange(-reach, reach, STEP)
    q = np.clip(np.round(centre[None] + s[:, None] * across[None]).astype(int), 0, n - 1)
    font = own[q[:, 1], q[:, 0]]
    if not font.any():
        return 0.0, 0.0
    j = int(np.argmin(np.where(font, np.abs(s), np.inf)))
    lo, hi = j, j
    while lo > 0 and font[lo - 1]:
        lo -= 1
    while hi < len(s) - 1 and font[hi + 1]:
        hi += 1
    pad = int(PAD / STEP)
    a, b = max(lo - pad, 0), min(hi + pad, len(s) - 1)
    return float(ink[q[a : b + 1, 1], q[a : b + 1, 0]].sum() * STEP), (hi - lo + 1) * STEP


def _body(own, median, corner, tip) -> np.ndarray:
    """The stroke's own font (``own``) nearer its median (``median``: up to the corner) from
    half a hook length to ``BODY`` hook lengths back up from the corner than the hook's line
    (corner to tip), image pixels."""
    from scipy.spatial import cKDTree

    length = float(np.linalg.norm(tip - corner))
    s = np.cumsum(np.linalg.norm(np.diff(median[::-1], axis=0), axis=1))
    back = median[::-1][1:][(s > 0.5 * length) & (s < BODY * length)]
    hook = corner[None] + np.linspace(0.0, 1.0, 16)[:, None] * (tip - corner)[None]
    yy, xx = np.nonzero(own)
    q = np.stack([xx, yy], axis=1).astype(float)
    if not len(back):
        return np.zeros_like(own)
    d_body = cKDTree(back).query(q)[0]
    d_hook = cKDTree(hook).query(q)[0]
    out = np.zeros_like(own)
    out[yy, xx] = d_body < d_hook
    return out


def _one_hook(ink, dark, font, own, corner, tip, median) -> tuple:
    """The figures of one hook (module doc), image pixels."""
    from scipy.ndimage import binary_dilation

    n = font.shape[0]
    length = float(np.linalg.norm(tip - corner))
    u = (tip - corner) / length
    v = np.array([-u[1], u[0]])
    yy, xx = np.mgrid[0:n, 0:n]
    along = (xx - corner[0]) * u[0] + (yy - corner[1]) * u[1]
    perp = (xx - corner[0]) * v[0] + (yy - corner[1]) * v[1]
    widths = [_cut(own, ink, corner + f * length * u, v, length) for f in (0.25, 0.5, 0.75)]
    region = binary_dilation(own, iterations=6) & (along > 0.2 * length) & (along < 1.15 * length)
    region &= np.abs(perp) < 0.6 * length
    outside = int((ink & ~binary_dilation(font, iterations=1) & region).sum())
    near = binary_dilation(own, iterations=2) & region & ink & (np.abs(perp) < 0.5 * length)
    short = length - (float(along[near].max()) if near.any() else 0.0)
    d50 = float(dark[own & (along > 0.5 * length) & (along < length)].mean())
    d75 = float(dark[own & (along > 0.75 * length)].mean())
    body = float(dark[_body(own, median, corner, tip)].mean())
    past = dark[own & (along > 0.25 * length) & (along < length)]
    pale = float(np.mean(past < 0.5 * body))
    return widths, short, outside, d50, d75, body, pale


def measure(task) -> list[tuple]:
    """Per hook of one character written at ``n`` px: (char, n, stroke, kind, widths, short,
    outside, darkness past 50 %, past 75 %, body's, pale share)."""
    from scripts.shoulders_eval import written  # the same writing as the corners' measure
    from sim.core.recording import DEFAULT_BRUSH
    from sim.writing.outline import fill, rasterise, stroke_polygons, to_image
    from sim.writing.writer import coverage_mask

    ch, n, data = task
    char, sim = written(ch, DEFAULT_BRUSH, n, data)
    ink = coverage_mask(sim)
    grey = sim.image8().astype(float).max(axis=2)
    dark = np.clip(1.0 - grey / float(np.median(grey[:8, :])), 0.0, 1.0)
    font = rasterise(char, n)
    polys = stroke_polygons(char)
    rows = []
    for si, corner, tip, median, kind in hooks(char):
        own = fill([to_image(q, n) for q in polys[si]], n)
        c, t = to_image(corner[None], n)[0], to_image(tip[None], n)[0]
        one = _one_hook(ink, dark, font, own, c, t, to_image(median, n))
        rows.append((ch, n, si, kind, *one))
    return rows


def _summary(rows, label: str) -> None:
    """The means over ``rows`` (``measure``'s) of one kind of hook (``label``)."""
    if not rows:
        return
    r = np.nanmean([[i / f if f else np.nan for i, f in row[4]] for row in rows], axis=0)
    m = np.mean([row[5:] for row in rows], axis=0)
    print(
        f"{label} mean {len(rows)} hooks: ink/font width {r[0]:.2f} {r[1]:.2f} {r[2]:.2f}; "
        f"short {m[0]:.1f} px; outside {m[1]:.1f} px; dark past 50 % {m[2]:.3f}, 75 % {m[3]:.3f}"
        f"; body {m[4]:.3f}; hook/body past 50 % {np.mean([r[7] / r[9] for r in rows]):.3f}; "
        f"pale {m[5]:.3f}"
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("chars")
    ap.add_argument("--size", type=int, nargs="+", default=[384, 512])
    ap.add_argument("--data", default="/tmp/chars/package")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    tasks = [(c, n, a.data) for n in a.size for c in a.chars]
    with ProcessPoolExecutor(a.workers) as ex:
        rows = [r for rs in ex.map(measure, tasks) for r in rs]
    print(
        f"{'ch':<3}{'px':>4}{'st':>3} kind  ink/font width at 25/50/75 % (px)      short  out  "
        "dark 50 75 body  pale"
    )
    for ch, n, si, kind, w, short, out, d50, d75, body, pale in rows:
        ws = "  ".join(f"{i:4.1f}/{f:4.1f}" for i, f in w)
        print(
            f"{ch:<3}{n:>4}{si:>3} {kind:<4}  {ws}  {short:5.1f} {out:4d}  {d50:.2f} {d75:.2f}"
            f" {body:.2f}  {pale:.2f}"
        )
    for kind in ("foot", "curl", None):
        _summary([r for r in rows if kind in (None, r[3])], kind or "all")
    return 0


if __name__ == "__main__":
    sys.exit(main())
