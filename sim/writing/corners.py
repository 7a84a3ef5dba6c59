# SPDX-License-Identifier: GPL-3.0-or-later
"""A median's corners (where a stroke turns sharply enough to be written as two movements)
and the shoulders of its 折 (the 顿 pressed out into the corner, the leg set off from there).
Data coordinates, as ``outline``."""

from __future__ import annotations

import numpy as np

from ..core import exact
from .feet import _body_width, _past_the_corner
from .polygons import _bands, _ray_hits, distance_to_outline

CORNER_TURN = 1.3  # rad of turn over +-CORNER_WINDOW: a hook's foot or a 折 is two movements
CORNER_WINDOW = 60.0  # data units either side (a median's corner spreads over 2-3 vertices)


def _heading_turn(a, b) -> np.ndarray:
    """Unsigned angle (rad) between direction vectors a and b, row by row."""
    return np.abs(exact.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.sum(a * b, axis=1)))


def _sharpest(turn, sharp) -> list[int]:
    """The index of the largest ``turn`` in each run of ``sharp``."""
    step_of = np.diff(np.concatenate([[False], sharp, [False]]).astype(int))
    starts, ends = np.flatnonzero(step_of == 1), np.flatnonzero(step_of == -1)
    return [i + int(np.argmax(turn[i:j])) for i, j in zip(starts, ends, strict=True)]


def corners(pts, step: float, chamfered: bool = True) -> list[int]:
    """Indices of the sharp corners of a median resampled every ``step``: where its heading,
    read off chords ``CORNER_WINDOW`` long before and after the point, turns more than
    ``CORNER_TURN`` (the sharpest point of each such run; none within a window of the ends);
    and (``chamfered``) the corners a median cuts across (``_chamfered``)."""
    win = max(int(round(CORNER_WINDOW / step)), 1)
    if len(pts) < 2 * win + 1:
        return []
    turn = _heading_turn(pts[win:-win] - pts[: -2 * win], pts[2 * win :] - pts[win:-win])
    found = [win + i for i in _sharpest(turn, turn > CORNER_TURN)]
    if chamfered:
        more = _chamfered(pts, win)
        found += [k for k in more if all(abs(k - f) > 2 * win for f in found)]
    return sorted(found)


LEG_STRAIGHT = 0.35  # rad: the most a leg of a chamfered corner may bend along its own length


def _chamfered(pts, win: int) -> list[int]:
    """Corners a median cuts across (a 横折's shoulder: the median runs along the horizontal,
    a short diagonal, then down; 永, 口, 日, 墨's 罒): two straight legs, each two windows long
    and bending less than ``LEG_STRAIGHT`` on its own, whose headings differ by more than
    ``CORNER_TURN`` across a gap of one window at the corner (a gentle curve turns as much only
    over a longer way, and its legs are not straight), turning clockwise as a 横折 does (a bend
    the other way, down and on to the right, is a 竖弯's round turn, 转: one movement). The
    corner is where the heading over one window either side turns most. Read over one window
    either side such a shoulder turns less than ``CORNER_TURN``: it was written as one
    movement, the pressed belly swept round the shoulder, a round knob. (Added in issue 26.)"""
    n, gap = len(pts), max(win // 2, 1)
    if n < 2 * (2 * win + gap) + 1:
        return []
    k = np.arange(2 * win + gap, n - 2 * win - gap)
    in1, in2, in3 = pts[k - gap - 2 * win], pts[k - gap - win], pts[k - gap]
    out1, out2, out3 = pts[k + gap], pts[k + gap + win], pts[k + gap + 2 * win]
    turn = _heading_turn(in3 - in1, out3 - out1)
    straight = (_heading_turn(in2 - in1, in3 - in2) < LEG_STRAIGHT) & (
        _heading_turn(out2 - out1, out3 - out2) < LEG_STRAIGHT
    )
    sharp = (turn > CORNER_TURN) & straight
    a, b = in3 - in1, out3 - out1
    sharp &= a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] < 0.0  # clockwise (y up)
    if not sharp.any():
        return []
    local = _heading_turn(pts[k] - pts[k - win], pts[k + win] - pts[k])
    return [int(k[i]) for i in _sharpest(local, sharp)]


