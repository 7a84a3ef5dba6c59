# SPDX-License-Identifier: GPL-3.0-or-later
"""Capillary wicking (a model addition, see WICK_MM): the sheet draws liquid and pigment a
little way out of a wet stroke's edge along its fibres, a window of the paper at a time
(``Paper.take`` calls ``_wick`` on each step's window)."""

from __future__ import annotations

import numpy as np

from ..core import exact
from .laying import FULL_WET
from .lift import same_colours

# Model addition (not in the paper): capillary wicking. Eq. 25 moves only a saturated pixel's
# excess; below saturation the paper still draws liquid from a wet pixel into its drier neighbours
# along its fibres, and the liquid carries pigment with it: a real stroke's edge is not the hair's
# cut drawn with a ruler but a front the sheet's fibres pulled a little way out, further along a
# fibre than between fibres. Each pass moves, between every two neighbouring pixels
# (four-neighbour), a rate (at most WICK_RATE) times their difference in wetness times how well
# both draw (``sheet_draw``: the sheet's fibres and pulp, in mm, from its seed, as uneven as the
# paper's fibre); a pixel that takes liquid takes the pigment it carries, laid over what it holds:
# 1 - exp(-taken / FULL_WET) of the givers' colour, times WICK_PIGMENT (the pigment lags the
# water), but never past the colour of the darkest pixel it came from (``_wick_lay``, issue 26:
# ink drawn into ink still wet with the same ink merges, no step, no line at a mark's edge inside
# a stroke), so the fringe darkens as the liquid keeps coming and never past the stroke itself,
# and a dry-brush gap inside a stroke, as wet as its neighbours, takes almost none. The sheet's
# reach, WICK_MM / capacity**2 mm a step while it is wet (a paper that holds little passes liquid
# on further: sized xuan 0.18 mm, raw xuan 0.6 mm, smooth paper none), is the same in mm at any
# resolution: the passes and their rate give the spreading (rate times passes) of that reach in
# pixels squared, up to WICK_MAX_PASSES passes at WICK_RATE (beyond, above about 5.5 px a mm on
# sized xuan or on a very absorbent sheet, it reaches less in mm: a pass a step is what it costs).
WICK_MM = 0.18
WICK_RATE = 0.24  # <= 1/4 keeps every pass stable (one axis at a time, draw <= 1)
WICK_PIGMENT = 0.8
WICK_MAX_PASSES = 1  # a pass costs about as much as the rest of a step's paper work


def wick_steps(capacity: float, ppm: float) -> tuple[int, float]:
    """Wicking passes per step and their rate for a sheet of this capacity at ``ppm`` pixels a
    mm: the sheet's reach in pixels, squared, shared out over passes of at most WICK_RATE."""
    reach_px = WICK_MM / max(capacity, 1e-9) ** 2 * ppm
    if reach_px < 0.05:
        return 0, 0.0
    spread = WICK_RATE * reach_px * reach_px
    passes = int(min(np.ceil(spread / WICK_RATE), WICK_MAX_PASSES))
    return passes, float(min(spread / passes, WICK_RATE))


# the pixel pairs of wicking (``_wick``): down the rows, then along them, as (giver a, taker b)
# of the window's (h, w) planes, and of its colours' planes (colours, h, w) the same pixels
_WICK_PAIRS = ((np.s_[:-1], np.s_[1:]), (np.s_[:, :-1], np.s_[:, 1:]))
_PLANE_PAIRS = ((np.s_[:, :-1], np.s_[:, 1:]), (np.s_[:, :, :-1], np.s_[:, :, 1:]))


