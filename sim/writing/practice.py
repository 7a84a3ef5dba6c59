# SPDX-License-Identifier: GPL-3.0-or-later
"""Practice passes (Sec. 7.2, as a student of MiaoHong): a stroke written, the band it left
read across its median (``measure_band``) against the outline's width, the press and the
sideways placement corrected, the stroke taken back and written again; the pass that best fills
the stroke's own outline stays."""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..core import exact
from ..engine.simulation import Simulation
from .feet import _along
from .hook_lift import _hooks, _lifted, _root_unread, _spill
from .planner import (
    LIFTING,
    WRITING,
    Plan,
    _flicks,
    _is_hook,
    _movements,
    _smooth,
)
from .response import Response, _coverage, _slope
from .zones import entry_zone, point_zone, rising_heads, shoulder_zone


class Pass(NamedTuple):
    """One practice pass of a stroke: how far its ink is from the outline (lower is better),
    the press, sideways placement and end moves (``_reach_moves``) it was written with, its
    number, the simulation as the pass left it (a snapshot; None for a pass the simulation is
    still at), and the press its hooks' roots were lifted by (``_lifted``)."""

    error: float
    press: np.ndarray
    side: np.ndarray
    moves: np.ndarray
    number: int
    state: dict | None
    lift: np.ndarray | None = None


def _probes(sim: Simulation, points, tangents, reach_mm: float):
    """The paper pixels across the way of travel at each of ``points`` (mm), out to
    ``reach_mm`` on either side: (rows, cols), each (n, 2k + 1), the point in the middle."""
    ppm = sim.paper.ppm
    normal = np.stack([-tangents[:, 1], tangents[:, 0]], axis=1)
    k = max(int(reach_mm * ppm), 1)
    off = np.arange(-k, k + 1) / ppm
    pts = points[:, None, :] + off[None, :, None] * normal[:, None, :]
    cols = np.clip((pts[..., 0] * ppm).astype(int), 0, sim.paper.W - 1)
    rows = np.clip((pts[..., 1] * ppm).astype(int), 0, sim.paper.H - 1)
    return rows, cols


def measure_band(ppm: float, cov, old=None):
    """Across the way of travel at each point, from the ink coverage (above half) ``cov`` read
    at its ``_probes``: the width (mm) of the ink band nearest the point, the offset (mm, along
    the left normal) of its centre from the point, and whether the reading is the brush's own
    there: ink that was on the paper before the brush came to the point (``old``, at the same
    pixels) makes up less than a third of the band."""
    old = np.zeros_like(cov) if old is None else old
    k = cov.shape[1] // 2
    width = np.zeros(len(cov))
    centre = np.zeros(len(cov))
    valid = np.zeros(len(cov), dtype=bool)
    for j in range(len(cov)):
        c = cov[j]
        if not c.any():
            valid[j] = True  # no ink near: a real reading of width zero
            continue
        edges = np.diff(np.concatenate([[0], c.astype(np.int8), [0]]))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        mid = (starts + ends - 1) / 2.0
        dist = np.where((starts <= k) & (k < ends), 0.0, np.abs(mid - k))
        r = int(np.argmin(dist))
        a, b = starts[r], ends[r]
        width[j] = (b - a) / ppm
        centre[j] = (mid[r] - k) / ppm
        valid[j] = np.count_nonzero(old[j, a:b]) < (b - a) / 3.0
    return width, centre, valid


@dataclass
class _Window:
    rows: slice  # paper rows (bottom first) of the window
    cols: slice
    inside: np.ndarray  # (h, w) the stroke's outline


def _stroke_masks(char: dict, H: int, W: int) -> list[_Window]:
    """Every stroke's filled outline on the paper grid (the sheet is the em box), as a window
    around it."""
    from .outline import fill, stroke_polygons, to_image

    out = []
    for polys in stroke_polygons(char):
        img = [to_image(p, H) for p in polys]  # top-first pixel coordinates, H x H em box
        m = fill(img, H)[::-1]  # bottom row first, as the paper
        ys, xs = np.nonzero(m)
        if ys.size == 0:
            ys, xs = np.array([0]), np.array([0])
        r0, r1 = max(ys.min() - 2, 0), min(ys.max() + 3, H)
        c0, c1 = max(xs.min() - 2, 0), min(xs.max() + 3, W)
        out.append(_Window(slice(r0, r1), slice(c0, c1), m[r0:r1, c0:c1]))
    return out


