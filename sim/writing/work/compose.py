# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written as a calligrapher writes it: one brush, one recording for the whole sheet.

The text is laid out (``layout``); each cell's character is varied (``variation``) and written
by the writer (``sim.writing.writer.write_character``: its plan and practice passes) at the
work's one size - every cell on its own, so the cells are written side by side, in processes
or on a cluster (``mapper``) - and the writings are put on the paper in order, the brush
travelling in the air from one to the next (``assemble``).

The ink: the brush is dipped before the first character and again when its ink runs low. What
a character uses of a full load is measured on the writer's own run of it (the brush's load,
``brush_load``, after one dip at its start, against a full one), and the load runs down from
character to character; the brush is dipped before a character that would end below
``LOW_INK`` (or every ``dip_every`` characters), and inside a character, as the writer dips,
before a stroke it would begin with too little ink (``writer.dips_when_low``: a large or
many-stroked character is not written to illegible grey on one load). Each cell starts with a
*restarting dip* (``Dip.restart``): the brush re-formed on the inkstone, as new, carrying the
load that is left (the dip's wetness), its random draws from the cell's own stream. So the tone
runs from wet and dark after a dip to dry, with flying white, before the next, and every cell
depends on nothing before it: the cells are simulated side by side, each on its own paper, and
put together bit for bit as the one run of the recording (``render``; ``sim render`` makes the
same image), one cell can be written again without touching the others (``rewrite_cell``), and
text can be added after the last character (``append_text``).

Model additions (not in the paper): the re-formed brush at each character's start, the load
measured as the area-weighted mean wetness of the key points."""

from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

import numpy as np

from ...brush.ink import brush_load, full_load
from ...core.params import MAX_PAPER_PIXELS, MAX_PAPER_SIDE_PX, ParameterError
from ...core.recording import PAPER_MM_RANGE, PX_PER_MM_RANGE, Dip, Recording, quantise
from ...engine.simulation import Simulation
from ..brush_size import brush_for_size
from ..hanzi import lookup
from ..response import Response, calibrate
from ..writer import LOW_INK as WRITER_LOW_INK
from ..writer import auto_size_mm, write_character
from . import variation as var
from .layout import Cell, Layout, Settings, lay_out
from .marks import mark_char
from .overlay import work_image8
from .text import CHAR, Glyph, MissingCharacters, drop, missing_characters, parse_text

WORK_KEY = "work"  # the recording's field that holds the work (Recording.extra)
WORK_VERSION = 1
# the brush is dipped before a character it would end with less than this share of a full load
# (measured on the poem: a character begun with 0.65 of a load is greyer and textured, one begun
# with 0.55 loses its last strokes; a calligrapher dips before the brush fails a character)
LOW_INK = 0.55
MIN_LOAD = 0.45  # with dip_every, a character starts with at least this share of a load


def longest_first(mapper, fn, tasks, costs, done=None) -> list:
    """``mapper(fn, tasks, done)`` with the costliest tasks handed out first (so no long task
    is left to run alone at the end); the results in the tasks' own order."""
    order = sorted(range(len(tasks)), key=lambda k: -costs[k])
    results = mapper(fn, [tasks[k] for k in order], done)
    out = [None] * len(tasks)
    for k, r in zip(order, results, strict=True):
        out[k] = r
    return out


def local_map(fn, tasks, done=None) -> list:
    """``[fn(t) for t in tasks]`` here, ``done(k, total)`` after each (the default mapper; the
    command line hands in processes or a Dask cluster, sim.fitting.cluster.map_tasks)."""
    out = []
    for t in tasks:
        out.append(fn(t))
        if done is not None:
            done(len(out), len(tasks))
    return out


# ------------------------------------------------------------------------------- the writing
class CellTask(NamedTuple):
    """One cell's writing: the (varied) stroke data, its em box in mm, the resolution, the
    work's settings with the cell's practice seed, the calibrated response, practice passes."""

    char: dict
    size_mm: float
    ppm: float
    template: Recording
    response: Response
    passes: int


class Written(NamedTuple):
    samples: np.ndarray  # (N, 6) on the writer's sheet: the em box, lower-left corner at 0
    used: float  # share of a full load the character used since its last dip
    # samples (of ``samples``) before which the writer dipped inside the character: a large
    # or many-stroked character the brush could not write on one load (``writer.dips_when_low``)
    dips: tuple = ()


def write_cell(task: CellTask) -> Written:
    """Write one cell's character (in a worker process or on a cluster: it reads nothing but
    its task)."""
    n_px = max(int(round(task.size_mm * task.ppm)), 1)
    rec, _, sim = write_character(
        task.char,
        n_px,
        task.template,
        size_mm=task.size_mm,
        response=task.response,
        dip_every_mm=None,  # dips inside the character when the brush runs low
        passes=task.passes,
        px_per_mm=task.ppm,
        paper=False,  # only the samples and the brush are kept: the cells are rendered again
    )
    full = full_load(task.template)
    used = max(full - brush_load(sim.brush), 0.0) / max(full, 1e-12)
    return Written(rec.samples, float(used), tuple(int(d.before_sample) for d in rec.dips[1:]))


def writing_cost(task: CellTask) -> float:
    """About how long a cell takes to write: the length of its medians on the paper."""
    medians = task.char["medians"]
    return task.size_mm * sum(float(np.abs(np.diff(np.asarray(m), axis=0)).sum()) for m in medians)


def practice_seed(seed: int, cell_seed: int) -> int:
    """The seed the writer practises a cell with (its own, from the work's)."""
    ss = np.random.SeedSequence([int(seed), int(cell_seed), 0x3173])
    return int(ss.generate_state(1, dtype=np.uint64)[0])


def glyph(cell: Cell, vertical: bool, data=None) -> dict:
    """The stroke data a cell's character is written from (a mark's shape for punctuation)."""
    if cell.mark:
        return mark_char(cell.char, vertical)
    d = lookup(cell.char, data)
    if d is None:
        raise MissingCharacters([cell.char], data)
    return d


def cell_task(cell: Cell, lay: Layout, template, response, ppm, passes, data, amount) -> CellTask:
    """The writing task of a cell; its variation (drawn from the work's seed and the cell's)
    is kept in the cell."""
    v = var.draw(template.seed, cell.seed, lay.vertical, 0.0 if cell.mark else amount)
    cell.variation = tuple(v.to_list())
    char = var.apply(glyph(cell, lay.vertical, data), v)
    own = replace(template, seed=practice_seed(template.seed, cell.seed))
    return CellTask(char, cell.size, ppm, own, response, passes)


# ------------------------------------------------------------------------------ the assembly
AIR_PACE = 6.0  # the hand between characters: steps of this many writing steps (the writer's
# own travel between strokes takes 2; a column's end to the next one's top is half a metre)


def _travel(a, b, step_mm: float) -> np.ndarray:
    """Samples in the air between two samples (neither included)."""
    k = max(int(np.linalg.norm(b[:2] - a[:2], axis=-1) / (AIR_PACE * step_mm)), 4)
    t = np.linspace(0.0, 1.0, k + 2)[1:-1, None]
    return a[None] * (1 - t) + b[None] * t


class Continued(NamedTuple):
    """Where a work goes on from: its samples and dips so far, the load left, cells before."""

    samples: np.ndarray
    dips: list
    load: float | None
    count: int


def assemble(template: Recording, cells, written, step_mm: float, dip_every=None, base=None):
    """The samples and dips of ``cells`` (in writing order, with their writings) after
    ``base`` (a Continued, or None for a new work): each writing placed in its cell, the brush
    travelling in the air between, a restarting dip before each (its load: what is left, or a
    full one when the brush is dipped). Updates each cell's samples, load, dip and use."""
    _, _, _, ink = template.resolve()
    base = base or Continued(np.zeros((0, 6)), [], None, 0)
    parts, dips = [], list(base.dips)
    at = len(base.samples)
    prev = base.samples[-1] if len(base.samples) else None
    load = base.load
    for k, (cell, w) in enumerate(zip(cells, written, strict=True)):
        s = np.array(w.samples, dtype=float)
        s[:, :2] += (cell.x, cell.y)
        if prev is not None:
            s = np.concatenate([_travel(prev, s[0], step_mm), s])
        s = quantise(s)
        n = base.count + k
        if load is None:
            dip = True
        elif dip_every:
            dip = n % dip_every == 0
        elif w.dips:  # it dips inside: begun as its writing was, from a load not yet low
            dip = load < WRITER_LOW_INK
        else:
            dip = load - w.used < LOW_INK
        load = 1.0 if dip else max(load, MIN_LOAD)
        wet = float(ink.wetness) * load
        dips.append(
            Dip(at, ink.depth, tuple(ink.color), wet, follows_ink=True, restart=int(cell.seed))
        )
        inside = len(s) - len(w.samples)  # the travel to the cell comes first
        dips += [
            Dip(at + inside + j, ink.depth, tuple(ink.color), ink.wetness, follows_ink=True)
            for j in w.dips
        ]
        after = (1.0 if w.dips else load) - w.used
        cell.samples, cell.load, cell.dip, cell.used = (at, at + len(s)), load, dip, load - after
        load = after
        at += len(s)
        parts.append(s)
        prev = s[-1]
    samples = np.concatenate([base.samples, *parts]) if parts else base.samples
    return samples, dips, load


def work_of(rec: Recording) -> dict | None:
    """The work a recording holds (its ``extra["work"]``), or None."""
    w = rec.extra.get(WORK_KEY)
    return w if isinstance(w, dict) and "layout" in w else None


def check_work(rec: Recording) -> None:
    """A recording's work, checked before any simulation (ParameterError names the field)."""
    from .overlay import _seal_glyphs

    w = rec.extra.get(WORK_KEY)
    if w is None:
        return
    if not isinstance(w, dict) or "layout" not in w:
        raise ParameterError("'work' must be an object with a 'layout'")
    lay = Layout.from_dict(w["layout"])
    if w.get("seal_glyphs"):
        _seal_glyphs(w["seal_glyphs"])
    for c in lay.cells:
        a, b = c.samples
        if not (isinstance(a, int) and isinstance(b, int) and 0 <= a <= b <= len(rec.samples)):
            raise ParameterError(
                f"'work.layout': cell {c.char!r} has samples outside the recording"
            )


def _recording(template: Recording, lay: Layout, samples, dips, ppm, seal_glyphs) -> Recording:
    work = {"version": WORK_VERSION, "layout": lay.to_dict(), "seal_glyphs": seal_glyphs}
    return replace(
        template,
        samples=samples,
        width_mm=lay.width_mm,
        height_mm=lay.height_mm,
        px_per_mm=ppm,
        brush=dict(template.brush),
        ink=dict(template.ink),
        quality=dict(template.quality),
        dips=dips,
        extra={**template.extra, WORK_KEY: work},
    )


def check_sheet(width_mm: float, height_mm: float, ppm: float) -> None:
    """The work's paper: sizes and a resolution a recording can hold (ParameterError)."""
    lo, hi = PX_PER_MM_RANGE
    if not lo <= ppm <= hi:
        raise ParameterError(
            f"the work's resolution is {ppm:.4g} px/mm; it must lie in [{lo:g}, {hi:g}] "
            "(change the character size in pixels, or the dpi)"
        )
    for side in (width_mm, height_mm):
        if not PAPER_MM_RANGE[0] <= side <= PAPER_MM_RANGE[1]:
            raise ParameterError(
                f"the work's paper would be {width_mm:.0f} x {height_mm:.0f} mm; each side must "
                f"lie in [{PAPER_MM_RANGE[0]:g}, {PAPER_MM_RANGE[1]:g}] mm"
            )
    w, h = round(width_mm * ppm), round(height_mm * ppm)
    if max(w, h) > MAX_PAPER_SIDE_PX or w * h > MAX_PAPER_PIXELS:
        raise ParameterError(
            f"the work's image would be {w} x {h} px; at most {MAX_PAPER_SIDE_PX} px a side "
            "(a smaller --char-size or --dpi, or more characters a line)"
        )


# ---------------------------------------------------------------------------------- compose
# practice passes a work's strokes get by default. The 20-character poem with its signature at
# the brush's own size is 24,000 samples and each pass simulates them again: measured (CPU
# seconds of the whole command, 256 px an em box) 82 s with 1 pass, 139 s with 2, 215 s with 4
# - on two free cores about 45, 70 and 110 s of waiting - for an IoU with the outlines of 0.80,
# 0.85 and 0.88 a character. At a sheet's scale one pass reads well; --passes 4 (the writer's
# own default) makes the finest sheet.
WORK_PASSES = 1


class Options(NamedTuple):
    """How the work is written: practice passes per stroke, characters between dips (None:
    when the ink runs low), how much the characters vary (1: a hand's usual, 0: none), whether
    a work not at the brush's own size is written with the brush made smaller or larger for
    it (``brush_size``; False: the brush as it is)."""

    passes: int = WORK_PASSES
    dip_every: int | None = None
    variation: float = 1.0
    fit_brush: bool = True


def natural_size_mm(chars, response: Response) -> float:
    """The em box at which the brush writes these characters best (the writer's own size for
    each, ``auto_size_mm``; their median, to half a millimetre): one size for the whole work."""
    sizes = [auto_size_mm(c, response) for c in chars]
    return float(np.round(np.median(sizes) * 2.0) / 2.0)


def _glyphs_of(text: str) -> str:
    """The characters of a signature or a seal: no spaces, no punctuation."""
    return "".join(g.text for line in parse_text(text) for g in line if g.kind == CHAR)


def prepare(text: str, settings: Settings, *, data=None, punctuation="omit", skip_missing=False):
    """Everything before the writing, checked (ParameterError; MissingCharacters naming every
    character without stroke data, in the text, the signature or the seal): (the text's
    lines, the settings with the signature's and seal's characters, the characters skipped)."""
    lines = parse_text(text, punctuation)
    settings = replace(
        settings, signature=_glyphs_of(settings.signature), seal=_glyphs_of(settings.seal)
    )
    named = [[Glyph(c, CHAR) for c in settings.signature + settings.seal]]
    missing = missing_characters(lines + named, data)
    if missing and not skip_missing:
        raise MissingCharacters(missing, data)
    if missing:
        lines = drop(lines, missing)
        gone = set(missing)
        settings = replace(
            settings,
            signature="".join(c for c in settings.signature if c not in gone),
            seal="".join(c for c in settings.seal if c not in gone),
        )
    if not any(g.kind != "space" for line in lines for g in line):
        raise ParameterError("the text has nothing to write (only spaces and punctuation?)")
    settings.check()
    return lines, settings, missing


def compose(
    text: str,
    settings: Settings,
    template: Recording,
    *,
    char_px: float | None = None,
    px_per_mm: float | None = None,
    data=None,
    punctuation: str = "omit",
    skip_missing: bool = False,
    options: Options | None = None,
    mapper=local_map,
    progress=None,
    response: Response | None = None,
    cache_dir=None,
):
    """A work from ``text``: (its recording, its layout, the characters skipped). The em box is
    ``settings.char_mm``, or fitted to ``settings.paper_mm``, or (neither) the brush's own
    size for the text; the resolution is ``char_px`` pixels an em box or ``px_per_mm``. At an
    em box other than the brush's own size the work is written with the brush made smaller or
    larger for it (``brush_size``, unless ``options.fit_brush`` is False): one brush for the
    whole work, its scale in the recording. ``progress(share)`` as cells are written;
    ``response``: the brush's calibrated response (``calibrate(template)``, measured here when
    not given; ``cache_dir``: where calibrations are kept). Raises ParameterError before any
    writing."""
    if (char_px is None) == (px_per_mm is None):
        raise ParameterError("give the character size in pixels or the resolution (one of them)")
    options = options or Options()
    lines, settings, missing = prepare(
        text, settings, data=data, punctuation=punctuation, skip_missing=skip_missing
    )
    response = response or calibrate(template, cache_dir=cache_dir)
    chars = sorted({g.text for line in lines for g in line if g.kind == CHAR})
    natural = natural_size_mm([lookup(c, data) for c in chars], response)
    if settings.char_mm is None and settings.paper_mm is None:
        settings = replace(settings, char_mm=natural)
    lay = lay_out(lines, settings)
    if options.fit_brush:
        template, response = brush_for_size(template, response, lay.char_mm, natural, cache_dir)
    ppm = float(px_per_mm) if px_per_mm is not None else float(char_px) / lay.char_mm
    check_sheet(lay.width_mm, lay.height_mm, ppm)
    seal_glyphs = [
        {"strokes": lookup(c, data)["strokes"]} for c in settings.seal if not c.isspace()
    ]
    tasks = [
        cell_task(c, lay, template, response, ppm, options.passes, data, options.variation)
        for c in lay.cells
    ]
    done = None if progress is None else (lambda k, n: progress(k / n))
    written = longest_first(mapper, write_cell, tasks, [writing_cost(t) for t in tasks], done)
    step_mm = response.speed_mm_s / template.sample_rate_hz
    samples, dips, _ = assemble(template, lay.cells, written, step_mm, options.dip_every)
    rec = _recording(template, lay, samples, dips, ppm, seal_glyphs)
    return rec, lay, missing


# ----------------------------------------------------------------------------------- render
class CellInk(NamedTuple):
    """What one cell left on the paper: the window (rows r0:r1, columns c0:c1 of the paper's
    arrays, bottom row first) its deposits touched, and the paper's ink, wetness and last step
    there (``mask``: the touched pixels)."""

    window: tuple
    mask: np.ndarray
    ink: np.ndarray
    wet: np.ndarray
    last: np.ndarray


def cell_recording(rec: Recording, cell: Cell) -> Recording:
    """The part of a work's recording that writes one cell, on the whole paper: its samples
    and its dips (the first its restarting one), numbered from 0."""
    a, b = cell.samples
    dips = [
        replace(dp, before_sample=dp.before_sample - a)
        for dp in rec.dips
        if a <= dp.before_sample < b
    ]
    if not dips or dips[0].before_sample != 0 or dips[0].restart is None:
        raise ParameterError(f"cell {cell.char!r} does not start with a restarting dip")
    return replace(rec, samples=rec.samples[a:b], dips=dips, extra={})


def render_cell(sub: Recording) -> CellInk:
    """One cell simulated alone (``cell_recording``): what it left on the paper."""
    from ...paper.paper import TILE

    paper = Simulation(sub).run().paper
    tiles = paper.tiles_since(0)
    if len(tiles) == 0:
        empty = np.zeros((0, 0), dtype=bool)
        return CellInk((0, 0, 0, 0), empty, np.zeros((0, 0, 3), np.float32), empty, empty)
    r0, c0 = tiles.min(axis=0) * TILE
    r1 = min((int(tiles[:, 0].max()) + 1) * TILE, paper.H)
    c1 = min((int(tiles[:, 1].max()) + 1) * TILE, paper.W)
    sl = (slice(int(r0), r1), slice(int(c0), c1))
    mask = (paper.last[sl] > 0) | (paper.ink[sl] > 0).any(axis=2)  # (a halo leaves no last)
    return CellInk((int(r0), r1, int(c0), c1), mask, paper.ink[sl], paper.wet[sl], paper.last[sl])


def _disjoint(inks) -> bool:
    """No pixel is touched by two cells (their windows' touched pixels do not meet)."""
    boxes = np.array([ci.window for ci in inks if ci.mask.size], dtype=np.int64).reshape(-1, 4)
    keep = [ci for ci in inks if ci.mask.size]
    if len(boxes) < 2:
        return True
    r0, r1, c0, c1 = boxes.T
    meet = (np.maximum(r0[:, None], r0[None]) < np.minimum(r1[:, None], r1[None])) & (
        np.maximum(c0[:, None], c0[None]) < np.minimum(c1[:, None], c1[None])
    )
    for i, j in zip(*np.nonzero(np.triu(meet, 1)), strict=True):
        a, b = keep[i], keep[j]
        ra, rb = max(a.window[0], b.window[0]), min(a.window[1], b.window[1])
        ca, cb = max(a.window[2], b.window[2]), min(a.window[3], b.window[3])
        ma = a.mask[ra - a.window[0] : rb - a.window[0], ca - a.window[2] : cb - a.window[2]]
        mb = b.mask[ra - b.window[0] : rb - b.window[0], ca - b.window[2] : cb - b.window[2]]
        if np.any(ma & mb):
            return False
    return True


def render(rec: Recording, mapper=local_map, progress=None):
    """The paper of a recording after all its samples (``sim.paper.Paper``), and the ink of
    each cell of its work (None for a recording without a work). A work's cells are simulated
    side by side (``mapper``) and put together: the same paper, bit for bit, as one run of
    the whole recording (``Simulation(rec).run()``, which is taken instead should two cells
    ever touch the same pixel)."""
    work = work_of(rec)
    if work is None:
        return Simulation(rec).run(progress=progress).paper, None
    lay = Layout.from_dict(work["layout"])
    subs = [cell_recording(rec, c) for c in lay.cells]
    done = None if progress is None else (lambda k, n: progress(k / n))
    inks = longest_first(mapper, render_cell, subs, [len(r.samples) for r in subs], done)
    if not _disjoint(inks):
        return Simulation(rec).run().paper, inks
    paper = Simulation(replace(rec, dips=[], extra={})).paper
    for cell, ci in zip(lay.cells, inks, strict=True):
        if not ci.mask.size:
            continue
        r0, r1, c0, c1 = ci.window
        m = ci.mask
        paper.ink[r0:r1, c0:c1][m] = ci.ink[m]
        paper.wet[r0:r1, c0:c1][m] = ci.wet[m]
        touched = ci.last[m]
        paper.last[r0:r1, c0:c1][m] = np.where(touched > 0, touched + cell.samples[0], 0)
    paper.step = len(rec.samples)
    return paper, inks


def image8(paper, rec: Recording) -> np.ndarray:
    """The work's image: the paper's ink, the grid printed under it, the seal over it."""
    return work_image8(paper, work_of(rec), rec.seed)


# --------------------------------------------------------------------------------- the layout
INK_SEEN = 0.002  # ink density that counts as ink in a cell's box


def layout_items(rec: Recording, inks=None) -> dict:
    """{"items": [...]}: every written character in the text's reading order, then the
    signature's, then the seal - {"char", "role", "box": [x0, y0, x1, y1]} with the box in
    pixels of the image (x right, y down; x1, y1 exclusive): the cell and half the gap to its
    neighbours, grown to take in all the ink the cell laid (``inks``: render's)."""
    work = work_of(rec)
    if work is None:
        return {"items": []}
    lay = Layout.from_dict(work["layout"])
    ppm, W, H = rec.px_per_mm, rec.width_px, rec.height_px
    ink_of = {}
    for cell, ci in zip(lay.cells, inks or [None] * len(lay.cells), strict=True):
        if ci is not None and ci.mask.size:
            rows, cols = np.nonzero(ci.mask & (ci.ink.max(axis=-1) > INK_SEEN))
            if rows.size:
                r0, _, c0, _ = ci.window
                # paper rows are bottom first: image rows are H - 1 - row
                ink_of[id(cell)] = (
                    c0 + int(cols.min()),
                    H - 1 - (r0 + int(rows.max())),
                    c0 + int(cols.max()) + 1,
                    H - (r0 + int(rows.min())),
                )
    items = []
    for cell in lay.reading_order():
        x0, y0, x1, y1 = cell.territory(lay.vertical)
        box = [
            max(int(np.floor(x0 * ppm)), 0),
            max(int(np.floor(H - y1 * ppm)), 0),
            min(int(np.ceil(x1 * ppm)), W),
            min(int(np.ceil(H - y0 * ppm)), H),
        ]
        if id(cell) in ink_of:
            a = ink_of[id(cell)]
            box = [min(box[0], a[0]), min(box[1], a[1]), max(box[2], a[2]), max(box[3], a[3])]
        items.append({"char": cell.char, "role": cell.role, "box": box})
    if lay.seal:
        x0, y0, x1, y1 = lay.seal["box"]
        pad = 0.08 * (x1 - x0)  # the stamp is set down a little askew and its edges wander
        box = [
            max(int(np.floor((x0 - pad) * ppm)), 0),
            max(int(np.floor(H - (y1 + pad) * ppm)), 0),
            min(int(np.ceil((x1 + pad) * ppm)), W),
            min(int(np.ceil(H - (y0 - pad) * ppm)), H),
        ]
        items.append({"char": lay.seal["text"], "role": "seal", "box": box})
    return {"items": items}
