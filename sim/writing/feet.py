# SPDX-License-Identifier: GPL-3.0-or-later
"""A hook's foot and a 折's corner read off the outline's widths: whether a stroke's last movement
is a hook (``is_hook``), where a hook sets off in its foot (``_from_the_foot``), the foot
gathered no wider than the stroke (``_gathered_foot``) and held where the outline has room for
it (``_held_foot``), a movement's own width and its width past a corner. Plain numpy on a
median's points and widths (data units); ``outline`` cuts the medians into movements with them.
(Added in issue 26, part 2.)"""

from __future__ import annotations

import numpy as np

HOOK_COS = -0.2  # a corner whose way out turns back by more than this (cosine, about 100
# degrees) from its way in, into a short last piece, is a hook's foot: the belly stays pressed
HOOK_UP_COS = 0.45  # ... or by more than this (about 63 degrees) into a short last piece that
# narrows to a point (HOOK_POINT): a 竖弯钩's, a 卧钩's, a 斜钩's flick, square to the way in
HOOK_RISE = 0.1  # ... or, from a way in going down, turns clockwise and back up (its way out
# rising by more than this sine): a 横折钩's or 弯钩's hook off a leg that slants or curves (刀,
# 力, 也, 同, 家's 豕, 了: 80-100 degrees from the way in, written as a 折 into a leg before)
HOOK_POINT = 0.6  # a hook's end is narrower than this share of its widest (a point, not a
# pressed end: a short leg after a 折 ends as wide as it began)
HOOK_LENGTH = 3.0  # a hook is at most this many times as long as the stroke before it is wide
# (a 竖折's leg turning back as much is a long stroke of its own)
HOOK_LENGTH_OWN = 3.4  # ... and, turned back down off a 横 (a level way in, ``is_level``, and
# a way out going down), at most this many times the stroke's own width before it
# (``_body_width``: its middle half's; the widest is often its pressed head). 子's 横撇 (浮 学
# 存 孕 子: 3.9-6.6 such widths) and 宀's and 冖's 横钩 (寒 家 宝 安 军 冗 写: 3.6-5.6) were read
# as hooks, gathered from the corner to a point: 子's 撇 a thin tail under a knob, 宀's corner a
# round knob pressed as wide as the font's triangle (2.4-3 times the 横) with the hook's point
# lost in it. As a 折 into a leg (a shoulder, ``corners._shoulders``, then the leg's own
# widths) both keep the outline's shape (issue 26.2). Other hooks keep the one test: a 斜钩's
# (戎 4.0), a 竖提's (以 6.3), a 撇折's (纟) or a 横折提's (讠) flick is short against the
# stroke's widest only.
LEVEL_SINE = 0.5  # a way into a corner is a 横's (level) when the sine of its slope is below this


def is_hook(
    cos: float, length: float, before, narrows: bool, curl: bool, off_heng: bool = False
) -> bool:
    """Whether a stroke's last movement, after a corner, is a hook (钩): short (at most
    ``HOOK_LENGTH`` times the widest of ``before``, the stroke's widths before the corner, and,
    turned back down off a 横 (``off_heng``), ``HOOK_LENGTH_OWN`` times its own width) and turned
    back on the way in (``cos`` of the turn below ``HOOK_COS``: a 竖钩, a 斜钩), or, after an
    end that curls off a curve or a leg going down that it leaves back upwards (``curl``:
    ``_curled_end``, ``_rises_back``), turned about square to it (below ``HOOK_UP_COS``) and
    narrowing to a point (``narrows``: a 竖弯钩, a 卧钩, 刀's 横折钩). A sharp corner turned
    only square into a short narrowing leg going down stays a 折 (墨's 罒, 口's shoulder)."""
    before = np.asarray(before, dtype=float)
    short = length <= HOOK_LENGTH * before.max()
    short = short and (not off_heng or length <= HOOK_LENGTH_OWN * _body_width(before))
    return short and (cos < HOOK_COS or (curl and cos < HOOK_UP_COS and narrows))


def narrows(width) -> bool:
    """Whether a movement's widths (along it) end narrower than ``HOOK_POINT`` of their widest."""
    w = np.asarray(width, dtype=float)
    return w.size > 1 and float(w[-1]) < HOOK_POINT * float(w.max())


