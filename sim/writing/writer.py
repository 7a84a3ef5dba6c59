# SPDX-License-Identifier: GPL-3.0-or-later
"""Automatic imitation (Sec. 9): write a character from stroke data with the brush.

The medians are the brush's path; the outlines say how wide each stroke is at every point of its
median; the brush's own response - how wide a mark each press depth leaves, and how far behind
the brush's base the mark lies, with the current brush, paper, ink and quality parameters - is
measured by simulation (``calibrate``) and turns width into press (z) and into where the base
must go so that the ink lands on the median. A stroke is written as a calligrapher writes it:
the brush comes down onto the start, presses where the stroke is thick, travels, eases off
where it thins and lifts off the end, leaving the point; between strokes it travels in the air,
and it dips before the first stroke and again when the brush runs low (``dips_when_low``), or after
every ``dip_every_mm`` of writing.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

from ..brush.ink import brush_load, full_load
from ..core.params import HOVER_MM, MAX_PAPER_SIDE_PX, ParameterError, number_within, short_repr
from ..core.recording import (
    PAPER_MM_RANGE,
    PX_PER_MM_RANGE,
    Dip,
    Recording,
    brush_scale,
    quantise,
)
from ..engine.simulation import Simulation
from .hanzi import check_char
from .outline import EM, median_radii, rasterise
from .planner import RUN_UP, WRITING, _fill, plan
from .practice import Lesson, _practise_stroke, _stroke_masks
from .response import Response, _coverage, _settings, calibrate

MAX_PASSES = 50
# practice passes a stroke gets by default (issue 28: 3 cost 0.88 of the CPU time at the same
# held-out IoU, 0.928, but 永 written at 768 px grew a second bump below its 横折 shoulder's
# knob that the fourth pass takes off)
DEFAULT_PASSES = 4
MIN_SHEET_PX = 8


def auto_size_mm(char: dict, response: Response, fill: float = 1.2) -> float:
    """A character size at which the character's widest stroke (twice the largest distance
    from a median to its outline) needs ``fill`` of the widest band the brush leaves as the
    writer moves it (measured so since issue 16; larger characters match their outline better,
    smaller ones carry more of the brush's texture: 1 is the measured balance)."""
    widest = max(float(r.max()) for _, r in median_radii(char)) * 2.0  # data units
    return float(np.clip(fill * response.max_width_mm * EM / max(widest, 1e-6), 20.0, 2000.0))


def _check_writing(n_px, size_mm, passes, dip_every_mm, px_per_mm) -> None:
    """The writer's arguments in range (the sheet's size and resolution are checked once the
    size is known)."""
    if isinstance(passes, bool) or not isinstance(passes, int) or not 1 <= passes <= MAX_PASSES:
        raise ParameterError(
            f"practice passes must be a whole number in [1, {MAX_PASSES}], got {short_repr(passes)}"
        )
    if px_per_mm is None and (
        isinstance(n_px, bool)
        or not isinstance(n_px, int)
        or not MIN_SHEET_PX <= n_px <= MAX_PAPER_SIDE_PX
    ):
        raise ParameterError(
            f"image size must be a whole number of pixels in [{MIN_SHEET_PX}, "
            f"{MAX_PAPER_SIDE_PX}], got {short_repr(n_px)}"
        )
    if px_per_mm is not None and not number_within(px_per_mm, *PX_PER_MM_RANGE):
        raise ParameterError(
            f"px_per_mm must be a number in [{PX_PER_MM_RANGE[0]:g}, {PX_PER_MM_RANGE[1]:g}], "
            f"got {short_repr(px_per_mm)}"
        )
    if size_mm is not None and not number_within(size_mm, *PAPER_MM_RANGE):
        raise ParameterError(
            f"character size must be a number of mm in [{PAPER_MM_RANGE[0]:g}, "
            f"{PAPER_MM_RANGE[1]:g}], got {short_repr(size_mm)}"
        )
    if dip_every_mm is not None and not number_within(dip_every_mm, 1e-3, 1e6):
        raise ParameterError(
            f"dip_every_mm must be a positive number, got {short_repr(dip_every_mm)}"
        )


def check_sheet(size_mm: float, ppm: float) -> None:
    """The em box's sheet: a resolution and a pixel size a recording can hold."""
    lo, hi = PX_PER_MM_RANGE
    if not number_within(ppm, lo, hi):
        raise ParameterError(
            f"a {size_mm:.4g} mm character at this image size is {ppm:.4g} px/mm; the paper "
            f"takes {lo:g} to {hi:g} px/mm (change the size in mm or in pixels)"
        )
    if round(size_mm * ppm) > MAX_PAPER_SIDE_PX:
        raise ParameterError(
            f"a {size_mm:.4g} mm character at {ppm:.4g} px/mm is {round(size_mm * ppm)} px "
            f"wide; at most {MAX_PAPER_SIDE_PX} px"
        )


def write_character(
    char: dict,
    n_px: int,
    template: Recording,
    size_mm: float | None = None,
    response: Response | None = None,
    dip_every_mm: float | None = None,
    passes: int = DEFAULT_PASSES,
    progress=None,
    px_per_mm: float | None = None,
    exact_ends: bool = False,
    paper: bool = True,
) -> tuple[Recording, Response, Simulation]:
    """Write ``char`` with the brush on an n_px x n_px sheet that is exactly the em box, with the
    template's brush, paper, ink, quality, rate and seed (``px_per_mm`` instead of n_px / size
    when a caller fixes the resolution). Returns the recording (it replays to the same image bit
    for bit), the response used and the finished simulation.

    The calibrated response gives each sample's press and the base's lead over the ink (feed
    forward). With ``passes`` > 1 the writer practises each stroke as a student of MiaoHong
    does (Sec. 7.2): it writes the stroke, reads the band it left across the median against the
    outline's width, corrects the press (through the response's slope) and the sideways
    placement, takes the stroke back (a snapshot) and writes it again; the best pass stays.
    With ``exact_ends`` (imitating a picture, whose ink shows where each stroke begins and
    ends) the brush lands on each stroke's start (as the writer's ``RUN_UP`` 0 does too), and
    the practice also reads how far the ink of each end reaches against the outline and carries
    the end on or draws it back (``practice._reach_moves``). With ``paper`` False and one pass
    (practice reads the paper) the brush writes alone: the recording and the brush are the
    same, bit for bit (the brush never reads the paper), the simulation's paper stays blank,
    for about half the work (a composed work simulates its cells again on the sheet).

    Bad arguments raise ParameterError (CharacterError for bad character data) before any
    work."""
    check_char(char, "character data")
    _check_writing(n_px, size_mm, passes, dip_every_mm, px_per_mm)
    if size_mm is not None:  # the sheet can be checked before the brush is calibrated
        check_sheet(float(size_mm), n_px / size_mm if px_per_mm is None else px_per_mm)
    if response is None:
        response = calibrate(template)
    size = auto_size_mm(char, response) if size_mm is None else float(size_mm)
    _, geometry, _, ink = template.resolve()
    hair = geometry.hair_length_mm
    step_mm = response.speed_mm_s / template.sample_rate_hz
    pl = plan(char, size, step_mm, dip_every_mm, font=not exact_ends)
    N = len(pl.target)
    samples = np.zeros((N, 6))
    dips = [Dip(i, ink.depth, tuple(ink.color), ink.wetness) for i in pl.dips]
    ppm = n_px / size if px_per_mm is None else float(px_per_mm)
    check_sheet(size, ppm)
    rec = _settings(
        template, samples=samples, width_mm=size, height_mm=size, px_per_mm=ppm, dips=dips
    )
    hover = hair + HOVER_MM
    samples[:, :2] = pl.target
    samples[:, 2] = hover
    samples[:] = quantise(samples)
    sim = Simulation(rec)
    sim.marks_to_paper = paper or passes > 1
    reach = max(float(pl.width.max()), 1.0)
    masks = _stroke_masks(char, sim.paper.H, sim.paper.W) if passes > 1 else None
    whole = None  # the whole character on the paper, for practising the ends' reach and joins
    if masks is not None:
        whole = np.zeros((sim.paper.H, sim.paper.W), dtype=bool)
        for m in masks:
            whole[m.rows, m.cols] |= m.inside

    brush = (hover, hair, step_mm, brush_scale(template.brush))
    run_up = 0.0 if exact_ends else RUN_UP

    def fill(a, b, press, side, ends=None, lift=None):
        return _fill(samples, pl, response, (a, b), press, side, brush, ends, run_up, lift)

    full = full_load(template)
    areas = stroke_areas(pl, step_mm)
    since = (full, 0.0)  # the load at the last dip and the area written since it
    lesson = None if exact_ends else Lesson()  # imitating: measured, 0.8411 -> 0.8385
    for n_stroke, (a, b) in enumerate(pl.strokes):
        fresh = _run_to_the_dip(sim, rec.dips, a)  # (a hold, the dip's index) or None
        sim.run(until=a)  # travel in the air up to the stroke
        load = brush_load(sim.brush)
        need = ink_needed(since, load, areas[n_stroke])
        if dip_every_mm is None and n_stroke and dips_when_low(load, full, need):
            rec.dips.append(Dip(a, ink.depth, tuple(ink.color), ink.wetness))
            sim.dips = rec.dips
            since = (full, 0.0)
            if fresh is not None:  # a hold left open would keep every later tile's copy
                sim.let_go(fresh[0])
            fresh = (sim.hold(), len(rec.dips) - 1)
        since = (since[0], since[1] + areas[n_stroke])
        own = masks[n_stroke] if passes > 1 else None
        ctx = (pl, response, step_mm, reach, lesson)
        taught = copy.deepcopy(lesson) if fresh is not None else None
        _practise_stroke(sim, a, b, passes, fill, own, ctx, whole, exact_ends)
        if fresh is not None and brush_load(sim.brush) < RUN_DRY * full:
            # begun on a fresh dip, it ran dry: dipped again as a soak, written again
            sim.take_back(fresh[0])
            rec.dips[fresh[1]] = soaked(rec.dips[fresh[1]])
            sim.dips = rec.dips
            sim.run(until=a)
            ctx = (pl, response, step_mm, reach, taught)
            lesson = taught
            _practise_stroke(sim, a, b, passes, fill, own, ctx, whole, exact_ends)
        elif fresh is not None:
            sim.let_go(fresh[0])
        if progress is not None:
            progress(b / N)
    sim.run()
    if progress is not None:
        progress(1.0)
    return rec, response, sim


LOW_INK = 0.6  # share of a full load (``brush_load``) below which the brush is dipped again
# before the next stroke (issue 26, point 1, measured: at 0.75 a character was dipped for again
# and again and stayed flat black, the judge proxy's mid_tone 0.089 against real scans' 0.136;
# at 0.6, with RUN_DRY guarding the long strokes, a stroke begun with two thirds of a load is
# written on it and greys with streaks along it: mid_tone 0.099, dry white 0.008 -> 0.011, and
# the held-out characters lose 0.006 of IoU; at 0.5 (RUN_DRY 0.3) mid_tone overshoots, 0.174,
# and 亡 and 凶 lose 0.04-0.05; at 0.62 with RUN_DRY 0.4 亡's 竖折 ends a dry broom, -0.011)
DIP_EVERY_STROKE = 1e-3  # a ``dip_every_mm`` that dips before every stroke


SOAK_DEPTH = 1.0  # share of the hair, from the tip, a soak dips: a stroke begun on a fresh dip
# that ends below ``RUN_DRY`` of a full load is written again on a soak (issue 26: 飞's 横折斜钩,
# imitated from a picture whose hook is solid, ended at 0.37 of a load, its hook a dry broom of
# hairs, box IoU 0.786; soaked as wet as before, 0.844, the hook solid with fine streaks along)


def soaked(dip: Dip) -> Dip:
    """``dip`` as a soak: the whole hair dipped (``SOAK_DEPTH``), as a calligrapher loads the
    brush fully (饱墨) for a stroke one ordinary dip does not carry to its end; as wet as the
    dip was (a dry ink stays dry). (Beyond the paper: its dips are given.)"""
    return dataclasses.replace(dip, depth=max(dip.depth, SOAK_DEPTH))


def _run_to_the_dip(sim: Simulation, dips, a: int):
    """Run ``sim`` up to the recording's dip before stroke sample ``a`` that no stroke has
    used yet (one at a sample from ``sim.index`` to ``a``: the plan's first, or its dips before
    every stroke) and hold it there, before the dip: (the hold, the dip's index), or None."""
    here = [k for k, d in enumerate(dips) if sim.index <= d.before_sample <= a]
    if not here:
        return None
    sim.run(until=dips[here[-1]].before_sample)
    return sim.hold(), here[-1]


RUN_DRY = 0.45  # share of a full load below which a stroke is foreseen to end: dip before it
# (issue 26: begun at 0.75, a long 横折钩 ended at 0.38 and its hook was a dry broom of hairs;
# with LOW_INK 0.6 it is what keeps a long last stroke, 亡's 竖折, from ending so)


def dips_when_low(load: float, full: float, need: float = 0.0) -> bool:
    """Without ``dip_every_mm``, the writer dips before the first stroke and before any later
    stroke that the brush would begin holding less than ``LOW_INK`` of a full load (the load
    the paper has taken from it, Eq. 15), or would end below ``RUN_DRY`` of it, spending
    ``need`` (``ink_needed``) on the stroke: as a calligrapher dips once for a character and
    again when the brush runs low or the next stroke is long: the tone runs from dark and wet
    after a dip to grey, with flying white, before the next. (Beyond the paper: it dips before
    every stroke of its figures.)"""
    return load < LOW_INK * full or load - need < RUN_DRY * full


def stroke_areas(pl, step_mm: float) -> list[float]:
    """The area (mm^2) each stroke of plan ``pl`` covers: its planned width summed along its
    body samples, a sample ``step_mm`` apart."""
    return [float(pl.width[a:b][pl.phase[a:b] == WRITING].sum() * step_mm) for a, b in pl.strokes]


FORESEE_FROM = 0.5  # share of a stroke's area written since the dip before its need is foreseen


def ink_needed(since, load: float, area: float) -> float:
    """The load a stroke of ``area`` mm^2 will take from the brush, foreseen from what the
    strokes since the last dip took per mm^2 (``since``: the load at the dip and the area
    written since); 0 until at least ``FORESEE_FROM`` of its area has been written since the
    dip (a dot, pressed on a small area, takes more a mm^2 than a long stroke: no guide)."""
    at_dip, written = since
    if written <= 0 or written < FORESEE_FROM * area:
        return 0.0
    return max(at_dip - load, 0.0) / written * area


def coverage_mask(sim: Simulation) -> np.ndarray:
    """Ink coverage above half, (H, W) bool, top row first."""
    return _coverage(sim)[::-1]


def font_mask(char: dict, n_px: int) -> np.ndarray:
    return rasterise(char, n_px)
