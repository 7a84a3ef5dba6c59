# SPDX-License-Identifier: GPL-3.0-or-later
"""The imitation read again against the picture (see ``imitate``, step 5): where the written
ink of a stroke's free end runs on past the picture's ink (the brush's round footprint and the
writer's reach to the tip overshoot a stroke's end) or stops short of it (a 露锋 entry's point,
a 撇 that should touch the 捺), the stroke's median end is moved back or on by the difference
and the character is written again.

The practice passes of ``writing.writer`` correct each stroke's press and sideways place
against its outline's width; they do not read how far along the stroke its ink reaches. The
ends matter most to a picture's shape: a stroke end a few pixels long sets the character's
bounding box, so every other stroke is measured against it. (Beyond the paper's Sec. 9, which
says imitation is done by comparing the written and the target images without saying how.)"""

from __future__ import annotations

import numpy as np

from ..image import morph as M
from ..writing.outline import TIP_REACH, to_image
from .outline import _to_data

END_BACK = 1.5  # the ends are compared from this many half-widths inside the median's end
END_LOOK = 3.0  # half-widths past the median's end the inks are followed (longer: a junction)
MOVE = (1.5, 1.0)  # at most this many half-widths back (overshoot) and on (short) an end moves
MIN_MOVE = 1.0  # px: a smaller difference is left alone
MIN_LEFT = 2.0  # half-widths of median kept when an end is moved back
SHAPE_SIDE = 256  # the shape's square (``shape_agreement``)
SHAPE_SPECK = 5e-3  # of the ink: a smaller piece does not set the ink's box


def _reach(mask: np.ndarray, p: np.ndarray, d: np.ndarray, limit: float) -> float:
    """How far from ``p`` along ``d`` the mask holds ink without a break (``limit`` at most;
    0 when ``p`` itself is paper)."""
    h, w = mask.shape
    s = 0.0
    while s < limit:
        x, y = np.round(p + (s + 1.0) * d).astype(int)
        if not (0 <= x < w and 0 <= y < h and mask[y, x]):
            break
        s += 1.0
    return s


