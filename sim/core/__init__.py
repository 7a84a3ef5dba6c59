# SPDX-License-Identifier: GPL-3.0-or-later
"""The engine's core types and formats (layer 0): the parameters and presets (``params``), the
recording (``recording``), rotations and vectors (``frames``), sums, products and
transcendentals that give the same bits on any machine (``exact``), the NURBS sweep (``nurbs``),
the bounded JSON reader (``jsonio``), writing files whole or not at all (``files``) and the
scene units the Blender glue places things in (``placement``).

May import: nothing of ``sim`` (every other package builds on it)."""
