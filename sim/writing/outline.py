# SPDX-License-Identifier: GPL-3.0-or-later
"""Stroke outlines of character data (hanzi-writer-data / Make Me a Hanzi): SVG paths parsed
and flattened to polygons, filled on a pixel grid, and read as stroke widths along the medians.

Data coordinates: the 1024-unit em box, y up; image coordinates of an N x N image are
x_img = x * N / 1024, y_img = (900 - y) * N / 1024 (top row first)."""

from __future__ import annotations

import re

import numpy as np

from ..core import exact
from .corners import CORNER_WINDOW, _clockwise, _heading_turn, _shoulders, _turn_at, corners
from .feet import (
    HOOK_FROM_FOOT,
    HOOK_FROM_MIDDLE,
    _body_width,
    _from_the_foot,
    _gathered_foot,
    _held_foot,
    _past_the_corner,
    _rises_back,
    _rooted,
    flicks,
    is_hook,
    is_level,
    narrows,
)
from .polygons import _bands, _ray_hits, distance_to_outline, fill

EM = 1024.0
TOP = 900.0
_TOKEN = re.compile(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_ARGS = {"M": 2, "L": 2, "Q": 4, "C": 6, "Z": 0}
_CURVE_STEPS = 8


def parse_path(d: str) -> list[np.ndarray]:
    """Closed polygons (K, 2) in data units from an SVG path of absolute M, L, Q, C, Z."""
    tokens = _TOKEN.findall(d)
    polys, cur, pos, cmd, i = [], [], None, None, 0
    while i < len(tokens):
        t = tokens[i]
        if t.isalpha():
            cmd = t
            i += 1
            if cmd not in _ARGS:
                raise ValueError(f"unsupported SVG path command {cmd!r} (absolute M L Q C Z only)")
            if cmd == "Z":
                if len(cur) >= 3:
                    polys.append(np.array(cur, dtype=float))
                cur = []
                continue
        if cmd is None:
            raise ValueError(f"SVG path starts with a number: {d[:40]!r}")
        n = _ARGS[cmd]
        if n == 0 or i + n > len(tokens):
            raise ValueError(f"SVG path command {cmd!r} is missing numbers: {d[:40]!r}")
        try:
            v = [float(x) for x in tokens[i : i + n]]
        except ValueError:
            raise ValueError(f"SVG path has a bad number near {tokens[i : i + n]}") from None
        i += n
        if cmd == "M":
            if len(cur) >= 3:
                polys.append(np.array(cur, dtype=float))
            cur = [v]
            cmd = "L"  # further pairs after M are line-tos
        elif cmd == "L":
            cur.append(v)
        else:
            if not cur and pos is None:
                raise ValueError(f"SVG path draws a curve before any point: {d[:40]!r}")
            p0 = np.array(cur[-1] if cur else pos)
            t = np.linspace(0, 1, _CURVE_STEPS + 1)[1:, None]
            c = np.array(v).reshape(-1, 2)
            if cmd == "Q":
                pts = (1 - t) ** 2 * p0 + 2 * (1 - t) * t * c[0] + t**2 * c[1]
            else:
                pts = (
                    (1 - t) ** 3 * p0
                    + 3 * (1 - t) ** 2 * t * c[0]
                    + 3 * (1 - t) * t**2 * c[1]
                    + t**3 * c[2]
                )
            cur.extend(pts.tolist())
        pos = cur[-1]
    if len(cur) >= 3:
        polys.append(np.array(cur, dtype=float))
    return polys


def stroke_polygons(char: dict) -> list[list[np.ndarray]]:
    """Every stroke's outline as polygons in data units."""
    return [parse_path(d) for d in char["strokes"]]


def to_image(points, n: int) -> np.ndarray:
    p = np.asarray(points, dtype=float)
    return np.stack([p[:, 0] * n / EM, (TOP - p[:, 1]) * n / EM], axis=1)


def rasterise(char: dict, n: int) -> np.ndarray:
    """The font's character: every stroke filled (a stroke's own contours even-odd, strokes
    united), (n, n) bool, top row first."""
    mask = np.zeros((n, n), dtype=bool)
    for polys in stroke_polygons(char):
        mask |= fill([to_image(p, n) for p in polys], n)
    return mask


def resample(polyline, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Points every ``step`` along a polyline (K, 2), and their arc length."""
    p = np.asarray(polyline, dtype=float)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    total = float(cum[-1])
    n = max(int(np.ceil(total / max(step, 1e-9))), 1) + 1
    s = np.linspace(0.0, total, n)
    return np.stack([np.interp(s, cum, p[:, 0]), np.interp(s, cum, p[:, 1])], axis=1), s


def median_radii(char: dict, step: float = 4.0) -> list[tuple[np.ndarray, np.ndarray]]:
    """For every stroke, points along its median (data units, every ``step``) and the
    stroke's half-width there: the distance to its outline (0 where the median leaves it)."""
    out = []
    for med, polys in zip(char["medians"], stroke_polygons(char), strict=True):
        pts, _ = resample(med, step)
        out.append((pts, np.maximum(distance_to_outline(pts, polys), 0.0)))
    return out


TIP_REACH = (0.3, 0.5)  # share of the way from a median's start and end to the outline the
# path goes on (measured: the end helps, the head - where the brush lands - does not)
JOIN_GAP = 3.0  # data units: a stroke's outline near its end this near another's joins it
JOIN_NEAR = 40.0  # data units round a median's end its outline is looked at for a join
JOIN_INTO = 6.0  # data units a joining end's path goes on into the stroke it joins
JOIN_WIDTH = 0.6  # share of its movement's own width a joining end keeps to the join ...
JOIN_SPAN = 1.0  # ... over this many of those widths before its end: it does not let go into
# a point short of the stroke it runs into (measured, issue 26.2: at 0.45 the belly of 好's
# 横撇 lifted into a dry broom of streaks short of the 竖钩 at 3 of 6 sizes; 0.6 joins at all)


def _join_point(p, d, polys, others) -> np.ndarray | None:
    """Where a stroke's end joins another stroke: the point its path goes on to, up to
    ``JOIN_INTO`` inside the stroke it joins; None where it joins none. The end at the median's
    last point ``p`` (its way out ``d``) joins a stroke of ``others`` that the outline's
    vertices ahead of ``p`` and within ``JOIN_NEAR`` of it reach into, or come within
    ``JOIN_GAP`` of: the tail of 好's 横撇 into its 竖钩, 北's 撇 into its 竖弯钩. (A median's
    last piece need not point at its outline's tip, so the join is looked for round it.) A
    pointed end that stops at its median leaves a hair of bare paper between two strokes the
    font joins."""
    v = np.concatenate([np.asarray(q, dtype=float) for q in polys])
    off = v - p
    near = v[(np.hypot(off[:, 0], off[:, 1]) <= JOIN_NEAR) & ((off * d).sum(axis=1) > 0.0)]
    best = None
    for o in others if len(near) else ():
        depth = distance_to_outline(near, o)
        k = int(np.argmax(depth))
        if depth[k] < -JOIN_GAP or (best is not None and depth[k] <= best[0]):
            continue
        c = near[k]
        if depth[k] < 1.0:  # touching: a little on, into it
            c = c + (1.0 - depth[k]) * (c - p) / max(float(np.hypot(*(c - p))), 1e-9)
        line = p + np.linspace(0.0, 1.0, 33)[:, None] * (c - p)
        deep = distance_to_outline(line, o) >= min(JOIN_INTO, max(float(depth[k]), 0.5))
        best = (float(depth[k]), line[int(np.argmax(deep))] if deep.any() else c)
    return None if best is None else best[1]


def _into_the_join(width, centre) -> np.ndarray:
    """The widths of a movement whose end joins another stroke: at least ``JOIN_WIDTH`` of its
    own width over its last ``JOIN_SPAN`` own widths (the path there runs on past its outline,
    where the font gives no width)."""
    own = _body_width(width)
    left = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(centre, axis=0), axis=1))])
    near = left[-1] - left <= JOIN_SPAN * own
    return np.where(near, np.maximum(width, JOIN_WIDTH * own), width)