SHOULDER_OVER = 1.1  # a 折's shoulder is at most this many times the leg's width (the font's
# is a knob 1.5-2 times it; issue 26: 1.15 with the 顿 aimed at the outline's outer corner,
# ``_dun_point``, pressed a lobe out past it; 1.05 fails test_shoulders' 马)
PICTURE_SHOULDER_OVER = 1.15  # the same for a picture's 折, whose shoulder is the one to match
# (imitating 福 at 1.1: box IoU 0.804 -> 0.777)
SHOULDER_SWELL = 2.0  # shoulder widths before a 折's corner over which the 横 swells from its
# own width to the shoulder's (issue 26.2: held at the shoulder's over them, its belly stood
# out above the 横, a knob: ink outside the font near 10 unseen corners 92 -> 58 px; 1.0: the
# 横's thinner end left the font bare, 口's IoU -0.012)


def _shoulders(pts, polys, step: float, edges, pieces, font: bool = True) -> list:
    """The movements either side of every 折 (a sharp corner not into a hook) made again
    so that the shoulder is an angular corner about the leg's width plus a little: the movement
    into the corner ends on the median's corner (no foot: the 顿 goes on from there, pressed,
    to ``_dun_point``), the leg sets off from the 顿's end (``_from_the_shoulder``), and both
    are held to ``SHOULDER_OVER`` times the leg's width (``_body_width``) within two such widths
    of the corner (the movement into it to its own, if wider, only on the corner: it swells to
    that evenly from its own over ``SHOULDER_SWELL`` such widths; beyond the paper, which
    presses to the outline's width, here the font's round knob). Only a clockwise corner
    (``_clockwise``: a 横折, a 横撇; a 竖折's stays as it was). (Added in issue 26: the font's
    shoulder is a round knob up to twice as wide as the leg, and the belly pressed into it, up
    to the calibration's deepest press, left a ball; pressed into a foot along the way in and
    the leg set off back on the corner, it left a round knob: SHOULDER_FAN 0, turned down the
    diagonal, -0.6, left 口's outer corner bare, IoU 0.916 -> 0.879, fanned up, FOOT_FAN, it
    pressed a ball.) Not ``font`` (a picture's strokes): the 顿 presses into the picture's own
    shoulder (``_dun_toward_the_knob``), held to ``PICTURE_SHOULDER_OVER``: a font's knob is
    the typeface's, a picture's the writing to imitate."""
    over = SHOULDER_OVER if font else PICTURE_SHOULDER_OVER
    dun_at = _dun_point if font else _dun_toward_the_knob
    out = list(pieces)
    for k in range(len(pieces) - 1):
        i0, i1 = edges[k], edges[k + 1]
        if pieces[k + 1][2] or not _clockwise(pts, i1, step):
            continue  # a hook's foot, or a 竖折's corner (down, then on to the right)
        centre, width = _bands(pts[i0 : i1 + 1], polys)
        if k:
            _past_the_corner(width, step)
        leg_c, leg_w, leg_h = out[k + 1]
        cap = over * _body_width(leg_w)
        if not cap > 0.0:
            continue  # a leg of no width (a degenerate outline): no shoulder to press
        dun = dun_at(pts, i1, polys, step, _body_width(leg_w))
        leg_c = _from_the_shoulder(leg_c, dun, DUN_SPAN * cap)
        corner = pts[i1]
        own = over * _body_width(width)
        d = np.linalg.norm(centre - corner, axis=1)  # swelling to the shoulder on the corner
        near = d < SHOULDER_SWELL * cap
        swell = own + (max(own, cap) - own) * np.clip(1.0 - d / (SHOULDER_SWELL * cap), 0.0, 1.0)
        width = np.where(near, np.minimum(width, swell), width)
        near = np.linalg.norm(leg_c - corner, axis=1) < 2.0 * cap
        out[k] = (centre, width, out[k][2])
        leg_w = np.where(near, np.minimum(leg_w, cap), leg_w)
        if font:
            leg_w = _belly_in(leg_c, leg_w, DUN_SPAN * cap, polys, _body_width(leg_w))
        out[k + 1] = (leg_c, leg_w, leg_h)
    return out


