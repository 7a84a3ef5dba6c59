# SPDX-License-Identifier: GPL-3.0-or-later
"""Dots (点) against the font (issue 26, point 2: the tip lands light, the belly presses, 回锋).

    python scripts/dots_eval.py write TAG CHARS [NAME=VALUE ...] [--data DIR] [--size 512]
    python scripts/dots_eval.py report TAG [TAG ...] [--png DIR]

``write`` writes each character with the default brush and seed (as shoulders_eval does) and
keeps its ink (coverage above half) and grey image in $DOTS_EVAL_OUT (/tmp/dots_eval)/TAG.npz;
with $DOTS_EVAL_ROOT another checkout's ``sim`` writes (a before/after pair). ``report`` prints
per dot (a stroke whose median is shorter than ``DOT`` times its widest, as entries_eval reads
them): the ink's width across the dot over the font's at 25, 50 and 75 % of the font dot's
length along its way (the median's start to end), where the widest cut lies (share of that
length) for the ink and for the font, the ink more than a pixel outside the font round the dot
(and of it past the font dot's end),
and the detached specks near it (ink pieces under ``SPECK`` px that touch no other stroke's
font), with ``--png`` a 4x crop of each dot with the font's edge drawn over it in red."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage as ndi

ROOT = Path(os.environ.get("DOTS_EVAL_ROOT", Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(ROOT))

OUT = os.environ.get("DOTS_EVAL_OUT", "/tmp/dots_eval")
DOT = 3.4  # median length over widest below which a stroke is read as a dot (entries_eval's)
SPECK = 40  # px: an ink piece smaller than this apart from the rest is a speck
SLAB = 1.0  # px either side of a cut across the dot where the ink and the font are counted
AT = (0.25, 0.5, 0.75)  # shares of the font dot's length the widths are compared at


def write(tag: str, chars: str, data: str, n: int, sets=()) -> None:
    """(``sets``: NAME=VALUE, a constant of sim.writing.lifts for an experiment.)"""
    import sim.writing.lifts as L
    from scripts.shoulders_eval import written

    for kv in sets:
        name, value = kv.split("=")
        setattr(L, name, float(value))
    from sim.core.recording import DEFAULT_BRUSH
    from sim.writing.writer import coverage_mask

    out = {"n": np.array(n)}
    for c in chars:
        _char, sim = written(c, DEFAULT_BRUSH, n, data)
        out[c] = coverage_mask(sim)
        out[c + "_img"] = sim.image8().astype(np.uint8)
        print(c, flush=True)
    os.makedirs(OUT, exist_ok=True)
    np.savez_compressed(f"{OUT}/{tag}.npz", **out)


def strokes(char: dict, n: int):
    """Per stroke of ``char``: (k, median (data units), its length, the half widths along it
    resampled every 4 units, the median in image px, a function giving the font's mask)."""
    from sim.writing.outline import distance_to_outline, fill, resample, stroke_polygons, to_image

    for k, (med, polys) in enumerate(zip(char["medians"], stroke_polygons(char), strict=True)):
        med = np.asarray(med, float)
        pts, _ = resample(med, 4.0)
        half = np.maximum(distance_to_outline(pts, polys), 0.0)
        length = float(np.linalg.norm(np.diff(med, axis=0), axis=1).sum())

        def mask(polys=polys):
            return fill([to_image(p, n) for p in polys], n)

        yield k, med, length, half, to_image(med, n), mask


def dots(char: dict, n: int) -> list[dict]:
    """Per dot of ``char``: its stroke, start and unit way (image px), and its font mask."""
    from sim.writing.outline import EM

    out = []
    for k, _, length, half, m, mask in strokes(char, n):
        w = 2 * half.max()
        if length >= DOT * w:
            continue
        d = (m[-1] - m[0]) / max(float(np.linalg.norm(m[-1] - m[0])), 1e-9)
        out.append({"stroke": k, "start": m[0], "way": d, "mask": mask(), "w": w * n / EM})
    return out


def _profile(region, along, across, lo, length) -> np.ndarray:
    """The width (px) of ``region`` in cuts across the dot every 2 % of its length (the pixels
    within ``SLAB`` of each cut over the cut's thickness), from ``lo`` along."""
    t = np.linspace(0.0, 1.0, 51)
    a, c = along[region], across[region]
    out = np.zeros(len(t))
    for i, ti in enumerate(t):
        cut = np.abs(a - (lo + ti * length)) <= SLAB
        if cut.any():  # the run across: from the nearest to the farthest pixel of the cut
            out[i] = min(cut.sum() / (2 * SLAB), c[cut].max() - c[cut].min() + 1)
    return out


def measure(char: dict, ink: np.ndarray) -> list[dict]:
    """The figures of each dot of ``char`` written as ``ink`` (module doc)."""
    from sim.writing.outline import rasterise

    n = ink.shape[0]
    font = rasterise(char, n)
    near_font = ndi.binary_dilation(font, iterations=1)
    info = dots(char, n)
    yy, xx = np.mgrid[0:n, 0:n] + 0.5
    labels, _ = ndi.label(ink, np.ones((3, 3), bool))
    sizes = np.bincount(labels.ravel())
    rows = []
    for s in info:
        own = s["mask"]
        others = font & ~own
        d, p0 = s["way"], s["start"]
        along = (xx - p0[0]) * d[0] + (yy - p0[1]) * d[1]
        across = -(xx - p0[0]) * d[1] + (yy - p0[1]) * d[0]
        lo, hi = along[own].min(), along[own].max()
        zone = ndi.binary_dilation(own, iterations=max(int(0.6 * s["w"]), 3))
        mine = ink & zone & ~ndi.binary_dilation(others, iterations=2)
        pf = _profile(own & ~ndi.binary_dilation(others, iterations=2), along, across, lo, hi - lo)
        pi = _profile(mine, along, across, lo, hi - lo)
        k = [int(round(a * 50)) for a in AT]
        touch = np.unique(labels[ndi.binary_dilation(others, iterations=2) & ink])
        near = np.unique(labels[zone & ink])
        specks = [q for q in near if q and sizes[q] < SPECK and q not in touch]
        past = [q for q in specks if along[labels == q].mean() > lo + 0.5 * (hi - lo)]
        rows.append(
            {
                "stroke": s["stroke"],
                "ratio": [pi[j] / max(pf[j], 1e-9) for j in k],
                "ink_w": [pi[j] for j in k],
                "font_w": [pf[j] for j in k],
                "peak_ink": float(np.argmax(_smooth3(pi)) / 50),
                "peak_font": float(np.argmax(_smooth3(pf)) / 50),
                "outside": int((mine & ~near_font).sum()),
                "beyond": int((mine & ~near_font & (along > hi + 1.0)).sum()),
                "specks": len(specks),
                "past": len(past),
                "box": (own, zone),
            }
        )
    return rows


def _smooth3(v) -> np.ndarray:
    return np.convolve(np.pad(v, 1, mode="edge"), np.ones(3) / 3, mode="valid")


def crop(img, own, zone, scale: int = 4) -> np.ndarray:
    """A ``scale`` x crop of ``img`` round the dot (``zone``), its font's edge in red."""
    ys, xs = np.nonzero(zone)
    y0, y1, x0, x1 = ys.min() - 4, ys.max() + 5, xs.min() - 4, xs.max() + 5
    y0, x0 = max(y0, 0), max(x0, 0)
    rgb = np.array(img[y0:y1, x0:x1, :3])
    edge = own & ~ndi.binary_erosion(own)
    rgb[edge[y0:y1, x0:x1]] = (230, 0, 0)
    return np.kron(rgb, np.ones((scale, scale, 1), np.uint8))


def save_crop(png: str | None, name: str, img, box) -> None:
    """With ``--png`` (a folder), ``crop`` of ``img`` round ``box`` saved as NAME.png there."""
    if not png:
        return
    from PIL import Image

    os.makedirs(png, exist_ok=True)
    Image.fromarray(crop(img, *box)).save(f"{png}/{name}.png")


def report(tags, png: str | None, data: str) -> None:
    from sim.writing.hanzi import find_char

    for tag in tags:
        z = np.load(f"{OUT}/{tag}.npz")
        chars = [c for c in z.files if c != "n" and not c.endswith("_img")]
        rows_all = []
        print(
            f"{tag}: ch st  ink/font width at 25/50/75 %   widest ink/font  out  past  specks past"
        )
        for c in chars:
            rows = measure(find_char(c, data), z[c])
            for i, r in enumerate(rows):
                rs = " ".join(f"{x:4.2f}" for x in r["ratio"])
                print(
                    f"  {c} {r['stroke']:2d}  {rs}   {r['peak_ink']:4.2f}/{r['peak_font']:4.2f}"
                    f"  {r['outside']:4d} {r['beyond']:4d}  {r['specks']:2d} {r['past']:2d}"
                )
                save_crop(png, f"{tag}_{c}_{i}", z[c + "_img"], r["box"])
            rows_all += rows
        if not rows_all:
            continue
        ratio = np.mean([r["ratio"] for r in rows_all], axis=0)
        late = [r for r in rows_all if r["peak_font"] >= 0.55]
        print(
            f"  mean {len(rows_all)} dots: ink/font {ratio[0]:.2f} {ratio[1]:.2f} {ratio[2]:.2f};"
            f" widest ink {np.mean([r['peak_ink'] for r in rows_all]):.2f} font "
            f"{np.mean([r['peak_font'] for r in rows_all]):.2f} (font's late, {len(late)} dots:"
            f" ink {np.mean([r['peak_ink'] for r in late] or [np.nan]):.2f}, at >= 0.55"
            f" {sum(r['peak_ink'] >= 0.55 for r in late)});"
            f" outside {sum(r['outside'] for r in rows_all)} px"
            f" (past the end {sum(r['beyond'] for r in rows_all)});"
            f" specks {sum(r['specks'] for r in rows_all)} (past the middle"
            f" {sum(r['past'] for r in rows_all)})"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("what", choices=("write", "report"))
    ap.add_argument("args", nargs="+")
    ap.add_argument("--data", default="/tmp/chars/package")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--png", default=None)
    a = ap.parse_args()
    if a.what == "write":
        write(a.args[0], a.args[1], a.data, a.size, a.args[2:])
    else:
        report(a.args, a.png, a.data)


if __name__ == "__main__":
    main()
