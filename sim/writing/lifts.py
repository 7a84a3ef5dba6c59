# SPDX-License-Identifier: GPL-3.0-or-later
"""How a movement leaves the paper (the planner's lift-off, ``planner._enter_and_leave``): a
movement that narrows to a point lets go as the brush sweeps on out to it (出锋: the reach, the
let-go's pace), and a dot (点) presses into its heel and turns back as it lifts (回锋). The
paper takes the brush's samples from the writer's hand (Sec. 4, S^t of Eq. 9) and lets the
hair recover as it is lifted (Sec. 5.2.3, Eq. 14); what the hand does as a stroke ends is
planned here, beyond the paper (issue 26: the point; issue 26 point 2: the dot)."""

from __future__ import annotations

import numpy as np

from .feet import _along

POINT_CLEAR = 1.0  # mm above the paper the tip has at the end of a point's let-go (POINT_LIFT)
POINT_PACE = 0.75  # a point's let-go moves on at most this share of the mark's width a sample


def _width_at(response):
    """The band's width (mm) a press leaves, from the response's measured widths (linear in
    between, falling linearly to none at no press below the lightest measured press)."""
    press = np.concatenate([[0.0], response.press_mm])
    width = np.concatenate([[0.0], response.width_mm])
    return lambda p: np.interp(p, press, width)


def _flick_travel(reach, press, down, width_at=None) -> np.ndarray:
    """How far (mm) the base has moved on along the way out at each sample of a point's
    let-go: towards ``reach`` (per sample), but while the tip may still touch (``down``, until
    it is ``POINT_CLEAR`` above the paper) each step at most ``POINT_PACE`` of the width the
    press (``press``, per sample; ``width_at``: the response's width for a press) lays, so the
    shrinking marks of the tip overlap into one taper; once clear, its steps are not held back.
    (Added in issue 26: moving on half a step a sample as the press fell below a millimetre,
    the tip's marks fell apart into a dotted hairline past the point, and the tip, still
    touching at no planned press, left a speck beyond it.)"""
    if width_at is None:
        return reach
    step = np.diff(reach, prepend=0.0)
    mark = np.where(down, width_at(press), np.inf)
    return np.cumsum(np.minimum(step, POINT_PACE * mark))


POINT_SHARE = 0.6  # a movement whose planned width ends below this share of its widest, ...
POINT_PEAK = 0.6  # ... its widest point lying in this first share of it, ends in a point
POINT_LIFT = 0.75  # share of the lift-off over which the belly lets go, sweeping out to the point
POINT_EASE = 3.0  # a 撇's or a 提's belly rises over its let-go as the let-go's share to this
# power: it lets go slowly at first and the tip stays down as it sweeps out to the point (1,
# linear, as a hook's still does: the tip cleared the paper a third of the way out and the
# ink ended 4 px (at 512) short of the font's point, blunt; 2: 2 px short; 3: 0.0 px, 12 of
# 16 ends within 2 px; scripts/ends_eval.py, issue 26 point 2)
SLANT = 0.3  # share of its chord a 撇 or 提 runs across (``_lets_go``)
POINT_SAMPLES = 16  # samples of a 撇's or a 提's lift-off to its point (planner.EXIT_SAMPLES: 8)


def _point_reach(path, width) -> float:
    """How far (mm) past its median's end a movement's outline runs on to its point (the
    median stops short of it), for a movement that narrows to its end (出锋: a hook, a 撇, a
    提; ``width`` planned per body sample along ``path``): from its widest, in its first
    ``POINT_PEAK`` share, to an end below ``POINT_SHARE`` of that; the last width over the
    rate it narrowed at, from half to twice that width. 0 for any other movement: a round or
    pressed end (收笔), whose width falls only over the end's cap, a 捺 that swells to its end."""
    n = len(width)
    top = int(np.argmax(width))
    w, w_max = float(width[-1]), float(width[top])
    if n < 5 or top > POINT_PEAK * (n - 1) or w >= POINT_SHARE * w_max:
        return 0.0
    run = float(np.linalg.norm(np.diff(path[top:], axis=0), axis=1).sum())
    rate = (w_max - w) / max(run, 1e-9)
    return float(np.clip(w / max(rate, 1e-6), 0.5 * w, 2.0 * w))


