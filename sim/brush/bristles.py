# SPDX-License-Identifier: GPL-3.0-or-later
"""Hair bundles inside a writing primitive (model addition, issue 26).

The paper treats a primitive's section as one cluster whose ink varies smoothly across it
(Eq. 21-23 with the texture function, Eq. 5) and makes the dry brush's white with a draw per
pixel (Eq. 27). A real cluster is made of bundles of hair that hold different amounts of ink,
run dry one after the other and each draw a line along the motion. Here every primitive's
section is divided into BUNDLES bundles of irregular width, side by side across the path the
brush is drawn along: a pixel's bundle is set by its signed distance from the recent path of
the middle of the hair's contact with the paper (the cut's, Sec. 6; ``across``, the brush's
``trail``, TRAIL points TRAIL_MM apart). Hair lying on the paper is dragged along that path,
so the same bundle passes over the same place of the stroke step after step, along a curve as
along a line, and a dry bundle leaves a streak along the stroke, not a stipple.

Each bundle has, as fields of the brush state (``state``: snapshots carry them):

- ``edge``: where the bundles meet, in units of the half width they lie across (``spread``:
  half the contact's width across the way, at most the middle control ellipse's a / 2, Eq. 6,
  which Eq. 16 lengthens as the belly presses flat; issue 26.2: every hair runs to the tip, so
  as the belly lifts the bundles gather inside the narrowing mark), in (-1, 1); the outermost
  bundles take the pixels past it;
- ``bundle``: its share of the primitive's ink, a factor on the wetness of Eq. 23; thinner
  toward the section's sides (their hair holds less), jittered; set at a dip;
- ``hair_u``: its dry-brush draw. Eq. 27 says a pixel takes no ink with probability
  min(ren ab gamma, 1); a bundle goes dry when its draw is below that probability plus
  ren FLY times its dryness: how far its wetness (its share times ``moist``, the wetness of
  the hair on the paper, ``contact_wetness``, followed over SETTLE_S) falls short of W_DRY,
  a threshold that rises with the brush's speed (fast hair leaves less) and falls as the hair
  gathers into a contact narrower than GATHER of the belly (``spread`` over GATHER a / 2: the
  gathered hair of a lifting point is held together by its ink and parts less; issue 26.2).
  A loaded bundle
  obeys Eq. 27 alone; as the ink is spent (Eq. 15 with what the paper takes,
  ``dynamics.lose_wetness``) the bundles with the least ink and the lowest draws go dry
  first: streaks along the stroke, first at its sides (their bundles hold less), so a dry
  stroke's edge frays into fibres along it while a loaded one's stays crisp. The draws are
  redrawn at REDRAW_RATE per second;
- ``gap``: how much of its width lays no ink, in [0, 1]: it opens from the bundle's middle
  as the bundle goes dry and closes as it takes ink again, over RAMP_S seconds, so a streak
  of flying white begins and ends in a point, as the hair parts and closes.

The liquid the hair offers the paper (the wetness of Eq. 23 times the bundle's share) grows
as the brush slows: hair that lingers over the paper (a pause, a pressed turn) gives it more,
up to (1 + POOL) times at rest, so the ink pools darker there (``sim.paper.Paper.deposit``;
past the paper's capacity it spreads, Eq. 25).

Model change to Eq. 23 and 27 (issue 26, points 1 and 2): a brush late on its load does not
lay a uniformly paler ink. The paper (and, before this, the model) made the colour of a pixel
follow the liquid the hair offers it (Eq. 26 with ``sim.paper.laying.FULL_WET``), so a mark
laid late on the load was a flat pale sheet with the mark's hard outline, the most
"computer-made" thing in the writing. A running-dry hair keeps its ink on fewer hairs: where
the offer o (Eq. 23's wetness times the bundle's share, ``lay``) falls below O_DARK, only
(o / O_DARK) ** COVER_POWER of the lines of hair across the path (lines HAIR_MM wide, each
with a fixed draw, ``_hairs``, measured from the same path as the bundles so they run along the
motion; the hair at the section's outside, Eq. 23's f near 1, drawn later by OUTER_FIRST: it
runs dry first) lay ink, and those lay it as a brush offering O_DARK would (``rich``, read by
``sim.paper.laying``; Eq. 24's wetness is the offer, unchanged). A dry stroke breaks into dark
lines along the stroke with white between, as real ink does (飞白), not into grey; a dry mark's
pale outer rim, laid where the font has no ink, is left bare rather than darkened.

A gathered point leaves as one (model addition, issue 26.2): where the hair lies across less
than GATHER of the belly (a / 2) the share 1 - g / GATHER of its bare lines closes
(``_closed``): the hair of a lifting hook's or 撇's point lies pressed together, held by
the ink between its hairs, and leaves one point, not parallel lines. And no line lies past
the hair (``_hairs``'s ``past``): a running-dry pixel farther from the path than the
bundles' span (``spread``) is bare, as the hair lays its ink on its lines only; a 折's
pressed shoulder (``sim.writing.corners``' 顿) left a grey fringe of lines there.

All draws come from the brush's one seeded generator; a split primitive's children draw
their own (Sec. 5.5)."""