def _to_the_tips(med, polys) -> np.ndarray:
    """``_tips_and_join`` of a stroke alone: its median carried on to its tips."""
    return _tips_and_join(med, polys, ())[0]


def _tips_and_join(med, polys, others) -> tuple[np.ndarray, bool]:
    """The median carried on at its ends, along its end directions, ``TIP_REACH`` of the way to
    the outline: a stroke's median stops short of its pointed or squared-off end (the point of a
    hook or a left-falling stroke), which the brush must still reach. An end (not the head,
    where the brush lands) that joins another stroke (``others``: their polygons) goes on into it
    (``_join_point``); the second value says whether it does."""
    m = np.asarray(med, dtype=float)
    if len(m) < 2:
        return m, False
    ends, joins = [], False
    for k, ((p, q), reach) in enumerate(
        zip(((m[0], m[1]), (m[-1], m[-2])), TIP_REACH, strict=True)
    ):
        d = p - q
        d = d / max(float(np.linalg.norm(d, axis=-1)), 1e-9)
        if distance_to_outline(p[None], polys)[0] <= 0:
            ends.append(p)  # the median already ends outside the outline
            continue
        hit = float(_ray_hits(p[None], d[None], polys)[0])
        hit = hit if np.isfinite(hit) else 0.0
        join = _join_point(p, d, polys, others) if k == 1 else None
        joins = joins or join is not None
        ends.append(p + reach * hit * d if join is None else join)
    return np.concatenate([ends[0][None], m, ends[1][None]]), joins