RECORD_EVERY = 4  # samples between the coverage records of a practice pass
HOLD_EVERY = 8  # samples (at least) between the holds a later pass of a stroke can begin from;
# further on, as far apart as the last hold is from the stroke's start (a correction mostly
# changes a stroke from its first body sample: a few holds there, a held tile costs memory)
SMALL_GAIN = 0.01  # from pass SMALL_GAIN_FROM (0 the first) on, a pass that brings the stroke
SMALL_GAIN_FROM = 2  # less than this much nearer its outline (IoU) than the best ends practice
# (an approximation, issue 28; measured on the 9 held-out characters at 512 px: mean IoU
# 0.9207 -> 0.9184 for about 0.8x the CPU time; ending it from the second pass on, or on
# filling 0.95 of the outline, or after three passes, cost 0.002-0.0045 for 0.75-0.83x). Not
# when imitating a picture (``exact_ends``): its passes are measured on its own (imitate.PASSES)
PRACTICE_GAIN = 0.45  # share of a pass's width error corrected for the next (measured best)
PRACTICE_SIDE_GAIN = 0.8  # share of the band's sideways offset corrected (issue 16: measured)


def _movement_ends(phase, body) -> np.ndarray:
    """For each body sample, the first sample after its movement has lifted off."""
    runs = _movements(body)
    ends = []
    for run in runs:
        e = run[-1] + 1
        while e < len(phase) and phase[e] == LIFTING:
            e += 1
        ends.append(np.full(len(run), e))
    return np.concatenate(ends)


class _Reading(NamedTuple):
    """When a stroke's band is read: the reading times (samples), and for every body point the
    time of its ``old`` reading (just before the brush's mark reaches it) and of its ``cov``
    reading (once its movement has lifted off), as indices into ``times``."""

    times: np.ndarray
    which: np.ndarray
    done: np.ndarray


def _reading(a, b, body, want, step_mm, pl) -> _Reading:
    """The reading times of samples a..b: every few samples and as each movement lifts off."""
    i = np.arange(a + 1, b)
    lifted = (pl.phase[i - 1] == LIFTING) & (pl.phase[i] != LIFTING)
    times = np.union1d(np.arange(a, b + 1, RECORD_EVERY), np.r_[i[lifted], b])
    # the brush's mark reaches a point about half its width (plus a millimetre) ahead of time
    ahead = np.ceil((want / 2.0 + 1.0) / step_mm).astype(int) + 1
    which = np.clip(np.searchsorted(times, body - ahead, side="right") - 1, 0, len(times) - 1)
    done = np.searchsorted(times, np.minimum(_movement_ends(pl.phase, body), b))
    return _Reading(times, which, done)


def _practise(sim, start, rd: _Reading, probes, band, holds) -> None:
    """Write from sample ``start`` (a reading time the simulation is at) to the stroke's end,
    reading the ink coverage at every body point's ``probes`` (rows, cols) twice: just before
    the brush's mark reached the point (into ``band``'s ``old``) and once the point's movement
    had lifted off (into its ``cov``). So a stroke crossing its own ink, as at a hook, reads
    only the band it is laying down, and the band at a 折's shoulder or a hook's foot is read
    before the next movement lays its ink across the cut. The readings are taken every few
    samples and as each movement lifts off, each at the pixels of the points that need it;
    those before ``start`` are kept (the stroke is the same up to there). At a reading every
    ``HOLD_EVERY`` samples, and further on as far apart as the last hold is from the stroke's
    start, the simulation is held (``holds``: sample -> hold), so that a later pass can begin
    there."""
    rows, cols = probes
    old, cov = band
    todo = np.flatnonzero(rd.times >= start)
    kept, last = {}, start
    for t in rd.times[todo[:-1]]:
        if t - last >= max(HOLD_EVERY, last - rd.times[0]):
            sim.advance(int(t))  # the brush as it is at the hold
            kept[int(t)], last = sim.brush_hold(), t
    sim.advance(int(rd.times[-1]))  # the brush never reads the paper: it runs ahead
    for n in todo:
        t = int(rd.times[n])
        sim.settle(t)  # the paper up to the reading (the same ink as step by step)
        for out, sel in ((old, rd.which == n), (cov, rd.done == n)):
            if sel.any():
                out[sel] = _coverage(sim, rows[sel], cols[sel])
        if t in kept:
            holds[t] = sim.hold(kept[t])


