# SPDX-License-Identifier: GPL-3.0-or-later
"""Virtual Hairy Brush engine: the solid-model brush, ink and paper of Xu et al., "A Solid Model
Based Virtual Hairy Brush" (Eurographics 2002). numpy and geomdl only; never bpy.

Its packages, in the order of the paper's data flow; each imports only packages before it (its
``__init__`` says which; tests/test_layout.py checks): ``core`` (parameters, recordings,
frames, NURBS), ``image`` (PNG, filters), ``brush`` (the primitive, dynamics, ink, inertia,
the mark), ``paper``, ``surface`` (writing on a 3D mesh), ``engine`` (the simulation, the
timeline, live painting), ``writing`` (characters from stroke data), ``picture`` (imitating a
picture), ``fitting`` (Sec. 7.2's fit) and ``cli`` (``python -m sim``)."""

import os

# The engine's matrices are small: BLAS threads cost more than they give and fight the worker
# processes of write-set and fit; each thread also maps a workspace of its own, and OpenBLAS
# spins for ever when a mapping is refused under a memory limit (issue 30, sim/cli/memory.py).
# One thread, unless the caller chose (this acts only if numpy is not loaded yet).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from .brush.inertia import InertiaPredictor
from .brush.primitive import HairyBrush
from .core.frames import rotation_matrix
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
