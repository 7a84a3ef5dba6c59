# SPDX-License-Identifier: GPL-3.0-or-later
"""Per 折 corner and hook foot (issue 26): ink standing out past the font's outline near the
corner, the outline's pixels left bare there, and how far the outline's corner point is from the
nearest ink (a crisp shoulder inks its corner; a foot's corner is its outer point). Corners are
found from the stroke data alone: the clockwise sharp corners of each median
(``outline.corners``, ``_clockwise``), and the corner into a hook (a foot). Prints a mean per
brush and kind (zhe, foot).

    python scripts/shoulders_eval.py [--brush default wolf_stiff] [--png DIR] [chars ...]
"""

from __future__ import annotations

import argparse
import os
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sim.core.recording import DEFAULT_BRUSH  # noqa: E402

SHIPPED = "永口日国月田门同的也几书"
UNSEEN = "四司旧里勇目因回水寸才小"
NEAR = 1.5  # stroke widths round the corner that are read


def corner_points(char: dict) -> list[tuple[str, np.ndarray, np.ndarray, float, int]]:
    """Each 横折's and hook foot's (kind "zhe" or "foot", median corner, outline corner, leg
    width, stroke), data units: the outline's
    corner is the stroke outline's point farthest along the corner's outer bisector within
    ``NEAR`` widths of the median's corner."""
    from sim.writing import outline as ol

    out = []
    step = 4.0
    moves = ol.median_movements(char, step)
    for st, (med, polys, (pieces, hook)) in enumerate(
        zip(char["medians"], ol.stroke_polygons(char), moves, strict=True)
    ):
        pts, _ = ol.resample(ol._to_the_tips(med, polys), step)
        ks = ol.corners(pts, step)
        for j, k in enumerate(ks):
            foot = hook and j == len(ks) - 1 and len(pieces) == len(ks) + 1
            if not foot and not ol._clockwise(pts, k, step):
                continue
            d, _ = ol._turn_at(pts, k, step)
            win = int(round(ol.CORNER_WINDOW / step))
            e = pts[min(k + win, len(pts) - 1)] - pts[k]
            bis = d / np.linalg.norm(d) - e / np.linalg.norm(e)
            bis /= np.linalg.norm(bis)
            leg = pts[k : k + 3 * win]
            width = float(np.median(ol._bands(leg, polys)[1]))
            edge = np.concatenate(polys)
            near = edge[np.linalg.norm(edge - pts[k], axis=1) < NEAR * width]
            if not len(near):
                continue
            tip = near[int(np.argmax((near - pts[k]) @ bis))]
            out.append(("foot" if foot else "zhe", pts[k], tip, width, st))
    return out


def _img(p, n):
    return np.array([p[0] * n / 1024.0, (900.0 - p[1]) * n / 1024.0])


def written(ch: str, brush: str, n: int, data):
    """The character ``ch`` (from ``data``) written at ``n`` px with the brush preset ``brush``
    and the defaults, its response from the cache in $XDG_CACHE_HOME: (char, simulation)."""
    from sim.core.recording import Recording
    from sim.writing.hanzi import find_char
    from sim.writing.response import calibrate
    from sim.writing.writer import write_character

    char = find_char(ch, data)
    tpl = Recording(np.zeros((1, 6)), seed=0, brush={"preset": brush})
    tpl.resolve()
    cache = os.environ.get("XDG_CACHE_HOME", "/tmp") + "/hairy-brush"
    _rec, _r, sim = write_character(char, n, tpl, response=calibrate(tpl, cache_dir=cache))
    return char, sim


def _median_width(dist, path, r, corners) -> float:
    """A stroke's median width (px) in a mask whose distance transform is ``dist``: twice the
    largest distance within ``r`` / 2 of each point of its median (``path``, image px) at
    least ``r`` from its ends and ``NEAR`` * ``r`` from its corners."""
    n = dist.shape[0]
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(path, axis=0), axis=1))])
    far = (s > r) & (s < s[-1] - r)
    for c in corners:
        far &= np.linalg.norm(path - c, axis=1) > NEAR * r
    if not far.any():  # a short leg: all of it past the corner's disc
        far = s > NEAR * r
    got = []
    h = max(int(r / 2), 1)
    for x, y in np.round(path[far]).astype(int):
        win = dist[max(y - h, 0) : min(y + h + 1, n), max(x - h, 0) : min(x + h + 1, n)]
        if win.size:
            got.append(win.max())
    return 2.0 * float(np.median(got)) if got else float("nan")


def shape(mask, char, n, stroke, corner, width) -> tuple[float, float]:
    """A corner's widest cross-section: the diameter of the largest disc inside ``mask`` within
    ``NEAR`` widths of ``corner`` (median corner, data units), over the median width in
    ``mask`` of the leg on from it (``_median_width``); and that median width (px). (A crisp
    L of two bands as wide as the leg: 1.17.)"""
    from scipy.ndimage import distance_transform_edt

    from sim.writing.outline import resample

    dist = distance_transform_edt(mask)
    c, r = _img(corner, n), width * n / 1024.0
    pts, _ = resample(np.asarray(char["medians"][stroke], float), 4.0)
    path = np.stack([_img(p, n) for p in pts])
    ks = [_img(k[1], n) for k in corner_points(char) if k[4] == stroke]
    leg = path[int(np.argmin(np.linalg.norm(path - c, axis=1))) :]  # the leg, on from the corner
    med = _median_width(dist, leg, r, ks)
    yy, xx = np.mgrid[0:n, 0:n]
    disc = (xx - c[0]) ** 2 + (yy - c[1]) ** 2 < (NEAR * r) ** 2
    return 2.0 * float(dist[disc].max()) / med, med


