# SPDX-License-Identifier: GPL-3.0-or-later
"""A flicked hook's root lifted off the lobe it spills past the outline (issue 26, point 2; a
model addition to Sec. 7.2's practice): as the belly swings from the leg's way onto the
flick's, the hair splayed in the heel sweeps out past the hook triangle's lower edge in a round
lobe below the hook's root (同, 永, 月). There the band across the hook is read in the leg's
ink, so practice's width correction (``practice._correct``) never sees it; and it could not
lighten it, a hook's press being held to its heel's taper (``feet._flicked``). Each pass the
student counts the ink past the outline round the hook (``_spill``) and lifts the brush a
little at the root on the next (``_lifted``)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .planner import Plan, _flicks, _is_hook, _movements, _smooth
from .response import _coverage, _slope

LIFT_GAIN = 1.0  # share of a hook's spill past the outline (``_spill``) lifted off its press
LIFT_MAX = 0.5  # share of its planned press a hook sample is lifted by at most


SPILL_CHUNK = 4096  # spilled pixels measured against the hook's bases at a time (memory)
HOOK_WINDOW = 3.0  # widths round a hook's targets its spill is looked for (the base leads the
# ink by up to about a width; the spill counted lies within a width of a base)


class _Hooks(NamedTuple):
    """A stroke's flicked hooks (``planner._flicks``): their runs of body samples (indices
    into the body), which body samples are theirs, and where they may spill (paper rows and
    columns, bottom row first: round their targets, out to ``HOOK_WINDOW`` of their widest
    width) with the paper's coverage there before the stroke."""

    runs: list
    hook: np.ndarray
    rows: slice
    cols: slice
    before: np.ndarray


def _hook_runs(pl: Plan, body) -> list:
    """The runs of body samples (indices into ``body``) of the stroke's flicked hooks."""
    runs, moves = _movements(np.arange(len(body)), body), _movements(body)
    return [run for run, f in zip(runs, _flicks(pl, moves, _is_hook(pl, moves)), strict=True) if f]


def _hooks(sim, pl: Plan, body) -> _Hooks | None:
    """The stroke's ``_Hooks``, or None if it has no flicked hook."""
    runs = _hook_runs(pl, body)
    if not runs:
        return None
    hook = np.zeros(len(body), dtype=bool)
    hook[np.concatenate(runs)] = True
    ppm, pts = sim.paper.ppm, pl.target[body[hook]]
    margin = HOOK_WINDOW * float(pl.width[body[hook]].max())
    lo = np.maximum(((pts.min(axis=0) - margin) * ppm).astype(int), 0)
    hi = np.minimum(((pts.max(axis=0) + margin) * ppm).astype(int) + 1, (sim.paper.W, sim.paper.H))
    rows, cols = slice(int(lo[1]), int(hi[1])), slice(int(lo[0]), int(hi[0]))
    return _Hooks(runs, hook, rows, cols, _coverage(sim, rows, cols))


def _spill(sim, pl: Plan, body, whole, hooks: _Hooks) -> np.ndarray:
    """How much wider (mm) than the character's outline (``whole``) the brush laid its flicked
    hooks (``_hooks``), per body sample (0 elsewhere): the new ink outside every outline round
    the hooks, each pixel counted to the hook sample whose base (the brush's handle: the belly
    lies under it, the tip trails) is nearest it, if within the hooks' widest width, as an area
    over the median step between those bases."""
    out = np.zeros(len(body))
    base = sim.rec.samples[body[hooks.hook], :2]
    if len(base) < 2:  # no step to spread a spill over
        return out
    ppm, reach = sim.paper.ppm, float(pl.width[body[hooks.hook]].max())
    new = _coverage(sim, hooks.rows, hooks.cols) & ~hooks.before & ~whole[hooks.rows, hooks.cols]
    ys, xs = np.nonzero(new)
    px = (np.stack([xs + hooks.cols.start, ys + hooks.rows.start], axis=1) + 0.5) / ppm
    count = np.zeros(len(base))
    for k in range(0, len(px), SPILL_CHUNK):
        d = np.linalg.norm(px[k : k + SPILL_CHUNK, None, :] - base[None, :, :], axis=2)
        near = d.argmin(axis=1)
        own = d[np.arange(len(near)), near] <= reach  # the hook's own spill, not a far stroke's
        count += np.bincount(near[own], minlength=len(base))
    step = max(float(np.median(np.linalg.norm(np.diff(base, axis=0), axis=1))), 1e-6)
    out[hooks.hook] = count / ppm**2 / step
    return out


def _root_unread(hooks: _Hooks, valid) -> np.ndarray:
    """The body samples of a hook's root whose band is read in the leg's ink (not ``valid``,
    ``practice.measure_band``): from where the hook sets off up to its first reading of its
    own."""
    out = np.zeros(len(valid), dtype=bool)
    for run in hooks.runs:
        out[run] = np.cumprod(~valid[run]).astype(bool)
    return out


def _lifted(response, lift, spill, press, unread) -> np.ndarray:
    """The next pass's lift off a hook's press (mm per body sample; ``planner._fill`` takes it
    off the press as finally shaped): this pass's ``lift`` and ``LIFT_GAIN`` of the spill
    (``_spill``) through the response's slope (band width per press) where the band is
    ``unread`` (``_root_unread``), smoothed along the stroke, at most ``LIFT_MAX`` of the
    planned ``press``."""
    more = _smooth(np.where(unread, LIFT_GAIN * spill / _slope(response, press), 0.0), 5)
    return np.clip(lift + more, 0.0, LIFT_MAX * press)
