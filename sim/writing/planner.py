# SPDX-License-Identifier: GPL-3.0-or-later
"""The plan of the writing: each median resampled at the brush's pace, one movement per
piece between sharp corners, entries and lifts, travel in the air and dips (``plan``); and
the samples of one stroke from its plan, press and sideways placement (``_fill``: the
calligrapher's entry, the base leading the ink along the path, the lift-off)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core import exact
from ..core.recording import quantise
from .feet import (
    _along,
    _bent,
    _fall,
    _flicked,
    _gathered,
    _heel,
    _into_the_heel,
    flicks,
)
from .lifts import (
    POINT_CLEAR,
    POINT_EASE,
    POINT_LIFT,
    POINT_SAMPLES,
    _flick_travel,
    _heel_held,
    _lets_go,
    _point_reach,
    _turned_back,
    _width_at,
    is_dot,
)
from .outline import EM, TOP, median_movements

if TYPE_CHECKING:  # the response is handed in (its module builds on this one)
    from .response import Response


ENTRY_SAMPLES = 8
EXIT_SAMPLES = 8
CORNER_SAMPLES = 4  # samples of the lift into a sharp corner and of the entry after it: the
# brush stays down there (issue 26's 折 and hooks; 8 before, and a shoulder read as a corner
# since then costs a movement more: with 4 the writing does about the same work as before)
HEEL_SAMPLES = 1  # ... and of the lift into the heel of a hook flicked up to a point and of its
# entry, with no turn between: the hook sets off from the heel at once (issue 26.2: 4, 4 and 4,
# the belly lifted on the heel, went 2 mm back up the vertical and pressed again there, a round
# bulb below the hook)
# what the brush does at a sample of a plan (Plan.phase)
IN_THE_AIR, ENTERING, WRITING, LIFTING, TURNING = 0, 1, 2, 3, 4


def _smooth(v, k: int) -> np.ndarray:
    if k <= 1 or len(v) < 3:
        return np.asarray(v, dtype=float)
    w = np.ones(k) / k
    pad = np.pad(np.asarray(v, dtype=float), (k // 2, k - 1 - k // 2), mode="edge")
    return np.convolve(pad, w, mode="valid")


@dataclass
class Plan:
    """Per sample of a character's writing: where the ink should land (paper mm), how wide the
    stroke is there, the way of travel, and what the brush does: IN_THE_AIR, ENTERING (coming
    down onto a stroke), WRITING, LIFTING (off the stroke's end), TURNING (between two
    movements of a stroke, at a sharp corner: the tip stays on the paper, lightly). ``dips``
    are the samples before which the brush dips again."""

    target: np.ndarray  # (N, 2)
    width: np.ndarray  # (N,)
    tangent: np.ndarray  # (N, 2)
    phase: np.ndarray  # (N,) int
    dips: list
    strokes: list  # (first, end) sample of every stroke: entry, writing, lift-off
    hooks: tuple = ()  # the first body sample of every movement that is a hook (the outline's
    # ``median_movements`` says which)


def _timed(dense, width, step_mm: float, slow_corners: float):
    """Sample a densely resampled median (mm) at the brush's pace: step_mm per sample on the
    straight, slower where the stroke turns (down to (1 - slow_corners) of the pace at a right
    angle), as a calligrapher slows into a turn so that the hair can follow."""
    seg = np.linalg.norm(np.diff(dense, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] <= 0 or len(dense) < 3:
        return dense[:1], width[:1]
    heading = np.unwrap(exact.arctan2(*np.gradient(dense, axis=0).T[::-1]))
    win = max(int(round(1.5 / max(s[1] - s[0], 1e-9))), 1)  # +-1.5 mm
    pad = np.pad(heading, win, mode="edge")
    turn = np.abs(pad[2 * win :] - pad[: -2 * win])
    pace = np.clip(1.0 - slow_corners * turn / (np.pi / 2), 1.0 - slow_corners, 1.0)
    t = np.concatenate([[0.0], np.cumsum(seg / (0.5 * (pace[1:] + pace[:-1])))])
    n = max(int(np.ceil(t[-1] / step_mm)), 1) + 1
    ts = np.linspace(0.0, t[-1], n)
    si = np.interp(ts, t, s)
    pts = np.stack([np.interp(si, s, dense[:, 0]), np.interp(si, s, dense[:, 1])], axis=1)
    return pts, np.interp(si, s, width)


def _air(tg, wd, tn, ph, a, b, tang, step_mm, phase=IN_THE_AIR) -> None:
    """Travel from ``a`` to ``b`` (mm), in the air or (``phase`` TURNING) on the tip."""
    k = max(int(np.linalg.norm(b - a, axis=-1) / (2 * step_mm)), 4)
    t = np.linspace(0.0, 1.0, k)[:, None]
    tg.append(a * (1 - t) + b * t)
    wd.append(np.zeros(k))
    tn.append(np.tile(tang, (k, 1)))
    ph.append(np.full(k, phase))


def plan(
    char: dict,
    size_mm: float,
    step_mm: float,
    dip_every_mm: float | None = None,
    origin=(0.0, 0.0),
    slow_corners: float = 0.7,
    font: bool = True,
) -> Plan:
    """The path of the writing: each median resampled every step_mm with the outline's width,
    one movement per piece of the median between its sharp corners (``median_pieces``: a
    hook's foot, a 折), each with an entry and a lift, the tip turning on the paper between the
    movements of a stroke, travel in the air between strokes. Each movement is smoothed on its
    own, so that a corner stays a corner. The brush is dipped before the first stroke and, with
    ``dip_every_mm``, before a stroke that would take it past that much writing since the last
    dip (without, the writer dips when the brush runs low, ``writer.dips_when_low``). ``font``:
    the character is stroke data, not a picture's strokes (``outline.median_movements``)."""
    scale = size_mm / EM
    dip_every = np.inf if dip_every_mm is None else dip_every_mm
    tg, wd, tn, ph, dips, strokes, hooks = [], [], [], [], [], [], []
    since_dip, prev = np.inf, None
    fine = max(step_mm / scale / 4.0, 0.25)
    k = max(int(round(3.0 / fine / scale)), 1)  # +-1.5 mm: the cut's jitter smoothed
    for pieces, hook in median_movements(char, step=fine, font=font):
        moves = []
        for pts_d, width_d in pieces:
            dense = np.stack(
                [origin[0] + pts_d[:, 0] * scale, origin[1] + (pts_d[:, 1] - (TOP - EM)) * scale],
                axis=1,
            )
            dense = np.stack([_smooth(dense[:, 0], k), _smooth(dense[:, 1], k)], axis=1)
            pts, width = _timed(dense, _smooth(width_d * scale, k), step_mm, slow_corners)
            tang = np.gradient(pts, axis=0) if len(pts) > 1 else np.array([[1.0, 0.0]])
            tang = np.stack([_smooth(tang[:, 0], 5), _smooth(tang[:, 1], 5)], axis=1)
            tang /= np.maximum(np.linalg.norm(tang, axis=1, keepdims=True), 1e-9)
            moves.append((pts, _unpinched(_smooth(width, 3)), tang))
        if prev is not None:  # travel in the air to the next stroke
            _air(tg, wd, tn, ph, prev, moves[0][0][0], moves[0][2][0], step_mm)
        n = sum(len(a) for a in tg)
        stroke_len = step_mm * sum(len(m[0]) - 1 for m in moves)
        if not strokes or since_dip + stroke_len > dip_every:
            dips.append(n)
            since_dip = 0.0
        since_dip += stroke_len
        flick = hook and flicks(moves[-1][0], moves[-1][1])  # a hook flicked up to a point
        for j, (p, w, t) in enumerate(moves):
            last = hook and j == len(moves) - 1
            heel = flick and j and last  # it flicks on from the heel: no turn
            if j and not heel:  # a sharp turn: ease to the tip, turn on it, press again
                _air(tg, wd, tn, ph, moves[j - 1][0][-1], p[0], t[0], step_mm, TURNING)
            # at a sharp corner the brush is already down: a shorter lift and entry
            m0 = CORNER_SAMPLES if j else ENTRY_SAMPLES
            m1 = CORNER_SAMPLES if j < len(moves) - 1 else EXIT_SAMPLES
            if j == len(moves) - 1 and not hook and _lets_go(p, w, len(moves)):
                m1 = POINT_SAMPLES  # a 撇's, a 提's let-go to its point: slower (``lifts``)
            if heel:  # into and out of the hook's heel
                m0 = HEEL_SAMPLES
            if flick and j == len(moves) - 2:
                m1 = HEEL_SAMPLES
            if j and last:
                hooks.append(sum(len(a) for a in tg) + m0)
            tg += [np.tile(p[0], (m0, 1)), p, np.tile(p[-1], (m1, 1))]
            wd += [np.full(m0, w[0]), w, np.full(m1, w[-1])]
            tn += [np.tile(t[0], (m0, 1)), t, np.tile(t[-1], (m1, 1))]
            ph += [np.full(m0, ENTERING), np.full(len(p), WRITING), np.full(m1, LIFTING)]
        strokes.append((n, sum(len(a) for a in tg)))
        prev = moves[-1][0][-1]
    return Plan(
        np.concatenate(tg),
        np.concatenate(wd),
        np.concatenate(tn),
        np.concatenate(ph),
        dips,
        strokes,
        tuple(hooks),
    )


PINCH_FLOOR = 0.5  # share of the lesser of its widest before and after that a movement's width
# keeps in its middle (``_unpinched``)


def _unpinched(width) -> np.ndarray:
    """A movement's widths, nowhere in its middle under ``PINCH_FLOOR`` of the lesser of the
    widest before it and the widest after it. The width is read as the distance from the median
    to the outline; a median that cuts across a corner (a picture's 竖折, read as one movement
    round a bevel) passes by the corner's inner point, and the width read there fell to a
    twentieth of the legs' (端's 山: 0.3 mm against 7.4 mm). The brush lifted to its tip in the
    middle of the stroke and the ink broke in two. A brush writing on round a turn keeps its
    belly on the paper; a stroke that narrows toward an end (a 撇, a 捺's head) is untouched:
    its narrow end has no wider part beyond it. (Model addition, issue 26.)"""
    w = np.asarray(width, dtype=float)
    before = np.maximum.accumulate(w)
    after = np.maximum.accumulate(w[::-1])[::-1]
    return np.maximum(w, PINCH_FLOOR * np.minimum(before, after))


ZHE_LEAD_SPAN = 2.0  # lags over which the base's lead runs out into a 折's corner (``_lead_along``)


def _lead_along(path, lag, stop: bool = False, ease: bool = False):
    """Where the brush's base must be so that the ink lands on ``path``: the hair trails the
    base along the way it came, so the base runs ahead of the mark by the lag *along the path*
    (round a curve, not off its tangent). The lead builds up over the first stretch of the
    stroke, as the hair bends over behind the base, and beyond the path's end the base goes on
    along the last direction."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    lead = np.asarray(lag, dtype=float) * np.clip(s / np.maximum(lag, 1e-6), 0.0, 1.0)
    q = s + lead
    if stop:  # into a corner: the base stops on the corner, the hair catches up beneath it
        q = np.minimum(q, s[-1])
    if ease:  # into a 折: the lead runs out over the last ``ZHE_LEAD_SPAN`` lags, the base
        # slowing to half the ink's pace but going on, to end on the corner (the 顿 sets off
        # from there, ``_turn_on_the_tip``)
        span = ZHE_LEAD_SPAN * np.maximum(lag, 1e-6)
        q = s + lead * np.clip((s[-1] - s) / span, 0.0, 1.0)
    out = np.stack([np.interp(q, s, path[:, 0]), np.interp(q, s, path[:, 1])], axis=1)
    if len(path) > 1 and s[-1] > 0:
        end_dir = path[-1] - path[-2]
        end_dir = end_dir / max(float(np.linalg.norm(end_dir, axis=-1)), 1e-9)
        past = np.maximum(q - s[-1], 0.0)
        out += past[:, None] * end_dir[None, :]
    return out


ENTRY_TOUCH = 0.15  # share of the press the tip lands with; the belly presses as it goes
TIP_TOUCH_MM = 0.2  # how far below touching height the tip comes down as a movement begins
# (a brush made k times as large, ``brush_size``: k times as far)
ZHE_TOUCH = 1.0  # ... and the leg after a 折 sets off with: the 顿 has pressed it down already
# (0.4 before issue 26's 顿: pressing again as the leg went down, it left a waist below the
# shoulder)
HOOK_KEEP = 0.7  # share of its press the belly keeps through the turn of a hook that is not
# flicked up to a point (``feet.flicks``: 子's 横撇; one that is keeps the heel's, ``_heel``)
ZHE_KEEP = 0.6  # share of its press the belly keeps through a 折's turn: the brush lifts only
# slightly as the 顿 sets off and presses again as it goes (eased to the tip, 0.05 of the hair,
# before issue 26, the leg began thin: the shoulder's outer corner bare, a round knob inside it;
# 0.5 with a leg entered at 0.4)
TURN_EASE = 0.8  # press taken off at a reversal (a hook), less at a milder turn


def _entry_ramp(path, width, touch=ENTRY_TOUCH) -> np.ndarray:
    """The press as a share of the planned press along the start of a stroke: the tip lands
    (``ENTRY_TOUCH``) while the brush already moves along the stroke, and the belly presses
    over the first stroke width of the way (a smoothstep), as a calligrapher enters - not a
    stationary press, which splays the hair into a round blob."""
    s = _along(path)
    t = np.clip(s / max(_ramp_length(s, width), 1e-6), 0.0, 1.0)
    entry = touch + (1.0 - touch) * t * t * (3.0 - 2.0 * t)
    return entry * _turn_ease(path, s)


ENTRY_SIDE = 1.0  # share of the sideways placement past the entry the entry is written with


def _entry_side(side, path, width) -> np.ndarray:
    """The sideways placement per body sample of a movement, over its entry (where the belly
    is still pressing down, ``_entry_ramp``) that of the first sample past it (``ENTRY_SIDE``):
    practice does not follow the band's centre at a head (the landing's head, which bent it
    into a claw) but corrects it past the entry, and the belly that lands there sits as far
    off the base as it does a little further on. Kept at none, the head sat off the stroke
    to the side the hair lays its ink, a knob beyond the outline (issue 26)."""
    s = _along(path)
    entry = s < _ramp_length(s, width)
    if not entry.any() or entry.all():
        return side
    first = int(np.argmin(entry))  # the first sample past the entry
    return np.where(entry, ENTRY_SIDE * side[first], side)


ENTRY_RAMP = 0.5  # share of the stroke's width (its first third's widest) the belly presses over
# (issue 26.2: 1.0, a press that grows about as fast as the base moves, took the knob off 秋's
# top 撇 but thinned every head: bare outline at the starts of ten characters 5711 -> 11057 px,
# imitation's first four cases -0.043, -0.019, +0.023, -0.011)


def _ramp_length(s, width) -> float:
    """How far (mm) into a movement the belly has pressed to the planned press (``_entry_ramp``):
    ``ENTRY_RAMP`` of the stroke's width over its first third, at least 0.5 mm, at most a
    quarter of the movement (``s``: distance along it per sample)."""
    w = np.max(width[: max(len(width) // 3, 1)])
    return float(np.clip(ENTRY_RAMP * w, 0.5, 0.25 * s[-1]))


def _turn_ease(path, s) -> np.ndarray:
    """Less press where the stroke turns back on itself (a hook, the sharp turn of a 折): a
    calligrapher eases the belly off and turns on the tip there; pressed through a sharp turn
    the hair sweeps round and leaves a round blot. 1 on the straight, down to 1 - TURN_EASE at a
    reversal, over +-1.5 mm."""
    if len(path) < 3 or s[-1] <= 0:
        return np.ones(len(path))
    d = np.gradient(path, axis=0)
    heading = np.unwrap(exact.arctan2(d[:, 1], d[:, 0]))
    win = max(int(round(1.5 / max(s[-1] / (len(s) - 1), 1e-9))), 1)
    pad = np.pad(heading, win, mode="edge")
    turn = np.abs(pad[2 * win :] - pad[: -2 * win])
    return 1.0 - TURN_EASE * np.clip((turn - 0.9) / 1.4, 0.0, 1.0)


RUN_UP = 1.0  # the entry's run-up along the stroke (half steps a sample): the tip lands moving
# on (against the stroke where it sets off down, ``_landing``); 0 lands it on the start (where
# a picture's ink begins: the run-up's tip lays a hairline before it)
HIDDEN_DOWN = 0.5  # a movement heading down by more than this (sine; 30 degrees below the
# horizontal: a 竖, a 撇, a dot, a 捺) hides its tip (``_landing``)


HIDDEN_REACH = 0.8  # share of the half width at its start a hidden-tip head's base reaches up
# past the median's start into the cap before it turns and presses down (``_reach_the_cap``;
# 0.5 left 子's 竖钩 head short of the 横撇 that ends on it in 好: ink in one piece more than the
# font, tests/sim/test_joins.py)


def _reach_the_cap(samples, pl, body) -> None:
    """A hidden-tip head (藏锋, ``_landing``): the base goes on up past the median's start
    against the stroke's way, into the cap, by ``HIDDEN_REACH`` of the half width there, and
    turns down from there, coming back onto the planned path over the entry's ramp
    (``_ramp_length``): the cap is filled by the turn. Landing on the median's start, the tip
    trailing into the stroke, the cap above it stayed bare (issue 26.2: 村's 竖 about 8 px
    short at its top)."""
    s = _along(pl.target[body])
    t = np.clip(s / max(_ramp_length(s, pl.width[body]), 1e-6), 0.0, 1.0)
    back = HIDDEN_REACH * 0.5 * float(pl.width[body[0]]) * (1.0 - t * t * (3.0 - 2.0 * t))
    samples[body, :2] -= back[:, None] * pl.tangent[body[0]]


NARROW_HEAD = 0.3  # a movement whose first widths (its first three samples') are below this
# share of its widest has a pointed head in the outline, and lands moving on (``_landing``): a
# 捺's (0.15-0.28 on 人八大天木禾又文之入永长水), not a 竖's, 撇's, 横's or dot's (0.32-0.54)


def _narrow_head(width) -> bool:
    """Whether a movement's planned widths begin in a point (``NARROW_HEAD``)."""
    return len(width) > 3 and float(np.mean(width[:3])) < NARROW_HEAD * float(np.max(width))