from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

import numpy as np

from ..core import exact
from ..core.frames import clip, per_pixel
from . import trailpath
from .state import BUNDLES, CONTACT_EPS

WIDTH_SPREAD = 1.2  # a bundle's width is (1 + WIDTH_SPREAD u) of the smallest's
EDGE_THIN = 0.25  # the outermost bundles hold (1 - EDGE_THIN) of the middle's ink
LOAD_SPREAD = 0.3  # a bundle's ink share is jittered by +- LOAD_SPREAD / 2
W_DRY = 0.28  # a bundle's wetness below which it starts to leave flying white, at rest
V_FLY = 120.0  # mm/s: at this speed the threshold W_DRY has doubled
FLY = 2.5  # how strongly a bundle's dryness adds to Eq. 27's probability (times ren)
RAMP_S = 0.12  # seconds a bundle's gap takes to open or close
GATHER = 0.5  # a contact narrower than this share of the belly's width (``spread`` over a / 2)
# is hair gathered to a point: its dryness threshold falls in proportion below it (the whole
# width: a dry pressed stroke's streaks closed, 0.02 of its pixels parted where 0.05 is a dry
# stroke's; issue 26.2)

SETTLE_S = 0.1  # seconds over which the bundles follow the wetness of the hair on the paper
POOL = 0.5  # the hair of a brush at rest offers (1 + POOL) times the liquid of a fast one
V_POOL = 15.0  # mm/s: the speed at which half of POOL is left
REDRAW_RATE = 1.5  # per second: how often a bundle's dry-brush draw changes
O_DARK = 0.5  # the liquid a pixel is offered below which the hair covers only part of it
COVER_POWER = 0.5  # the share of the lines of hair that lay ink: (offer / O_DARK) ** this
OUTER_FIRST = 1.0  # how much earlier the hair at the section's outside runs dry (``_hairs``)
HAIR_MM = 0.3  # mm: the width of a line of hair that lays ink or not (``_hairs``)
TRAIL = 48  # points of the contact's recent path kept (``trail``)
TRAIL_MM = 0.25  # mm the contact moves before the trail takes a new point


class BristleState(NamedTuple):
    """What the marks of one step need of the bundles, as they were at that step."""

    bundle: np.ndarray  # (m, BUNDLES) ink shares
    gap: np.ndarray  # (m, BUNDLES) share of each bundle's width that lays no ink
    edge: np.ndarray  # (m, BUNDLES - 1) bundle boundaries across the section
    radius: np.ndarray  # (m,) mm: the bundles span -radius..radius across the path
    trail: np.ndarray  # (k, 2) mm: the contact's recent path, oldest first (``across``)
    travel: np.ndarray  # (2,) the brush's last direction of motion over the paper
    speed: float  # mm/s, the brush's speed over the paper
    belly: np.ndarray | None = None  # (m,) mm: a / 2 (Eq. 6, 16), the span the hair has
    # when the belly lies flat (``_gather``); None: ``radius`` (the hair not gathered)
    pressed: np.ndarray | None = None  # (m,) the contact's area S_i (Eq. 10) over the middle
    # control ellipse's, pi a b / 4 (Eq. 6, 16): how flat the belly lies (``_gather``)