def flicks(piece, width) -> bool:
    """Whether a hook (``piece``: its points, y up; ``width``: its widths along it) is flicked up
    to a point: it narrows (``narrows``) and its end lies above its start (a 竖钩's, a 弯钩's, a
    横折钩's, a 卧钩's; not 子's 横撇 read as a hook, nor a picture's 口 read with its bottom as
    one). Such a hook sets off from the heel (``_from_the_foot``, ``_rooted``; planner's
    ``_flicked``). (Issue 26.2, after feet16's ``flicks``.)"""
    p = np.asarray(piece, dtype=float)
    return narrows(width) and len(p) > 1 and float(p[-1, 1]) > float(p[0, 1])


def _rises_back(way_in, way_out) -> bool:
    """Whether a corner from a way in going down turns clockwise (y up) into a way out that
    rises (by more than ``HOOK_RISE``, as a sine): a hook flicked back up off a leg (刀, 力,
    了), not a 折 into a leg going down nor a 竖折 on to the right. (Added in issue 26.)"""
    d, e = np.asarray(way_in, dtype=float), np.asarray(way_out, dtype=float)
    clockwise = d[0] * e[1] - d[1] * e[0] < 0.0
    return bool(d[1] < 0.0 and clockwise and e[1] > HOOK_RISE * float(np.linalg.norm(e, axis=-1)))


HOOK_FROM_FOOT = 1.0  # share of the way from the median's corner to the foot's end (where the
# movement before pressed into) a hook flicked up to a point (``flicks``) sets off from: the
# heel, straight out of it (``_rooted``). (0.5 before issue 26.2, the middle of the triangle's
# base: the base went back up the vertical from the foot's end, pressed, and the hook's lower
# edge met the round end of the vertical below it in a notch, a round bulb at 永 小 水 寸 子)
HOOK_FROM_MIDDLE = 0.5  # ... and any other hook (子's 横撇, a picture's 口 read with its bottom as
# a hook): the middle of the foot (from its end, the 撇 ran off outside 子's outline)


def _from_the_foot(piece, foot, share: float = HOOK_FROM_FOOT) -> np.ndarray:
    """A hook's points moved to set off ``share`` of the way from the median's corner to
    ``foot`` (where the movement before ended, pressed into the foot), the shift fading out
    along the hook to its tip: the hook's ink is the triangle from the foot out to the point,
    as a calligrapher flicks it from the pressed foot. Added in issue 26."""
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(piece, axis=0), axis=1))])
    fade = share * (1.0 - s / max(float(s[-1]), 1e-9))
    return piece + fade[:, None] * (np.asarray(foot) - piece[0])[None, :]


def _rooted(piece, centre, width) -> np.ndarray:
    """A hook's centres (``centre``: ``piece``, its points set off from the foot, moved to the
    middle of the outline's cuts) kept on ``piece`` over its root, the first of its own widths
    (``width``), the move easing in beyond: across the root the cut runs into the leg's band and
    its middle lies up the leg, and the hook went back up the vertical before it flicked."""
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(piece, axis=0), axis=1))])
    t = np.clip(s / max(float(width[0]), 1e-9), 0.0, 1.0)[:, None]
    return piece + t * t * (3.0 - 2.0 * t) * (centre - piece)


HOOK_FOOT_OVER = 1.3  # a hook's foot is at most this many times the stroke's own width before it
# (the font's foot, where the hook's triangle joins the vertical, is cut up to twice as wide,
# slanting along the triangle; measured: 1.0-1.2 left the font's foot 5-6 % bare at 永, 1.3 keeps
# it filled and the bulb in)


def _gathered_foot(width, k: int, step: float) -> np.ndarray:
    """The widths of the movement into a hook's foot (``k``: the corner's point) held to
    ``HOOK_FOOT_OVER`` times its own width (``_body_width``) from half such a width before the
    corner on: the calligrapher gathers the brush at the foot, no wider than the stroke, and
    the hook's triangle is the flick's, set off from the foot (``_from_the_foot``; the belly
    keeps its press through the turn, planner's ``_heel``). (Added in issue 26: planned as
    wide as the font's foot, whose cut slants along the hook's triangle, up to twice the
    vertical, the pressed belly left a round bulb beside and below the corner, out past the
    triangle's lower edge. Narrowed from the hook's side only, the band's outer side kept, a
    speck was left past 永's hook point.) Only a hook turning clockwise (y up: a 竖钩, a 横折钩,
    a 弯钩, a 横钩); a 斜钩 flicks up off its end, whose round heel in the font the pressed end
    fills (gathered, it was left bare)."""
    cap = HOOK_FOOT_OVER * _body_width(width)
    near = np.arange(len(width)) >= k - int(0.5 * cap / step)
    return np.where(near, np.minimum(width, cap), width)


