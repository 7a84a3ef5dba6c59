# SPDX-License-Identifier: GPL-3.0-or-later
"""Live painting (Sec. 4, Fig. 6(b)): mouse, keyboard and tablet events become 6-DOF samples
taken on a clock, fed to a running Simulation as they come.

Fig. 6(b) (READING-NOTES.md): moving the mouse sets x, y; the wheel sets z (how far the brush is
pressed); q/w, e/r, c/v decrease/increase d, q and r. Holding the left button doubles a key's
step; the paper multiplies it by four with the right button, which Blender reserves for
cancelling, so Shift does that here. A tablet's pressure drives z and its tilt drives d and q.

Added beyond the paper, so that painting by hand reads as a brush does (issue 29):

- the pointer is where the hair's tip touches: a tilted brush (a tablet's tilt, or the keys)
  turns about the tip, its base placed up the tilted hair, so tilting never lifts the tip off
  the paper nor moves the mark sideways (the paper's mouse sets the base, which a tilt of 40
  degrees lifts a quarter of the hair length);
- the pen's pressure is read from every pointer event, not only from those flagged as a
  tablet's (Blender reports pressure 1 for a mouse; a tablet whose events are not flagged had
  its pressure ignored, so a pressure ramp swelled only as the belly does). The press stays the
  paper's, Press x pressure: on a ramp 0.15 -> 1 at 100 mm/s it widens evenly (wolf_kaishu,
  Press 4 mm: from a hairline to 3.3 mm; an offset to the first touch, p^1.5 or p^2 were
  measured too and read less evenly across the brushes);
- each stroke lands and lifts: before the brush goes down it hovers LAND_S where it lands (the
  inertia predictor of Eq. 9 carries a jump from the last stroke's end on for about ten samples,
  so a brush lowered at once drags ink from there), and after the stroke it rises in place and
  hovers LIFT_S, so consecutive strokes are separated by a lift and leave nothing between them;
- Ctrl+Z takes back the stroke being painted and painting goes on; with nothing painted yet it
  ends painting (``handle`` returns 'UNDO') so that the caller takes back the last stroke kept.

Event names and values are Blender's (``event.type``/``event.value``), so the Blender operator
passes its events straight through, and tests drive this class with the same sequences.

The sample clock is the wall clock, not the UI loop: samples are the brush's pose at uniform
times k / rate from the stroke's start, whatever the display or the engine costs. Every event
carries the time it was handled (``LiveEvent.time``, seconds on a monotonic clock); when one
arrives late, all the samples due by then are produced, the pointer's position interpolated in
time between the positions the brush knows. Producing samples and simulating them are separate:
``advance(budget)`` simulates what is due, in batches as ``Simulation.run`` does, for at most a
time budget, so the engine may fall behind the clock while painting and catches up; ``keep()``
catches up fully, so the kept recording is complete and equals what the paper shows.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass

import numpy as np

from ..core.frames import rotation_matrix
from ..core.params import HOVER_MM
from ..core.recording import Dip, brush_scale, quantise
from .simulation import BATCH_STEPS, Simulation

WHEEL_STEP_MM = 0.5
MAX_TILT_DEG = 60.0
ANGLE_LIMIT = 80.0
ANGLE_KEYS = {"Q": (0, -1), "W": (0, +1), "E": (1, -1), "R": (1, +1), "C": (2, -1), "V": (2, +1)}
KEEP_KEYS = {"RET", "NUMPAD_ENTER"}
CANCEL_KEYS = {"ESC", "RIGHTMOUSE"}
UNDO_KEY = "Z"  # with Ctrl (Cmd): take back the stroke
LAND_S = 0.1  # the brush hovers this long where it lands before it goes down (see above)
LIFT_S = 0.1  # and rises in place and hovers this long after the stroke


@dataclass
class LiveEvent:
    type: str
    value: str = "PRESS"
    paper_xy: tuple | None = None  # mm on the paper under the cursor; None when off the paper
    pressure: float = 1.0
    tilt: tuple = (0.0, 0.0)
    is_tablet: bool = False  # kept for the record: pressure and tilt are read from any pointer
    shift: bool = False
    time: float | None = None  # when it was handled (s, monotonic); None: a TIMER is one period
    ctrl: bool = False  # Ctrl (or Cmd) held


POINTER_EVENTS = ("MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "LEFTMOUSE")
STALL_PERIODS = 2  # a gap of more sample periods than this between events is a stalled UI loop
BURST_S = 0.002  # events handled within this time of each other were queued together


class LiveBrush:
    """A stroke being painted onto an existing Simulation (which may already hold a recording).
    ``keep()`` leaves the new samples in ``sim.rec``; ``cancel()`` puts the simulation back
    exactly as it was."""

    def __init__(self, sim: Simulation, press_mm: float = 4.0, step_deg: float = 2.0, xy=None):
        self.sim = sim
        # Press is the preset brush's: a brush made smaller for the writing's size (its
        # recording's 'brush.scale', sim.writing.brush_size) presses as much less deep
        self.press_mm = float(press_mm) * brush_scale(sim.rec.brush)
        self.step_deg = float(step_deg)
        self.L = sim.geometry.hair_length_mm
        self.n0 = len(sim.rec.samples)
        if sim.index != self.n0:
            raise ValueError("the simulation must have run to the end of its recording")
        self._hold = sim.hold()
        self._dips0 = list(sim.rec.dips)
        self._sim_dips0 = list(sim.dips)
        last = sim.rec.samples[-1] if self.n0 else np.zeros(6)
        self.x, self.y = (float(v) for v in (xy if xy is not None else last[:2]))
        self.angles = np.zeros(3)  # key offsets of d, q, r
        self.tilt = np.zeros(2)
        self.pressure = 1.0
        self.down = False
        self.left_held = False
        self.pressed = False  # the button went down in this stroke
        self.state = "RUNNING"
        self._buf = np.array(sim.rec.samples, dtype=float, copy=True)
        self._n = self.n0
        self.period = 1.0 / sim.rec.sample_rate_hz
        self.land = max(1, round(LAND_S / self.period))  # samples of a landing
        self.lift = max(1, round(LIFT_S / self.period))  # and of a lift
        self._t0 = None  # the stroke's start on the clock (the first event's time)
        self._t = 0.0  # the clock's time of the last event handled
        self._anchor = (0.0, self.x, self.y)  # the pointer at the last sample: (time, x, y)
        self._moves = []  # (time, x, y) of the pointer positions received since then

    # ------------------------------------------------------------------ the current pose
    def pose(self) -> np.ndarray:
        """The sample: the hair's tip under the pointer, pressed ``press()`` into the paper or
        hovering HOVER_MM above it, the base up the (tilted) hair from there."""
        d = self.angles[0] + self.tilt[0] * MAX_TILT_DEG
        q = self.angles[1] + self.tilt[1] * MAX_TILT_DEG
        d, q = np.clip([d, q], -ANGLE_LIMIT, ANGLE_LIMIT)
        r = self.angles[2]
        up = rotation_matrix(d, q, r)[:, 2]  # from the tip up the unbent hair to the base
        tip = np.array([self.x, self.y, -self.press() if self.down else HOVER_MM])
        return np.r_[tip + self.L * up, d, q, r]

    def press(self) -> float:
        """How far the tip is pressed into the paper (mm): Press x the pen's pressure (1 with
        a mouse)."""
        return self.press_mm * self.pressure

    @property
    def new_samples(self) -> np.ndarray:
        return self._buf[self.n0 : self._n]

    @property
    def behind(self) -> int:
        """Samples produced by the clock and not simulated yet."""
        return self._n - self.sim.index

    # ------------------------------------------------------------------ the clock
    def _sample_time(self, k: int) -> float:
        """Clock time of the stroke's k-th sample (k = 0 is one period after the start)."""
        return self._t0 + (k + 1) * self.period

    def _clock(self, ev: LiveEvent) -> float:
        if ev.time is not None:
            t = float(ev.time)
            if self._t0 is None:
                self._t0 = self._t = t
                self._anchor = (t, self.x, self.y)
            return max(t, self._t)  # a clock never runs backwards
        if self._t0 is None:
            self._t0 = 0.0
        return self._sample_time(self._n - self.n0) if ev.type == "TIMER" else self._t

    def _knots(self, t: float) -> np.ndarray:
        """(time, x, y) of the pointer from the last sample's time to t."""
        ta, xa, ya = self._anchor
        pts = np.array(self._moves, dtype=float).reshape(-1, 3)
        pts[:, 0] = _spread_bursts(np.r_[ta, pts[:, 0]], STALL_PERIODS * self.period)[1:]
        pts[:, 0] = np.clip(pts[:, 0], ta, t)
        last = pts[-1, 1:] if len(pts) else (xa, ya)
        return np.vstack([[ta, xa, ya], pts, [t, *last]])

    def _produce_until(self, t: float):
        """Every sample due by clock time t, the pointer interpolated in time along the
        positions received since the last sample."""
        knots = self._knots(t)
        while self._sample_time(self._n - self.n0) <= t + 1e-9:
            ts = self._sample_time(self._n - self.n0)
            self.x = float(np.interp(ts, knots[:, 0], knots[:, 1]))
            self.y = float(np.interp(ts, knots[:, 0], knots[:, 2]))
            self._append(self.pose())
        self.x, self.y = float(knots[-1, 1]), float(knots[-1, 2])
        self._anchor = (t, self.x, self.y)
        self._moves = []
        self._t = t

    def _append(self, pose):
        if self._n == len(self._buf):
            grown = np.empty((max(64, 2 * len(self._buf)), 6))
            grown[: self._n] = self._buf[: self._n]
            self._buf = grown
        self._buf[self._n] = quantise(pose)  # as stored in recordings
        self._n += 1
        self.sim.rec.samples = self._buf[: self._n]

    def advance(self, budget_s: float | None = None) -> int:
        """Simulate the samples that are due, a batch at a time, for at most ``budget_s``
        seconds (None: all of them). Returns how many are still waiting."""
        deadline = None if budget_s is None else _time.perf_counter() + budget_s
        sim = self.sim
        while sim.index < self._n:
            sim.run(min(self._n, sim.index + BATCH_STEPS))
            if deadline is not None and _time.perf_counter() >= deadline:
                break
        return self.behind

    # ------------------------------------------------------------------ events
    def handle(self, ev: LiveEvent) -> str:
        """Process one event; returns 'RUNNING', 'FINISHED' (stroke kept) or 'CANCELLED'.
        Samples due by the event's time are produced (not simulated: see ``advance``)."""
        if self.state != "RUNNING":
            return self.state
        t, v = ev.type, ev.value
        now = self._clock(ev)
        if ev.paper_xy is not None and t in POINTER_EVENTS:
            self._moves.append((now, float(ev.paper_xy[0]), float(ev.paper_xy[1])))
        if t not in ("MOUSEMOVE", "INBETWEEN_MOUSEMOVE"):  # moves only tell where the pointer is
            self._produce_until(now)
        if t in POINTER_EVENTS:  # a mouse reports pressure 1 and no tilt
            self.pressure = float(np.clip(ev.pressure, 0.0, 1.0))
            self.tilt = np.clip(np.asarray(ev.tilt, dtype=float), -1.0, 1.0)
        if t == UNDO_KEY and v == "PRESS" and ev.ctrl:
            return self.undo(now)
        if t == "LEFTMOUSE":
            if v == "PRESS":
                if not self.down:
                    self._land()
                self.left_held = self.down = self.pressed = True
            elif v == "RELEASE" and self.down:
                return self.keep()
        elif t in KEEP_KEYS and v == "PRESS":
            return self.keep()
        elif t in CANCEL_KEYS and v == "PRESS":
            return self.cancel()
        elif t in ("WHEELUPMOUSE", "WHEELDOWNMOUSE"):
            sign = -1.0 if t == "WHEELUPMOUSE" else 1.0  # wheel up lifts the brush
            self.press_mm = float(np.clip(self.press_mm + sign * WHEEL_STEP_MM, 0.0, self.L))
        elif t in ANGLE_KEYS and v == "PRESS":
            axis, sign = ANGLE_KEYS[t]
            step = self.step_deg * (2.0 if self.left_held else 1.0) * (4.0 if ev.shift else 1.0)
            limit = ANGLE_LIMIT if axis < 2 else 180.0
            self.angles[axis] = np.clip(self.angles[axis] + sign * step, -limit, limit)
        return self.state

    def dip(
        self,
        depth: float,
        color,
        wetness: float,
        time: float | None = None,
        follows_ink: bool = False,
    ):
        """A dip before the next sample, recorded like any other dip event; samples due by
        ``time`` come before it. ``follows_ink``: it loads the recording's ink colour (see
        ``Dip``), ``color`` being the colour that is now."""
        if time is not None:
            self._produce_until(self._clock(LiveEvent("D", time=time)))
        rec = self.sim.rec
        if not rec.dips:  # keep the implicit default dip at the start
            rec.dips = list(self.sim.dips)
        dp = Dip(self._n, float(depth), tuple(float(c) for c in color), float(wetness), follows_ink)
        rec.dips.append(dp)
        self.sim.dips = rec.dips

    def _land(self):
        """The landing: ``land`` samples hovering where the brush goes down, inserted before
        the press; the stroke's clock moves back as much, so the samples still come when due."""
        self.down = False
        for _ in range(self.land):
            self._append(self.pose())
        self._t0 -= self.land * self.period

    def keep(self) -> str:
        """The stroke is kept: the brush lifts in place (``lift`` samples hovering), the engine
        catches up with the clock, the recording is final."""
        if self.down:
            self.down = False
            for _ in range(self.lift):
                self._append(self.pose())
        self.advance()
        self.sim.rec.samples = self._buf[: self._n].copy()
        self.sim.let_go(self._hold)
        self.state = "FINISHED"
        return self.state

    def undo(self, now: float) -> str:
        """Ctrl+Z: the stroke painted so far is taken back and painting goes on, the brush
        hovering under the pointer, the clock starting again now; with nothing painted yet,
        painting ends: 'UNDO' (the caller takes back the last stroke kept before)."""
        if not self.pressed:
            self.cancel()
            return "UNDO"
        self._back()
        self.down = self.left_held = self.pressed = False
        self._t0 = self._t = now
        self._anchor = (now, self.x, self.y)
        self._moves = []
        self._hold = self.sim.hold()
        return self.state

    def _back(self):
        """The simulation and the recording exactly as at the stroke's start; the hold ends."""
        self.sim.take_back(self._hold)
        self.sim.rec.samples = self._buf[: self.n0].copy()
        self.sim.rec.dips = list(self._dips0)
        self.sim.dips = list(self._sim_dips0)
        self._n = self.n0

    def cancel(self) -> str:
        self._back()
        self.state = "CANCELLED"
        return self.state


def _spread_bursts(times: np.ndarray, stall_s: float) -> np.ndarray:
    """Blender does not stamp events with the time they happened: positions queued while the UI
    loop stalled are handled together after it, all at about the same time. Each such burst (a
    gap longer than ``stall_s`` followed by events within BURST_S of each other) is spread
    evenly over the gap, as the pointer moved through it."""
    times = times.copy()
    for i in np.nonzero(np.diff(times) > stall_s)[0] + 1:
        end = i + int(np.searchsorted(times[i:], times[i] + BURST_S, side="right"))
        n = end - i
        times[i:end] = times[i - 1] + (times[end - 1] - times[i - 1]) * np.arange(1, n + 1) / n
    return times
