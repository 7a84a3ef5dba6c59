# SPDX-License-Identifier: GPL-3.0-or-later
"""The first, plain implementations of the paper's deposit (Eq. 24-27, one mark after the other)
and saturation (Eq. 25, neighbour by neighbour), kept as the references the batched
``sim.paper.Paper.deposit`` and the box-sum ``Paper._saturate`` must agree with. Bind the
deposit to a Paper: ``types.MethodType(reference_deposit, paper)``."""

import numpy as np

from sim.paper.paper import (
    FULL_WET,
    GRAIN_DEPTH,
    LAYER_S,
    TILE,
    _set_share,
    paper_grain,
)
from sim.paper.texture import sheet_draw
from sim.paper.wick import _wick

_NEIGHBOURS = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]


def reference_deposit(self, marks, q, dt: float, step: int, saturate=None):
    """Apply this step's marks (one per touching primitive), Eq. 24-27 (a mark's ``skip``:
    Eq. 27's Cr = 0, drawn by the brush's hair bundles)."""
    saturate = saturate or reference_saturate
    self.step = step
    marks = [mk for mk in marks if mk.rows.size]
    if not marks:
        return
    margin = self.sat_passes + self.wick_passes + 1
    y0 = max(min(mk.iy0 for mk in marks) - margin, 0)
    x0 = max(min(mk.ix0 for mk in marks) - margin, 0)
    y1 = min(max(mk.iy0 + mk.shape[0] for mk in marks) + margin, self.H)
    x1 = min(max(mk.ix0 + mk.shape[1] for mk in marks) + margin, self.W)
    wet = self.wet[y0:y1, x0:x1]
    ink = self.ink[y0:y1, x0:x1]
    last = self.last[y0:y1, x0:x1]
    drystep = np.float32(self.dry_per_step)
    # lazy drying through the previous step; this step's "- dry" follows (Eq. 24)
    missed = np.maximum(step - 1 - last, 0).astype(np.float32)
    w = np.maximum(wet - drystep * missed, 0.0)
    dried = np.zeros(w.shape, dtype=bool)
    ab = np.float32(q.ab)
    for mk in marks:
        r = mk.rows + (mk.iy0 - y0)
        c = mk.cols + (mk.ix0 - x0)
        lam = w[r, c]
        first = ~dried[r, c]
        # Eq. 24: wet' = ab * wet_lambda + (1 - ab) * wet_tau - dry
        new = ab * lam + (1 - ab) * mk.wet.astype(np.float32)
        new = np.maximum(new - np.where(first, drystep, 0), 0.0)
        dried[r, c] = True
        w[r, c] = new
        # Eq. 26-27 as sim.paper.paper changes them: where the bundle lays ink, the pixel takes
        # the colour the liquid offered to it can hold (1 - exp(-offer / FULL_WET) of the
        # brush's, the offer scaled by the sheet's grain) and keeps the darker
        grain = paper_grain((r + y0) * self.W + (c + x0), self.grain_seed) - 0.5
        offer = mk.wet.astype(np.float32) * (1.0 - GRAIN_DEPTH * self.fibre * grain).astype(
            np.float32
        )
        held = (-np.expm1(-offer / (FULL_WET / self.pigment))).astype(np.float32)
        skip = mk.skip if mk.skip is not None else np.zeros(r.size, bool)
        held = np.where(skip, 0.0, held).astype(np.float32)
        lay = mk.col.astype(np.float32) * held[:, None]
        # a second layer over ink that has set, on a pixel's first visit of the step (a model
        # change, sim.paper.paper.LAYER_S): the pigments add where it has set
        old = ink[r, c]
        after = LAYER_S / dt if dt > 0 else np.inf
        set_ = np.where(first, _set_share(lam, missed[r, c], after), np.float32(0.0))
        top = np.maximum(old, lay)
        stacked = old + lay * (1.0 - old)
        lay = top + set_.astype(np.float32)[:, None] * (stacked - top)
        ink[r, c] = np.maximum(old, lay)
    w = np.where(dried, w, np.maximum(w - drystep, 0.0))
    for _ in range(self.sat_passes):
        over = np.nonzero(w > self.capacity)
        if over[0].size == 0:
            break
        # only the neighbourhood of saturated pixels can change
        sy0, sy1 = max(over[0].min() - 1, 0), over[0].max() + 2
        sx0, sx1 = max(over[1].min() - 1, 0), over[1].max() + 2
        saturate(w[sy0:sy1, sx0:sx1], ink[sy0:sy1, sx0:sx1], self.capacity)
    if self.wick_passes:  # capillary wicking (a model addition, sim.paper.wick._wick)
        draw = sheet_draw(
            slice(y0, y1), slice(x0, x1), self.ppm, self.grain_seed, TILE, self.wick_fibre
        )
        _wick(w, ink, draw, self.wick_passes, self.wick_rate)
    wet[...] = w
    last[...] = step


def reference_saturate(w, ink, cap: float):
    """Eq. 25: a pixel wetter than the paper's bound gives its excess to its unsaturated
    neighbours, each in proportion to how unsaturated it is. The ink goes with the water:
    a neighbour's ink moves toward the giver's by the share of a full load it receives."""
    excess = np.maximum(w - cap, 0.0)
    if not np.any(excess > 0):
        return
    unsat = np.maximum(cap - w, 0.0)
    p = np.pad(unsat, 1)
    H, Wd = w.shape
    rho = sum(p[1 + dy : 1 + dy + H, 1 + dx : 1 + dx + Wd] for dy, dx in _NEIGHBOURS)
    give = np.where(rho > 0, excess / np.where(rho > 0, rho, 1.0), 0.0)  # per unit unsat
    gp = np.pad(give, 1)
    ip = np.pad(ink, ((1, 1), (1, 1), (0, 0)))
    inflow = np.zeros_like(w)
    pigment = np.zeros_like(ink)
    for dy, dx in _NEIGHBOURS:
        g = gp[1 + dy : 1 + dy + H, 1 + dx : 1 + dx + Wd] * unsat
        inflow += g
        pigment += g[..., None] * ip[1 + dy : 1 + dy + H, 1 + dx : 1 + dx + Wd]
    gave = rho > 0
    w -= np.where(gave, excess, 0.0)
    w += inflow
    got = inflow > 0
    mix = pigment / np.where(got, inflow, 1.0)[..., None]
    share = np.minimum(inflow, 1.0)[..., None]
    ink += np.where(got[..., None], (mix - ink) * share, 0.0)