def _at(line: np.ndarray, back: float) -> tuple[np.ndarray, np.ndarray]:
    """The point ``back`` px inside the end of a polyline (its last point is the end) and the
    way out of the end there (unit vector)."""
    seg = np.linalg.norm(np.diff(line, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    total = s[-1]
    t = max(total - back, 0.0)
    p = np.array([np.interp(t, s, line[:, 0]), np.interp(t, s, line[:, 1])])
    q = np.array(
        [np.interp(max(t - back, 0.0), s, line[:, 0]), np.interp(max(t - back, 0.0), s, line[:, 1])]
    )
    d = line[-1] - q if np.linalg.norm(line[-1] - q, axis=-1) > 1e-9 else line[-1] - line[-2]
    return p, d / max(float(np.linalg.norm(d, axis=-1)), 1e-9)


def end_moves(line: np.ndarray, r: float, written: np.ndarray, picture: np.ndarray) -> float:
    """How far the end of ``line`` (its last point; image px) should move on (> 0) or back
    (< 0): from END_BACK half-widths inside it, the picture's ink reaches on along the end's way
    as far as it does, the written ink as far as it does; the difference, when the picture's
    ink ends within END_LOOK half-widths (a free end, or the end touching a stroke whose ink
    the writing did not reach), else nothing (the end runs into a junction in both)."""
    back = END_BACK * r
    p, d = _at(line, back)
    look = back + END_LOOK * r
    want = _reach(picture, p, d, look)
    got = _reach(written, p, d, look)
    if got >= look and want >= look:
        return 0.0
    if want >= look:  # the picture's ink runs on into another stroke: reach it
        want = min(want, got + MOVE[1] * r)
    delta = float(np.clip(want - got, -MOVE[0] * r, MOVE[1] * r))
    return delta if abs(delta) >= MIN_MOVE else 0.0


def _moved(line: np.ndarray, delta: float, keep: float) -> np.ndarray:
    """The polyline with its last point moved on by ``delta`` px along its way (> 0) or cut
    back by -delta px of arc (< 0, at most down to ``keep`` px of arc)."""
    if delta > 0:
        d = line[-1] - line[-2]
        d = d / max(float(np.linalg.norm(d, axis=-1)), 1e-9)
        out = line.copy()
        out[-1] = line[-1] + delta * d
        return out
    seg = np.linalg.norm(np.diff(line, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = max(s[-1] + delta, min(keep, s[-1]))
    k = int(np.searchsorted(s, t, side="left"))
    end = np.array([np.interp(t, s, line[:, 0]), np.interp(t, s, line[:, 1])])
    return np.vstack([line[:k], end[None]]) if k >= 1 else line


def corrected(
    char: dict, strokes: list, written: np.ndarray, picture: np.ndarray, scale: float = 1.0
) -> dict:
    """The character data with each stroke's median ends moved by ``end_moves``: the written
    ink ``written`` against the picture's ink ``picture``, both on the em box's n x n grid, top
    row first; ``strokes`` (as read, in the same order, in pixels ``scale`` times the em box's)
    give the half-widths near the ends. The writer carries a median on past its ends part of
    the way to its outline (``writing.outline.TIP_REACH``): a median end moved by x moves the
    brush's by (1 - reach) x, so it is moved by x / (1 - reach)."""
    n = picture.shape[0]
    medians = []
    for med, s in zip(char["medians"], strokes, strict=True):
        line = to_image(np.array(med, dtype=float), n)
        if len(line) < 2:
            medians.append(med)
            continue
        k = max(len(s.radius) // 5, 1)
        radii = (np.median(s.radius[:k]) * scale, np.median(s.radius[-k:]) * scale)
        for end, (r, reach) in enumerate(zip(radii, TIP_REACH, strict=True)):
            r = max(float(r), 1.0)
            ln = line if end == 1 else line[::-1]
            delta = end_moves(ln, r, written, picture)
            if delta:
                ln = _moved(ln, delta / (1.0 - reach), MIN_LEFT * r)
            line = ln if end == 1 else ln[::-1]
        medians.append([[round(float(x), 1), round(float(y), 1)] for x, y in _to_data(line, n)])
    return {**char, "medians": medians}


def ink_box(mask: np.ndarray) -> np.ndarray:
    """The ink's bounding box: of its pieces, specks left out (a piece of under SHAPE_SPECK of
    the ink: a droplet thrown off a fast exit, dust on a scan), so that one speck a stroke's
    width outside the character does not move the box."""
    lab, k = M.label(mask)
    area = np.bincount(lab.ravel(), minlength=k + 1)
    area[0] = 0
    keep = area >= SHAPE_SPECK * area.sum()
    ys, xs = np.nonzero(keep[lab] if keep.any() else mask)
    return mask[ys.min() : ys.max() + 1, xs.min() : xs.max() + 1]


def box_shape(mask: np.ndarray, side: int = SHAPE_SIDE) -> np.ndarray:
    """The ink cropped to its box (``ink_box``) and scaled to ``side`` square (area-averaged:
    a pixel is inked when more than half of what it covers is)."""
    box = ink_box(np.asarray(mask, bool)).astype(np.float64)
    big = np.repeat(np.repeat(box, 4, axis=0), 4, axis=1)  # a small box averaged fairly
    return M.resize(big, side, side) > 0.5


def shape_agreement(written: np.ndarray, picture: np.ndarray, side: int = SHAPE_SIDE) -> float:
    """How well the written ink's shape matches the picture's, whatever its place and size on
    the sheet: both cropped to their boxes and scaled to one square (``box_shape``), then IoU
    (the box-normalised IoU imitations are measured by, ``scripts/picture_real``). The shape is
    what a picture asks of an imitation: a stroke end overshooting by a few pixels moves the
    box, and so every other stroke against it. 0 when either holds no ink."""
    if not np.any(written) or not np.any(picture):
        return 0.0
    a, b = box_shape(written, side), box_shape(picture, side)
    return float(np.count_nonzero(a & b) / np.count_nonzero(a | b))