def _landing(path, run_up: float, pointed: bool = False) -> float:
    """The run-up a movement's entry comes down with (``_enter_and_leave``; ``path``: its
    body samples' targets, paper mm, y up). A stroke that sets off down (竖, 撇, a 捺 with a
    round head: its way from start to end heads down by more than ``HIDDEN_DOWN``) is entered
    with the tip hidden (藏锋, 逆锋起笔): the brush comes down moving back up the stroke,
    against its way, so the landing tip trails into the stroke, the belly presses on the start
    and the body covers the tip. One that sets off along (横, 提) lands moving on, its tip
    showing at the head as the outline's point does (露锋). (Added in issue 26: landing moving
    on, every downward head had the tip's hairline standing out behind it, a beak above-left
    of the outline's round head; entered so, a 横's head flipped the hair over, a horn on its
    top.)
    A ``pointed`` head lands moving on whichever way it heads, the tip touching at the
    outline's point: a dot's (点, ``is_dot``: the belly presses down along the dot, 露锋入笔;
    hidden, its head came out round and the dot short of the font's by 8 %, 51 dots of 18
    characters) and a head that is a point in the outline (``_narrow_head``: a 捺 sets off thin
    and swells; hidden, its head was a round knob beside the 撇 it sets off from, 人, 八).
    0 (a picture's exact start) stays 0."""
    if run_up <= 0.0 or pointed:
        return run_up
    chord = path[-1] - path[0]
    down = -chord[1] / max(float(np.sqrt(chord[0] * chord[0] + chord[1] * chord[1])), 1e-9)
    return -run_up if down > HIDDEN_DOWN else run_up