DUN_WAIST = 0.7  # leg widths the leg set off from the 顿 is planned at least (``_belly_in``)


def _belly_in(leg_c, leg_w, span: float, polys, body: float) -> np.ndarray:
    """A 折's leg widths (``leg_w``, centres ``leg_c``) past its first point (the 顿's, whose
    belly ``_dun_point`` set inside) and within ``span`` of it (the leg's set-off from there,
    ``_from_the_shoulder``; on, a 横折钩's foot goes out to the hook) held to where their
    belly, half their width round the centre, stays inside the outline, but at least
    ``DUN_WAIST`` of
    the leg's ``body`` width: set off from the 顿 out in the corner, the leg's outer edge
    otherwise stood out past the font's leg, narrower under its knob (墨's 罒: 3.2 px at 256
    px, 2.8 before). Beyond the paper, which presses to the outline's width along the median."""
    room = 2.0 * np.maximum(distance_to_outline(leg_c, polys), 0.0)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(leg_c, axis=0), axis=1))])
    held = (s > 0.0) & (s < span)
    return np.where(held, np.minimum(leg_w, np.maximum(room, DUN_WAIST * body)), leg_w)


DUN_BELLY = 0.8  # the 顿's belly, in half leg widths, that stays inside the outline at its
# press (``_dun_point``: the base goes out into the corner till the belly meets the outline)
DUN_NEAR = 1.5  # leg widths round a 折's corner the 顿 may press to
DUN_UP = 0.5  # weight of the way out, reversed, in the way the 顿 presses along: 1 the
# bisector (贝, 且: it pressed a ball up out of the 横), 0 straight on along the way in
DUN_GRID = 25  # candidate points a side of the square round the corner ``_dun_point`` reads
DUN_MIN = 0.3  # leg widths the 顿 goes on at least (the base never stands pressed on the spot)
DUN_SPAN = 1.0  # shoulder widths (SHOULDER_OVER times the leg's) over which a 折's leg, set off
# from the 顿's end, comes back to its band's centres (``_from_the_shoulder``)


def _dun_point(pts, k: int, polys, step: float, leg_width: float) -> np.ndarray:
    """Where the 顿 at a 折's corner ``k`` presses to: the point within ``DUN_NEAR`` leg widths
    of the median's corner farthest along the way in less ``DUN_UP`` of the way out (each a
    chord of ``CORNER_WINDOW``: to the right and a little up at a 横折) at which a belly of
    ``DUN_BELLY`` half leg widths stays inside the outline: the press's belly set into the
    outline's outer corner, touching both its outer edges, so the shoulder is inked out to its
    corner and squared, not a disc pressed short of it. The calligrapher runs the horizontal
    into the corner, lifts a little and presses on out into the shoulder, and sets the leg off
    from there. (The paper takes the brush's samples, S^t of Eq. 9 in Sec. 4, from the
    writer's hand and plans no 顿: where it presses is added here. Issue 26: aimed at the
    outline's point farthest along the bisector, 0.75 of the way to where the belly would meet
    the outline along that ray, the ray met the outline's upper edge short of a font's knob
    standing out to the right (贝, 且), the shoulder's outer side was bare and the press stood
    up out of the 横 as a knob: shoulders_eval's bare 433 px, corner 4.98 px on 巴 贝 页 西 酉
    且 旦 亚, now 255 px and 2.61 px; aimed down the bisector, 口's knob up-right was left
    bare, held-out IoU 0.924 ->
    0.901.)"""
    d, e = _chords(pts, k, step)
    way_out = e / max(float(np.linalg.norm(e)), 1e-9)
    outer = d / max(float(np.linalg.norm(d)), 1e-9) - DUN_UP * way_out
    reach = DUN_NEAR * leg_width
    g = np.linspace(-reach, reach, DUN_GRID)
    near = np.stack(np.meshgrid(g, g), axis=-1).reshape(-1, 2)
    near = pts[k] + near[np.linalg.norm(near, axis=1) <= reach]
    near = near[distance_to_outline(near, polys) >= DUN_BELLY * 0.5 * leg_width]
    if not len(near):
        return pts[k]
    off = near[int(np.argmax((near - pts[k]) @ outer))] - pts[k]
    far = float(np.linalg.norm(off))
    way = off / far if far > 1e-9 else outer / max(float(np.linalg.norm(outer)), 1e-9)
    return pts[k] + max(far, DUN_MIN * leg_width) * way