def _wick(w, ink, draw, passes: int, rate: float = WICK_RATE) -> None:
    """Capillary wicking (see WICK_MM) of the window's wetness ``w`` (h, w) and ink (h, w, 3),
    in place, over ``passes`` passes at ``rate``; ``draw`` (h, w) in [0, 1] how well each pixel
    draws.
    Each pass moves liquid down the rows, then along them (each stable on its own). The ink is
    worked on as planes of colours (colours, h, w), each pixel's liquid taken for all its
    colours by broadcasting (no copies of it a colour); of ink whose colours hold the same
    numbers (black ink all three, the default ink two: ``lift.same_colours``) only the colours
    that differ, the others set from them: each colour's numbers are made by the same
    operations from the same numbers (issue 28)."""
    if not (w > 0.0).any():
        return
    same = same_colours(ink)
    keep = sorted(set(same))
    planes = np.empty((len(keep),) + ink.shape[:2], dtype=ink.dtype)
    for i, c in enumerate(keep):  # a colour at a time: no fancy indexing's copies
        planes[i] = ink[..., c]
    _wick_planes(w, planes, draw, passes, rate)
    for c, k in enumerate(same):
        ink[..., c] = planes[keep.index(k)]


def _wick_planes(w, planes, draw, passes: int, rate: float) -> None:
    """``_wick`` of ink as planes (colours, h, w): what each pixel gave or took multiplies
    every colour's plane at once (the same products as a colour at a time; issue 28)."""
    rate = np.float32(rate)
    down = rate * draw[:-1] * draw[1:]  # between a pixel and the one below it, ...
    along = rate * draw[:, :-1] * draw[:, 1:]  # ... and the one beside it
    for k in range(passes):
        if k and not (w > 0.0).any():
            break
        inflow = np.zeros_like(w)
        # what the liquid carried in, and the darkest colour of the pixels each took it from
        carried, darkest = np.zeros((2, *planes.shape), dtype=planes.dtype)
        for g, (a, b), (ia, ib) in zip((down, along), _WICK_PAIRS, _PLANE_PAIRS, strict=True):
            flux = g * (w[a] - w[b])  # > 0: from a to b
            to_b, to_a = np.maximum(flux, 0.0), np.maximum(-flux, 0.0)
            inflow[b] += to_b
            inflow[a] += to_a
            carried[ib] += to_b * planes[ia]
            carried[ia] += to_a * planes[ib]
            np.maximum(darkest[ib], (to_b > 0.0) * planes[ia], out=darkest[ib])
            np.maximum(darkest[ia], (to_a > 0.0) * planes[ib], out=darkest[ia])
            w[a] -= flux
            w[b] += flux
        # the pigment the liquid carried in: the givers' colour, weighted by what each gave,
        # laid over what the pixel holds as Eq. 26's change lays it (more liquid, more of it),
        # up to the darkest giver's colour (``_wick_lay``)
        carried *= _wick_take(inflow)
        _wick_lay(planes, carried, darkest)


def _wick_lay(ink, laid, darkest) -> None:
    """Lay the pigment the liquid carried in (``laid``: 1 - exp(-inflow / FULL_WET) times
    WICK_PIGMENT of the givers' colour) over the ``ink`` (any shape), in place, as before, but
    never past the colour of the darkest pixel the liquid came from (``darkest``; issue 26:
    ink drawn into ink still wet with the same ink merges with it. Laid over it as a layer
    without end, every pass of liquid between two pixels of a grey pool darkened the taker
    toward black, and the window's and the marks' edges, where the liquid keeps moving one way
    step after step, drew thin dark lines inside the stroke, and a grid where the hair
    lingered). A fringe on dry paper darkens as the liquid keeps coming, as before, up to the
    ink it came from."""
    laid *= 1.0 - ink
    room = np.subtract(darkest, ink, out=darkest)
    np.maximum(room, 0.0, out=room)
    np.minimum(laid, room, out=laid)
    ink += laid


def _wick_take(inflow):
    """The share of the carried pigment a pixel that took ``inflow`` of liquid keeps, per unit
    of liquid: WICK_PIGMENT (1 - exp(-inflow / FULL_WET)) / inflow, and -0.0 (as that sum
    gives it) where it took none; the exponential only where it took some (issue 28)."""
    took = np.flatnonzero(inflow > 0.0)
    some = np.take(inflow, took)
    take = exact.expm1(some / -FULL_WET)
    take *= -WICK_PIGMENT
    take /= some
    out = np.full(inflow.shape, -0.0, dtype=inflow.dtype)
    np.put(out, took, take)
    return out