def _enter_and_leave(
    samples,
    pl,
    body,
    brush,
    corner=(None, None),
    run_up=RUN_UP,
    width_at=None,
    ease=1.0,
) -> None:
    """The brush comes down moving along the movement's first direction (over ``run_up`` times
    half a step a sample: with 0, straight down onto the start; a stroke that sets off down
    comes down moving back up it, ``_landing``), the tip touching where the body begins, and
    lifts off moving on along the last direction (a flick, so that hooks and left-falling
    strokes end in a point, not a blot from a lift on the spot; ``ease``: the power the belly's
    rise over a point's let-go goes as, ``POINT_EASE`` for a 撇's or a 提's). ``corner``:
    the base's height at the sharp corner the movement begins after / ends at
    (``median_pieces``; None: none). At a 折 the brush lifts only slightly (``ZHE_KEEP``), on
    the corner itself (a flick there overshoots the corner), and presses again (``ENTRY_TOUCH``):
    lifted off the paper and set down again, the pressed belly landed on the corner as a round
    blot; eased to the tip, the leg began thin and the shoulder's outer corner stayed bare. At
    a hook's foot (``_is_hook``) the belly stays pressed through the turn and
    the hook sets off pressed, lifting as it goes: eased to the tip there, the hook began thin
    and swelled, a blunt tail apart from the foot. ``brush``: as ``_fill``'s."""
    hover, hair, step_mm, scale = brush
    a = body[0] - 1
    while a >= 0 and pl.phase[a] == ENTERING:
        a -= 1
    entry = np.arange(a + 1, body[0])
    t0 = pl.tangent[body[0]]
    f = np.arange(1, len(entry) + 1) / max(len(entry), 1)
    dot = corner[0] is None and corner[1] is None and is_dot(pl.target[body], pl.width[body])
    run_up = _landing(pl.target[body], run_up, dot or _narrow_head(pl.width[body]))
    if run_up < 0.0 and corner[0] is None:
        _reach_the_cap(samples, pl, body)
    back = (len(entry) + 1 - np.arange(1, len(entry) + 1)) * 0.5 * step_mm * run_up
    if corner[0] is not None:  # after a sharp turn the tip comes down on the corner, not before it
        back = back * 0.0
    samples[entry, :2] = samples[body[0], :2] - back[:, None] * t0
    z_touch = max(samples[body[0], 2], hair - TIP_TOUCH_MM * scale)  # the tip touches
    if corner[0] is not None and corner[0] < hair:  # after a corner the belly is still pressed
        z_touch = samples[body[0], 2]
    top = hover if corner[0] is None else corner[0]
    samples[entry, 2] = top + (z_touch - top) * f
    b = body[-1] + 1
    while b < len(pl.phase) and pl.phase[b] == LIFTING:
        b += 1
    lift = np.arange(body[-1] + 1, b)
    t1 = pl.tangent[body[-1]]
    f = np.arange(1, len(lift) + 1) / max(len(lift), 1)
    flick = 0.5 * step_mm if corner[1] is None else 0.0  # into a sharp turn: lift on the corner
    travel = f * len(lift) * flick
    top = hover if corner[1] is None else corner[1]
    z0 = samples[body[-1], 2]
    rise = z0 + (top - z0) * np.sqrt(f)
    point = _point_reach(pl.target[body], pl.width[body]) if corner[1] is None else 0.0
    point = 0.0 if dot else point  # a dot ends in its heel (``_heel_held``), not a point
    if point > 0.0:  # 出锋: the belly lets go evenly as the brush sweeps on, out to the point
        g = np.clip(f / POINT_LIFT, 0.0, 1.0)
        clear = hair + POINT_CLEAR  # the let-go ends with the tip clear of the paper
        rise = np.where(f <= POINT_LIFT, z0 + (clear - z0) * g**ease, rise)
        travel = _flick_travel(np.maximum(travel, g * point), hair - rise, g < 1.0, width_at)
    if dot:
        travel = _turned_back(samples[body[-1], :2] - pl.target[body[-1]], t1, f)  # 回锋
    samples[lift, :2] = samples[body[-1], :2] + travel[:, None] * t1
    samples[lift, 2] = rise


