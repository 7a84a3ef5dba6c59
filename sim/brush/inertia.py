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
        h = list(self.history)  # h[0] = S^{t-1}
        n = min(len(self.weights), len(h) - 1)
        if n <= 0:
            return np.zeros(6)
        w = self.weights[:n]
        diffs = np.array([(h[k] - h[k + 1]) / self.dt for k in range(n)])
        return (w[:, None] * diffs).sum(axis=0) / w.sum()

    def __call__(self, sample) -> np.ndarray:
        sam = np.asarray(sample, dtype=float)
        if not self.history:
            s = sam.copy()
            self.velocity = np.zeros(6)
        else:
            vel = self.estimate_velocity()
            m = vel * self.dt + self.history[0]  # M^t
            s = self.wei_sam * sam + (1.0 - self.wei_sam) * m  # Eq. 9
            # the brush's velocity for Eq. 12 and 16 is the motion of the virtual position
            self.velocity = (s - self.history[0]) / self.dt
        self.history.appendleft(s)
        return s

    def state(self):
        return [h.copy() for h in self.history], self.velocity.copy()

    def set_state(self, state):
        hist, vel = state
        self.history = deque([h.copy() for h in hist], maxlen=len(self.weights) + 1)
        self.velocity = vel.copy()
