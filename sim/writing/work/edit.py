# SPDX-License-Identifier: GPL-3.0-or-later
"""Going on with a work, and changing one cell of it, as the Blender operator does
(``hairy_brush.write_text``): text appended after the last character written (the next place,
or a new line when asked) on the same paper, the earlier samples and dips untouched; one cell
written again with another seed, every other cell's samples and ink untouched (each cell starts
with its own restarting dip, sim.writing.work.compose). Both return a new recording."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...core.params import ParameterError
from ...core.recording import Dip, Recording, quantise
from ..response import calibrate
from .compose import (
    WORK_KEY,
    Continued,
    Options,
    _travel,
    assemble,
    cell_task,
    local_map,
    work_of,
    write_cell,
)
from .layout import TEXT, Cell, Layout, sign
from .text import SPACE, MissingCharacters, drop, missing_characters, parse_text


def _template(rec: Recording) -> Recording:
    """The recording's settings (brush, paper, ink, quality, rate, seed), no samples."""
    return replace(rec, samples=np.zeros((1, 6)), dips=[], extra={})


def _with_layout(rec: Recording, lay: Layout, samples, dips) -> Recording:
    work = {**work_of(rec), "layout": lay.to_dict()}
    return replace(rec, samples=samples, dips=dips, extra={**rec.extra, WORK_KEY: work})


def _layout(rec: Recording) -> Layout:
    work = work_of(rec)
    if work is None:
        raise ParameterError("the recording holds no work (compose one first)")
    return Layout.from_dict(work["layout"])


def place_text(lay: Layout, lines, new_line: bool = False) -> list[Cell]:
    """Cells for ``lines`` (sim.writing.work.text) after the last character of the work's
    text: on at its next place, a newline starting the next line; every cell on the paper
    (ParameterError naming how many would fall off it)."""
    line, index = lay.next_place(new_line)
    seed = max((c.seed for c in lay.cells), default=-1) + 1
    pad = ((lay.pitch_mm - lay.char_mm) / 2, (lay.line_mm - lay.char_mm) / 2)
    cells, off = [], 0
    for n, glyphs in enumerate(lines):
        if n:
            line, index = line + 1, 0
        for g in glyphs:
            if index >= lay.per_line:
                line, index = line + 1, 0
            if g.kind != SPACE:
                x, y = lay.place(line, index)
                inside = 0 <= x and x + lay.char_mm <= lay.width_mm and 0 <= y
                inside = inside and y + lay.char_mm <= lay.height_mm
                off += not inside
                cells.append(
                    Cell(g.text, TEXT, x, y, lay.char_mm, line, index, g.kind == "mark", seed, pad)
                )
                seed += 1
            index += 1
    if off:
        raise ParameterError(
            f"the text does not fit the paper: {off} of its {len(cells)} characters would fall "
            "off it (a larger paper, or a smaller size)"
        )
    return cells


def append_text(
    rec: Recording,
    text: str,
    *,
    data=None,
    punctuation: str = "omit",
    skip_missing: bool = False,
    new_line: bool = False,
    options: Options | None = None,
    mapper=local_map,
    progress=None,
    response=None,
) -> tuple[Recording, list[Cell]]:
    """The work with ``text`` written after its last character (a new line first when
    ``new_line``): (the new recording, the new cells). The paper, the earlier samples, dips and
    cells are kept as they are; the brush goes on with the ink it had left. ``response``: the
    brush's calibrated response (measured when not given)."""
    options = options or Options()
    lay = _layout(rec)
    if lay.seal or any(c.role != TEXT for c in lay.cells):
        raise ParameterError("the work is signed: no text goes after its signature and seal")
    lines = parse_text(text, punctuation)
    missing = missing_characters(lines, data)
    if missing and not skip_missing:
        raise MissingCharacters(missing, data)
    lines = drop(lines, missing)
    cells = place_text(lay, lines, new_line)
    if not cells:
        raise ParameterError("the text has nothing to write (only spaces and punctuation?)")
    template = _template(rec)
    response = response or calibrate(template)
    tasks = [
        cell_task(
            c, lay, template, response, rec.px_per_mm, options.passes, data, options.variation
        )
        for c in cells
    ]
    done = None if progress is None else (lambda k, n: progress(k / n))
    written = mapper(write_cell, tasks, done)
    last = lay.cells[-1] if lay.cells else None
    base = Continued(
        rec.samples if last else np.zeros((0, 6)),
        list(rec.dips) if last else [],
        None if last is None else last.load - last.used,
        len(lay.cells),
    )
    step = response.speed_mm_s / template.sample_rate_hz
    samples, dips, _ = assemble(template, cells, written, step, options.dip_every, base)
    lay.cells.extend(cells)
    return _with_layout(rec, lay, samples, dips), cells


