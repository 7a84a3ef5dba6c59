# SPDX-License-Identifier: GPL-3.0-or-later
"""Every stroke end's cap against the font's (issue 26 point 2: ends rounder than real ones).

    python scripts/caps_eval.py DIR CHARS [DIR CHARS ...] [--data DIR]

DIR holds ``sim write-set``'s images of CHARS (000.png, 001.png, ... in CHARS' order, the em box
filling the image, as ``sim write-set`` writes them). The ends are the skeleton's end points of
the font's mask and of the ink (the mask smoothed at 1.5 px, as ``judge_proxy.py``'s end_taper
reads them); each font end is matched with the ink's nearest within ``MATCH`` px. Printed per
DIR: the ends, the ink outside the font and the font left bare within ``NEAR`` of the stroke
width's half of each font end (px), and the mean half-width at the ends over the median half
width, the ink's and the font's: a round U where the font closes in a V reads wider."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage as ndi
from skimage import morphology

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

MATCH = 12  # px: an ink end this near a font end is its end
NEAR = 1.5  # median half widths round a font end its ink is counted in


def ends(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """The skeleton's end points (y, x), their half width over the median half width, and the
    median half width (px)."""
    smooth = ndi.gaussian_filter(mask.astype(float), 1.5) > 0.5
    sk = morphology.skeletonize(smooth)
    dts = ndi.distance_transform_edt(smooth)
    nb = ndi.convolve(sk.astype(int), np.ones((3, 3), int), mode="constant") - 1
    end = sk & (nb == 1)
    med = float(np.median(dts[sk]))
    return np.argwhere(end), dts[end] / med, med


def measure(folder: Path, chars: str, data) -> dict:
    from sim.image.png import read_png
    from sim.writing.hanzi import find_char
    from sim.writing.writer import font_mask

    out = {"ends": 0, "outside": 0, "bare": 0, "ink": [], "font": []}
    for i, ch in enumerate(chars):
        g = np.asarray(read_png(folder / f"{i:03d}.png"), float)
        g = g.mean(axis=-1) if g.ndim == 3 else g
        ink = g < 0.5 * g.max()
        font = font_mask(find_char(ch, data), g.shape[0])
        pi, wi, _ = ends(ink)
        pf, wf, mf = ends(font)
        yy, xx = np.mgrid[: g.shape[0], : g.shape[1]]
        for p, w in zip(pf, wf, strict=True):
            near = (yy - p[0]) ** 2 + (xx - p[1]) ** 2 <= (NEAR * mf) ** 2
            out["ends"] += 1
            out["outside"] += int(np.count_nonzero(near & ink & ~font))
            out["bare"] += int(np.count_nonzero(near & font & ~ink))
            d = np.hypot(*(pi - p).T) if len(pi) else np.array([np.inf])
            if d.min() < MATCH:
                out["ink"].append(float(wi[np.argmin(d)]))
                out["font"].append(float(w))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sets", nargs="+", help="DIR CHARS pairs")
    ap.add_argument("--data", default=None, help="stroke data (default: the built-in)")
    args = ap.parse_args(argv)
    if len(args.sets) % 2:
        ap.error("give DIR CHARS pairs")
    for folder, chars in zip(args.sets[::2], args.sets[1::2], strict=True):
        r = measure(Path(folder), chars, args.data)
        ink, font = np.mean(r["ink"]), np.mean(r["font"])
        print(
            f"{folder}: ends {r['ends']}  outside {r['outside']}  bare {r['bare']}  "
            f"end half-width ink {ink:.3f} font {font:.3f} ({ink - font:+.3f}, "
            f"{len(r['ink'])} matched)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