PICTURE_DUN_REACH = 0.7  # a picture's 折 (``_dun_toward_the_knob``): share of the way to where the
# belly, half the leg's width round the base, would reach the outline that the 顿 presses to
PICTURE_DUN_FAN = 0.5  # rad past the way in, away from the turn, that 顿 may aim (from the
# turn's bisector)


def _dun_toward_the_knob(pts, k: int, polys, step: float, leg_width: float) -> np.ndarray:
    """Where the 顿 at a picture's 折 corner ``k`` presses to: from the median's corner toward
    the outline's farthest point among the ways from the turn's bisector (the way in and the
    way out, each a chord of ``CORNER_WINDOW``, added: down and to the right at a 横折) round
    past the way in by ``PICTURE_DUN_FAN``, ``PICTURE_DUN_REACH`` of the way to where the belly
    would reach the outline: into whatever shoulder the picture's ink has, a facet or a knob,
    since imitating, it is the shoulder to match. (Issue 26: the stroke data's own aim,
    ``_dun_point``, at the outline's outer corner, pressed a knob out past 为's facet, box IoU
    0.891 -> 0.755; kept from 6 px off the outline, 0.869, with 福 0.833 -> 0.777.)"""
    d, e = _chords(pts, k, step)
    way = d / max(float(np.linalg.norm(d)), 1e-9) + e / max(float(np.linalg.norm(e)), 1e-9)
    a0 = exact.arctan2(way[1], way[0])
    a1 = exact.arctan2(d[1], d[0])
    a1 = a0 + np.remainder(a1 - a0 + np.pi, 2.0 * np.pi) - np.pi  # the way in, from the bisector
    ang = a0 + (a1 - a0 + np.sign(a1 - a0) * PICTURE_DUN_FAN) * np.linspace(0.0, 1.0, 11)
    dirs = np.stack(exact.sin_cos(ang)[::-1], axis=1)
    hits = _ray_hits(np.repeat(pts[k][None], len(dirs), axis=0), dirs, polys)
    hits = np.where(np.isfinite(hits), hits, 0.0)
    j = int(np.argmax(hits))
    return pts[k] + PICTURE_DUN_REACH * max(float(hits[j]) - 0.5 * leg_width, 0.0) * dirs[j]


def _from_the_shoulder(leg, dun, span: float) -> np.ndarray:
    """A 折's leg (its centres) set off from ``dun`` (``_dun_point``) instead of the median's
    corner: its points over its first ``span`` data units on a straight line from there to
    the leg's point at ``span`` (the band's centres round the corner wander with the font's
    knob), the rest as they were."""
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(leg, axis=0), axis=1))])
    j = min(int(np.searchsorted(s, span)), len(leg) - 1)
    if j < 1:
        return leg
    t = (np.arange(j) / j)[:, None]
    out = leg.copy()
    out[:j] = np.asarray(dun)[None, :] * (1.0 - t) + leg[j][None, :] * t
    return out


def _clockwise(pts, k: int, step: float) -> bool:
    """Whether a median turns clockwise (y up) at corner ``k``, read over ``CORNER_WINDOW``
    either side: a 横折's shoulder (right, then down), not a 竖折's corner."""
    return bool(_turn_at(pts, k, step)[1] < 0.0)


def _turn_at(pts, k: int, step: float) -> tuple[np.ndarray, float]:
    """A median's way into point ``k`` (its chord over ``CORNER_WINDOW``) and how it turns
    there: the cross product of the chords in and out (> 0 anticlockwise, y up)."""
    d, e = _chords(pts, k, step)
    return d, float(d[0] * e[1] - d[1] * e[0])


def _chords(pts, k: int, step: float) -> tuple[np.ndarray, np.ndarray]:
    """A median's chords over ``CORNER_WINDOW`` into point ``k`` and out of it."""
    win = max(int(round(CORNER_WINDOW / step)), 1)
    return pts[k] - pts[max(k - win, 0)], pts[min(k + win, len(pts) - 1)] - pts[k]