def _correct(response, placed, want, band, ceiling, zones):
    """The next pass's press and sideways placement: where the reading is this stroke's own,
    a share of the width error through the response's slope, and of the band's offset; smoothed
    along the stroke. ``placed``: the press and sideways placement per body sample; ``band``:
    the band's width, centre offset and whether the reading is the stroke's own (``measure_band``);
    ``entering``: the samples of a movement's entry (``entry_zone``), which keep their sideways
    placement: there the band is the landing's head, and following its centre bent it into a
    hooked claw; ``pointing``: the last stretch of a movement that ends in a point
    (``point_zone``), where the press is not raised: the band narrows there as the belly lets
    go, and pressing to widen it left a blunt end; ``shoulder``: held (``shoulder_zone``)."""
    press, side = placed
    got, centre, valid = band
    entering, pointing, shoulder = zones
    slope = _slope(response, press)
    dp = np.where(valid, PRACTICE_GAIN * (want - got) / slope, 0.0)
    dp = np.where(valid & (got == 0) & (want > 0), 0.5, dp)
    dp = np.where(pointing, np.minimum(dp, 0.0), dp)
    press = np.clip(press + _smooth(dp, 5), 0.0, ceiling)
    steady = valid & (got > 0) & ~entering
    side = side - _smooth(np.where(steady, PRACTICE_SIDE_GAIN * centre, 0.0), 5)
    return _held(press, shoulder), _held(side, shoulder)


def _one_flick(pl: Plan, body, placed, first) -> tuple[np.ndarray, np.ndarray]:
    """The press and sideways placement per body sample (``placed``, as ``_correct`` left
    them) with every hook flicked up to a point (``planner._flicks``: a 竖钩, a 横折钩, a 弯钩,
    a 竖弯钩's 乚, a 斜钩; not a picture's 口 read with its bottom as a hook) written as one
    movement: over the hook the press no deeper than where the movement into its foot ended
    (``first``, the first pass's, where it sets off: a stroke of a hook alone) and nowhere
    deepening again (the lightest such press nowhere lighter than practice's: the belly lets go
    through the flick); the placement the
    straight line (in the distance along the hook) nearest the corrected one; and over the last
    width of the movement into the hook's foot, where the base stops and rests on the corner
    (``_lead_along``'s ``stop``), the placement eased to none, as planned. Sec. 7.2's student
    corrects where the band lies sample by sample; across a short hook that narrows and turns
    the band is the flick's triangle, its centre swinging from side to side, and the correction
    followed it: the flick zigzagged (its direction swinging 50-125 degrees a sample, 虎's 乚),
    every zig laying its own crisp hair lines, a cross-hatched broom; the base crept about on
    the foot as it rested; and the hook was pressed again past its root where the band read
    narrow. (Model addition, issue 26 points 1-2: a hook's placement is corrected as a whole.)"""
    press, out = (np.asarray(x, dtype=float).copy() for x in placed)
    runs, moves = _movements(np.arange(len(body)), body), _movements(body)
    for r, hook in enumerate(_flicks(pl, moves, _is_hook(pl, moves))):
        if not hook:
            continue
        run = runs[r]
        settled = np.maximum.accumulate(press[run][::-1])[::-1]  # nowhere lighter than after
        press[run] = np.minimum(settled, press[runs[r - 1][-1]] if r else first[run[0]])
        s = _along(pl.target[body[run]])
        line = np.stack([np.ones_like(s), s], axis=1)
        out[run] = line @ np.linalg.lstsq(line, out[run], rcond=None)[0]
        if r:  # the foot the hook sets off from: the base rests there as planned
            foot = runs[r - 1]
            s = _along(pl.target[body[foot]])
            wide = max(float(pl.width[body[foot]].max()), 1e-6)
            t = np.clip(1.0 - (s[-1] - s) / wide, 0.0, 1.0)
            out[foot] *= 1.0 - t * t * (3.0 - 2.0 * t)
    return press, out


