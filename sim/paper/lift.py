# SPDX-License-Identifier: GPL-3.0-or-later
"""What a stroke leaves as the brush lifts off the paper, beyond the paper's model (Sec. 6):
the wet film levelling (``level_rows``, see LEVEL_MM) and the droplets the brush throws
(``spatter``, see SPATTER_EXIT). ``Paper._halo`` lays them, with the water halo, once a stroke;
``paper`` below is that ``sim.paper.paper.Paper``."""

from __future__ import annotations

import numpy as np

from ..core import exact
from .grain import paper_grain

# Model addition (not in the paper): the wet film levels. Where the hair left a pixel wet
# (Eq. 24's wetness above LEVEL_WET, a full film LEVEL_SPAN above that), the ink is still a
# liquid film on the sheet as the brush leaves it, and its pigment spreads within the film
# before the sheet takes it: the grey bands the hair bundles laid inside a loaded stroke even
# out into solid ink, while a dry or fast stroke (little liquid left) keeps its streaks and
# gaps (飞白), and the paper round a stroke (dry) and a hair bundle's gap (Eq. 27's Cr = 0: the
# hair laid no liquid there, though Eq. 24 wets it) take nothing. Laid once a stroke, with the
# halo (``Paper._halo``): each pixel's pigment (Beer-Lambert, p = -ln(1 - density), the
# density Eq. 26's change gives) moves toward the mean of the film around it (two box filters
# of LEVEL_MM a side, weighted by how much film each pixel holds) by the share of a film the
# pixel holds. Pigment is conserved, not density: where it evens out, the stroke's density is
# 1 - e^-(mean p), a little darker than the mean density it had (wet ink is darker than the
# same pigment in bands).
# A full film also levels across the whole stroke (issue 26): a loaded stroke's liquid stays
# on the sized sheet long enough to spread from the middle of the stroke, where the belly laid
# most (its section's longest chord passes there), out to its edges, so the stroke is evenly
# black to its edge and not a shaded tube (darkest down its middle, a fifth lighter at its
# edges: sRGB grey 15 against 45 across 十's 竖 at 512 px); a thin film is taken by the sheet
# at once and keeps its streaks. After the first levelling, the film's local mean round each
# pixel (LEVEL_MM) moves toward the mean of the full films within LEVEL_WIDE_MM (less on a
# sheet that takes the film sooner, ``wide_px``), by the share of the film round it that is
# full (a film's share to the power LEVEL_WIDE_POWER); what a pixel holds above or below its
# local mean, a line of hair, stays. (Like the first levelling's, the move is normalised by
# the film round each pixel: a pixel at the edge moves as far toward the middle's pigment as
# one in the middle, so a shaded stroke gains a little pigment at its edges, a few per cent.)
LEVEL_MM = 0.5
LEVEL_WIDE_MM = 2.5
LEVEL_WIDE_POWER = 4.0
LEVEL_WET = 0.2
LEVEL_SPAN = 0.3
LEVEL_INKED = 0.3  # a pixel holds a full film where its ink is this share of the stroke's colour
LEVEL_DENSEST = 0.999  # densities are read at most this dark (the pigment stays finite)
LEVEL_LEAST = 0.01  # less film than this is none (a film's share far above the sums' rounding)


def level_px(ppm: float, mm: float = LEVEL_MM) -> int:
    """Half-width (px) of each box filter of the wet film's levelling (LEVEL_MM, or across
    the stroke LEVEL_WIDE_MM)."""
    return max(int(round(mm * ppm)), 1)


def wide_px(paper) -> int:
    """Half-width (px) of each box filter of the levelling across the stroke: LEVEL_WIDE_MM on
    a sized sheet (capacity 1) or a smooth one, less on one that takes the film sooner (raw
    xuan, capacity 0.55: the film is drawn into the sheet before it spreads on it)."""
    return level_px(paper.ppm, LEVEL_WIDE_MM * min(paper.capacity, 1.0))


def level_reach(paper) -> int:
    """Rows (px) the levelling of a pixel reads above and below it (two box filters a side of
    each scale, the wide one over the first's result)."""
    return 2 * (level_px(paper.ppm) + wide_px(paper))


def _box2(a, r: int) -> np.ndarray:
    """The mean of ``a`` over two box filters of 2 r + 1 pixels a side."""
    return box_mean(box_mean(box_mean(box_mean(a, r, 0), r, 1), r, 0), r, 1)


