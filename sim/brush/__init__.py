# SPDX-License-Identifier: GPL-3.0-or-later
"""The hairy brush (layer 2; Sec. 4-6 of the paper): the writing primitives and their NURBS
surfaces (``primitive``: HairyBrush, Sections), the primitive's and key point's fields declared
once (``state``), the ink the hair carries (``ink``, Eq. 7-8, 21), the hair's dynamics
(``dynamics``, Eq. 10-20), the inertia predictor (``inertia``, Eq. 9) and the brush's cut by the
paper with its per-pixel ink (``mark``, Eq. 21-23).

May import: ``core``."""