END_GAIN = 0.7  # share of an end's reach error corrected for the next pass
END_MAX = 0.6  # widths an end may be carried on or drawn back in all
END_BACK = 0.5  # widths inside a movement's end its reach is read from
END_LOOK = 1.5  # widths past the end the inks are followed (further: the ink runs on)
END_FAN = np.radians(np.linspace(-60.0, 60.0, 9))  # rays round the way out of an end
JOIN_MAX = END_LOOK  # widths a joining end may be shifted in all: as far as its fan sees a join
# (model addition, issue 26.2: a thin entry lays its ink short of where it is placed)


class _Ends(NamedTuple):
    """Where each movement end's reach is read: the end's (movement, 0 start / 1 end), the
    paper pixels of a fan of rays out of it (rows, cols: (ends, rays, steps)), each step's
    distance along the way out (mm, from the end), how far the stroke's outline reaches there
    (mm, ``_extent``) and the planned width there (mm: an end moves at most ``END_MAX`` of it,
    a joining one ``JOIN_MAX``)."""

    which: np.ndarray
    rows: np.ndarray
    cols: np.ndarray
    along: np.ndarray
    want: np.ndarray
    width: np.ndarray
    outline: np.ndarray  # (ends, rays, steps): the character's outlines there (``whole``)
    dirs: np.ndarray  # (ends, rays, 2): each ray's direction (the middle one the way out)


def _extent(ink: np.ndarray, along: np.ndarray) -> np.ndarray:
    """How far along the way out an end's ink reaches: along each ray of the fan, the ink
    unbroken from the ray's foot (inside the end), its last step's distance along the way out;
    the farthest of the fan (``along`` is (ends, rays, steps); nothing where the foot is paper:
    -inf)."""
    run = np.cumprod(ink, axis=-1).astype(bool)
    far = np.where(run, along, -np.inf).max(axis=-1)
    return far.max(axis=-1)


def _end_probes(sim, pl: Plan, body, own: _Window, whole: np.ndarray) -> _Ends:
    """The fans of rays out of the free ends of a stroke (the start of its first movement,
    the end of its last; ``body``'s runs) and the outline's reach along them: from
    ``END_BACK`` widths inside the end to ``END_LOOK`` widths past it, one pixel a step. Where
    the character's ink (``whole``: all the outlines, on the paper) runs on past the end into
    another stroke, the end touches it: its outline is taken to run on too (the end is carried
    on to it if the ink falls short, never drawn back from it)."""
    ppm = sim.paper.ppm
    which, rows, cols, along, width, dirs = [], [], [], [], [], []
    runs = _movements(body)
    for m, run in enumerate(runs):
        for e, (i, sign) in enumerate(((run[0], -1.0), (run[-1], 1.0))):
            if (m, e) not in ((0, 0), (len(runs) - 1, 1)):
                continue  # a sharp corner: its shape is the foot's and the turn's
            w = max(float(pl.width[i]), 1.0 / ppm)
            out = sign * pl.tangent[i]
            d = np.arange(-END_BACK * w, END_LOOK * w + 1e-9, 1.0 / ppm)
            sn, c = exact.sin_cos(END_FAN)
            rays = np.stack([c * out[0] - sn * out[1], sn * out[0] + c * out[1]], axis=1)
            pts = pl.target[i] + d[None, :, None] * rays[:, None, :]
            cols.append(np.clip((pts[..., 0] * ppm).astype(int), 0, sim.paper.W - 1))
            rows.append(np.clip((pts[..., 1] * ppm).astype(int), 0, sim.paper.H - 1))
            along.append(d[None, :] * c[:, None])
            dirs.append(rays)
            which.append((m, e))
            width.append(w)
    k = max(len(r[0]) for r in rows)
    rows, cols, along = (
        np.stack([np.pad(x, ((0, 0), (0, k - x.shape[1])), "edge") for x in a])
        for a in (rows, cols, along)
    )  # the fans of the wider ends are longer: the others padded with their last step
    r, c = rows - own.rows.start, cols - own.cols.start
    h, w = own.inside.shape
    ok = (r >= 0) & (r < h) & (c >= 0) & (c < w)
    inside = np.where(ok, own.inside[np.clip(r, 0, h - 1), np.clip(c, 0, w - 1)], False)
    inside |= _coverage(sim, rows, cols)  # ink already there: an end running into a stroke
    want = _extent(inside, along)
    look = along.max(axis=(1, 2))
    outline = whole[rows, cols]
    touches = _extent(outline, along) >= look - 1e-9
    want = np.where(touches & np.isfinite(want), look, want)
    return _Ends(np.array(which), rows, cols, along, want, np.array(width), outline, np.array(dirs))