def box_mean(a, r: int, axis: int) -> np.ndarray:
    """Mean of ``a`` (2-D) over 2 r + 1 pixels along ``axis`` (zero beyond the ends)."""
    n = a.shape[axis]
    c = np.cumsum(a, axis=axis, dtype=np.float32)  # (along the rows as they lie: the same sums)
    out = np.empty_like(c)
    k = min(r, n - 1)

    def at(part):  # the part of the pixels along ``axis``
        return (slice(None), part) if axis == 1 else part

    out[at(slice(0, n - k))] = c[at(slice(k, None))]  # the sum up to r ahead, ...
    out[at(slice(n - k, None))] = c[at(slice(n - 1, n))]  # ... or to the end
    if n > r + 1:  # less what lies before the window, where there is some
        out[at(slice(r + 1, None))] -= c[at(slice(0, n - r - 1))]
    return out * np.float32(1.0 / (2 * r + 1))


def level_rows(paper, start: int, colour, rows, outer):
    """The levelled ink (see LEVEL_MM) of the rows ``rows`` (by0, by1) of the window
    ``outer``: (row, column) of the pixels that change, in the sheet, and their new ink; None
    where nothing levels. The film's reach (``level_reach``) above and below them is read."""
    (by0, by1), (y0, y1, x0, x1) = rows, outer
    r, wide_r, reach = level_px(paper.ppm), wide_px(paper), level_reach(paper)
    sy0, sy1 = max(by0 - reach, y0), min(by1 + reach, y1)
    last = paper.last[sy0:sy1, x0:x1]
    left = np.where(last >= start, paper.wet[sy0:sy1, x0:x1], np.float32(0.0))
    film = np.clip((left - np.float32(LEVEL_WET)) * np.float32(1.0 / LEVEL_SPAN), 0.0, 1.0)
    if not film[by0 - sy0 : by1 - sy0].any():
        return None
    ink = np.minimum(paper.ink[sy0:sy1, x0:x1], np.float32(LEVEL_DENSEST))
    inked = _darkest(ink) * np.float32(1.0 / (LEVEL_INKED * max(max(colour), 1e-6)))
    film *= np.minimum(inked, 1.0)  # a bundle's gap (Eq. 27's Cr = 0) laid no film
    film = np.where(film >= LEVEL_LEAST, film, np.float32(0.0))
    moves = np.nonzero(film[by0 - sy0 : by1 - sy0] > 0.0)
    if moves[0].size == 0:
        return None
    depth_max = -exact.log1p(-np.float32(LEVEL_DENSEST))
    # the pigment a pixel holds (Beer-Lambert: density 1 - e^-p), where it holds film (elsewhere
    # the film's zero weighs it out: read as 0, the same sums; issue 28)
    depth = np.zeros_like(ink)
    held = film > 0.0
    depth[held] = -exact.log1p(-ink[held])
    share = _box2(film, r)
    full = film**LEVEL_WIDE_POWER  # the full films, which level across the stroke
    wide_share = _box2(full, wide_r)
    full_share = np.divide(_box2(full, r), share, out=np.zeros_like(share), where=share > 0.0)
    here = (moves[0] + (by0 - sy0), moves[1])
    level = np.empty((moves[0].size, 3), dtype=np.float32)
    # a colour that holds the same numbers as an earlier one has its sums (issue 28)
    same = same_colours(ink)
    for c in sorted(set(same)):
        p = depth[..., c]
        mean = np.divide(_box2(film * p, r), share, out=p.copy(), where=share > 0.0)
        mean = np.clip(mean, 0.0, depth_max)  # (the box sums' float32 rounding)
        lv = p + film * (mean - p)
        # across the stroke: the film's local mean moves toward the mean of the full films
        # within LEVEL_WIDE_MM, by the full films' share of the film round the pixel; what
        # the pixel holds above or below its local mean (a line of hair) stays
        local = np.divide(_box2(film * lv, r), share, out=lv.copy(), where=share > 0.0)
        wide = np.divide(
            _box2(full * lv, wide_r), wide_share, out=local.copy(), where=wide_share > 0.0
        )
        level[:, c] = np.clip(lv + full_share * (wide - local), 0.0, depth_max)[here]
    level = level[:, same]
    new = -exact.expm1(-level)
    return (moves[0] + by0, moves[1] + x0), new


def same_colours(ink) -> list:
    """For each colour of ``ink`` (h, w, 3), the first colour that holds the same number as it
    at every pixel (itself when none does): [0, 0, 0] for black ink, [0, 0, 2] for the default
    ink (its red and green one), [0, 1, 2] when all differ. Each colour's numbers are then those
    of its first, made by the same operations from the same numbers: the work of the colours
    that differ is enough (issue 28)."""
    same = [0]
    for c in (1, 2):
        first = (k for k in range(c) if same[k] == k and np.array_equal(ink[..., k], ink[..., c]))
        same.append(next(first, c))
    return same