def draw(rng: np.random.Generator, m: int) -> dict:
    """New bundles for m primitives (at a dip, and for a split's children)."""
    widths = 1.0 + WIDTH_SPREAD * rng.random((m, BUNDLES))
    cum = np.cumsum(widths, axis=1)
    bounds = -1.0 + 2.0 * cum / cum[:, -1:]
    edge = bounds[:, :-1]
    lo = np.concatenate([np.full((m, 1), -1.0), edge], axis=1)
    centre = 0.5 * (lo + bounds)
    share = (1.0 - EDGE_THIN * centre**2) * (1.0 + LOAD_SPREAD * (rng.random((m, BUNDLES)) - 0.5))
    return {
        "edge": edge,
        "bundle": share,
        "hair_u": rng.random((m, BUNDLES)),
        "gap": np.zeros((m, BUNDLES)),
    }


def state(brush, speed: float) -> BristleState:
    """The bundles as they are now (copies: the brush moves on before the paper takes them)."""
    radius = spread(brush, speed)
    return BristleState(
        brush.bundle.copy(),
        brush.gap.copy(),
        brush.edge.copy(),
        radius,
        brush.trail[np.isfinite(brush.trail[:, 0])],
        brush.travel.copy(),
        float(speed),
        0.5 * brush.a,
        brush.contact / np.maximum(0.25 * np.pi * brush.a * brush.b, 1e-12),
    )


def spread(brush, speed: float) -> np.ndarray:
    """(m,) mm: half the span the bundles lie across, each primitive's: half the width of its
    contact with the paper across the way it moves (``sweep``, that width times the speed, over
    the speed), at most half the middle control ellipse's major axis a (Eq. 6, 16); a / 2
    where the primitive sweeps no paper (off it, or the brush at rest). Model addition (issue
    26.2): every hair of a primitive runs from the ferrule to the tip, so all its bundles pass
    through the contact however narrow it is: as the belly lifts off, the hair gathers to the
    point and the bundles close up side by side inside the narrowing mark. Laid across the
    belly's a / 2 whatever the contact, a lifting hook's narrow mark held one or two of them,
    and where those were dry its point broke off short or splayed into hairs."""
    half = 0.5 * brush.a
    if speed <= 0.0:
        return half.copy()
    width = brush.sweep / speed
    return np.where(width > 0.0, np.minimum(0.5 * width, half), half)


def _gather(st: BristleState, i: int) -> float:
    """How far primitive ``i``'s hair is gathered, in (0, 1] (1: the hair lies as wide as the
    belly): the contact's half width across the way (``spread``) over the belly's a / 2, or
    if larger the square root of its area over the middle control ellipse's (``pressed``).
    A lifting point's contact is narrow and small; a belly pressed flat and drawn along its
    length is narrow across but as large as the ellipse, and its dry hair lays its lines
    (measured across alone, a dry brush's last strokes closed to dark,
    tests/sim/test_bristles.py::test_the_ink_runs_out_along_a_long_stroke)."""
    if st.belly is None or not st.belly[i] > 0.0:
        return 1.0
    across = st.radius[i] / st.belly[i]
    flat = 0.0 if st.pressed is None else float(np.sqrt(max(st.pressed[i], 0.0)))
    return float(min(max(across, flat), 1.0))


def contact_wetness(brush):
    """(on, wet_on): which key points lie on the paper (m, n) - the active point (Eq. 13), or
    the lowest one, always - and the mean wetness of each primitive's (m,)."""
    m = brush.m
    if m == 1:
        on_one, wet_one = contact_wetness_one(brush)
        return np.array([on_one]), np.array([wet_one])
    act = np.where(brush.active >= 0, brush.active, brush.cc[..., 2].argmin(axis=1))
    on = brush.cc[..., 2] <= CONTACT_EPS
    on[:, 0] = False
    on[np.arange(m), act] = True
    return on, np.where(on, brush.wet, 0.0).sum(axis=1) / on.sum(axis=1)


