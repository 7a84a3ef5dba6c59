# SPDX-License-Identifier: GPL-3.0-or-later
"""Imitating a picture of writing (layer 7; Sec. 9, automatic imitation): the ink read off the
picture (``ink``), its strokes (``strokes``), their direction and writing order (``order``),
each stroke's own ink traced into character data (``outline``), a piece of several characters
(``piece``), and the picture read and written with the brush (``imitate``).

May import: ``core``, ``image``, ``engine``, ``writing``."""