FOOT_HOLD = 0.85  # a clockwise hook's foot goes on only while the outline holds a disc of at
# least this share of the stroke's own half-width round it (measured at 512 px, default
# brush, 地 鸟 雹 也 句 刀 书 力 月 勺 包 场 阳: ink outside the outline near the hook feet
# 1192 -> 523 px, the outline left bare there 2118 -> 2343; 0.8: 734 and 2185, 0.9: 377, 2650)


def is_level(way) -> bool:
    """Whether a way into a corner (a vector) is a 横's: its slope's sine below ``LEVEL_SINE``."""
    return abs(float(way[1])) < LEVEL_SINE * float(np.hypot(way[0], way[1]))


def _held_foot(foot, room, width: float) -> np.ndarray:
    """A hook's foot (its points past the corner, ``room``: the outline's inscribed radius at
    each) cut where that radius falls below ``FOOT_HOLD`` of half the stroke's own ``width``:
    off a curved leg (也, 地's 也, 鸟, 雹's 勹, 句, 勺) the font's foot is a narrowing round V,
    and the foot ray, aimed at the outline's farthest point, went on into it as far as at a
    straight leg's square foot (刀, 力): the belly, pressed there as wide as the stroke, stood
    out past the V's sides and bottom in a round bulb. A straight leg's foot keeps its room to
    its end and is not cut. (Added in issue 26, part 2.)"""
    short = np.flatnonzero(np.asarray(room) < FOOT_HOLD * 0.5 * width)
    return foot[: short[0]] if short.size else foot


def _body_width(width) -> float:
    """A movement's own width: the median of its middle half (not its ends, feet or heads)."""
    w = np.asarray(width, dtype=float)
    n = len(w)
    return float(np.median(w[n // 4 : max(3 * n // 4, n // 4 + 1)]))


def _past_the_corner(width, step: float) -> None:
    """A movement after a corner keeps its own width from where it leaves the corner's disc on
    (in place): its first half-width is held to the width there."""
    off = min(int(np.ceil(0.5 * width[0] / step)), len(width) - 1)
    width[:off] = np.minimum(width[:off], width[off])


def _along(path) -> np.ndarray:
    """Distance (mm) along ``path`` from its first point, per point."""
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(path, axis=0), axis=1))])


# The press of a hook that flicks out of its heel (sim.writing.planner writes it).
HOOK_HEEL = 1.6  # a hook's heel is pressed at most this share of the stroke's own press before
# it (``feet._body_width`` of its presses): as the foot and the hook's root are planned, from the
# outline's or a picture's widths, up to a kaishu heel's weight (1.0 and 1.3: the same imitation
# of 学 and 高, with the base eased into the foot; the font's V foot was left barer)
HOOK_GATHER = 0.85  # share of the planned press a hook has left at its tip: the belly lets go
# faster than the outline narrows, so the splayed hair of the pressed foot gathers to a point


def _gathered(n: int) -> np.ndarray:
    """The press along a hook's ``n`` body samples as a share of the planned press: 1 where it
    sets off from the foot, easing (a smoothstep) to ``HOOK_GATHER`` at its tip. (Added in issue
    26: written at the planned press, the hair splayed in the foot spread the hook's last
    stretch about as wide as half the vertical, a blunt tail, not a point.)"""
    t = np.linspace(0.0, 1.0, max(n, 1))
    return 1.0 - (1.0 - HOOK_GATHER) * t * t * (3.0 - 2.0 * t)


def _heel(p, root: float) -> float:
    """The press a hook's heel keeps (``p``: the press per body sample of the movement into its
    foot; ``root``: the hook's planned press where it sets off): the deeper of the two, the
    belly staying pressed from the foot into the flick, at most ``HOOK_HEEL`` of the movement's
    own press (``feet._body_width``). (Issue 26.2: 0.7 of the foot's press, and the hook pressed
    again on the spot after a rest, 2 mm back up the vertical: the round bulb below every
    竖钩's hook.)"""
    return min(max(float(p[-1]), float(root)), HOOK_HEEL * _body_width(p))


def _into_the_heel(p, path, width) -> np.ndarray:
    """The press per body sample of a movement into a hook's foot (``p``; ``path``: its
    targets, ``width``: its planned widths) over its last stretch, as long as the movement is
    wide, easing (a smoothstep) to at most the heel's (``HOOK_HEEL`` of its own press): the base
    stops on the heel, and pressed much deeper there the belly splays into a round bulb beside
    and below the font's narrow foot (issue 26.2)."""
    to_end = _along(path)[-1] - _along(path)
    t = np.clip(1.0 - to_end / max(float(np.max(width)), 1e-6), 0.0, 1.0)
    heel = HOOK_HEEL * _body_width(p)
    return np.minimum(p, np.max(p) - (np.max(p) - heel) * t * t * (3.0 - 2.0 * t))


