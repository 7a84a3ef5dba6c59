# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written from text (issue 27): a poem becomes a signed, sealed sheet - the text's
glyphs and punctuation (``text``, ``marks``), where they go on the paper (``layout``), each
character varied as a calligrapher varies it (``variation``), the seal (``seal``) and the
practice grid printed on the paper (``overlay``), and the work written with one brush into one
recording, its cells simulated side by side (``compose``).

Part of ``sim.writing``: may import ``core``, ``image``, ``brush``, ``paper``, ``engine``."""