def contact_wetness_one(brush) -> tuple[list, float]:
    """``contact_wetness`` of the one primitive, (on, wet_on) as a list and a float: which
    key points lie on the paper found on Python floats, their mean wetness summed by
    np.add.reduce as the arrays' row is (numpy's own order; issue 28)."""
    z = brush.cc[0, :, 2]
    act = int(brush.active[0])
    if act < 0:
        act = int(z.argmin())
    on = [v <= CONTACT_EPS for v in z.tolist()]
    on[0] = False
    on[act] = True
    held = [w if o else 0.0 for o, w in zip(on, brush.wet[0].tolist(), strict=True)]
    return on, float(np.add.reduce(np.array(held))) / sum(on)


def step(brush, speed: float, dt: float):
    """The bundles after this step: dry-brush draws redrawn at REDRAW_RATE per second, and
    every bundle's gap opening toward 1 where the bundle is dry (Eq. 27 with its dryness) and
    closing toward 0 where it is not, by dt / RAMP_S."""
    chance = 1.0 - exact.exp(-REDRAW_RATE * dt)
    again = brush.rng.random(brush.hair_u.shape) < chance
    fresh = brush.rng.random(brush.hair_u.shape)
    brush.hair_u = np.where(again, fresh, brush.hair_u)
    q = brush.q
    _, wet_on = contact_wetness(brush)
    # the hair's wetness on the paper as the bundles feel it: followed over SETTLE_S seconds
    # (the key points on the paper change from step to step; the hair's load does not)
    follow = 1.0 - exact.exp(-dt / SETTLE_S)
    brush.moist = np.where(brush.moist > 0, brush.moist + follow * (wet_on - brush.moist), wet_on)
    w = brush.moist[:, None] * brush.bundle
    # hair gathered into a contact narrower than GATHER of the belly (``spread``: a lifting
    # point) is held together by its ink and parts less: its dryness threshold shrinks in
    # proportion (model addition, issue 26.2)
    gathered = np.minimum(spread(brush, speed) / (GATHER * 0.5 * brush.a), 1.0)[:, None]
    dryness = clip(1.0 - w / (W_DRY * (1.0 + speed / V_FLY) * gathered), 0.0, 1.0)
    p = np.minimum(q.ren * (q.ab * brush.gamma[:, None] + FLY * dryness), 1.0)
    dry = (brush.hair_u < p) & brush.touching[:, None]
    ramp = min(dt / RAMP_S, 1.0)
    brush.gap = clip(brush.gap + np.where(dry, ramp, -ramp), 0.0, 1.0)


def new_trail() -> np.ndarray:
    """An empty trail: TRAIL points, infinite until the hair has touched the paper (not NaN:
    a snapshot's copy of it compares equal)."""
    return np.full((TRAIL, 2), np.inf)


def extend_trail(trail, xy, fresh: bool = False) -> np.ndarray:
    """The trail with the contact at ``xy`` (mm): a new point once it is TRAIL_MM from the
    last, the oldest dropped; otherwise the trail as it is. ``fresh``: the hair has just come
    down on the paper, a new path begins."""
    if fresh:
        trail = new_trail()
    last = trail[-1]
    if np.isfinite(last[0]) and np.hypot(*(np.asarray(xy) - last)) < TRAIL_MM:
        return trail
    return np.concatenate([trail[1:], np.asarray(xy, dtype=float)[None]], axis=0)


def _trail_path(st: BristleState) -> np.ndarray:
    """The polyline the pixels are measured from (``across``): the trail, or at the stroke's
    first contact the way the brush is going."""
    path = st.trail
    if len(path) < 2:  # the stroke's first contact: the way the brush is going
        here = path[-1] if len(path) else np.zeros(2)
        path = np.stack([here - st.travel, here])
    return path


def across_steps(marks_per_step, states, ppm: float) -> list:
    """``across`` of many steps' marks (each step with its bundles' state) in one pass, bit
    for bit as step by step (``trailpath.signed_distances_many``; issue 28)."""
    live = [(s, mk) for s, marks in enumerate(marks_per_step) for mk in marks if mk.rows.size]
    if not live:
        return [list(marks) for marks in marks_per_step]
    steps = sorted({s for s, _ in live})
    which = {s: j for j, s in enumerate(steps)}
    lateral = trailpath.signed_distances_many(
        [_trail_path(states[s]) for s in steps],
        np.concatenate([np.full(mk.rows.size, which[s]) for s, mk in live]),
        np.concatenate([mk.rows + mk.iy0 for _, mk in live]),
        np.concatenate([mk.cols + mk.ix0 for _, mk in live]),
        ppm,
    )
    parts = iter(np.split(lateral, np.cumsum([mk.rows.size for _, mk in live])[:-1]))
    return [
        [replace(mk, lateral=next(parts)) if mk.rows.size else mk for mk in marks]
        for marks in marks_per_step
    ]


