# SPDX-License-Identifier: GPL-3.0-or-later
"""The Blender glue: Blender data to the engine's inputs (``sim``) and back. Operators and panels
call these modules; these modules never call operators or panels.

What each module owns, in the order they may import each other (a module imports only those
before it): ``runtime`` (the one object that holds the runtime state: caches, the playback, the
live painter), ``checks`` (the settings read and checked, the paper's size and memory),
``transforms`` (matrices and 6-DOF samples), ``frames`` (the timeline), ``recordings`` (the
recording text in the .blend), ``images`` (the paper image), ``keyframes`` (the brush empty's
animation), ``surfaces`` (a mesh that is the paper), ``primitives`` (the NURBS objects of the
writing primitives), ``playback`` (the artwork at any frame), ``materials``, ``presets``,
``scene_setup`` (building the brush and paper), ``properties`` (``scene.hairy_brush``), ``jobs``
(long work with a progress bar and Esc), ``writing`` (Write Character and Imitate Picture into
the scene), ``work`` (a work written from text: Write Text, Sign and Seal, Write Cell Again)
and ``handlers`` (frame change, undo, save, load)."""
