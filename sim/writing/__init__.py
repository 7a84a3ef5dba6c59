# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing a character from stroke data with the brush (layer 6; Sec. 9, automatic imitation):
strokes as 6-DOF samples (``strokes``), the bundled and hanzi-writer character data
(``hanzi``; all of hanzi-writer-data in one lazily read file, ``bundle``), outlines and medians
(``outline``; their polygons' fill and distances, ``polygons``; hooks' feet, ``feet``), the
brush's measured response and its calibration (``response``), the plan of the writing
(``planner``), practice passes and their corrections (``practice``) and the writer that puts
them together (``writer``); whole works from text, signed and sealed, written with one brush
into one recording (the subpackage ``work``).

May import: ``core``, ``image``, ``brush``, ``paper``, ``engine``."""