def across(marks, st: BristleState, ppm: float) -> list:
    """The marks with ``lateral`` set to every pixel's signed distance (mm) from the recent
    path of the hair's contact with the paper, the trail: the nearest point of its polyline
    (its ends going on straight), positive to the left of the way it went. On a surface this is
    done on the chart's marks, before they are splatted into the texture."""
    path = st.trail
    if len(path) < 2:  # the stroke's first contact: the way the brush is going
        here = path[-1] if len(path) else np.zeros(2)
        path = np.stack([here - st.travel, here])
    # every pixel of the step's marks at once, each measured once (trailpath: the plain
    # measure against every segment, less the work that cannot change it)
    live = [mk for mk in marks if mk.rows.size]
    if not live:
        return list(marks)
    lateral = trailpath.signed_distances(
        path,
        np.concatenate([mk.rows + mk.iy0 for mk in live]),
        np.concatenate([mk.cols + mk.ix0 for mk in live]),
        ppm,
    )
    parts = iter(np.split(lateral, np.cumsum([mk.rows.size for mk in live])[:-1]))
    return [replace(mk, lateral=next(parts)) if mk.rows.size else mk for mk in marks]


def lay(marks, st: BristleState, ppm: float) -> list:
    """The marks as the bundles lay them: each pixel's bundle (by its offset from the path,
    ``across``), the wetness of Eq. 23 times the bundle's share (and more where the hair
    lingers), and the share of the pixel (a pixel wide across the path) that lies outside the
    gaps of its bundle and of the bundle next to it, so a streak's edge is smooth, not a
    staircase of pixels: the colour of Eq. 23 is scaled by it, and ``skip`` (Eq. 27's Cr = 0)
    marks the pixels wholly in a gap."""
    out = []
    pool = np.float32(1.0 + POOL * V_POOL / (V_POOL + st.speed))
    for mk in marks:
        if not mk.rows.size:
            out.append(mk)
            continue
        i = mk.primitive
        px = np.float32(st.radius[i] * ppm)  # pixels per unit of the bundles' coordinate
        bounds = np.concatenate([[-1.0], st.edge[i], [1.0]]).astype(np.float32)
        centre = 0.5 * (bounds[:-1] + bounds[1:])
        half = 0.5 * (bounds[1:] - bounds[:-1])
        gap = (st.gap[i] * half).astype(np.float32)  # half width of each bundle's gap
        u = np.clip(mk.lateral / np.float32(st.radius[i]), -1.0, 1.0)
        b = np.searchsorted(bounds[1:-1], u)
        near = np.where(u < centre[b], b - 1, b + 1).clip(0, BUNDLES - 1)

        h = np.float32(0.5) / px  # half a pixel, in the bundles' coordinate
        own = _in_gap(u, h, centre[b], gap[b], px)
        beside = np.where(near == b, 0.0, _in_gap(u, h, centre[near], gap[near], px))
        share = np.clip(1.0 - own - beside, 0.0, 1.0)
        wet = mk.wet * st.bundle[i, b].astype(np.float32) * pool
        past = np.abs(mk.lateral) > np.float32(st.radius[i])  # beyond the bundles' span
        bare, rich = _hairs(wet, mk.lateral, mk.depth, np.int64(i), _closed(_gather(st, i)), past)
        share = np.where(bare, 0.0, share)
        out.append(
            replace(
                mk,
                wet=wet,
                col=per_pixel(mk.col, share.astype(np.float32)),
                skip=share <= 0.0,
                rich=rich,
            )
        )
    return out


