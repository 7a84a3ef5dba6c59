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
    char: dict,
    strokes: list,
    written: np.ndarray,
    picture: np.ndarray,
    scale: float = 1.0,
    boxes: bool = False,
) -> dict:
    """The character data with each stroke's median ends moved by ``end_moves`` (and, with
    ``boxes``, an end that sets a side of the ink's box where ``end_moves`` reads nothing to
    move, by ``box_moves``, and a median's point that sets a side no end is moved for, by
    ``box_shifts``; the ends' moves are read before any point is shifted, where the written
    ink is): the written ink ``written`` against the picture's ink
    ``picture``, both on the em box's n x n grid, top row first; ``strokes`` (as read, in the
    same order, in pixels ``scale`` times the em box's) give the half-widths near the ends.
    The writer carries a median on past its ends part of the way to its outline
    (``writing.outline.TIP_REACH``): a median end moved by x moves the brush's by (1 - reach)
    x, so it is moved by x / (1 - reach)."""
    n = picture.shape[0]
    lines, radii = [], []
    for med, s in zip(char["medians"], strokes, strict=True):
        k = max(len(s.radius) // 5, 1)
        lines.append(to_image(np.array(med, dtype=float), n))
        radii.append([max(float(np.median(r)) * scale, 1.0) for r in (s.radius[:k], s.radius[-k:])])
    gaps = _box_gaps(written, picture) if boxes else []  # the sides, read once for both
    boxed = box_moves(lines, radii, written, picture, gaps)
    shifts = box_shifts(lines, radii, written, picture, gaps)
    medians = []
    for i, (med, line) in enumerate(zip(char["medians"], lines, strict=True)):
        if len(line) < 2:
            medians.append(med)
            continue
        deltas = [  # read where the written ink is: before any point is shifted
            end_moves(line if end == 1 else line[::-1], r, written, picture)
            or boxed.get((i, end), 0.0)
            for end, r in enumerate(radii[i])
        ]
        line = line.copy()
        for (j, k), shift in shifts.items():
            if j == i:
                line[k] += shift
        for end, (r, reach, delta) in enumerate(zip(radii[i], TIP_REACH, deltas, strict=True)):
            ln = line if end == 1 else line[::-1]
            if delta:
                ln = _moved(ln, delta / (1.0 - reach), MIN_LEFT * r)
            line = ln if end == 1 else ln[::-1]
        medians.append([[round(float(x), 1), round(float(y), 1)] for x, y in _to_data(line, n)])
    return {**char, "medians": medians}


# the four sides of an ink's box: its outward normals (x, y; image px, top row first)
SIDES = np.array([[0.0, -1.0], [0.0, 1.0], [-1.0, 0.0], [1.0, 0.0]])
BOX_MOVE = 2.5  # at most this many half-widths an end is moved for a side of the box
BOX_NEAR = 1.5  # half-widths (past its own) from where a side is set an end may lie to set it
BOX_OUT = 0.5  # the least cosine of an end's way out with a side's normal (an end, not a flank)
BOX_THIN = 3.0  # px at 512: ink thinner than twice this does not set a side (a grid's line)
BOX_NEAR_POINT = 0.5  # half-widths a median's point may lie farther than the nearest point of
# any median's segments from where a side is set (farther: a stroke's flank sets it)


def box_moves(
    lines: list, radii: list, written: np.ndarray, picture: np.ndarray, gaps: list | None = None
) -> dict:
    """How far the end that sets each side of the written ink's box should move on (> 0) or
    back (< 0) so that the side lies where the picture's does: {(stroke, end): px along the
    end's way out}. The box is what an imitation's shape is measured in (``shape_agreement``):
    a dot's head landing a few pixels short of the picture's moves every stroke against it,
    and ``end_moves`` misses it where the median runs along the ink's edge rather than its
    middle (a heavy dot's skeleton). The end moved is the one nearest where the side is set:
    by the picture's ink where the writing falls short of it, by the written ink where it
    runs past it; it must point out of the side (BOX_OUT) and lie within its own half-width
    and BOX_NEAR more (and the shortfall) of that place, else the side is left to
    ``box_shifts``; an end at a corner of the box moves by the larger of its two sides' moves.
    A side is left alone when it differs by MIN_MOVE or less (``_box_gaps``); an end moves at
    most BOX_MOVE half-widths. ``gaps``: the sides' ``_box_gaps``, where read already."""
    out = {}
    for normal, gap, at in _box_gaps(written, picture) if gaps is None else gaps:
        best = _side_end(lines, radii, normal, gap, at)
        if best is not None:  # an end at a corner of the box: the larger of its two moves
            _, i, end, cos, r = best
            move = float(np.clip(gap / cos, -BOX_MOVE * r, BOX_MOVE * r))
            out[(i, end)] = max(out.get((i, end), 0.0), move, key=abs)
    return out


def box_shifts(
    lines: list, radii: list, written: np.ndarray, picture: np.ndarray, gaps: list | None = None
) -> dict:
    """For each side of the box that no end is moved for (``box_moves``: none near where it is
    set points out of it), the median's point that sets it shifted across to where the
    picture sets it: {(stroke, point): (dx, dy) px}. The point is a corner of a median (a
    hook's heel, a 折's shoulder) or an end whose ink reaches out sideways (a heavy head
    pressed past its median's start); it is the median's point nearest where the side is set
    (by the picture's ink where the writing falls short, by the written ink where it runs
    past), no farther than the nearest point of any median's segments by BOX_NEAR_POINT
    half-widths (a stroke's flank sets the side there: its width, the press's, not a point's
    place) and within its half-width (an end's own; an inner point's, the larger of its
    stroke's ends') and BOX_NEAR more (and the shortfall); it shifts along the side's normal
    by the difference, at most BOX_MOVE half-widths. A point that sets two sides (a corner of
    the box) shifts by both, one along each normal. A median of one point is no point to
    shift (a dot's reading is never one point). ``gaps``: as ``box_moves``'."""
    out = {}
    for normal, gap, at in _box_gaps(written, picture) if gaps is None else gaps:
        if _side_end(lines, radii, normal, gap, at) is not None:
            continue
        best = None
        for i, line in enumerate(lines):
            if len(line) < 2:
                continue
            far = np.linalg.norm(line - at, axis=1)
            k = int(np.argmin(far))
            if best is None or far[k] < best[0]:
                best = (float(far[k]), i, k, _point_radius(radii[i], k, len(line)))
        if best is None:
            continue
        far, i, k, r = best
        if far > (1.0 + BOX_NEAR) * r + max(gap, 0.0):
            continue
        if far > _nearest_on(lines, at) + BOX_NEAR_POINT * r:  # a flank sets the side
            continue
        move = float(np.clip(gap, -BOX_MOVE * r, BOX_MOVE * r)) * normal
        out[(i, k)] = out.get((i, k), np.zeros(2)) + move
    return out


def _point_radius(radii: list, k: int, n: int) -> float:
    """The half-width at point k of a median of n points whose ends' are ``radii``: an end's
    own, an inner point's the larger of the two."""
    return radii[0] if k == 0 else radii[1] if k == n - 1 else max(radii)


def _box_gaps(written: np.ndarray, picture: np.ndarray) -> list:
    """For each of SIDES where the written ink's box differs from the picture's by more than
    MIN_MOVE: (its normal, how far the written ink falls short of it (< 0: runs past), where
    it is set: by the picture's ink where the writing falls short, by the written ink where it
    runs past, ``_extreme``). The sides are those of the inks without their thin parts
    (``_opened``, BOX_THIN; both whole where either has nothing thicker): a grid's line the
    reading kept where it touches the character, or a hair's thread, is no side to reach."""
    thin = BOX_THIN * picture.shape[0] / 512
    inks = (_opened(picture, thin), _opened(written, thin))
    if not (inks[0].any() and inks[1].any()):  # nothing thicker in one: both as they are
        inks = (np.asarray(picture, bool), np.asarray(written, bool))
    want, got = _sides(inks[0]), _sides(inks[1])
    if want is None or got is None:
        return []
    out = []
    for side, normal in enumerate(SIDES):
        gap = float(want[side] - got[side])  # > 0: the written ink falls short of the side
        if abs(gap) > MIN_MOVE:
            at = _extreme(*((inks[0], want) if gap > 0 else (inks[1], got)), side)
            out.append((normal, gap, at))
    return out


def _side_end(lines: list, radii: list, normal: np.ndarray, gap: float, at: np.ndarray):
    """The end (far, stroke, end, cosine, half-width) nearest ``at`` that points out of the
    side of ``normal`` (BOX_OUT) within its half-width and BOX_NEAR more (and the shortfall
    ``gap``), or None."""
    best = None
    for i, line in enumerate(lines):
        if len(line) < 2:
            continue
        for end in (0, 1):
            ln = line if end == 1 else line[::-1]
            way = ln[-1] - ln[-2]
            cos = float(way @ normal) / max(float(np.linalg.norm(way)), 1e-9)
            r = radii[i][end]
            far = float(np.linalg.norm(ln[-1] - at))
            if cos >= BOX_OUT and far <= (1.0 + BOX_NEAR) * r + max(gap, 0.0):
                if best is None or far < best[0]:
                    best = (far, i, end, cos, r)
    return best


def _nearest_on(lines: list, at: np.ndarray) -> float:
    """The distance from ``at`` to the nearest point of the medians' segments."""
    near = np.inf
    for line in lines:
        if len(line) < 2:
            near = min(near, float(np.linalg.norm(line[0] - at))) if len(line) else near
            continue
        a, d = line[:-1], np.diff(line, axis=0)
        t = np.clip(((at - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-12), 0, 1)
        near = min(near, float(np.linalg.norm(a + t[:, None] * d - at, axis=1).min()))
    return near


def _extreme(mask: np.ndarray, sides: np.ndarray, side: int) -> np.ndarray:
    """Where the ink sets one of SIDES of its box (``sides``, ``_sides``): the middle (x, y)
    of its pixels on that side's row or column."""
    ys, xs = np.nonzero(mask)
    on = (ys, ys, xs, xs)[side] == abs(int(sides[side]))
    return np.array([xs[on].mean(), ys[on].mean()])


def _opened(mask: np.ndarray, r: float) -> np.ndarray:
    """The ink without what is thinner than 2 ``r`` px (an opening by a disc of radius r): a
    copybook grid's line touching the character, a hair's thread off a tip (no ink where
    nothing is that thick)."""
    core = M.edt(mask) > r
    return np.asarray(mask, bool) & (M.edt(~core) <= r) if core.any() else np.zeros_like(core)


def _sides(mask: np.ndarray):
    """The ink's box (specks left out, ``ink_box``) as the outward reach of each of SIDES: (-top,
    bottom, -left, right) in px; None when there is no ink."""
    rows, cols = _box_slices(mask)
    if rows is None:
        return None
    return np.array([-rows.start, rows.stop - 1, -cols.start, cols.stop - 1], dtype=float)


def _box_slices(mask: np.ndarray):
    """The rows and columns of the ink's box, specks left out (see ``ink_box``)."""
    mask = np.asarray(mask, bool)
    if not mask.any():
        return None, None
    lab, k = M.label(mask)
    area = np.bincount(lab.ravel(), minlength=k + 1)
    area[0] = 0
    keep = area >= SHAPE_SPECK * area.sum()
    ys, xs = np.nonzero(keep[lab] if keep.any() else mask)
    return slice(ys.min(), ys.max() + 1), slice(xs.min(), xs.max() + 1)


def ink_box(mask: np.ndarray) -> np.ndarray:
    """The ink's bounding box: of its pieces, specks left out (a piece of under SHAPE_SPECK of
    the ink: a droplet thrown off a fast exit, dust on a scan), so that one speck a stroke's
    width outside the character does not move the box."""
    rows, cols = _box_slices(mask)
    if rows is None:
        raise ValueError("an ink box of no ink")
    return np.asarray(mask)[rows, cols]


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
