# SPDX-License-Identifier: GPL-3.0-or-later
"""What the paper (Sec. 6) takes of a step's marks that does not depend on the paper: where their
pixels lie in the sheet and in the step's window, the liquid the hair offers each (Eq. 24's
wet_tau, as the sheet's grain lets it take it), the colour it can hold (Eq. 26-27 with the
model change of ``FULL_WET`` below) and the order in which a pixel that several marks
cover takes them. Worked out for many steps in one pass of numpy calls (``lay_out``), before the
paper takes them one step after the other (``Paper.take``): the per-sample cost of small marks
is the numpy calls', not the pixels' (issue 28). The arithmetic is the same, element by element,
as a step at a time: the images are byte-identical."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core import exact
from ..core.frames import per_pixel
from .grain import paper_grain

# Model change to Eq. 26 (not in the paper). The paper moves a pixel's colour toward the brush's
# by Cr = wet' (the pixel's wetness of Eq. 24) per time slice: a pixel under the hair for a few
# slices takes the ink's full colour whatever the load (every stroke as black as the ink), and
# how many slices it gets depends on the sample rate and on where the step's mark happened to
# end (bands across the stroke, a step apart, where the hair passes only a few times). Here a
# pixel takes, at once, the colour the liquid offered to it can hold - the ink's colour times
# 1 - exp(-offer / FULL_WET): more liquid, more pigment, saturating - and keeps the darker of
# that and what it had (pigment laid is not taken back). The offer is the hair bundle's
# (``sim.brush.bristles.lay``: Eq. 23's wetness times the bundle's share of the ink, more where
# the hair lingers): a brush just dipped (offer about 1) lays 98% of the ink's colour, a brush
# run low (offer 0.3) about 70% of it, a pause or a pressed turn pools darker, and Eq. 27's
# Cr = 0 (the bundle's gap) leaves the pixel as it is. Eq. 24 still gives the pixel's wetness
# (drying, and saturation, Eq. 25). A diluted ink (``InkSpec.pigment`` below 1: light ink,
# 淡墨) carries that much less pigment in the same liquid: a pixel needs FULL_WET / pigment of it
# to take the ink's full colour, so a pale stroke is paler where the hair passes quickly and
# darker where it lingers or the brush was just dipped, as diluted ink is, not one flat grey.
FULL_WET = 0.25

_RGB = np.dtype((np.void, 12))  # a pixel's three float32 ink densities as one item


class Laying(NamedTuple):
    """One step's marks as the paper will take them (``lay_out``, ``Paper.take``): the
    window; the pixels the marks cover, each once, by their index in it (``loc``) and in the
    paper (``full``); the liquid offered at each visit (Eq. 24's wet_tau), round by round (a
    pixel's k-th visit in round k, ``wet_tau[bounds[k]:bounds[k + 1]]``: the pixels are
    ordered by their visits, most first, so round k's are the first ``bounds[k + 1] -
    bounds[k]`` of ``loc``); the colour each can hold (Eq. 26-27) at its first visit
    (``lay``) and the darkest of its later visits' (``over``, for the pixels visited more
    than once; None: none is); which pixels of the window a mark covers; and the step's
    darkest colour and middle (``Paper._follow``; None without a halo)."""

    window: tuple
    loc: np.ndarray
    full: np.ndarray
    wet_tau: np.ndarray
    lay: np.ndarray
    bounds: list
    dried: np.ndarray
    follow: tuple | None
    over: np.ndarray | None = None


def lay_out(paper, steps, grain_depth: float, full_wet: float) -> list:
    """What the paper (``paper``, a ``sim.paper.paper.Paper``) takes of each step's marks
    (``steps``: a list of steps' marks) that does not depend on the paper: where their pixels
    lie, the liquid each is offered and the colour it can hold (Eq. 26-27), and the order in
    which a pixel several marks cover takes them - for many steps in one pass of numpy calls
    (issue 28). ``Paper.take`` puts each down, in order: the same arithmetic, element by
    element, as step by step. A ``Laying`` a step, None for a step whose marks have no pixels.
    ``grain_depth``: the paper's GRAIN_DEPTH times its fibre; ``full_wet``: the liquid that
    gives a pixel the ink's full colour (FULL_WET over the ink's pigment)."""
    steps = [[mk for mk in marks if mk.rows.size] for marks in steps]
    live = [mk for marks in steps for mk in marks]
    if not live:
        return [None] * len(steps)
    n = np.array([mk.rows.size for mk in live])
    rows = np.concatenate([mk.rows for mk in live]) + np.repeat([mk.iy0 for mk in live], n)
    cols = np.concatenate([mk.cols for mk in live]) + np.repeat([mk.ix0 for mk in live], n)
    full = rows * paper.W + cols  # index in the paper
    wet_tau = np.concatenate([mk.wet for mk in live]).astype(np.float32, copy=False)
    col = np.concatenate([mk.col for mk in live]).astype(np.float32, copy=False)
    skip = np.concatenate(
        [mk.skip if mk.skip is not None else np.zeros(mk.rows.size, bool) for mk in live]
    )
    # the liquid the hair offers, as the sheet's grain lets it take it (model addition,
    # paper_grain): some pixels take a little more of it, some a little less
    grain = paper_grain(full, paper.grain_seed) - 0.5
    offer = wet_tau * (1.0 - grain_depth * grain).astype(np.float32)
    # Eq. 26-27 (model change, see FULL_WET): where the hair bundle lays ink (Cr not 0)
    # the pixel takes the colour the liquid offered to it can hold; a hair running dry lays
    # its ink on fewer lines, each as rich as a wetter hair's (``rich``, sim.brush.bristles)
    if any(mk.rich is not None for mk in live):
        rich = np.concatenate(
            [mk.rich if mk.rich is not None else np.ones(mk.rows.size, np.float32) for mk in live]
        )
        offer = offer * rich
    held = -exact.expm1(-offer / full_wet)
    held = np.where(skip, 0.0, held).astype(np.float32)
    lay = per_pixel(col, held)
    out, at, m = [], 0, 0
    for marks in steps:
        if not marks:
            out.append(None)
            continue
        size = int(n[m : m + len(marks)].sum())
        part = slice(at, at + size)
        out.append(
            _laying(
                paper,
                marks,
                (rows[part], cols[part]),
                full[part],
                wet_tau[part],
                (col[part], lay[part]),
            )
        )
        at, m = at + size, m + len(marks)
    return out


def _laying(paper, marks, pixels, full, wet_tau, colours) -> Laying:
    """One step's ``Laying`` (``lay_out``) on ``paper``: its ``marks`` (with pixels), their pixels'
    (rows, columns) and ``full`` index in the paper, the liquid offered, and (colours, the
    colours the pixels can hold), all in the marks' order."""
    y0, y1, x0, x1 = window = paper._window(marks)
    ww = x1 - x0
    rows, cols = pixels
    loc = (rows - y0) * ww + (cols - x0)  # index in the window
    # a pixel that several marks cover takes them one after the other (its k-th visit in
    # round k), exactly as in sequence
    cut = np.cumsum([mk.rows.size for mk in marks])[:-1]
    rank, visits = _visit_ranks(np.split(loc, cut), (y1 - y0) * ww)
    col, lay = colours
    follow = None
    if paper.halo_px:  # the stroke's darkest colour and the marks' middle (_follow)
        row_sum, col_sum = _pixel_sums(marks)
        n = wet_tau.size
        here = (
            float(np.float64(row_sum) / n),  # as the pixels' rows' mean() gives it
            float(np.float64(col_sum) / n),
            float(wet_tau.mean()),
            float(np.sqrt(n / np.pi)),
        )
        follow = (tuple(float(np.maximum.reduce(col[:, c])) for c in range(3)), here)
    if not rank.max():  # each pixel visited once: one round, in the marks' order
        return Laying(window, loc, full, wet_tau, lay, [0, loc.size], visits > 0, follow)
    loc, full, wet_tau, lay, bounds, over = _by_rounds(loc, full, wet_tau, lay, rank, visits)
    return Laying(window, loc, full, wet_tau, lay, bounds, visits > 0, follow, over)