def rewrite_cell(
    rec: Recording,
    index: int,
    seed: int | None = None,
    *,
    data=None,
    options: Options | None = None,
    mapper=local_map,
    response=None,
) -> Recording:
    """The work with cell ``index`` (of the layout's cells, in writing order) written again
    with another ``seed`` (default: one no cell has): its own variation, practice and random
    stream; it starts with the same load. Every other cell's samples are kept, and so is its
    ink; the cells after it keep their time too unless the new writing is longer (then they
    come that much later)."""
    options = options or Options()
    lay = _layout(rec)
    if not (isinstance(index, int) and 0 <= index < len(lay.cells)):
        raise ParameterError(f"no cell {index!r}: the work has {len(lay.cells)} cells")
    old = lay.cells[index]
    if seed is None:
        seed = max(c.seed for c in lay.cells) + 1
    cell = replace(old, seed=int(seed))
    template = _template(rec)
    response = response or calibrate(template)
    task = cell_task(
        cell, lay, template, response, rec.px_per_mm, options.passes, data, options.variation
    )
    (w,) = mapper(write_cell, [task], None)
    a, b = old.samples
    s = np.array(w.samples, dtype=float)
    s[:, :2] += (cell.x, cell.y)
    if a > 0:
        step = response.speed_mm_s / template.sample_rate_hz
        s = np.concatenate([_travel(rec.samples[a - 1], s[0], step), s])
    s = quantise(s)
    inside = len(s) - len(w.samples)  # the travel to the cell comes first
    if len(s) < b - a:  # the brush waits in the air: the later cells keep their time
        s = np.concatenate([s, np.repeat(s[-1:], b - a - len(s), axis=0)])
    shift = len(s) - (b - a)
    samples = np.concatenate([rec.samples[:a], s, rec.samples[b:]])
    _, _, _, ink = template.resolve()
    dips = []
    for dp in rec.dips:
        if dp.before_sample == a and dp.restart is not None:
            dips.append(replace(dp, restart=cell.seed))
            dips += [  # the new writing's own dips inside the character
                Dip(a + inside + j, ink.depth, tuple(ink.color), ink.wetness, follows_ink=True)
                for j in w.dips
            ]
        elif dp.before_sample >= b:
            dips.append(replace(dp, before_sample=dp.before_sample + shift))
        elif not a < dp.before_sample < b:
            dips.append(dp)
    cell.samples = (a, a + len(s))
    cell.used = cell.load - ((1.0 if w.dips else cell.load) - w.used)
    lay.cells[index] = cell
    for c in lay.cells[index + 1 :]:
        c.samples = (c.samples[0] + shift, c.samples[1] + shift)
    return _with_layout(rec, lay, samples, dips)


def sign_work(
    rec: Recording,
    signature: str,
    seal: str = "",
    seal_style: str = "baiwen",
    *,
    data=None,
    options: Options | None = None,
    mapper=local_map,
    response=None,
) -> Recording:
    """The work signed (its signature written after its text, as ``compose`` places it) and
    sealed; the earlier samples, dips and cells kept. A character without stroke data raises
    MissingCharacters."""
    from .compose import _glyphs_of
    from .text import CHAR, Glyph

    options = options or Options()
    lay = _layout(rec)
    signature, seal = _glyphs_of(signature), _glyphs_of(seal)
    missing = missing_characters([[Glyph(c, CHAR) for c in signature + seal]], data)
    if missing:
        raise MissingCharacters(missing, data)
    if not (signature or seal):
        raise ParameterError("give a signature or a seal")
    cells = sign(lay, signature, seal, seal_style)
    template = _template(rec)
    response = response or calibrate(template)
    tasks = [
        cell_task(
            c, lay, template, response, rec.px_per_mm, options.passes, data, options.variation
        )
        for c in cells
    ]
    written = mapper(write_cell, tasks, None)
    last = next(c for c in reversed(lay.cells) if c.samples != (0, 0) or c is lay.cells[0])
    base = Continued(
        rec.samples, list(rec.dips), last.load - last.used, len(lay.cells) - len(cells)
    )
    step = response.speed_mm_s / template.sample_rate_hz
    samples, dips, _ = assemble(template, cells, written, step, options.dip_every, base)
    work = {**work_of(rec), "layout": lay.to_dict()}
    if seal:
        from ..hanzi import lookup

        work["seal_glyphs"] = [{"strokes": lookup(c, data)["strokes"]} for c in seal]
    return replace(rec, samples=samples, dips=dips, extra={**rec.extra, WORK_KEY: work})
