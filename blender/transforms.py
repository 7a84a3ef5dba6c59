# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender's matrices and the engine's 6-DOF samples: the maths is in ``sim.core.placement``;
here it meets the settings (the paper's size) and objects."""

from __future__ import annotations

import numpy as np

from ..sim.core import placement
from . import checks

MM = placement.MM


def engine_to_paper_local(st) -> np.ndarray:
    """4x4: engine mm (paper corner origin) -> paper object's local metres (centred)."""
    return placement.engine_to_paper_local(st.paper_width_mm, st.paper_height_mm)


def engine_to_world(st, paper_obj) -> np.ndarray:
    return np.array(paper_obj.matrix_world) @ engine_to_paper_local(st)


def sample_from_matrices(st, brush_mw, paper_mw) -> np.ndarray:
    """One 6-DOF sample from the brush empty's and the paper's world matrices."""
    try:
        return placement.sample_from_matrices(
            brush_mw, paper_mw, st.paper_width_mm, st.paper_height_mm
        )
    except placement.PlacementError as exc:
        raise checks.UserError(str(exc)) from None


def matrix_from_sample(st, paper_mw, sample) -> np.ndarray:
    """World matrix of the brush empty for a 6-DOF sample."""
    return placement.matrix_from_sample(paper_mw, sample, st.paper_width_mm, st.paper_height_mm)
