# SPDX-License-Identifier: GPL-3.0-or-later
"""Virtual Hairy Brush engine: the solid-model brush, ink and paper of Xu et al., "A Solid Model
Based Virtual Hairy Brush" (Eurographics 2002). numpy and geomdl only; never bpy."""

from .brush.inertia import InertiaPredictor
from .brush.primitive import HairyBrush, rotation_matrix
from .core.params import BrushGeometry, InkSpec, PaperSpec, ParameterError, QualityParams
from .core.recording import Dip, Recording, RecordingError
from .engine.simulation import Simulation, render

__all__ = [
    "BrushGeometry",
    "Dip",
    "HairyBrush",
    "InertiaPredictor",
    "InkSpec",
    "PaperSpec",
    "ParameterError",
    "QualityParams",
    "Recording",
    "RecordingError",
    "Simulation",
    "render",
    "rotation_matrix",
]
