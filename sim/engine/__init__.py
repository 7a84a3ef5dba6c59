# SPDX-License-Identifier: GPL-3.0-or-later
"""Running a recording through the brush and the paper (layer 5; the paper's data flow, Sec.
3): the simulation of 6-DOF samples into ink on the paper, on flat paper or a surface
(``simulation``: Simulation, render), seeking it to any sample through snapshots
(``timeline``), its checkpoints on disk (``checkpoints``), live painting, sample by sample
from events (``live``), and the recording as pen strokes for Grease Pencil (``pen``).

May import: ``core``, ``brush``, ``paper``, ``surface``."""