def _lets_go(path, width, movements: int) -> bool:
    """Whether a stroke of ``movements`` movements, its last one's body samples' targets
    ``path`` (mm, y up) planned ``width`` wide, is a 撇 or a 提: one movement that ends in a
    point (``_point_reach``), not a dot, running down to the left or up to the right, at least
    ``SLANT`` of its chord across (not a 竖 that narrows to its end). Its lift-off takes
    ``POINT_SAMPLES`` and its belly rises as ``POINT_EASE``, so that paced by its shrinking
    marks (``_flick_travel``) the tip reaches the point before it is clear of the paper.
    (Added in issue 26 point 2: in 8 samples, rising evenly, the tip cleared the paper a third
    of the way out, and 撇 and 提 ended 4 px (at 512) short of the font's point, blunt.)"""
    if movements != 1 or is_dot(path, width):
        return False
    chord = np.asarray(path[-1], float) - np.asarray(path[0], float)
    slant = abs(chord[0]) >= SLANT * float(np.linalg.norm(chord))
    return bool(slant and chord[0] * chord[1] > 0.0 and _point_reach(path, width) > 0.0)


DOT_LENGTH = 3.4  # a movement alone in its stroke shorter than this many of its widest is a dot
# (scripts/entries_eval.py and dots_eval.py read the font so), ...
DOT_PEAK = 0.5  # ... its planned width widest past this share of it (a 侧点 swells to its heel;
# a short 竖, 撇 or 提 is widest at its head: 出's, 左's, 冰's, 求's are not dots)
HEEL_IN = 1.25  # half widths of the widest a dot's heel is pressed in from the outline's end
# (``_heel_held``; 1.5 left the heels of 墨's 灬 and 主's dot a little short of the outline)
RETURN = 1.0  # share of the base's lead over the ink it draws back as a dot's brush lifts


def is_dot(path, width) -> bool:
    """Whether a movement (``path``: its body samples' targets, mm; ``width``: planned) is a dot:
    shorter than ``DOT_LENGTH`` times its widest, which lies past ``DOT_PEAK`` of it."""
    top = int(np.argmax(width))
    if len(width) < 3 or top < DOT_PEAK * (len(width) - 1):
        return False
    return float(_along(path)[-1]) < DOT_LENGTH * float(width[top])


def _heel_held(path, p, width) -> tuple[np.ndarray, np.ndarray]:
    """A dot written as a calligrapher writes it (侧点): from its widest planned point on the
    belly keeps that press (``p``: per body sample), and the brush stops where its pressed mark
    (half the widest across) reaches the outline's end (the median's end plus half the width
    there, ``HEEL_IN`` of that half width in), pressing into the heel (顿) for the rest of the
    way: the end is a full rounded heel. (Added in issue 26 point 2: following the font's
    narrowing cap, the belly lifted as the brush went on, and the dot's end was a thin spike
    with a speck or two past it.) Returns the path and the press."""
    top = int(np.argmax(width))
    s = _along(path)
    stop = s[-1] + 0.5 * float(width[-1]) - HEEL_IN * 0.5 * float(width[top])
    h = int(np.searchsorted(s, max(stop, s[top])))
    if h >= len(path) - 1:
        return path, p
    p = np.array(p, dtype=float)
    p[top:] = np.maximum(p[top:], p[top])
    path = np.array(path, dtype=float)
    path[h:] = path[h]
    return path, p


def _turned_back(lead, way, f) -> np.ndarray:
    """How far (mm, along ``way``, the last direction) the base goes on at each sample of a
    dot's lift-off (``f``: the share of the lift done): back over its lead on the ink (``lead``,
    the base's offset from the ink's end, mm) by ``RETURN`` of it, eased in and out (回锋), so
    that the tip folds back into the heel, not out past it."""
    back = RETURN * max(float(np.asarray(lead) @ way), 0.0)
    return -back * f * f * (3.0 - 2.0 * f)
