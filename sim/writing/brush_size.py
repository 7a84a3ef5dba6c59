# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush for the size of the writing (a model addition, not in the paper): a calligrapher
writes small characters with a small brush (小楷) and large ones with a large one (大楷, 斗笔).

A brush writes a character best at its own size (``writer.auto_size_mm``: where the
character's widest stroke needs about the widest band the brush leaves). Much smaller, every
stroke asks for a band the pressed belly cannot make narrow enough, and the strokes swell into
each other; much larger, the deepest press falls short of the widest strokes. So when the
writing is set to a size other than the brush's own (a character's size, a work's em box or a
work fitted to its paper), the writer takes the same brush made smaller or larger in
proportion (the recording's 'brush.scale': its hair, base and belly; the quality values,
shares, are the same) and moves it at a pace slower or faster with the square root of that
(``response.PACE_POWER``; the response measured so, ``response.calibrate``).

Measured (the nine held-out characters at 512 px, ``scripts/sizes_eval.py``): IoU at 30, 50,
70 and 150 mm with the brush as it is 0.820, 0.913, 0.927, 0.854; with the brush for the size
0.908, 0.921, 0.924, 0.916 (at its own size, about 105 mm: 0.931). What does not scale with
the brush is the paper: its fibres, wicking and halo are as large in mm on any writing, so
very small writing still shows more of them (as it does on real paper). The planner's tip
touches as much less deep (``planner.TIP_TOUCH_MM``) and the brush's droplets are as much
smaller (``lift.spatter``): at the preset's depth the tip of a brush a quarter as large came
down early, a speck above every hidden-tip head.

A brush whose own size or geometry is already set (the recording's 'brush.scale' or
'brush.geometry': a work written on, a user's own brush) is kept as it is."""

from __future__ import annotations

from dataclasses import replace

from ..core.params import BRUSH_SCALE_RANGE
from ..core.recording import Recording
from .response import Response, calibrate
from .writer import auto_size_mm

FIT_WITHIN = 0.1  # writing within 10 % of the brush's own size is written with it as it is
SCALE_DIGITS = 3  # the scale kept in the recording, rounded (a readable number)


def brush_scale_for(size_mm: float, natural_mm: float) -> float:
    """How many times as large a brush that writes best at ``natural_mm`` should be to write at
    ``size_mm``: 1 within ``FIT_WITHIN`` of its own size, else their ratio, within
    ``BRUSH_SCALE_RANGE``."""
    k = float(size_mm) / max(float(natural_mm), 1e-9)
    if 1.0 / (1.0 + FIT_WITHIN) <= k <= 1.0 + FIT_WITHIN:
        return 1.0
    lo, hi = BRUSH_SCALE_RANGE
    return round(min(max(k, lo), hi), SCALE_DIGITS)


def sized_brush(template: Recording, size_mm: float, natural_mm: float) -> Recording:
    """The template with the brush for writing at ``size_mm`` (``brush_scale_for``): the same
    template when the brush is kept (its size within reach, or its size or geometry set)."""
    if "scale" in template.brush or "geometry" in template.brush:
        return template
    k = brush_scale_for(size_mm, natural_mm)
    if k == 1.0:
        return template
    return replace(template, brush={**template.brush, "scale": k})


def brush_for_size(
    template: Recording, response: Response, size_mm: float, natural_mm: float, cache_dir=None
) -> tuple[Recording, Response]:
    """``sized_brush`` and its calibrated response (``response`` when the brush is kept)."""
    sized = sized_brush(template, size_mm, natural_mm)
    if sized is template:
        return template, response
    return sized, calibrate(sized, cache_dir=cache_dir)


def brush_for_char(
    template: Recording, response: Response, char: dict, size_mm: float, cache_dir=None
) -> tuple[Recording, Response]:
    """``brush_for_size`` of one character (its own size: ``writer.auto_size_mm``; a picture's
    strokes as read, too)."""
    natural = auto_size_mm(char, response)
    return brush_for_size(template, response, size_mm, natural, cache_dir)