def _onto_the_dun(pl: Plan, run, leg) -> bool:
    """Whether the movement ``run`` (body samples) ends at a 折's shoulder the outline made a
    顿 of (``corners._dun_point``): the next movement, ``leg``, sets off ahead of its end, not
    back on the corner behind a foot it pressed into (a 竖折's corner, a picture's)."""
    ahead = pl.target[leg[0]] - pl.target[run[-1]]
    return float(ahead @ pl.tangent[run[-1]]) >= 0.0


def _is_hook(pl: Plan, runs) -> list[bool]:
    """For each movement of a stroke (``runs``: its body samples), whether it leaves a hook's
    foot (``Plan.hooks``, from ``outline.median_movements``: a short last movement that turns
    back on the way in, a 竖钩, a 斜钩, or sets off about square from an end that curls off a
    curve and narrows to a point, a 竖弯钩, a 卧钩; not a 折's turn into a leg)."""
    return [bool(len(run)) and int(run[0]) in pl.hooks for run in runs]


def _flicks(pl: Plan, runs, hook) -> list[bool]:
    """For each movement of a stroke (``runs``; ``hook``: ``_is_hook``'s), whether it is a hook
    flicked up to a point (``feet.flicks``), which sets off from its heel at once
    (``HEEL_SAMPLES``, ``_heel``, ``_flicked``); any other hook turns on the tip and presses
    again (``HOOK_KEEP``) as before issue 26.2."""
    return [h and flicks(pl.target[run], pl.width[run]) for h, run in zip(hook, runs, strict=True)]