def _reach_error(sim, ends: _Ends, before) -> np.ndarray:
    """How much farther (mm, per end) the outline (with the ink already on the paper) reaches
    than the ink does (< 0: the ink runs on past it), where the reading is the stroke's own
    (its foot was paper before the stroke) and not an end running on into ink in both; 0
    elsewhere."""
    got = _extent(_coverage(sim, ends.rows, ends.cols), ends.along)
    look = ends.along.max(axis=(1, 2))
    own = ~before[:, :, 0].any(axis=1) & np.isfinite(ends.want) & np.isfinite(got)
    runs_on = (ends.want >= look - 1e-9) & (got >= look - 1e-9)
    err = np.zeros(len(got))
    use = own & ~runs_on
    err[use] = ends.want[use] - got[use]
    return err


def _join_error(sim, ends: _Ends, before) -> tuple[np.ndarray, np.ndarray]:
    """How far (mm, per end) the stroke's ink falls short of joining a stroke already written
    that its outline runs into, and which way (a unit vector per end, the ray of the least
    gap) (model addition, issue 26: strokes that touch in the outline touch in the ink); 0
    where it joins, where no such stroke is, or at a join with a stroke written later (that
    stroke's to make). Along each ray of an end's fan whose foot is not in that stroke's ink:
    the outline unbroken from the foot (``_Ends.outline``) reaching ink that was there
    ``before`` the stroke is a join, ``first`` that far out; the stroke's own new ink nearest it
    on the ray (the foot where there is none) falls short of it by the distance between them,
    the gap, least over the rays: a pixel's worth where they only touch (a join one pixel wide
    that drying and wicking can open again), so the end is carried into the stroke it joins.
    Only the joins are practised so outside ``exact_ends``: every other end is written as
    planned."""
    fresh = ~before[..., :1]
    run = np.cumprod(ends.outline, axis=-1).astype(bool) & fresh
    first = np.where(run & before & (ends.along > 0.0), ends.along, np.inf).min(axis=-1)
    new = _coverage(sim, ends.rows, ends.cols) & ~before & (ends.along < first[..., None])
    near = np.where(new, ends.along, ends.along[..., :1]).max(axis=-1)  # (ends, rays)
    # the distance along the ray itself (``along`` is its projection on the way out)
    cos = np.maximum(np.abs(exact.cos(END_FAN)), 1e-6)
    gap = np.where(np.isfinite(first), (first - near) / cos, np.inf)  # touching: one pixel
    ray = gap.argmin(axis=-1)
    gap = gap.min(axis=-1)
    way = ends.dirs[np.arange(len(ray)), ray]
    return np.where(np.isfinite(gap), np.maximum(gap, 0.0), 0.0), way


