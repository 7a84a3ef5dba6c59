# SPDX-License-Identifier: GPL-3.0-or-later
"""Sampling of the input data (Sec. 4): 6-DOF samples and the inertia predictor (Eq. 9)."""

from __future__ import annotations

from collections import deque

import numpy as np

# Paper's defaults (Sec. 4): el = 4, wei_1..4 = 4, 2, 1, 1, wei_sam = 0.6.
DEFAULT_WEIGHTS = (4.0, 2.0, 1.0, 1.0)
DEFAULT_WEI_SAM = 0.6


class InertiaPredictor:
    """S^t = wei_sam * Sam^t + (1 - wei_sam) * M^t, M^t = Vel^t dT + S^{t-1} (Eq. 9), with
    Vel^t the weighted mean of the last el displacements of the virtual position S."""

    def __init__(self, dt: float, weights=DEFAULT_WEIGHTS, wei_sam: float = DEFAULT_WEI_SAM):
        if not dt > 0:
            raise ValueError("sampling interval dT must be positive")
        self.dt = float(dt)
        self.weights = np.asarray(weights, dtype=float)
        self.wei_sam = float(wei_sam)
        self.history: deque = deque(maxlen=len(self.weights) + 1)  # S^{t-1}, S^{t-2}, ...
        self.velocity = np.zeros(6)

    def reset(self):
        self.history.clear()
        self.velocity = np.zeros(6)

    def estimate_velocity(self) -> np.ndarray:
        """Vel^t = sum_k wei_k (S^{t-k} - S^{t-k-1}) / dT / sum_k wei_k, over the history kept."""
        return np.array(self._velocity([s.tolist() for s in self.history]))

    def _velocity(self, h: list) -> list:
        """``estimate_velocity`` of the history as lists of Python floats (h[0] = S^{t-1}): the
        same operations in the same order as on arrays (numpy's sum over the displacements
        starts from 0.0, then adds them in order), without a numpy call per step (issue 28)."""
        n = min(len(self.weights), len(h) - 1)
        if n <= 0:
            return [0.0] * 6
        dt = self.dt
        w = self.weights[:n].tolist()
        total = 0.0
        for wk in w:
            total += wk
        vel = [0.0] * len(h[0])
        for k in range(n):
            wk = w[k]
            vel = [v + wk * ((a - b) / dt) for v, a, b in zip(vel, h[k], h[k + 1], strict=True)]
        return [v / total for v in vel]

    def __call__(self, sample) -> np.ndarray:
        sam = np.asarray(sample, dtype=float)
        if not self.history:
            s = sam.copy()
            self.velocity = np.zeros(6)
        else:
            # on Python floats, element by element as the arrays' operations (issue 28)
            h = [x.tolist() for x in self.history]
            vel = self._velocity(h)
            dt, ws = self.dt, self.wei_sam
            rest = 1.0 - ws
            h0 = h[0]
            s = [  # Eq. 9: M^t = Vel^t dT + S^{t-1}
                ws * a + rest * (v * dt + b) for a, v, b in zip(sam.tolist(), vel, h0, strict=True)
            ]
            # the brush's velocity for Eq. 12 and 16 is the motion of the virtual position
            self.velocity = np.array([(a - b) / dt for a, b in zip(s, h0, strict=True)])
            s = np.array(s)
        self.history.appendleft(s)
        return s

    def state(self):
        return [h.copy() for h in self.history], self.velocity.copy()

    def set_state(self, state):
        hist, vel = state
        self.history = deque([h.copy() for h in hist], maxlen=len(self.weights) + 1)
        self.velocity = vel.copy()
