# SPDX-License-Identifier: GPL-3.0-or-later
"""The paper (layer 3; Sec. 8 of the paper): absorption and drying (Eq. 24), saturation (Eq.
25), colour and dry brush (Eq. 26-27), the grain and the fibre (``paper``: Paper), and the
paper shown while it changes, a tile at a time (``display``).

May import: ``core``, ``image``."""
