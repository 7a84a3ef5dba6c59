# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written from text (issue 27): a poem becomes a signed, sealed sheet - the text's
glyphs and punctuation (``text``, ``marks``), where they go on the paper (``layout``), each
character varied as a calligrapher varies it (``variation``), the seal (``seal``) and the
practice grid printed on the paper (``overlay``), the work written with one brush into one
recording, its cells simulated side by side (``compose``), and a work continued, signed or one
of its cells written again (``edit``).

What a caller (the command line, the Blender operator) uses, all pure, none of it Blender's:

- ``compose.compose(text, layout.Settings(...), template, char_px= | px_per_mm=, data=,
  punctuation=, skip_missing=, options=compose.Options(passes, dip_every, variation),
  mapper=, progress=, response=)`` -> (recording, layout, skipped): a new work. With both
  ``Settings.char_mm`` and ``Settings.paper_mm`` it is laid on that paper from its corner, room
  left for more (an empty recording in Blender); with only one of them the other follows.
- ``edit.append_text(recording, text, new_line=, ...)`` -> (recording, new cells): more text
  after the last character, on the same paper; ``edit.sign_work(recording, signature, seal,
  seal_style, ...)``: the signature and seal after the text; ``edit.rewrite_cell(recording,
  index, seed=None, ...)``: one cell written again, every other cell's ink untouched.
- ``compose.render(recording, mapper=)`` -> (paper, cells' ink): the cells simulated side by
  side, bit for bit as ``Simulation(recording).run()``; ``compose.image8(paper, recording)``:
  the image with the grid under the ink and the seal over it (``overlay.Overlay`` does it a
  band of rows at a time for any paper, e.g. one played back frame by frame).
- The layout in the recording: ``layout.Layout.from_dict(recording.extra["work"]["layout"])``,
  every cell's em box in paper mm (x right, y up; UV = mm / the paper's size) and its samples.

A ``mapper(fn, tasks, done)`` returns ``[fn(t) for t in tasks]`` in order (``compose.local_map``
here; the command line's runs them in processes or on a Dask cluster); a Blender job can hand
in one that reports progress and stops between tasks, leaving nothing half written.

Part of ``sim.writing``: may import ``core``, ``image``, ``brush``, ``paper``, ``engine``."""
