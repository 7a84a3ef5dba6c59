# SPDX-License-Identifier: GPL-3.0-or-later
"""The ink's outline as SVG for cutters and engravers (issue 29.4), in millimetres.

The density (the channels' largest: the matte's alpha) is smoothed a little (a Gaussian of
``smooth_mm``: the paper's fibrous edge would otherwise be a cutter's saw-tooth), traced at the
``threshold`` (``contours.trace``: sub-pixel crossings, holes kept, every outline closed),
outlines and holes smaller than ``min_area_mm2`` dropped (specks, pinholes), each simplified to
a tenth of a pixel, then drawn through its points as smooth cubic curves (Catmull-Rom). All of
it in one path, filled with the even-odd rule, so a hole cuts out of the stroke around it. The
document is the paper's size (or ``width_mm`` wide), its units millimetres (viewBox in mm)."""

from __future__ import annotations

import numpy as np

from .contours import area, simplify, trace
from .filters import _gaussian

DEFAULT_THRESHOLD = 0.5
DEFAULT_SMOOTH_MM = 0.1
DEFAULT_MIN_AREA_MM2 = 0.05
SIMPLIFY_PX = 0.1  # Ramer-Douglas-Peucker's tolerance, in the paper's pixels


def ink_outlines(
    paper,
    threshold: float = DEFAULT_THRESHOLD,
    smooth_mm: float = DEFAULT_SMOOTH_MM,
    min_area_mm2: float = DEFAULT_MIN_AREA_MM2,
) -> list[np.ndarray]:
    """The outlines of the ink at ``threshold`` density, (N, 2) arrays in mm from the paper's
    top-left corner (x right, y down), simplified; outer outlines and holes run opposite ways.
    ``paper``: a sim.paper.Paper, or anything with its ``ink`` (bottom row first) and ``ppm``."""
    if not 0.0 < threshold < 1.0:
        raise ValueError(f"the outline's threshold must lie in (0, 1), got {threshold}")
    density = np.clip(paper.ink.max(axis=2), 0.0, 1.0)[::-1].astype(np.float64)
    if smooth_mm > 0:
        density = _gaussian(density, smooth_mm * paper.ppm)
    ppm = float(paper.ppm)
    out = []
    for loop in trace(density, threshold):
        if abs(area(loop)) / ppm**2 < min_area_mm2:
            continue
        out.append((simplify(loop, SIMPLIFY_PX) + 0.5) / ppm)  # pixel centres at +0.5 px
    return out


def path_data(loops, scale: float = 1.0, decimals: int = 3) -> str:
    """SVG path data: each closed loop through its points as cubic curves (Catmull-Rom: the
    tangent at a point parallel to the chord of its neighbours), ``Z``-closed."""
    parts = []
    for loop in loops:
        p = np.asarray(loop, dtype=np.float64) * scale
        if len(p) < 3:
            continue
        prev, nxt, nxt2 = np.roll(p, 1, axis=0), np.roll(p, -1, axis=0), np.roll(p, -2, axis=0)
        c1 = p + (nxt - prev) / 6.0
        c2 = nxt - (nxt2 - p) / 6.0
        f = f"{{:.{decimals}f}}"
        cmds = [f"M{f.format(p[0, 0])} {f.format(p[0, 1])}"]
        for a, b, q in zip(c1, c2, nxt, strict=True):
            nums = (*a, *b, *q)
            cmds.append("C" + " ".join(f.format(v) for v in nums))
        parts.append("".join(cmds) + "Z")
    return "".join(parts)


def ink_svg(
    paper,
    threshold: float = DEFAULT_THRESHOLD,
    smooth_mm: float = DEFAULT_SMOOTH_MM,
    min_area_mm2: float = DEFAULT_MIN_AREA_MM2,
    width_mm: float | None = None,
) -> str:
    """The SVG document of the ink's outline (see the module); ``width_mm`` scales it to that
    width (default: the paper's own size, 1:1)."""
    h_px, w_px = paper.ink.shape[:2]
    paper_w, paper_h = w_px / paper.ppm, h_px / paper.ppm
    scale = 1.0 if width_mm is None else float(width_mm) / paper_w
    if not np.isfinite(scale) or scale <= 0:
        raise ValueError(f"the outline's width must be a positive number of mm, got {width_mm}")
    w, h = paper_w * scale, paper_h * scale
    d = path_data(ink_outlines(paper, threshold, smooth_mm, min_area_mm2), scale)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.3f}mm" height="{h:.3f}mm" '
        f'viewBox="0 0 {w:.3f} {h:.3f}">\n'
        f"<title>Ink outline at density {threshold:g} (Virtual Hairy Brush)</title>\n"
        f'<path fill="#000000" fill-rule="evenodd" stroke="none" d="{d}"/>\n'
        "</svg>\n"
    )