def _join_moves(ends: _Ends, gap, way, moves) -> np.ndarray:
    """The next pass's end shifts (movements, 2 ends, 2: mm on the paper) for the joins: each
    end shifted on by ``END_GAIN`` of its gap ``gap`` the way ``way`` (``_join_error``: toward
    the stroke it joins, not only along its own way out: a 横 setting off beside a 撇 moves
    onto it), at most ``JOIN_MAX`` of its width in all (as far as the fan sees a join: a thin
    entry's head lays its ink short of where it is placed, more than ``END_MAX`` of its width)."""
    out = moves.copy()
    m, e = ends.which[:, 0], ends.which[:, 1]
    shift = moves[m, e] + END_GAIN * gap[:, None] * way
    size = np.maximum(np.linalg.norm(shift, axis=1), 1e-12)
    out[m, e] = shift * np.minimum(1.0, JOIN_MAX * ends.width / size)[:, None]
    return out


def _reach_moves(ends: _Ends, err, moves) -> np.ndarray:
    """The next pass's end moves (movements, 2; mm): each end carried on (drawn back) by
    ``END_GAIN`` of its reach error ``err`` (``_reach_error``), at most ``END_MAX`` widths in
    all."""
    out = moves.copy()
    m, e = ends.which[:, 0], ends.which[:, 1]
    limit = END_MAX * ends.width
    out[m, e] = np.clip(moves[m, e] + END_GAIN * err, -limit, limit)
    return out


def _held(v, zone) -> np.ndarray:
    """``v`` with each stretch of ``zone`` set to its value at the first sample past it."""
    n = len(v)
    nxt = np.minimum.accumulate(np.where(zone, n, np.arange(n))[::-1])[::-1]
    return np.where(zone & (nxt < n), v[np.minimum(nxt, n - 1)], v)


CORNER_WIDTH = 0.9  # share of the widest band the brush is pressed for into a corner (measured:
# 0.8 is cleaner still but costs texture, 0.748 -> 0.73 on the bundled characters)


def _ceiling(pl: Plan, body, response: Response) -> np.ndarray:
    """The deepest press per body sample: the deepest measured, but into a sharp corner (the
    last stretch, as long as the movement is wide, of a movement ending at a 折's shoulder or a
    hook's foot) easing to the press that leaves ``CORNER_WIDTH`` of the widest band. The brush
    slows there and lifts on the spot, and a belly pressed to the calibration's limit splays
    and sweeps a grey, fibrous puff round the corner; a calligrapher presses into the turn
    firmly, not to the heel of the hair."""
    p_max = float(response.press_mm[-1])
    at_corner = float(response.press_for(CORNER_WIDTH * response.max_width_mm))
    top = np.full(len(body), p_max)
    runs = _movements(np.arange(len(body)), body)
    for run in runs[:-1]:  # every movement but the stroke's last ends at a corner
        path = pl.target[body[run]]
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        to_end = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
        t = np.clip(1.0 - to_end / max(float(pl.width[body[run]].max()), 1e-6), 0.0, 1.0)
        top[run] = p_max - (p_max - at_corner) * t * t * (3.0 - 2.0 * t)
    return top


LESSON_BINS = 5  # stretches of a stroke's body (equal shares of its samples) a lesson is kept for
LESSON_MIN = 10  # body points a stretch must have been taught on before its lesson is used