def _darkest(ink) -> np.ndarray:
    """ink.max(axis=2) of (h, w, 3) ink, a colour at a time (the same picks, in the same
    order: long runs of numbers, not three at a time; issue 28)."""
    return np.maximum(np.maximum(ink[..., 0], ink[..., 1]), ink[..., 2])


# Model addition (not in the paper): the droplets a brush throws. A loaded brush that leaves
# the paper fast (出锋, a flicked hook or 撇) flings a few droplets of ink on along its exit,
# drawn out along the way it went; one that comes down overloaded, just dipped, lets a drop
# fall round the place it lands (the liquid the hair cannot hold by capillarity). Real writing
# shows a few such loose specks a character, near its strokes; a rendering with none looks
# printed. Per stroke, as the brush leaves the paper: the exits' count is Poisson with mean
# SPATTER_EXIT times (exit speed / SPATTER_SPEED)^2 (the liquid's kinetic energy against its
# surface tension) times the liquid the hair offered there against SPATTER_WET; the landings'
# with mean SPATTER_LAND times the share of SPATTER_DRIP_SPAN by which the liquid offered as
# it landed passes SPATTER_DRIP (issue 26: a drop beside the head of any stroke, wherever the
# brush was in its load, read as a detached speck; a calligrapher's brush drips, if at all,
# on the first strokes after a dip).
# A brush that leaves in a gathered point (a hook's or a 撇's let-go: its last contact under
# SPATTER_POINT_MM in radius) throws none: the hair closed round the point holds its liquid
# (capillarity), only a spread, loaded belly leaving fast sheds it (times the share of
# SPATTER_POINT_MM by which the contact is wider than that, up to 1; issue 26: no specks past
# a point).
# A droplet that falls on the stroke's ink or touches it (within a pixel) runs into the wet
# film and is not laid: a bead stuck to a head or a point reads as a blob, not as a speck
# (issue 26.2; SPATTER_MERGE: ink darker than that share of the stroke's colour, above the
# water halo's faint tint, HALO_PIGMENT).
# Each droplet is SPATTER_MM across (mostly the small end), up to SPATTER_REACH_MM away; a brush
# made k times as large (sim.writing.brush_size) throws droplets k times as large, as far, at k
# times the speed, from a point k times as fine (paper.brush_scale). Every
# draw is the sheet's hash of where the stroke landed and of its seed (``paper_grain``), not
# the brush's generator: the brush's draws are unchanged, and the same stroke throws the same
# droplets in any frame order.
SPATTER_EXIT = 0.6
SPATTER_LAND = 0.2
SPATTER_SPEED = 60.0  # mm/s
SPATTER_WET = 0.6
SPATTER_DRIP = 0.95  # the liquid offered as it lands (a dip's first strokes: 0.9-1.1) above
SPATTER_DRIP_SPAN = 0.1  # which the brush may drip, fully this much above it
SPATTER_MM = (0.15, 0.8)  # a droplet's radius, mm: the smallest, the largest
SPATTER_REACH_MM = 3.0
SPATTER_DENSITY = 0.8  # a droplet's density (of the ink's), SPATTER_FULL_MM or larger
SPATTER_FULL_MM = 0.2  # a smaller droplet is a thinner film: lighter
SPATTER_MAX = 6
SPATTER_POINT_MM = 0.3  # an exit's contact radius below which the hair is gathered in a point
SPATTER_MERGE = 0.3  # ink this dark (share of the stroke's colour) takes a droplet in
SPATTER_DRAWS = 2 + 4 * SPATTER_MAX
SPATTER_SALT = 21 << 40  # keeps these draws apart from the grain's and the texture's


def _poisson(mean: float, u: float) -> int:
    """The Poisson count of ``mean`` whose cumulative probability first passes ``u``."""
    k, p = 0, exact.exp(-mean)
    total = p
    while u > total and k < SPATTER_MAX:
        k += 1
        p *= mean / k
        total += p
    return k


