# SPDX-License-Identifier: GPL-3.0-or-later
"""The working diagram (Fig. 1): samples -> inertia predictor -> brush step (dynamics) ->
marks -> paper. One seeded generator feeds every random draw, so a recording replays bit for
bit, and snapshots let a caller jump to any sample and get exactly the same state."""

from __future__ import annotations

import math
import time
from typing import NamedTuple

import numpy as np

from ..brush import bristles
from ..brush.inertia import InertiaPredictor
from ..brush.ink import interpolate_rows
from ..brush.mark import cut_marks, fill_marks
from ..brush.primitive import HairyBrush
from ..brush.state import ink_keys
from ..core.params import HOVER_MM
from ..core.recording import Recording, brush_scale
from ..paper.paper import DRY_RATE, Paper
from ..surface.paper import CHART_SHAPE

# samples whose marks are filled in together by ``run`` (the brush never reads the paper, so its
# dynamics can run ahead of the paper; each step's deposit still comes in order)
BATCH_STEPS = 8
# at most this many waiting samples have their marks filled in one pass when the paper catches
# up with a brush that ran ahead (``advance``, ``settle``): fewer passes, each over more pixels
# (issue 28); any grouping gives the same marks, bit for bit (``fill_marks``)
FILL_STEPS = 32
# the hair bundles measure and lay the marks of the filled samples together, as many samples
# at a time as have about this many pixels: one pass of numpy calls for many small marks,
# while large marks' temporaries stay in the processor's cache (issue 28)
LAY_PIXELS = 1 << 13


class PendingDeposit(NamedTuple):
    """A sample the brush has made and the paper has not taken yet (see ``run``)."""

    cut: object  # the solid's cut by the paper (sim.brush.mark.Cut), None when it does not touch
    bristles: bristles.BristleState  # the hair bundles then (pressure, draws, ink shares)
    step: int  # the sample's number, from 1, as the paper counts steps