def _way_in(path) -> np.ndarray:
    """The chord of the last half of a movement's ``path``: its way into the corner after it."""
    return path[-1] - path[len(path) // 2]


def _movements(items, body=None) -> list[np.ndarray]:
    """``items`` cut where the body samples (``body``, or the items themselves) jump: one piece
    per movement of the stroke (the brush lifts between them)."""
    body = items if body is None else body
    return np.split(items, np.flatnonzero(np.diff(body) > 1) + 1)


def _turn_on_the_tip(samples, pl: Plan, span, heights, dun=()) -> None:
    """The TURNING samples of samples a..b (``span``): the base goes straight from where the
    lift into the corner ended to where the next entry begins, at the corner's height
    (``heights``, one per corner in order): the belly lifted slightly at a 折 (``ZHE_KEEP``),
    pressed at a hook's foot (``HOOK_KEEP``). At a 折 (``dun``: per corner, whether it is one)
    the lift, the turn and the entry are one move (the 顿): the base goes on evenly from the
    movement's end to where the leg sets off (``corners._dun_point``), lifting a little
    and pressing again as it goes, never at rest while pressed. (Issue 26: lifted and entered
    on the spot, and the turn dragged back across the shoulder, it laid a round knob.)"""
    a, b = span
    turning = np.flatnonzero(pl.phase[a:b] == TURNING) + a
    runs = [r for r in _movements(turning) if r.size]
    for c, (run, z) in enumerate(zip(runs, heights, strict=False)):
        samples[run, 2] = z
        if c < len(dun) and dun[c]:
            i0, i1 = run[0] - 1, run[-1] + 1
            while pl.phase[i0] == LIFTING:
                i0 -= 1
            while pl.phase[i1] == ENTERING:
                i1 += 1
            run = np.arange(i0 + 1, i1)
        p0, p1 = samples[run[0] - 1, :2], samples[run[-1] + 1, :2]
        t = (np.arange(1, len(run) + 1) / (len(run) + 1))[:, None]
        samples[run, :2] = p0 * (1.0 - t) + p1 * t


END_SPAN = 2.0  # stroke widths along a movement over which a moved end's shift fades out


def _ends_moved(path, tangent, width, moves) -> np.ndarray:
    """A movement's path with its start and end carried on (> 0) or drawn back (< 0) along the
    way out of each end by ``moves`` (mm, start and end; or (2, 2): each end shifted so far on
    the paper, x and y), the shift fading out over ``END_SPAN`` widths inside the end, so the
    body of the stroke stays where it is."""
    if len(path) < 2 or not np.any(moves):
        return path
    s = _along(path)
    span = max(END_SPAN * float(np.max(width)), 1e-6)
    w0 = np.clip(1.0 - s / span, 0.0, 1.0)[:, None]
    w1 = np.clip(1.0 - (s[-1] - s) / span, 0.0, 1.0)[:, None]
    if np.ndim(moves) == 2:
        return path + w0 * moves[0] + w1 * moves[1]
    return path - w0 * moves[0] * tangent[0] + w1 * moves[1] * tangent[-1]


def _fill(
    samples,
    pl: Plan,
    response: Response,
    span,
    press,
    side,
    brush,
    ends=None,
    run_up=RUN_UP,
    lift=None,
):
    """Samples a..b (``span``) of one stroke of plan ``pl``: for each of its movements, come
    down, write with the given press and sideways placement per body sample (the press eased at
    the entry and at sharp turns, the base leading the ink by the response's lag), lift off
    (``_enter_and_leave``), and turn on the tip between them (``_turn_on_the_tip``). ``brush``
    is (hover, hair length, step in mm, the brush's scale: ``brush_size``); ``ends``
    (movements, 2): how far each movement's start and end are carried on along its way out
    (``_ends_moved``; practice's reach correction);
    ``run_up``: the entries' (``_enter_and_leave``); ``lift`` (mm per body sample, or None):
    taken off the press as it is finally shaped (practice's ``_lifted``: a hook's root).
    Returns the body samples."""
    a, b = span
    hair = brush[1]
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    normal = np.stack([-pl.tangent[:, 1], pl.tangent[:, 0]], axis=1)
    j0 = 0
    runs = _movements(body)
    hook = _is_hook(pl, runs)
    flick = _flicks(pl, runs, hook)
    at, heights, dun = None, [], []  # the base's height at the corner the movement begins after
    heel = 0.0  # the press a hook's heel keeps (``_heel``)
    width_at = _width_at(response)  # the band a press lays (a point's let-go paces by it)
    for r, run in enumerate(runs):
        j1 = j0 + len(run)
        touch = 1.0 if hook[r] else ZHE_TOUCH if r else ENTRY_TOUCH  # a hook sets off pressed
        p = press[j0:j1] * _entry_ramp(pl.target[run], pl.width[run], touch)
        if flick[r]:  # the hook flicks out of the heel, letting go to its point
            fall = _fall(_way_in(pl.target[runs[r - 1]]), pl.target[run[-1]] - pl.target[run[0]])
            p = _flicked(p, heel, pl.target[run], pl.width[run], fall)
        elif hook[r]:  # the hook gathers the hair to its point as it flicks out
            p = p * _gathered(len(run))
        if r < len(runs) - 1 and flick[r + 1]:  # into a hook's heel, pressed no deeper
            p = _into_the_heel(p, pl.target[run], pl.width[run])
        path = pl.target[run]
        if len(runs) == 1 and is_dot(path, pl.width[run]):  # pressed into its heel
            path, p = _heel_held(path, p, pl.width[run])
        if ends is not None:
            path = _ends_moved(path, pl.tangent[run], pl.width[run], ends[r])
        corner = r < len(runs) - 1  # the base stops on a corner's foot (a hook's, a 竖折's);
        # into a 折's shoulder it goes on into the 顿 (``_turn_on_the_tip``)
        into_zhe = corner and not hook[r + 1] and _onto_the_dun(pl, run, runs[r + 1])
        lag = response.lag_for(p)  # a flicked hook's hair stays bent from the heel (``_bent``)
        lag = _bent(lag) if flick[r] else lag
        samples[run, :2] = _lead_along(path, lag, corner and not into_zhe, into_zhe)
        placed = side[j0:j1]
        if r == 0:  # the head; a leg sets off from the corner (a hook pressed from its foot)
            placed = _entry_side(placed, pl.target[run], pl.width[run])
        samples[run, :2] += placed[:, None] * normal[run]
        samples[run, 2] = hair - (p if lift is None else np.maximum(p - lift[j0:j1], 0.0))
        nxt = None
        if r < len(runs) - 1:  # into a corner: a 折 lifts slightly, a hook's foot stays pressed
            keep = HOOK_KEEP * p[-1] if hook[r + 1] else 0.0
            heel = _heel(p, press[j1]) if flick[r + 1] else keep
            nxt = hair - (heel if hook[r + 1] else ZHE_KEEP * p[-1])
        last = len(runs) == 1 and _lets_go(pl.target[run], pl.width[run], 1)  # a 撇, a 提
        ease = POINT_EASE if last else 1.0
        _enter_and_leave(samples, pl, run, brush, (at, nxt), run_up, width_at, ease)
        if nxt is not None:
            heights.append(nxt)
            dun.append(into_zhe)
        at = nxt
        j0 = j1
    _turn_on_the_tip(samples, pl, span, heights, dun)
    samples[a:b] = quantise(samples[a:b])  # as the saved recording will hold them
    return body
