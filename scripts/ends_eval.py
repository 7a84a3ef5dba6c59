# SPDX-License-Identifier: GPL-3.0-or-later
"""The points of 撇 and 提 against the font (issue 26 point 2: ends blunter than real ones).

    python scripts/dots_eval.py write TAG CHARS [--data DIR] [--size 512]   (the same ink files)
    python scripts/ends_eval.py TAG [TAG ...] [--png DIR] [--data DIR]

Reads the ink ``dots_eval.py write`` keeps ($DOTS_EVAL_OUT, /tmp/dots_eval) and prints per
pointed stroke (a 撇: its median running down-left; a 提: up-right; nearly straight, longer than
``dots_eval.DOT`` times its widest, the font narrowing to a point: at 95 % of its length below
``TIP`` of its widest) the ink's width over the font's at 70, 85 and 95 % of the font stroke's
length along its way (the median's start to end), how far the ink runs past (+) or stops short
of (-) the font's point (px, the stroke's ink connected to its body), and the detached specks
near it; with ``--png`` a 4x crop of the end with the font's edge in red."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage as ndi

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from scripts.dots_eval import DOT, OUT, SPECK, _profile, save_crop, strokes  # noqa: E402

AT = (0.70, 0.85, 0.95)  # shares of the font stroke's length the widths are compared at
TIP = 0.5  # the font's width at 95 % of the stroke below this share of its widest: a point
STRAIGHT = 0.9  # chord over the median's length above this: one straight-ish movement


def pointed(char: dict, n: int) -> list[dict]:
    """Per 撇 or 提 of ``char``: its stroke, start, unit way (image px), kind and font mask."""
    from sim.writing.outline import EM

    out = []
    for k, _, length, half, m, font in strokes(char, n):
        chord = m[-1] - m[0]
        c = float(np.linalg.norm(chord))
        if length < DOT * 2 * half.max() or c < STRAIGHT * length * n / EM:
            continue
        if half[int(0.95 * (len(half) - 1))] > TIP * half.max():
            continue
        d = chord / c
        kind = "pie" if d[0] < 0 < d[1] else "ti" if d[0] > 0 > d[1] else None
        if kind is None:
            continue
        mask = font()
        out.append(
            {
                "stroke": k,
                "start": m[0],
                "way": d,
                "kind": kind,
                "mask": mask,
                "w": 2 * half.max() * n / EM,
            }
        )
    return out


def measure(char: dict, ink: np.ndarray) -> list[dict]:
    """The figures of each pointed stroke of ``char`` written as ``ink`` (module doc)."""
    from sim.writing.outline import rasterise

    n = ink.shape[0]
    font = rasterise(char, n)
    yy, xx = np.mgrid[0:n, 0:n] + 0.5
    labels, _ = ndi.label(ink, np.ones((3, 3), bool))
    sizes = np.bincount(labels.ravel())
    rows = []
    for s in pointed(char, n):
        own = s["mask"]
        away = ndi.binary_dilation(font & ~own, iterations=2)
        d, p0 = s["way"], s["start"]
        along = (xx - p0[0]) * d[0] + (yy - p0[1]) * d[1]
        across = -(xx - p0[0]) * d[1] + (yy - p0[1]) * d[0]
        lo, hi = along[own].min(), along[own].max()
        zone = ndi.binary_dilation(own, iterations=max(int(0.6 * s["w"]), 3))
        mine = ink & zone & ~away
        pf = _profile(own & ~away, along, across, lo, hi - lo)
        pi = _profile(mine, along, across, lo, hi - lo)
        near = [q for q in np.unique(labels[zone & ink]) if q]
        on = labels[mine]
        body = int(np.bincount(on).argmax()) if on.size and on.any() else 0
        touch = set(np.unique(labels[away & ink]))
        specks = [q for q in near if sizes[q] < SPECK and q not in touch and q != body]
        reach = along[mine & (labels == body)].max() - hi if body else -(hi - lo)
        k = [int(round(a * 50)) for a in AT]
        rows.append(
            {
                "stroke": s["stroke"],
                "kind": s["kind"],
                "ratio": [pi[j] / max(pf[j], 1e-9) for j in k],
                "font_w": [pf[j] for j in k],
                "reach": float(reach),
                "specks": len(specks),
                "box": (own, zone & (along > lo + 0.6 * (hi - lo))),
            }
        )
    return rows


def report(tags, png: str | None, data: str) -> None:
    from sim.writing.hanzi import find_char

    for tag in tags:
        z = np.load(f"{OUT}/{tag}.npz")
        chars = [c for c in z.files if c != "n" and not c.endswith("_img")]
        rows_all = []
        print(f"{tag}: ch st kind  ink/font width at 70/85/95 %  (font px)  reach px  specks")
        for c in chars:
            for i, r in enumerate(measure(find_char(c, data), z[c])):
                rs = " ".join(f"{x:4.2f}" for x in r["ratio"])
                fw = " ".join(f"{x:4.1f}" for x in r["font_w"])
                print(
                    f"  {c} {r['stroke']:2d} {r['kind']:4s}  {rs}  ({fw})"
                    f"  {r['reach']:+5.1f}  {r['specks']}"
                )
                save_crop(png, f"{tag}_{c}_{i}", z[c + "_img"], r["box"])
                rows_all.append(r)
        if rows_all:
            ratio = np.mean([r["ratio"] for r in rows_all], axis=0)
            reach = np.array([r["reach"] for r in rows_all])
            ok85 = sum(0.8 <= r["ratio"][1] <= 1.2 for r in rows_all)
            print(
                f"  mean {len(rows_all)} ends: ink/font {ratio[0]:.2f} {ratio[1]:.2f} "
                f"{ratio[2]:.2f}; 85 % within 0.8-1.2: {ok85}; reach mean {reach.mean():+.1f} px,"
                f" within 2 px {int((np.abs(reach) <= 2).sum())}, short > 2 px "
                f"{int((reach < -2).sum())}, past > 2 px {int((reach > 2).sum())}; specks "
                f"{sum(r['specks'] for r in rows_all)}"
            )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("tags", nargs="+")
    ap.add_argument("--data", default="/tmp/chars/package")
    ap.add_argument("--png", default=None)
    a = ap.parse_args()
    report(a.tags, a.png, a.data)


if __name__ == "__main__":
    main()