def lay_steps(marks_per_step, states, ppm: float) -> list:
    """``lay`` of many steps' marks (each step with its bundles' state) in one pass: every
    mark's numbers (its bundles' bounds, gaps, shares, its pixels per unit) gathered per
    pixel, then the same arithmetic, element by element, as mark by mark (issue 28)."""
    live = [(s, mk) for s, marks in enumerate(marks_per_step) for mk in marks if mk.rows.size]
    if not live:
        return [list(marks) for marks in marks_per_step]
    n = np.array([mk.rows.size for _, mk in live])
    st_of = [states[s] for s, _ in live]
    prim = [mk.primitive for _, mk in live]
    radius = np.array([st.radius[i] for st, i in zip(st_of, prim, strict=True)])
    px_k = np.array([np.float32(r * ppm) for r in radius.tolist()], dtype=np.float32)
    bounds_k = np.concatenate(
        [
            np.full((len(live), 1), -1.0),
            np.stack([st.edge[i] for st, i in zip(st_of, prim, strict=True)]),
            np.ones((len(live), 1)),
        ],
        axis=1,
    ).astype(np.float32)
    centre_k = 0.5 * (bounds_k[:, :-1] + bounds_k[:, 1:])
    half_k = 0.5 * (bounds_k[:, 1:] - bounds_k[:, :-1])
    gap_rows = np.stack([st.gap[i] for st, i in zip(st_of, prim, strict=True)])
    gap_k = (gap_rows * half_k).astype(np.float32)
    share_k = np.stack([st.bundle[i] for st, i in zip(st_of, prim, strict=True)])
    pool_k = np.array(
        [np.float32(1.0 + POOL * V_POOL / (V_POOL + st.speed)) for st in st_of], dtype=np.float32
    )
    mark = np.repeat(np.arange(len(live)), n)  # every pixel's mark
    lateral = np.concatenate([mk.lateral for _, mk in live])
    u = np.clip(lateral / radius.astype(np.float32)[mark], -1.0, 1.0)
    b = _bundle_of(bounds_k[:, 1:-1], mark, u)
    near = np.where(u < centre_k[mark, b], b - 1, b + 1).clip(0, BUNDLES - 1)
    px = px_k[mark]
    h = np.float32(0.5) / px  # half a pixel, in the bundles' coordinate
    own = _in_gap(u, h, centre_k[mark, b], gap_k[mark, b], px)
    beside = np.where(near == b, 0.0, _in_gap(u, h, centre_k[mark, near], gap_k[mark, near], px))
    share = np.clip(1.0 - own - beside, 0.0, 1.0)
    bundle = share_k[mark, b].astype(np.float32)
    cut = np.cumsum(n)[:-1]
    wet = np.concatenate([mk.wet for _, mk in live]) * bundle * pool_k[mark]
    # (wet * bundle) * pool, as ``lay`` multiplies
    depth = np.concatenate([mk.depth for _, mk in live])
    closed = np.array([_closed(_gather(st, i)) for st, i in zip(st_of, prim, strict=True)])
    past = np.abs(lateral) > radius.astype(np.float32)[mark]  # beyond the bundles' span
    prim_px = np.array(prim, dtype=np.int64)[mark]
    bare, rich = _hairs(wet, lateral, depth, prim_px, closed.astype(np.float32)[mark], past)
    share = np.where(bare, 0.0, share)
    shares = np.split(share.astype(np.float32), cut)
    skips = np.split(share <= 0.0, cut)
    laid = iter(
        replace(mk, wet=w, col=per_pixel(mk.col, sh), skip=sk, rich=r)
        for (_, mk), w, sh, sk, r in zip(
            live, np.split(wet, cut), shares, skips, np.split(rich, cut), strict=True
        )
    )
    return [[next(laid) if mk.rows.size else mk for mk in marks] for marks in marks_per_step]


def _closed(g: float) -> np.float32:
    """The share of the bare lines of hair that close for hair gathered to ``g`` of the
    belly's width (``_gather``). Model addition (issue 26.2, beyond Eq. 27): every hair runs
    to the tip (``spread``), so a contact narrower than GATHER of the belly (as ``step``
    takes it: a lifting point) holds the hair pressed together, held by the ink between its
    hairs as its bundles are (``step``): 1 - g / GATHER of its bare lines close, whatever
    the ink, and the point leaves as one. The lines stay HAIR_MM wide: narrowed with the
    contact (branch tips26) they fell below a pixel and a dry flick's point turned to a
    stipple (tests/sim/test_flicks.py) and a pressed stroke's streaks to grey."""
    return np.float32(1.0 - min(g / GATHER, 1.0))


