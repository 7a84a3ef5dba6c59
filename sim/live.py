# SPDX-License-Identifier: GPL-3.0-or-later
"""Live painting (Sec. 4, Fig. 6(b)): mouse, keyboard and tablet events become 6-DOF samples
taken on a clock, fed to a running Simulation as they come.

Fig. 6(b) (READING-NOTES.md): moving the mouse sets x, y; the wheel sets z (how far the brush is
pressed); q/w, e/r, c/v decrease/increase d, q and r. Holding the left button doubles a key's
step; the paper multiplies it by four with the right button, which Blender reserves for
cancelling, so Shift does that here. A tablet's pressure drives z and its tilt drives d and q.

Event names and values are Blender's (``event.type``/``event.value``), so the Blender operator
passes its events straight through, and tests drive this class with the same sequences.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .engine import Simulation
from .recording import Dip, quantise

HOVER_MM = 5.0  # brush base above the hair length while the button is up
WHEEL_STEP_MM = 0.5
MAX_TILT_DEG = 60.0
ANGLE_LIMIT = 80.0
ANGLE_KEYS = {"Q": (0, -1), "W": (0, +1), "E": (1, -1), "R": (1, +1), "C": (2, -1), "V": (2, +1)}
KEEP_KEYS = {"RET", "NUMPAD_ENTER"}
CANCEL_KEYS = {"ESC", "RIGHTMOUSE"}


@dataclass
class LiveEvent:
    type: str
    value: str = "PRESS"
    paper_xy: tuple | None = None  # mm on the paper under the cursor; None when off the paper
    pressure: float = 1.0
    tilt: tuple = (0.0, 0.0)
    is_tablet: bool = False
    shift: bool = False


class LiveBrush:
    """A stroke being painted onto an existing Simulation (which may already hold a recording).
    ``keep()`` leaves the new samples in ``sim.rec``; ``cancel()`` puts the simulation back
    exactly as it was."""

    def __init__(self, sim: Simulation, press_mm: float = 4.0, step_deg: float = 2.0, xy=None):
        self.sim = sim
        self.press_mm = float(press_mm)
        self.step_deg = float(step_deg)
        self.L = sim.geometry.hair_length_mm
        self.n0 = len(sim.rec.samples)
        if sim.index != self.n0:
            raise ValueError("the simulation must have run to the end of its recording")
        self._snapshot = sim.snapshot()
        self._dips0 = list(sim.rec.dips)
        self._sim_dips0 = list(sim.dips)
        last = sim.rec.samples[-1] if self.n0 else np.zeros(6)
        self.x, self.y = (float(v) for v in (xy if xy is not None else last[:2]))
        self.angles = np.zeros(3)  # key offsets of d, q, r
        self.tilt = np.zeros(2)
        self.pressure = 1.0
        self.tablet = False
        self.down = False
        self.left_held = False
        self.state = "RUNNING"
        self._buf = np.array(sim.rec.samples, dtype=float, copy=True)
        self._n = self.n0

    # ------------------------------------------------------------------ the current pose
    def pose(self) -> np.ndarray:
        if self.down:
            press = self.press_mm * (self.pressure if self.tablet else 1.0)
            z = self.L - press
        else:
            z = self.L + HOVER_MM
        d = self.angles[0] + self.tilt[0] * MAX_TILT_DEG
        q = self.angles[1] + self.tilt[1] * MAX_TILT_DEG
        d, q = np.clip([d, q], -ANGLE_LIMIT, ANGLE_LIMIT)
        return np.array([self.x, self.y, z, d, q, self.angles[2]])

    @property
    def new_samples(self) -> np.ndarray:
        return self._buf[self.n0 : self._n]

    # ------------------------------------------------------------------ events
    def handle(self, ev: LiveEvent) -> str:
        """Process one event; returns 'RUNNING', 'FINISHED' (stroke kept) or 'CANCELLED'."""
        if self.state != "RUNNING":
            return self.state
        t, v = ev.type, ev.value
        if ev.paper_xy is not None and t in ("MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "LEFTMOUSE"):
            self.x, self.y = float(ev.paper_xy[0]), float(ev.paper_xy[1])
        if ev.is_tablet and t in ("MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "LEFTMOUSE"):
            self.tablet = True
            self.pressure = float(np.clip(ev.pressure, 0.0, 1.0))
            self.tilt = np.clip(np.asarray(ev.tilt, dtype=float), -1.0, 1.0)
        if t == "LEFTMOUSE":
            if v == "PRESS":
                self.left_held = self.down = True
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
        elif t == "TIMER":
            self.tick()
        return self.state

    def tick(self):
        """Take one sample of the current pose and simulate it."""
        if self._n == len(self._buf):
            grown = np.empty((max(64, 2 * len(self._buf)), 6))
            grown[: self._n] = self._buf[: self._n]
            self._buf = grown
        self._buf[self._n] = quantise(self.pose())  # as stored in recordings
        self._n += 1
        self.sim.rec.samples = self._buf[: self._n]
        self.sim.step()

    def dip(self, depth: float, color, wetness: float):
        """A dip before the next sample, recorded like any other dip event."""
        rec = self.sim.rec
        if not rec.dips:  # keep the implicit default dip at the start
            rec.dips = list(self.sim.dips)
        dp = Dip(self._n, float(depth), tuple(float(c) for c in color), float(wetness))
        rec.dips.append(dp)
        self.sim.dips = rec.dips

    def keep(self) -> str:
        self.sim.rec.samples = self._buf[: self._n].copy()
        self.state = "FINISHED"
        return self.state

    def cancel(self) -> str:
        self.sim.restore(self._snapshot)
        self.sim.rec.samples = self._buf[: self.n0].copy()
        self.sim.rec.dips = self._dips0
        self.sim.dips = self._sim_dips0
        self._n = self.n0
        self.state = "CANCELLED"
        return self.state