class Simulation:
    def __init__(self, recording: Recording, surface=None):
        """``surface``: a ``sim.surface.SurfacePaper`` when the paper is a 3D surface (the
        samples are then on its chart and every mark is splatted into its texture); None for
        the flat paper, which is the chart itself."""
        self.rec = recording
        self.surface = surface
        self.q, self.geometry, self.paper_spec, self.ink = recording.resolve()
        self.dt = 1.0 / recording.sample_rate_hz
        self.rng = np.random.Generator(np.random.PCG64(recording.seed))
        self.brush = HairyBrush(self.geometry, self.q, self.rng)
        self.paper = Paper(
            recording.width_px,
            recording.height_px,
            recording.px_per_mm,
            self.paper_spec.color,
            self.paper_spec.capacity,
            dry_per_step=self.q.dry * DRY_RATE * self.dt,
            grain_seed=recording.seed,
            fibre=self.paper_spec.fibre,
            texture=self.paper_spec.texture if surface is None else 0.0,  # a mesh is not xuan
        )
        self.paper.pigment = self.ink.pigment  # how much pigment the ink's liquid carries
        self.paper.brush_scale = brush_scale(recording.brush)  # (a smaller brush's droplets)
        if surface is not None:  # nor do its texels lie evenly in mm: the ink wicks evenly,
            self.paper.wick_fibre = 0.0  # and no halo (a texel's neighbours are not the sheet's)
            self.paper.halo_px = 0
        self.predictor = InertiaPredictor(self.dt)
        self.dips = recording.dips_or_default()
        self.index = 0  # next sample to process
        self.last_marks = []
        self._pending: list[PendingDeposit] = []  # moved but not yet deposited (see run)
        self._filled: list = []  # the marks of the first waiting samples, filled in already
        self.timings = None  # a dict to keep the seconds spent in every stage (the benchmark)
        # whether ``run`` lets the paper take the brush's marks: False runs the brush alone
        # (a caller that wants only the recording and the brush, as a composed work's writer
        # of one pass, whose cells are simulated again on the sheet: the brush never reads the
        # paper, so it moves bit for bit as with the paper, which stays blank) (issue 28)
        self.marks_to_paper = True
        first = self._sample(0)
        self.brush.place(
            np.r_[first[:2], max(first[2], self.geometry.hair_length_mm + HOVER_MM), first[3:]]
        )

    @property
    def done(self) -> bool:
        return self.index >= len(self.rec.samples)

    @property
    def dips(self) -> list:
        """The dip events, in order, looked up by sample (a long list costs nothing a step).
        Assign a new list to change them: the lookup is built on assignment."""
        return self._dips

    @dips.setter
    def dips(self, dips):
        self._dips = dips
        self._dips_at = {}
        for dp in dips:
            self._dips_at.setdefault(dp.before_sample, []).append(dp)

    def _dip_now(self):
        for dp in self._dips_at.get(self.index, ()):
            if dp.restart is not None:
                self._restart(dp.restart)
            self.brush.dip(self.ink, dp.depth, dp.color_with(self.ink), dp.wetness)
            self.predictor.reset()

    def _restart(self, stream: int):
        """A dip that starts a cell of a composed work (``Dip.restart``, sim.writing.work): the
        calligrapher re-forms the brush on the inkstone, so it is as new - its hair gathered into
        one primitive, at rest over the sample - and its random draws come from the stream
        (seed, stream) of the one seeded generator from now on. What follows depends on nothing
        before it: the cells of a work can be simulated side by side, bit for bit as in one
        run, and one cell can be written again without changing the others. (Beyond the
        paper: its brush carries every state from sample to sample.)"""
        self.rng.bit_generator.state = np.random.PCG64([self.rec.seed, stream]).state
        fresh = HairyBrush(self.geometry, self.q, self.rng)
        s = self._sample(self.index)
        fresh.place(np.r_[s[:2], max(s[2], self.geometry.hair_length_mm + HOVER_MM), s[3:]])
        self.brush.restore(fresh.snapshot())

    def step(self):
        """Process one 6-DOF sample: the brush moves and the paper takes its marks."""
        self._advance()
        self._deposit_pending()

    def _advance(self):
        """The brush's part of one sample; its marks wait in ``_pending`` for the paper."""
        t0 = time.perf_counter()
        self._dip_now()
        i = self.index
        s = self.predictor(self._sample(i))  # Eq. 9
        vel = self.predictor.velocity
        b = self.brush
        b.move(s, vel, self.dt)  # Sec. 5.2
        t0 = self._tick("brush", t0)
        sec = b.sections()
        t0 = self._tick("sweep", t0)
        shape = self.paper.shape if self.surface is None else CHART_SHAPE
        # the ink at the surface rows (Eq. 21) only feeds the marks: it is interpolated when
        # they are filled, for many samples at once (``_fill``), from the key points' ink now
        cut = cut_marks(b, sec, None, self.paper.ppm, shape)
        if cut is not None:
            cut.ink_source = (sec.params, ink_keys(b))
        t0 = self._tick("cut", t0)
        area, height = cut.sizes(b.m) if cut is not None else (np.zeros(b.m), np.zeros(b.m))
        if cut is not None:
            b.follow(cut.contact())  # the path the hair bundles are drawn along (bristles)
        vx, vy, vz = vel[:3].tolist()  # |vel[:3]| summed as np.add.reduce, not BLAS (issue 28.2)
        speed = math.sqrt((vx * vx + vy * vy) + vz * vz)
        b.update_stress(area, height, speed, self.dt)  # Eq. 10-12
        tx, ty = b.travel.tolist()
        across = (-ty, tx)
        b.sweep = (cut.widths(b.m, across) if cut is not None else np.zeros(b.m)) * speed
        if cut is not None and b.state == "dipping":
            b.state = "working"
        # what the deposit of this sample needs, as it is now (Eq. 24-27)
        self._pending.append(PendingDeposit(cut, bristles.state(b, speed), i + 1))
        b.lose_wetness(self.dt)  # Eq. 15
        b.adjust_ellipse(vel, self.dt)  # Eq. 16, 17
        b.split()  # Eq. 18, 19
        b.ink_flow()  # Eq. 20
        b.capillary(self.dt)
        b.step_bundles(speed, self.dt)
        self.index += 1
        self._tick("brush", t0)

    def _sample(self, i: int) -> np.ndarray:
        """Sample i as the brush takes it: on a surface, on the chart (see sim.surface)."""
        sample = self.rec.samples[i]
        return sample if self.surface is None else self.surface.engine_sample(i, sample)

    def _tick(self, stage: str, t0: float) -> float:
        """Add the time since t0 to ``stage`` when timings are kept; returns now."""
        now = time.perf_counter()
        if self.timings is not None:
            self.timings[stage] = self.timings.get(stage, 0.0) + (now - t0)
        return now

    def advance(self, until: int):
        """The brush alone up to sample ``until`` (not past the recording's end): its marks
        wait for the paper, which ``settle`` or ``run`` brings up to it (the brush never reads
        the paper)."""
        end = min(until, len(self.rec.samples))
        while self.index < end:
            self._advance()

    def settle(self, until: int):
        """The paper up to sample ``until`` (as ``run(until)`` leaves it), the brush having run
        at least that far (``advance``)."""
        self._deposit_pending(until)

    def _drop_pending(self):
        """Forget the samples the paper has not taken (the brush is put back)."""
        self._pending = []
        self._filled = []

    def _deposit_pending(self, until: int | None = None):
        """Fill in the waiting samples' marks together (up to FILL_STEPS at a time), then
        deposit them in order: all of them, or those of samples before ``until``."""
        while self._pending and (until is None or self._pending[0].step <= until):
            if not self._filled:
                self._filled = self._fill(self._pending[:FILL_STEPS])
            stop = len(self._filled)
            if until is not None:
                stop = min(stop, sum(1 for p in self._pending[:stop] if p.step <= until))
            self._deposit(self._pending[:stop], self._filled[:stop])
            del self._pending[:stop]
            del self._filled[:stop]

    def _take_pending(self):
        """The paper takes the waiting samples' marks (``_deposit_pending``), or, with
        ``marks_to_paper`` False, they are let go."""
        if self.marks_to_paper:
            self._deposit_pending()
        else:
            self._drop_pending()

    def _fill(self, pending) -> list:
        """The marks of waiting samples, filled in together (Eq. 21-23). Small marks are
        measured and laid by the hair bundles (``bristles``) here too, many samples at once;
        a sample with large marks is left to ``_deposit``, which lays them just before the
        paper takes them, while they are in the processor's cache. On the flat paper the
        measured samples' marks are laid out for it together too (``Paper.lay_out``: what the
        paper takes of them that does not depend on the paper; issue 28). Each sample's
        (marks, whether measured, its ``Laying`` or None)."""
        t0 = time.perf_counter()
        ppm = self.paper.ppm
        _rows_ink([p.cut for p in pending], self.brush.layout.grid_s)
        marks = fill_marks([p.cut for p in pending], ppm)
        t0 = self._tick("mark pixels", t0)
        out = []
        for a, b in _groups([sum(mk.rows.size for mk in m) for m in marks], LAY_PIXELS):
            part, states = marks[a:b], [p.bristles for p in pending[a:b]]
            if b - a == 1:  # large marks: a sample at a time, as the paper takes them
                out.append((part[0], False, None))
                continue
            part = bristles.across_steps(part, states, ppm)  # on the chart, on a surface
            if self.surface is None:
                part = bristles.lay_steps(part, states, ppm)  # the hair bundles (Eq. 27)
            out += [(m, True, None) for m in part]
        if self.surface is None:
            laid = [k for k, f in enumerate(out) if f[1]]
            for k, laying in zip(laid, self.paper.lay_out([out[k][0] for k in laid]), strict=True):
                out[k] = (out[k][0], True, laying)
        self._tick("paper", t0)
        return out

    def _deposit(self, pending, filled):
        """Deposit the filled marks of waiting samples, in order (Eq. 24-27): ``filled`` has
        each sample's marks, whether the bundles have measured them and on the flat paper
        their ``Laying`` (``_fill``)."""
        t0 = time.perf_counter()
        ppm = self.paper.ppm
        if self.surface is None:
            self._deposit_flat(pending, filled)
            self._tick("paper", t0)
            return
        for p, (marks, measured, _) in zip(pending, filled, strict=True):
            if not measured:
                marks = bristles.across(marks, p.bristles, ppm)  # on the chart, on a surface
            t1 = time.perf_counter()
            groups = self.surface.splat(marks, p.step - 1) or [[]]  # texels under the marks
            self._tick("surface splat", t1)
            groups = [bristles.lay(group, p.bristles, ppm) for group in groups]
            for group in groups:  # far apart in the texture (a seam): a window each
                self.paper.deposit(group, self.q, self.dt, p.step)
            self.last_marks = [mk for group in groups for mk in group]
        self._tick("paper", t0)

    def _deposit_flat(self, pending, filled):
        """``_deposit`` on the flat paper: the paper takes each sample's marks as ``_fill``
        laid them out; a sample with large marks is measured, laid by the hair bundles (Eq.
        27) and laid out here, just before (issue 28)."""
        ppm = self.paper.ppm
        for p, (marks, measured, laying) in zip(pending, filled, strict=True):
            if not measured:
                marks = bristles.lay(bristles.across(marks, p.bristles, ppm), p.bristles, ppm)
                laying = self.paper.lay_out([marks])[0]
            self.paper.take(laying, self.q, self.dt, p.step)  # Eq. 24-27
            self.last_marks = marks

    def run(self, until: int | None = None, progress=None):
        end = len(self.rec.samples) if until is None else min(until, len(self.rec.samples))
        total = max(end - self.index, 1)
        start = self.index
        while self.index < end:
            self._advance()
            done = self.index - start
            if len(self._pending) >= BATCH_STEPS or self.index >= end:
                self._take_pending()
            if progress is not None and done % 64 == 0:
                self._take_pending()
                progress(done / total)
        if progress is not None:
            progress(1.0)
        return self

    def image(self) -> np.ndarray:
        """RGB float image (H, W, 3), top row first."""
        return self.paper.rgb()[::-1]

    def image8(self) -> np.ndarray:
        """RGB uint8 image (H, W, 3), top row first, made band by band (little memory)."""
        return self.paper.rgb8()

    # -------------------------------------------------------------- snapshots
    def snapshot(self) -> dict:
        """The whole simulation as it is now, to ``restore`` any time later."""
        self._deposit_pending()
        return self._state(self.paper.snapshot())

    def hold(self, brush: dict | None = None) -> dict:
        """The simulation as it is now, to ``take_back`` later; unlike a snapshot it copies no
        paper up front: the paper keeps each tile as it was before its first change. With
        ``brush`` (``brush_hold`` at the sample ``settle`` has brought the paper to) the brush
        may have run ahead (``advance``): the hold is of that sample, the waiting marks kept."""
        if brush is not None:
            return {**brush, "paper": self.paper.hold()}
        self._deposit_pending()
        return self._state(self.paper.hold())

    def brush_hold(self) -> dict:
        """The brush's part of a ``hold`` as it is now, while the paper lags behind it
        (``advance``); ``hold(brush)`` completes it once the paper has caught up."""
        return self._state(None)

    def restore(self, snap: dict):
        self._set_state(snap)
        self.paper.restore(snap["paper"])

    def take_back(self, hold: dict):
        """Back exactly to ``hold()``; the hold ends."""
        self._set_state(hold)
        self.paper.give_back(hold["paper"])

    def let_go(self, hold: dict):
        """End a hold without going back."""
        self.paper.release(hold["paper"])

    def _state(self, paper) -> dict:
        return {
            "index": self.index,
            "brush": self.brush.snapshot(),
            "paper": paper,
            "rng": self.rng.bit_generator.state,
            "predictor": self.predictor.state(),
        }

    def _set_state(self, state: dict):
        """Everything of a snapshot or hold but the paper."""
        self._drop_pending()
        self.index = state["index"]
        self.brush.restore(state["brush"])
        self.rng.bit_generator.state = state["rng"]
        self.predictor.set_state(state["predictor"])


def _groups(sizes, budget: int):
    """Runs [a, b) of consecutive items whose sizes add up to about ``budget`` (at least one
    item each)."""
    a, total = 0, 0
    for i, size in enumerate(sizes):
        if i > a and total + size > budget:
            yield a, i
            a, total = i, 0
        total += size
    if a < len(sizes):
        yield a, len(sizes)


def _rows_ink(cuts, grid_s):
    """Every cut's ink at its surface rows' axis points V^ (Eq. 21), all samples' at once, from
    the key points' ink each kept (``Cut.ink_source``)."""
    todo = [c for c in cuts if c is not None and c.ink_source is not None]
    if not todo:
        return
    t = np.concatenate([c.ink_source[0] for c in todo])
    keys = np.concatenate([c.ink_source[1] for c in todo])
    rows = interpolate_rows(grid_s, t, keys)
    at = 0
    for c in todo:
        m = c.ink_source[0].shape[0]
        c.rows = c.rows._replace(ink=rows[at : at + m])
        c.ink_source = None
        at += m


def render(recording: Recording, until: int | None = None, progress=None) -> np.ndarray:
    return Simulation(recording).run(until, progress).image()
