# SPDX-License-Identifier: GPL-3.0-or-later
"""The sheet's grain: a fixed value per pixel (or per point of any lattice) from a hash, the same
in every step, snapshot and replay (``paper_grain``)."""

from __future__ import annotations

import numpy as np


def paper_grain(index, seed: int = 0) -> np.ndarray:
    """Model addition (not in the paper): the sheet's grain, a fixed value in [0, 1) per pixel
    (a hash of the pixel's index in the sheet, so the same pixel has the same grain in every
    step, in a snapshot and in a replay; no generator is drawn, so the brush's draws are
    unchanged). A pixel where the grain is high takes a little less of the liquid the hair
    offers, one where it is low a little more (times 1 - GRAIN_DEPTH fibre (grain - 1/2),
    ``fibre`` the sheet's): where the hair is loaded every pixel still takes the ink's colour;
    where it offers little (a dry or fast stroke) the grain shows in the grey."""
    # the seed picks the sheet (the recording's seed: the one seeded generator's, so the same
    # recording and seed give the same sheet, another seed another one)
    offset = (0x9E3779B97F4A7C15 + int(seed) * 0xD1B54A32D192ED03) % 2**64
    x = np.atleast_1d(np.asarray(index, dtype=np.uint64)) + np.uint64(offset)  # wraps mod 2**64
    x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    x = (x ^ (x >> np.uint64(31))).reshape(np.shape(index))
    return (x >> np.uint64(40)).astype(np.float64) / float(1 << 24)