class Lesson:
    """What practice has taught the writer about the brush in the character so far: at each
    stretch of a stroke's body, how much wider than the plan's width the calibrated response
    says the press was that practice settled on (its best pass), as ratios over the body points
    of the strokes practised so far. A student who found the brush writing narrow on the first
    strokes presses harder on the first pass of the next (model addition, issue 28: the first
    pass's band ran 3-5 % narrow over the back half of a body on the held-out characters; with
    the lesson 2-4 %; held-out IoU with 3 passes 0.9256 -> 0.9267, within the run-to-run
    spread; not when imitating a picture, where it measured 0.8411 -> 0.8385)."""

    def __init__(self):
        self.ratios = [[] for _ in range(LESSON_BINS)]

    @staticmethod
    def _bins(n: int) -> np.ndarray:
        return np.minimum((np.arange(n) * LESSON_BINS) // max(n, 1), LESSON_BINS - 1)

    def widen(self, want, steady) -> np.ndarray:
        """The width to plan the first pass's press for: ``want`` times the median ratio of
        its stretch, where the body is ``steady`` and the stretch has been taught."""
        f = np.ones(len(want))
        bins = self._bins(len(want))
        for k, r in enumerate(self.ratios):
            if sum(len(x) for x in r) >= LESSON_MIN:
                f[bins == k] = np.median(np.concatenate(r))
        return np.where(steady, want * f, want)

    def learn(self, response, press, want, use) -> None:
        """Keep the ratios of the width the response gives the settled ``press`` (its
        envelope) to ``want``, where ``use``."""
        w_env = np.maximum.accumulate(response.width_mm)
        said = np.interp(press, response.press_mm, w_env)
        use = use & (want > 0) & (press > response.press_mm[0])
        bins = self._bins(len(press))
        for k in range(LESSON_BINS):
            sel = use & (bins == k)
            if sel.any():
                self.ratios[k].append(said[sel] / want[sel])


def _rewind(sim, holds: dict, first: int) -> int:
    """Back to the last of ``holds`` (sample -> hold) at or before sample ``first``, the later
    holds let go and that one held again; returns its sample."""
    start = max(t for t in holds if t <= first)
    for t in sorted(holds, reverse=True):
        if t > start:
            sim.let_go(holds.pop(t))
    sim.take_back(holds[start])
    holds[start] = sim.hold()
    return start


def _practise_stroke(sim, a, b, passes, fill, own, ctx, whole=None, exact=True) -> None:
    """Write samples a..b (one stroke) with ``fill(a, b, press, side)``; with passes > 1,
    practise it: write, read the band, correct, take it back and write it again; the pass that
    best fills the stroke's own outline ``own`` stays: the simulation goes back to where that
    pass left it (a snapshot taken then), the recording gets its samples again. A later pass is
    not written again from the stroke's start but from the last hold (``_practise``) before the
    first sample its correction changes: up to there the stroke, and so the simulation, are the
    same bit for bit. Practice ends after ``passes`` passes, or sooner when a pass from
    ``SMALL_GAIN_FROM`` on brings the stroke less than ``SMALL_GAIN`` nearer its outline than
    the best before it: the student stops once practice no longer pays (an approximation: the
    passes left might still have found a better one; not with ``exact``). With ``whole`` (the
    whole character's outlines on the paper) each pass also reads how far the ink of the
    stroke's free ends reaches against the outline (``_reach_error``), the next pass carries
    them on or draws them back (``_reach_moves``), and the pass that stays is the one whose IoU
    less its ends' error over the stroke's length is best: a stroke 5 % too long is as wrong as
    one 5 % short of its area. Without ``exact`` (stroke data; the writer's ``exact_ends``,
    set when imitating a picture, is ``exact``) only the joins are practised so: an end whose
    outline runs on into a stroke already written and whose ink falls short of it is carried
    on (``_join_error``), the rest left as planned, and a flicked hook's root is lifted off
    the lobe it spills past the outline (``_lifted``). ``ctx``'s ``lesson`` (a ``Lesson``, or
    None) plans the first pass's press and learns from the press practice settled on."""
    pl, response, step_mm, reach, lesson = ctx
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    want = pl.width[body]
    ceiling = _ceiling(pl, body, response)
    side = np.zeros(len(body))
    if passes == 1:
        fill(a, b, np.minimum(response.press_for(want), ceiling), side)
        sim.run(until=b)
        return
    held = np.zeros(len(body), dtype=bool) if exact else shoulder_zone(pl, body)  # a picture's
    # band below its shoulder is its own (为's, with stroke data's 顿: box IoU 0.882 -> 0.869 held)
    zones = (entry_zone(pl, body), point_zone(pl, body), held)
    steady = ~zones[0] & ~zones[1] & ~zones[2]
    taught = want if lesson is None else lesson.widen(want, steady)
    press = np.minimum(response.press_for(taught), ceiling)
    inked_before = _coverage(sim, own.rows, own.cols)
    hooks = None if whole is None or exact else _hooks(sim, pl, body)  # their spill
    probes = _probes(sim, pl.target[body], pl.tangent[body], reach)
    rd = _reading(a, b, body, want, step_mm, pl)
    band = (np.zeros(probes[0].shape, dtype=bool), np.zeros(probes[0].shape, dtype=bool))
    # the ends' moves: along the way out of each end (mm; exact ends), or shifts on the paper
    # (mm, x and y; the joins)
    moves = np.zeros((len(_movements(body)), 2) if exact else (len(_movements(body)), 2, 2))
    if whole is not None:
        ends = _end_probes(sim, pl, body, own, whole)
        ends_before = _coverage(sim, ends.rows, ends.cols)
        length = max(float(np.linalg.norm(np.diff(pl.target[body], axis=0), axis=1).sum()), 1e-6)
    holds = {a: sim.hold()}  # sample -> the simulation held there (the tiles changed since)
    best, start, first = None, a, press.copy()
    lift = np.zeros(len(body))  # a hook's root lifted off its spill (``_lifted``)
    fill(a, b, press, side, moves, lift)
    for k in range(passes):
        if start is not None:  # (None: the pass is the last one again, sample for sample)
            _practise(sim, start, rd, probes, band, holds)
        got, centre, valid = measure_band(sim.paper.ppm, band[1], band[0])
        # the pass that best fills the stroke's own outline stays (new ink against it)
        new = _coverage(sim, own.rows, own.cols) & ~inked_before
        inter = np.count_nonzero(new & own.inside)
        err = -inter / max(np.count_nonzero(new | own.inside), 1)
        if whole is not None:  # and the stroke as long as its outline: the ends' reach error
            if exact:  # against the stroke's length
                reach_err = _reach_error(sim, ends, ends_before)
            else:
                reach_err, way = _join_error(sim, ends, ends_before)
            err += float(np.abs(reach_err).sum()) / length
        gain = np.inf if best is None else best.error - err  # how much nearer than the best
        if best is None or err < best.error:
            best = Pass(err, press.copy(), side.copy(), moves.copy(), k, None, lift.copy())
        elif start is None and best.number == k - 1:
            best = best._replace(number=k)  # the same pass: the simulation is where it left off
        if k == passes - 1:
            break
        if not exact and k >= SMALL_GAIN_FROM and gain < SMALL_GAIN:  # no longer pays
            break
        if whole is not None and exact:
            moves = _reach_moves(ends, reach_err, moves)
        elif whole is not None:
            moves = _join_moves(ends, reach_err, way, moves)
        if hooks is not None:  # stroke data's hooks (a picture's: measured, 24 imitations
            # 0.8530 -> 0.8498, 雨's 冂 0.79)
            spill = _spill(sim, pl, body, whole, hooks)
            lift = _lifted(response, lift, spill, press, _root_unread(hooks, valid))
        press, side = _correct(response, (press, side), want, (got, centre, valid), ceiling, zones)
        press, side = _one_flick(pl, body, (press, side), first)
        press = rising_heads(press, want, _movements(np.arange(len(body)), body))
        was = sim.rec.samples[a:b].copy()
        fill(a, b, press, side, moves, lift)
        changed = np.flatnonzero(np.any(sim.rec.samples[a:b] != was, axis=1))
        if changed.size == 0:
            start = None  # the next pass is this one again: nothing to write
            continue
        if best.number == k:  # the best so far: kept before it is taken back
            best = best._replace(state=sim.snapshot())
        start = _rewind(sim, holds, a + int(changed[0]))
    for h in holds.values():
        sim.let_go(h)
    if lesson is not None:
        lesson.learn(response, best.press, want, steady & (best.press < ceiling))
    if best.number != k:  # the last pass was not the best: back to where the best left off
        sim.restore(best.state)
        fill(a, b, best.press, best.side, best.moves, best.lift)
