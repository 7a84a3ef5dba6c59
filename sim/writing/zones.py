# SPDX-License-Identifier: GPL-3.0-or-later
"""Where a practice pass (Sec. 7.2) does not read the band it left as the stroke's own width:
a movement's entry, where the belly is still pressing down; the let-go into a point; the first
widths of a 折's leg below its shoulder. For each body sample of a stroke, whether it lies in
such a zone (``practice`` corrects the press only outside them); and the press practice may
not leave at a head that opens from a point (``rising_heads``)."""

from __future__ import annotations

import numpy as np

from .feet import _along
from .lifts import _point_reach
from .planner import Plan, _is_hook, _movements, _onto_the_dun, _ramp_length


def entry_zone(pl: Plan, body) -> np.ndarray:
    """For each body sample of a stroke, whether it lies in a movement's entry, where the belly
    is still pressing down (``_entry_ramp``): the planned gesture (起笔), not yet the stroke's
    band. A hook, which sets off pressed, has none."""
    runs = _movements(body)
    zone = [np.zeros(len(r), dtype=bool) for r in runs]
    for r, (run, hook) in enumerate(zip(runs, _is_hook(pl, runs), strict=True)):
        if not hook:
            s = _along(pl.target[run])
            zone[r] = s < _ramp_length(s, pl.width[run])
    return np.concatenate(zone)


def point_zone(pl: Plan, body) -> np.ndarray:
    """For each body sample of a stroke, whether it lies in the last stretch of a movement that
    ends in a point (``_point_reach``), as long as the stroke is wide there: where the belly
    lets go, and the band read there narrows because the brush lifts off, not because it is
    pressed too little."""
    runs = _movements(body)
    zone = [np.zeros(len(r), dtype=bool) for r in runs]
    for r, run in enumerate(runs):
        if r == len(runs) - 1 and _point_reach(pl.target[run], pl.width[run]) > 0.0:
            s = _along(pl.target[run])
            zone[r] = s > s[-1] - float(pl.width[run][-1])
    return np.concatenate(zone)


SHOULDER_HOLD = 1.5  # leg widths below a 折's shoulder practice holds the leg's press over


def shoulder_zone(pl: Plan, body) -> np.ndarray:
    """For each body sample of a stroke, whether it lies in the first ``SHOULDER_HOLD`` widths
    of a leg set off from a 折's 顿 (``planner._onto_the_dun``), where the band read is the
    shoulder's, not the leg's: practice holds the press and placement there at those past it
    (``_held``: beyond Sec. 7.2's correction per sample, issue 26 point 2: the 顿's ink read
    as the leg's band, practice lifted there and pressed again below, a knob and bumps down
    the leg's side, 口's press 5.6 -> 4.3 -> 5.6 -> 4.8 -> 5.6 mm over two leg widths. Not when
    imitating a picture: the band below its shoulder is the picture's own.)"""
    runs = _movements(body)
    hook = _is_hook(pl, runs)
    zone = [np.zeros(len(r), dtype=bool) for r in runs]
    for r in range(1, len(runs)):
        if not hook[r] and _onto_the_dun(pl, runs[r - 1], runs[r]):
            s = _along(pl.target[runs[r]])
            zone[r] = s < SHOULDER_HOLD * float(np.median(pl.width[runs[r]]))
    return np.concatenate(zone)


NECK = 0.5  # share of the press before it that a head opening from a point keeps after its tip


def rising_heads(press, want, runs) -> np.ndarray:
    """The press per body sample with no neck after a head that opens from a point: over the
    stretch from a movement's start along which its planned width ``want`` keeps widening (a
    露锋 head, a 捺's), the press nowhere under ``NECK`` of the deepest before it. Practice
    corrects each sample on its own; at a pointed head it pressed the tip down (its band read
    narrow) and lifted just after it (the tip's blob spread into the band there) to a fifth of
    the tip's press: a drop of ink at the tip, a bare neck, then the stroke (長's long 横
    imitated from a copybook: its tip a separate piece, which moved the imitation's box). A
    calligrapher presses on from the tip. (Model addition, issue 26.)"""
    out = np.asarray(press, dtype=float).copy()
    for run in runs:
        w = want[run]
        falls = np.flatnonzero(np.diff(w) <= 0.0)
        stop = int(falls[0]) + 1 if falls.size else len(run)
        if stop >= 3:
            head = out[run[:stop]]
            out[run[:stop]] = np.maximum(head, NECK * np.maximum.accumulate(head))
    return out