def _hairs(offer, lateral, depth, prim, closed=None, past=None) -> tuple[np.ndarray, np.ndarray]:
    """Which pixels the hair running dry leaves bare, and the pigment per unit of liquid of
    the others (model change, see the module's docstring). A pixel offered ``offer`` below
    O_DARK (full = offer / O_DARK below 1) is covered by c = full ** COVER_POWER of the lines
    of hair: it is bare where its line's draw - a hash of the line (HAIR_MM wide across the
    path, at ``lateral`` mm, and of the primitive ``prim``), drawn later the farther out in
    the section the pixel lies (Eq. 23's f, ``depth``; OUTER_FIRST) - is not below c. The
    covered pixels' pigment is that of O_DARK (``rich`` = 1 / full). Only the pixels offered
    less than O_DARK are drawn (a loaded brush covers its mark whole: the draw is below 1).
    ``closed`` (none if None), a scalar or per pixel: the share of the bare lines that close
    (``_closed``). ``past`` (per pixel, or None): the pixel lies farther from the path than
    the bundles' span (``spread``); no line of hair lies there, so if it is drawn (offered
    less than O_DARK) it is bare (model addition, issue 26.2: Eq. 27's Cr = 0 past the hair;
    the outermost bundle's lines, measured from a path that turns at a 折's pressed shoulder,
    ran on past the hair in pale arcs round it, a grey fringe off the corner)."""
    full = np.minimum(offer * np.float32(1.0 / O_DARK), np.float32(1.0))
    bare = np.zeros(full.shape, dtype=bool)
    low = np.flatnonzero(full < 1.0)
    if low.size:
        line = np.floor(lateral[low] * np.float32(1.0 / HAIR_MM)).astype(np.int64)
        line += (np.take(prim, low) if np.ndim(prim) else prim) * 4099
        x = (line & 0xFFFFFFFF).astype(np.uint32)  # a 32-bit integer hash of the line
        x *= np.uint32(0x9E3779B1)
        x ^= x >> np.uint32(15)
        x *= np.uint32(0x85EBCA77)
        x ^= x >> np.uint32(13)
        draw = x.astype(np.float32) * np.float32(1.0 / 4294967296.0)
        draw += np.float32(OUTER_FIRST) * depth[low].astype(np.float32)
        draw *= np.float32(1.0 / (1.0 + OUTER_FIRST))
        cover = full[low] ** np.float32(COVER_POWER)
        if closed is not None:  # a gathered point's bare lines close (``_closed``)
            shut = closed[low] if np.ndim(closed) else closed
            cover += (np.float32(1.0) - cover) * shut
        bare[low] = draw >= cover
        if past is not None:  # no line of hair lies past the bundles' span
            bare[low] |= past[low]
    rich = np.float32(1.0) / np.maximum(full, np.float32(1e-6))
    return bare, rich.astype(np.float32)


def _bundle_of(inner, mark, u) -> np.ndarray:
    """np.searchsorted(inner[mark[i]], u[i]) for every i (``inner`` (k, BUNDLES - 1) float32,
    each row ascending; u float32): the rows' values and u as integers in the same order as
    the floats (-0 taken as +0, as a float compares), row by row, and one search."""
    k, w = inner.shape
    rows = _ordered(inner) + (np.arange(k, dtype=np.int64) << 32)[:, None]
    at = np.searchsorted(rows.ravel(), _ordered(u) + (mark.astype(np.int64) << 32))
    return at - mark * w


def _ordered(x) -> np.ndarray:
    """float32 values (no NaN) as int64 in the same order (and equal where they are equal)."""
    i = (x + np.float32(0.0)).view(np.int32).astype(np.int64)  # -0 + 0 = +0
    return np.where(i < 0, -(i & 0x7FFFFFFF), i)


def _in_gap(u, h, centre, gap, px):
    """The share of the pixels [u - h, u + h] that lies in the gaps [centre - gap, centre + gap]
    (all in the bundles' coordinate; px pixels per unit)."""
    lo, hi = np.maximum(u - h, centre - gap), np.minimum(u + h, centre + gap)
    return np.maximum(hi - lo, 0.0) * px