def spatter(paper, t, colour) -> None:
    """The droplets the brush threw (see SPATTER_EXIT), laid as the brush leaves the paper:
    how many, where and how large from the sheet's hash of where the stroke landed (the
    same stroke gives the same droplets in any frame order, live or replayed)."""
    if not t.land or paper.dt <= 0.0:
        return
    (ly, lx, lwet, lr), (hy, hx, hwet, hr) = t.land, t.trail[-1]
    by, bx = t.trail[0][:2]
    steps = max(len(t.trail) - 1, 1)
    vy, vx = (hy - by) / steps, (hx - bx) / steps  # px a step as the hair left the paper
    k = paper.brush_scale  # the brush's size: its droplets' (see SPATTER_MM)
    speed = float(np.hypot(vy, vx)) / (paper.ppm * paper.dt * k)  # mm/s (at the preset's size)
    key = int(min(max(ly, 0), paper.H - 1)) * paper.W + int(min(max(lx, 0), paper.W - 1))
    u = paper_grain(
        np.arange(SPATTER_DRAWS, dtype=np.uint64) + np.uint64(key * SPATTER_DRAWS + SPATTER_SALT),
        paper.grain_seed,
    )
    drops = []
    fling = SPATTER_EXIT * min(hwet / SPATTER_WET, 1.0) * (speed / SPATTER_SPEED) ** 2
    fling *= min(max(hr / (paper.ppm * SPATTER_POINT_MM * k) - 1.0, 0.0), 1.0)  # not a point
    land = SPATTER_LAND * min(max((lwet - SPATTER_DRIP) / SPATTER_DRIP_SPAN, 0.0), 1.0)
    n_exit, n_land = _poisson(fling, u[0]), _poisson(land, u[1])
    ahead = np.array([vy, vx]) / max(float(np.hypot(vy, vx)), 1e-9)
    for j in range(min(n_exit + n_land, SPATTER_MAX)):
        a, b, c, d = u[2 + 4 * j : 6 + 4 * j]
        size = (SPATTER_MM[0] + (SPATTER_MM[1] - SPATTER_MM[0]) * a * a) * k  # mostly small
        if j < n_exit:  # flung on along the exit, drawn out along it
            dist = hr / paper.ppm + SPATTER_REACH_MM * k * (0.2 + 0.8 * b)  # past its last mark
            way = ahead + (c - 0.5) * 0.8 * np.array([-ahead[1], ahead[0]])
            way /= np.hypot(*way)
            centre = (hy + way[0] * dist * paper.ppm, hx + way[1] * dist * paper.ppm)
            drops.append((centre, way, size, 1.5 + 2.0 * d))
        else:  # dripped round the landing, round
            dist = lr / paper.ppm + SPATTER_REACH_MM * k * (0.1 + 0.5 * b)
            ang = 2.0 * np.pi * c
            way = np.array(exact.sin_cos(ang))
            centre = (ly + way[0] * dist * paper.ppm, lx + way[1] * dist * paper.ppm)
            drops.append((centre, way, size, 1.0 + 0.3 * d))
    merge = SPATTER_MERGE * float(np.max(colour))
    for centre, way, size, stretch in drops:
        dens = SPATTER_DENSITY * min(size / (SPATTER_FULL_MM * k), 1.0)
        _drop(paper, centre, way, (size * paper.ppm, stretch), (dens * colour, merge))


def _drop(paper, centre, way, shape, colours) -> None:
    """One droplet at ``centre`` (row, column, px): an ellipse of radius ``shape[0]`` px,
    ``shape[1]`` times that along ``way``, its rim anti-aliased, of the ink ``colours[0]``,
    laid where darker than what the pixels hold; not laid at all where it falls on or touches
    (its ellipse grown by a pixel) ink darker than ``colours[1]``: it runs into that film."""
    colour, merge = colours
    radius, stretch = shape
    reach = radius * stretch + 1.5
    y0, y1 = int(np.floor(centre[0] - reach)), int(np.ceil(centre[0] + reach)) + 1
    x0, x1 = int(np.floor(centre[1] - reach)), int(np.ceil(centre[1] + reach)) + 1
    y0, y1, x0, x1 = max(y0, 0), min(y1, paper.H), max(x0, 0), min(x1, paper.W)
    if y0 >= y1 or x0 >= x1:
        return
    dy = (np.arange(y0, y1) + 0.5 - centre[0])[:, None]
    dx = (np.arange(x0, x1) + 0.5 - centre[1])[None, :]
    along = (dy * way[0] + dx * way[1]) / (radius * stretch)
    across = (-dy * way[1] + dx * way[0]) / radius
    r = np.sqrt(along * along + across * across)
    cover = np.clip((1.0 - r) * radius + 0.5, 0.0, 1.0)  # a pixel's share of the drop
    ink = paper.ink[y0:y1, x0:x1]
    near = (1.0 - r) * radius + 1.5 > 0.0  # the drop and a pixel round it
    if (_darkest(ink)[near] > merge).any():
        return  # it runs into the wet stroke
    tint = cover.astype(np.float32)[..., None] * colour
    if not (tint > ink).any():
        return
    paper._touch(y0, y1, x0, x1)
    np.maximum(ink, tint, out=ink)