HOOK_ROOT = 0.25  # at most this share of a hook is its root, pressed as the heel (``_flicked``)


def _flicked(p, heel: float, path, width, fall: float = 1.0) -> np.ndarray:
    """A hook's press per body sample (``p``: as planned; ``path``: its targets, ``width``: its
    planned widths) as it flicks out of a heel pressed ``heel``: gathered to its point
    (``_gathered``), but no lighter than the font's triangle: the heel's press held over the
    hook's root (its first half-width, at most ``HOOK_ROOT`` of it), falling from there to none
    at the tip, evenly or (``fall``, ``_fall``: a power above 1) faster near the root. The hook
    leaves the heel as wide as the heel and thins steadily to its point. (Issue 26.2: set off
    from the heel at its planned press, read across a path that runs along the triangle's
    lower edge, it fell at once to a thin stick glued to a round
    heel, feet16's 水 寸 利. Held at most the heel's and never pressed again, as tried first
    with the base eased into the foot, 学's imitation was the same as without: 0.734 and 0.735;
    not measured with the base stopping on the heel.)"""
    s = _along(path)
    root = min(0.5 * float(width[0]), HOOK_ROOT * float(s[-1]))
    taper = heel * np.clip((s[-1] - s) / max(float(s[-1]) - root, 1e-9), 0.0, 1.0) ** fall
    return np.maximum(p * _gathered(len(p)), taper)


HOOK_UP_FALL = 1.5  # the power a hook pushed up anticlockwise off its way in (``_fall``) lets
# go of its heel's press by (measured at 512 px, default brush, the 乚 of 元 光 儿 电 见: 1, an
# even fall as a 竖钩's, ink/font width at 50 % 1.13, ink outside the font round the hook 78.8
# px, most of it a bulge on the hook's outer side; 1.5: 0.98 and 41.4 px, the same darkness;
# 2: 0.94, 0.90 at 75 %, 31.4 px. On the 竖钩s and 横折钩s of 村 时 守 寸 月 马 丁 小 水 利,
# 1.5 left them 0.76 of the font's width at 50 %, paler: they keep 1)


def _fall(way_in, way_out) -> float:
    """The power a flicked hook's press falls by from its heel to its point (``_flicked``):
    ``HOOK_UP_FALL`` for a hook that turns anticlockwise (y up) off its way in (``way_in``,
    ``way_out``: chords), pushed up off a stroke going right (a 竖弯钩's 乚: 元 光 也 儿 九; a
    卧钩, a 斜钩), 1 (evenly) for one turned back clockwise up its leg (a 竖钩, a 横折钩, a
    弯钩). The calligrapher presses the 乚's heel at the end of the 弯 (顿) and lifts as the
    hook sets off up, its triangle narrowing fastest at its root; held to the heel's press
    falling evenly to the point, the hook swelled halfway up past the font's outer edge, a
    candle flame 1.1-1.2 times the font's width at its middle. (Issue 26.2.)"""
    d, e = np.asarray(way_in, dtype=float), np.asarray(way_out, dtype=float)
    return HOOK_UP_FALL if d[0] * e[1] - d[1] * e[0] > 0.0 else 1.0


HOOK_BENT = 0.85  # share of the heel's lag the base keeps leading a flicked hook's ink by, to its
# point (``_bent``; measured at 384 and 512 px, 村 时 守 寸 月 马 丁 小 水 利: the ink short of the
# font's tip 6.8 -> 1.1 px, ink outside round the hook 79.7 -> 85.9 px; 0.7: 2.4 and 81.5 px;
# 1.0: 0.0 and 93.2 px, ink past the tip of 马 丁 小 利)


def _bent(lag) -> np.ndarray:
    """The lag (mm, per body sample) the base leads a hook flicked up to a point (``flicks``)
    by: at least ``HOOK_BENT`` of the heel's, where it sets off. The hair pressed into the heel
    is bent back and stays so through the quick flick; the response's lag (``_lead_along``,
    the base leading the ink along the path, Sec. 5.2's hair trailing the brush) is measured in
    a steady stroke at each press, and falling with the lightening press it drew the base back
    onto the ink: the hair's tip, still trailing the heel's lag behind the base, let go some
    1.7 mm short of the font's point (a blunt end). (Model addition, issue 26.2.)"""
    lag = np.asarray(lag, dtype=float)
    return np.maximum(lag, HOOK_BENT * float(lag[0])) if lag.size else lag