def _by_rounds(loc, full, wet_tau, lay, rank, visits) -> tuple:
    """A step's mark pixels (window ``loc``, paper ``full``, wet_tau, ``lay``: in the marks'
    order, with their visit ``rank``) as ``Laying`` takes them round by round: the pixels
    each once, most visited first, (loc, full, wet_tau of every round, the first visit's lay,
    bounds, over). Taking the visits in turn a pixel keeps the darkest colour it is offered
    (Eq. 26-27, FULL_WET), so its later visits' colours are one: their maximum, which
    ``Paper.take`` lays after the first visit's (the same numbers: a maximum is one of its
    arguments, in any order, for densities, which are never NaN nor -0); its wetness (Eq.
    24) still takes each visit in turn, as the first ``bounds[k + 1] - bounds[k]`` pixels of
    round k (issue 28)."""
    counts = np.bincount(rank)  # pixels visited more than k times, k = 0, 1, ...
    bounds = np.r_[0, np.cumsum(counts)]
    first = rank == 0
    once = loc[first]
    order = np.argsort(counts.size - visits[once], kind="stable")  # most visits first
    once = once[order]
    pos = np.empty(visits.size, dtype=np.intp)
    np.put(pos, once, np.arange(order.size))
    # where each visit goes: its round, then its pixel's place (np.put: the same items, faster
    # than an assignment through an index array)
    at = np.take(bounds, rank) + np.take(pos, loc)
    tau = np.empty_like(wet_tau)
    np.put(tau, at, wet_tau)
    laid = np.empty(at.size, dtype=_RGB)
    np.put(laid, at, lay.reshape(-1).view(_RGB))
    laid = laid.view(np.float32).reshape(-1, 3)
    over = laid[bounds[1] : bounds[2]].copy()
    for k in range(2, counts.size):  # the later visits' darkest, round by round
        head = over[: counts[k]]
        np.maximum(head, laid[bounds[k] : bounds[k + 1]], out=head)
    return once, full[first][order], tau, laid[: bounds[1]], bounds.tolist(), over


def _pixel_sums(marks) -> tuple[int, int]:
    """The sums of the paper rows and of the paper columns of every pixel of the marks, as
    exact integers (their mean is the float64 mean of the pixels' rows, bit for bit: every
    partial sum of integers below 2**53 is exact), a mark at a time (issue 28)."""
    rows = sum(int(mk.rows.sum(dtype=np.int64)) + mk.iy0 * mk.rows.size for mk in marks)
    cols = sum(int(mk.cols.sum(dtype=np.int64)) + mk.ix0 * mk.cols.size for mk in marks)
    return rows, cols


def _visit_ranks(locs, size: int) -> tuple[np.ndarray, np.ndarray]:
    """A pixel that several marks cover takes them in the marks' order: the rank of each mark
    pixel (its pixel's k-th visit is made in round k, visits counted mark by mark) and the
    visits of every pixel of the window (``size`` of them)."""
    visits = np.zeros(size, dtype=np.uint16)
    rank = np.empty(sum(li.size for li in locs), dtype=np.uint16)
    at = 0
    for li in locs:
        before = np.take(visits, li)
        rank[at : at + li.size] = before
        np.put(visits, li, before + 1)  # a mark covers each of its pixels once
        at += li.size
    return rank, visits