FOOT_REACH = 0.58  # share of the way to the outline a movement goes on past a corner (the
# foot; measured with issue 26's 折: 0.65 fills 永's and 口's shoulders further but presses a
# round knob out past a pointed shoulder's sides, as 力's; 0.5 leaves more of them bare)


FOOT_FAN = 1.0  # rad the foot may turn from the way in, away from the turn, towards the
# outline's farthest point (a 竖钩's median bends into the hook before its corner; the foot
# hangs on the outer side of the turn)


def _foot(pts, k: int, polys, step: float, fan: float = FOOT_FAN) -> np.ndarray:
    """The points a movement ending at corner ``k`` goes on past it, ``FOOT_REACH`` of the way to
    the outline: the foot of a hook or the shoulder of a 折, where the calligrapher presses
    before turning. Its way is its last direction (a chord of ``CORNER_WINDOW``) turned up to
    ``FOOT_FAN`` away from the corner's turn, towards the farthest outline: the font's foot
    hangs on the corner's outer side, not where the median already bends to the next
    movement."""
    d, turn = _turn_at(pts, k, step)
    away = -1.0 if turn > 0 else 1.0  # against the turn
    ang = exact.arctan2(d[1], d[0]) + away * np.linspace(0.0, fan, 11)
    dirs = np.stack(exact.sin_cos(ang)[::-1], axis=1)
    hits = _ray_hits(np.repeat(pts[k][None], len(dirs), axis=0), dirs, polys)
    hits = np.where(np.isfinite(hits), hits, 0.0)
    j = int(np.argmax(hits))
    n = int(FOOT_REACH * hits[j] // step)
    return pts[k] + (np.arange(1, n + 1) * step)[:, None] * dirs[j]


HOOK_WINDOW = 100.0  # data units either side over which a stroke's end curls into a hook off a
# curve (乙, 也, 九, 飞: its turn spreads over more of the median than a corner's CORNER_WINDOW)
CURL_FOOT = 0.5  # share of the foot (FOOT_REACH) the movement before such a hook presses into:
# the outline's outer side is round there, and pressed as far as at a corner the belly stood
# out past it in a round knob (乙, 巴: 189 and 286 px more than 2 px outside the outline at
# 512 px against 56 and 55)
HOOK_TURN = 0.9  # rad of turn over +-HOOK_WINDOW where such a hook leaves the curve


def _hooks_back(way_in, piece, before, step: float, width, curl: bool = False) -> bool:
    """Whether the last piece of a median, after a corner (``piece``: its points, ``width``:
    its widths; ``curl``: the corner is where the end curls off a curve), is a hook
    (``is_hook``): its way out (a chord of ``CORNER_WINDOW``) turns away from the way in
    (``way_in``: the median's points over the second half of the movement up to the corner;
    nearer the corner it already bends into the hook), and it is short against the width of
    the piece ``before`` it (centres, widths) (a 竖钩, a 斜钩, a 卧钩; not a 折 into a long
    leg), and, turned back down off a 横 (a level way in, ``is_level``), short against that
    piece's own width too (``feet.HOOK_LENGTH_OWN``: 宀's 横钩, 子's 横撇 are legs). The
    planner takes it from ``median_movements``."""
    win = max(int(round(CORNER_WINDOW / step)), 1)
    d = way_in[-1] - way_in[0]
    e = piece[min(win, len(piece) - 1)] - piece[0]
    cos = float(np.add.reduce(d * e)) / max(
        float(np.linalg.norm(d, axis=-1) * np.linalg.norm(e, axis=-1)), 1e-9
    )
    length = float(np.linalg.norm(np.diff(piece, axis=0), axis=1).sum())
    back = curl or _rises_back(d, e)
    off_heng = is_level(d) and float(e[1]) < 0.0  # turned back down off a 横 (宀's, 子's)
    return is_hook(cos, length, before[1], narrows(width), back, off_heng)


def _curled_end(pts, step: float, after: int) -> int | None:
    """Where a median's end curls into a hook off a curve (乙's, 也's, 九's 竖弯钩: the turn
    spreads over more than a corner's window, and read over ``CORNER_WINDOW`` it stays under
    ``CORNER_TURN``): the point after ``after`` (the last corner) where the heading over
    ``HOOK_WINDOW`` either side turns most, if that is more than ``HOOK_TURN``; None otherwise.
    Whether it is a hook is ``_hooks_back``'s to say. (Added in issue 26: written as one
    sweeping movement, the pressed belly dragged round the curl left a smear and a round knob
    at its end, not a flick.)"""
    win = max(int(round(HOOK_WINDOW / step)), 1)
    k = np.arange(max(after + win, win), len(pts) - win)
    if k.size == 0:
        return None
    turn = _heading_turn(pts[k] - pts[k - win], pts[k + win] - pts[k])
    i = int(np.argmax(turn))
    return int(k[i]) if turn[i] > HOOK_TURN else None


def median_pieces(char: dict, step: float = 4.0) -> list[list[tuple[np.ndarray, np.ndarray]]]:
    """For every stroke, points along the middle of its outline and the stroke's full width there
    (``_bands``, every ``step`` along the median), split into movements at the median's sharp
    corners (``corners``): each movement that ends at a corner goes on into the foot (``_foot``;
    a hook's foot gathered, ``_gathered_foot``, and held, ``_held_foot``), the next starts on
    the corner, but a hook (``_hooks_back``) from the foot (``_from_the_foot``); an end that
    curls into a hook off a curve (``_curled_end``) is cut there too. A calligrapher writes a
    hook or a 折 so: presses into the corner, turns the tip and sets off anew; dragging the
    pressed hair round the corner sweeps a round blot."""
    return [pieces for pieces, _ in median_movements(char, step)]


def median_movements(char: dict, step: float = 4.0, font: bool = True) -> list[tuple[list, bool]]:
    """``median_pieces`` of every stroke, with whether its last movement is a hook. With
    ``font`` (stroke data, not a picture's strokes) an end that joins another stroke goes on
    into it (``_tips_and_join``; a picture's strokes are read as pieces that meet everywhere:
    its imitation practises its joins, ``practice._join_error``), and a 折's shoulder is the
    calligrapher's, not the typeface's knob (``corners._shoulders``)."""
    out = []
    strokes = stroke_polygons(char)
    for i, (med, polys) in enumerate(zip(char["medians"], strokes, strict=True)):
        others = strokes[:i] + strokes[i + 1 :] if font else []
        tipped, joined = _tips_and_join(med, polys, others)
        pts, _ = resample(tipped, step)
        edges = [0, *corners(pts, step), len(pts) - 1]
        pieces = _pieces(pts, polys, step, edges, font=font)
        curl = None if len(pieces) > 1 and pieces[-1][2] else _curled_end(pts, step, edges[-2])
        if curl is not None:  # a hook off a curve, if the piece after it is one
            curled = _pieces(pts, polys, step, [*edges[:-1], curl, edges[-1]], True, font)
            pieces = curled if curled[-1][2] else pieces
        if joined:
            centre, width, hook = pieces[-1]
            pieces[-1] = (centre, _into_the_join(width, centre), hook)
        out.append(([(centre, width) for centre, width, _ in pieces], pieces[-1][2]))
    return out


def _pieces(pts, polys, step: float, edges, curl: bool = False, font: bool = True) -> list:
    """``median_pieces`` of one median (``pts``) cut at ``edges`` (``curl``: the last cut is
    where its end curls off a curve): (centres, widths, whether it is a hook) per movement."""
    pieces = []
    for k, (i0, i1) in enumerate(zip(edges[:-1], edges[1:], strict=True)):
        p = pts[i0 : i1 + 1]
        if k < len(edges) - 2:
            foot = _foot(pts, i1, polys, step)
            if k == len(edges) - 3 and _clockwise(pts, i1, step):  # a hook's foot (a 折's
                # shoulder is made again by _shoulders): only while the outline holds it
                own = _body_width(_bands(p, polys)[1])
                foot = _held_foot(foot, distance_to_outline(foot, polys), own)
            if curl and k == len(edges) - 3:  # into a curled end's hook: less far
                foot = foot[: int(len(foot) * CURL_FOOT)]
            p = np.concatenate([p, foot])
        way_in = pts[(edges[k - 1] + i0) // 2 : i0 + 1]
        hook = 0 < k == len(edges) - 2 and _hooks_back(
            way_in, p, pieces[-1], step, _bands(p, polys)[1], curl
        )
        flick = hook and flicks(p, _bands(p, polys)[1])  # flicked up to a point
        if hook:  # a hook sets off from the foot the movement before pressed into
            p = _from_the_foot(p, pieces[-1][0][-1], HOOK_FROM_FOOT if flick else HOOK_FROM_MIDDLE)
        centre, width = _bands(p, polys)
        if flick:  # straight out of the heel, down the middle of the triangle: cut again
            # from the first cut's middles (from the line out of the heel, near the lower
            # edge, the cut's far side is capped at 3x that distance: its middle lay 4-6 px
            # low at 384 px, and the ink, which follows the plan, spilled past the lower edge)
            centre = _rooted(p, _bands(_rooted(p, centre, width), polys)[0], width)
        if k:  # the corner is inked by the foot: the movement's own width
            # from where it leaves the corner's disc on (a hook's too: pressed wider, the
            # belly spilled over the hook's inner edge)
            _past_the_corner(width, step)
        pieces.append((centre, width, hook))
    if pieces[-1][2] and _clockwise(pts, edges[-2], step):  # a foot gathered, as wide as the stroke
        centre, width, _ = pieces[-2]
        k = edges[-2] - edges[-3]  # the corner, in the movement into it
        pieces[-2] = (centre, _gathered_foot(width, k, step), False)
    return _shoulders(pts, polys, step, edges, pieces, font)


def discs(centres_img, radii_img, n: int) -> np.ndarray:
    """Union of discs (image pixels) on an (n, n) grid, top row first."""
    mask = np.zeros((n, n), dtype=bool)
    for (cx, cy), r in zip(centres_img, radii_img, strict=True):
        if r <= 0:
            continue
        x0, x1 = max(int(cx - r - 1), 0), min(int(cx + r + 2), n)
        y0, y1 = max(int(cy - r - 1), 0), min(int(cy + r + 2), n)
        if x1 <= x0 or y1 <= y0:
            continue
        yy, xx = np.mgrid[y0:y1, x0:x1]
        mask[y0:y1, x0:x1] |= (xx + 0.5 - cx) ** 2 + (yy + 0.5 - cy) ** 2 <= r * r
    return mask


def iou(a, b) -> float:
    a, b = np.asarray(a, bool), np.asarray(b, bool)
    union = np.count_nonzero(a | b)
    return float(np.count_nonzero(a & b) / union) if union else 1.0


def baseline_masks(char: dict, n: int) -> dict:
    """The issue's two yardsticks at n x n: a constant-width round pen along the medians (its
    radius the character's mean half-width) and discs whose radii are read off the outline."""
    per = median_radii(char)
    centres = np.concatenate([to_image(p, n) for p, _ in per])
    radii = np.concatenate([r for _, r in per]) * n / EM
    mean_r = float(np.mean(radii[radii > 0])) if np.any(radii > 0) else 1.0
    return {
        "round_pen": discs(centres, np.full(len(radii), mean_r), n),
        "true_discs": discs(centres, radii, n),
    }