def measure(task):
    """Per corner of one character written with one brush: (char, brush, index, outside px,
    bare px, corner distance px, widest over median (ink, font; ``shape``), outside on the
    corner's inner side px, holes px); and the written image."""
    from scipy.ndimage import binary_dilation, binary_fill_holes, distance_transform_edt, label

    from sim.writing.outline import rasterise
    from sim.writing.writer import coverage_mask

    ch, brush, n, data, png = task
    char, sim = written(ch, brush, n, data)
    ink = coverage_mask(sim)
    font = rasterise(char, n)
    outside = ink & ~binary_dilation(font, iterations=1)
    dist = distance_transform_edt(~ink)
    holes, _ = label(binary_fill_holes(ink) & ~ink)
    holes = holes * ~np.isin(holes, holes[~font])  # wholly inside the font: not 口's counter
    yy, xx = np.mgrid[0:n, 0:n]
    rows = []
    for i, (kind, mc, tip, w, st) in enumerate(corner_points(char)):
        c, t, r = _img(mc, n), _img(tip, n), NEAR * w * n / 1024.0
        disc = (xx - c[0]) ** 2 + (yy - c[1]) ** 2 < r * r
        inner = (xx - c[0]) * (t[0] - c[0]) + (yy - c[1]) * (t[1] - c[1]) < 0.0
        ti = np.clip(np.round(t).astype(int), 0, n - 1)
        wide = shape(ink, char, n, st, mc, w)[0], shape(font, char, n, st, mc, w)[0]
        rows.append(
            (
                ch,
                brush,
                kind,
                i,
                int((outside & disc).sum()),
                int((font & ~ink & disc).sum()),
                float(dist[ti[1], ti[0]]),
                *wide,
                int((outside & disc & inner).sum()),
                int(((holes > 0) & disc).sum()),
            )
        )
        if png:
            _crop(png, f"{ch}_{brush}_{kind}{i}", sim.image8(), font, c, r)
    return rows


def _crop(folder, name, rgb, font, c, r):
    """A 4x crop round the corner: the writing, and beside it the font's outline over it."""
    from sim.image.png import write_png

    n = font.shape[0]
    h = int(r * 1.2)
    y0, y1 = max(int(c[1]) - h, 0), min(int(c[1]) + h, n)
    x0, x1 = max(int(c[0]) - h, 0), min(int(c[0]) + h, n)
    a = rgb[y0:y1, x0:x1].copy()
    f = font[y0:y1, x0:x1]
    edge = f ^ np.roll(f, 1, 0) | f ^ np.roll(f, 1, 1)
    b = a.copy()
    b[edge] = (220, 30, 30)
    both = np.concatenate([a, np.full((a.shape[0], 2, 3), 255, np.uint8), b], axis=1)
    write_png(os.path.join(folder, name + ".png"), both.repeat(4, 0).repeat(4, 1))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("chars", nargs="*", default=list(SHIPPED + UNSEEN))
    ap.add_argument("--brush", nargs="+", default=[DEFAULT_BRUSH, "wolf_stiff"])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--data", default="/tmp/chars/package")
    ap.add_argument("--png", default=None, help="folder for 4x crops of every corner")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    if a.png:
        os.makedirs(a.png, exist_ok=True)
    tasks = [(c, b, a.size, a.data, a.png) for b in a.brush for c in a.chars]
    with ProcessPoolExecutor(a.workers) as ex:
        rows = [r for rs in ex.map(measure, tasks) for r in rs]
    head = f"{'char':<4} {'brush':<10} {'kind':<4} {'#':>2} {'outside':>8} {'bare':>6}"
    print(f"{head} {'corner px':>9} {'widest':>6} {'font':>5} {'inner':>5} {'holes':>5}")
    for ch, b, kind, i, o, bare, d, wi, wf, inner, hole in rows:
        line = f"{ch:<4} {b:<10} {kind:<4} {i:>2} {o:>8} {bare:>6} {d:>9.1f}"
        print(f"{line} {wi:>6.2f} {wf:>5.2f} {inner:>5} {hole:>5}")
    for b in a.brush:
        for kind in ("zhe", "foot"):
            sel = [r for r in rows if r[1] == b and r[2] == kind]
            if not sel:
                continue
            figures = (np.nanmean([r[k] for r in sel]) for k in range(4, 11))  # a short leg: nan
            o, bare, d, wi, wf, inner, hole = figures
            head = f"mean {b:<10} {kind:<4} {len(sel)} corners"
            print(f"{head}  outside {o:.1f}  bare {bare:.1f}  corner {d:.2f} px")
            print(f"{' ' * len(head)}  widest {wi:.2f} (font {wf:.2f}) x the median width,")
            print(f"{' ' * len(head)}  outside inside the corner {inner:.1f}, holes {hole:.1f} px")
    return 0


if __name__ == "__main__":
    sys.exit(main())
