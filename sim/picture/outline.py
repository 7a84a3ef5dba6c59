# SPDX-License-Identifier: GPL-3.0-or-later
"""Character data from a picture's strokes (see ``imitate``, step 4): each stroke's own ink
(``stroke_regions``) traced into polygons (``trace_outline``, ``simplify``) as its SVG
outline, its median simplified, in data units (``read_strokes``)."""

from __future__ import annotations

import numpy as np

from ..core import exact
from ..core.exact import matmul
from ..image import morph as M
from ..writing.hanzi import MAX_MEDIAN_POINTS as DATA_MEDIAN_POINTS
from ..writing.hanzi import MAX_OUTLINE_POINTS as DATA_OUTLINE_POINTS
from ..writing.hanzi import MAX_STROKES
from ..writing.outline import EM, TOP, discs
from .ink import Ink, PictureError
from .order import orient, writing_order
from .strokes import Stroke, find_strokes

TUBE = (1.0, 0.5)  # a stroke's own ink: within its half-width of its median, plus pixels
MEDIAN_EPS = 2.0  # px at 512: the median simplified this closely
OUTLINE_EPS = 0.6  # px: the outline's polygons simplified this closely
# a stroke read from a picture is simplified to within 3/4 of what stroke data may hold (its
# curves are flattened again when the data is read: a margin for that)
OUTLINE_POINT_BUDGET = DATA_OUTLINE_POINTS * 3 // 4
MEDIAN_POINT_BUDGET = DATA_MEDIAN_POINTS * 3 // 4
BLOT_CURL = np.radians(35.0)  # a median's end that turns more than this inside its blot
CORNER_TURN = np.radians(55.0)  # a median that turns more than this within a stroke-width
CHAMFER = 4.0  # half-widths: a shorter leg of the simplified skeleton is a chamfer across a turn
MEET_HOLD = 0.5  # ... whose corner goes out towards where the legs' lines meet while the ink is
# this share of the median half-width thick
MEET_REACH = 3.0  # ... and no farther than this many half-widths from the chamfer's middle
CORNER_HOLD = 0.5  # a corner's vertex goes out as far as the ink is this share of the legs'
# half-width thick (the skeleton of a thick turn cuts across it, the writer's median goes in;
# a hook's foot tapers to a heel below the turn, and from 0.85 the brush's foot stopped short
# of it, the character's lowest ink, and the box shrank: imitate_eval 0.832 -> 0.842, 高 uneven
# 0.775 -> 0.854, 京 photo 0.755 -> 0.825; 0.7 lost 0.014 of that on the cases it moves;
# 0.6 -> 0.5 with strokes.HOOK_COS 0.0: imitate_eval 0.835 -> 0.841, 鹤 photo 0.722 -> 0.775,
# 端 clean 0.780 -> 0.760; 0.4: 0.839, 学 small 0.767 -> 0.721)
FOOT_DOWN = 0.6  # a turn whose way in goes down this steeply (image y) is a hook's foot
SHOULDER_HOLD = 0.5  # a 折's corner goes out into its shoulder's pressed bump (顿笔) as far as
# the ink is this share of the legs' half-width thick (0.7 and 0.85: less of the bump reached;
# imitate_eval: 国 clean 0.812 -> 0.898, 品 small 0.755 -> 0.798, 高 uneven 0.812 -> 0.858)
SHOULDER_DOWN = 0.5  # ... a turn whose way out goes down this steeply (image y): a 横折, 横撇,
# 横钩; not the turn up into a hook's tip at the end of a 竖弯钩 or 横斜钩 (虎, 飞), whose tip the
# brush flicks out of the corner (pushed out, 虎's hook overshot the picture's: 0.81 -> 0.74)
CORNER_ALIGN = np.radians(35.0)  # the line out of a moved corner keeps this close to its leg
CORNER_SKIP = 2.0  # ... within this many half-widths along the leg
STEP_PX = 2.0  # a stroke's centre line has a point every this many pixels (strokes._finish)
JOIN_REACH = 1.0  # a stroke ending on another runs on this many times the ink's half-width
JOIN_HOLD = 0.5  # ... while the ink is this share of that thick (``into_join``)
CORNER_HEEL = 0.6  # rad inside the way straight on that a corner's foot is looked for
LINE_HOLD = 0.4  # the line into a corner runs through ink this share of the legs' half-width
# thick (``_inside``; where the corner lies thinner, as thin as the corner over MEET_HOLD)


# ----------------------------------------------------------------- each stroke's own ink
def stroke_regions(strokes: list, mask: np.ndarray) -> list[np.ndarray]:
    """Each stroke's own ink: the ink within its width of its median (strokes overlap at
    crossings), and the ink no stroke reaches so goes to the nearest stroke."""
    n = mask.shape[0]
    tubes = [discs(s.pts + 0.5, s.radius * TUBE[0] + TUBE[1], n) & mask for s in strokes]
    rest = mask & ~np.any(tubes, axis=0) if tubes else mask
    if rest.any():
        owner = np.zeros(mask.shape, dtype=np.int32)
        for i, s in enumerate(strokes):
            iy = np.clip(np.round(s.pts[:, 1]).astype(int), 0, n - 1)
            ix = np.clip(np.round(s.pts[:, 0]).astype(int), 0, n - 1)
            owner[iy, ix] = i + 1
        _, ry, rx = M.nearest_feature(owner > 0)
        near = owner[np.maximum(ry, 0), np.maximum(rx, 0)]
        for i in range(len(strokes)):
            tubes[i] |= rest & (near == i + 1)
    return tubes


def trace_outline(region: np.ndarray) -> list[np.ndarray]:
    """The boundary of a pixel region as closed polygons along the pixels' edges (image
    pixels, x right, y down); filled even-odd by pixel centres they give the region back."""
    r = np.pad(np.asarray(region, dtype=bool), 1)
    edges = []
    for (dy, dx), (a, b) in (
        ((-1, 0), ((0, 0), (1, 0))),  # top edge, left to right
        ((0, 1), ((1, 0), (1, 1))),  # right edge, downwards
        ((1, 0), ((1, 1), (0, 1))),  # bottom edge, right to left
        ((0, -1), ((0, 1), (0, 0))),  # left edge, upwards
    ):
        ys, xs = np.nonzero(r & ~np.roll(r, (-dy, -dx), axis=(0, 1)))
        for y, x in zip(ys.tolist(), xs.tolist(), strict=True):
            edges.append(((x + a[0] - 1, y + a[1] - 1), (x + b[0] - 1, y + b[1] - 1)))
    out_of: dict = {}
    for e in edges:
        out_of.setdefault(e[0], []).append(e[1])
    polys = []
    while out_of:
        start = next(iter(out_of))
        loop, cur = [start], start
        while True:
            nxt = out_of[cur].pop()
            if not out_of[cur]:
                del out_of[cur]
            if nxt == start:
                break
            loop.append(nxt)
            cur = nxt
        if len(loop) >= 3:
            polys.append(np.array(loop, dtype=np.float64))
    return polys


def simplify(poly: np.ndarray, eps: float, closed: bool = True) -> np.ndarray:
    """Douglas-Peucker on a closed polygon (or an open polyline): its points within ``eps``
    of the original."""
    n = len(poly)
    if n <= 3:
        return poly
    far = int(np.argmax(np.linalg.norm(poly - poly[0], axis=1))) if closed else n - 1
    keep = np.zeros(n, dtype=bool)
    keep[[0, far]] = True
    stack = [(0, far), (far, n)] if closed else [(0, n - 1)]
    while stack:
        i, j = stack.pop()
        a, b = poly[i], poly[j % n]
        if j - i < 2:
            continue
        seg = poly[i + 1 : j]
        ab = b - a
        L = float(np.linalg.norm(ab, axis=-1))
        if L < 1e-9:
            d = np.linalg.norm(seg - a, axis=1)
        else:
            d = np.abs(ab[0] * (seg[:, 1] - a[1]) - ab[1] * (seg[:, 0] - a[0])) / L
        k = int(np.argmax(d))
        if d[k] > eps:
            m = i + 1 + k
            keep[m] = True
            stack += [(i, m), (m, j)]
    return poly[keep]


# ------------------------------------------------------------------ corners of a median
def _turns(pts: np.ndarray, radius: np.ndarray, dist: np.ndarray | None = None) -> list[tuple]:
    """Where the stroke's centre line turns sharply: the line simplified to within its median
    half-width, each interior vertex between legs of a half-width or more turning more than
    CORNER_TURN; for each its index, its place, the ways in and out and the points of the
    skeleton where the legs leave the turn. The skeleton of a thick turn cuts across it: in one
    vertex, or in a chamfer, a short leg (under CHAMFER half-widths) between two vertices, taken
    as one turn when the legs on either side of it turn more than at its first vertex (飞's
    and 学's shoulders: taken apart, the corner stayed on the chamfer, inside the shoulder,
    and the next leg set off from below the shoulder's ink, the two apart). The place is where
    the legs' lines meet, or as far towards it from the chamfer's middle as the ink (``dist``,
    the distance to the paper) is MEET_HOLD of the median half-width thick."""
    r = float(np.median(radius))
    simple = simplify(pts, max(r, 1.0), closed=False)
    out = []
    i = 1
    while i < len(simple) - 1:
        a, v = simple[i - 1], simple[i]
        legs = [(v, simple[i + 1], i + 1)]  # the vertex: the leg out from it
        way_in = (v - a) / max(float(np.linalg.norm(v - a, axis=-1)), 1e-9)
        if (
            i + 2 < len(simple)
            and np.linalg.norm(simple[i + 1] - v, axis=-1) < CHAMFER * r
            and way_in[1] <= FOOT_DOWN  # a hook's foot is found from its vertex (into_corners)
        ):
            legs.append((simple[i + 1], simple[i + 2], i + 2))  # across a chamfer
        best = None
        for v1, b, nxt in legs:
            u, w = v - a, b - v1
            lu, lw = float(np.linalg.norm(u, axis=-1)), float(np.linalg.norm(w, axis=-1))
            if min(lu, lw) < r:  # a kink of the skeleton, not a turn of the stroke
                continue
            u, w = u / lu, w / lw
            turn = float(exact.arccos(float(np.clip(matmul(u, w), -1.0, 1.0))))
            if turn > CORNER_TURN and (best is None or turn > best[0]):
                best = (turn, v1, u, w, nxt)
        if best is None:
            i += 1
            continue
        _, v1, u, w, nxt = best
        k = int(np.argmin(np.linalg.norm(pts - 0.5 * (v + v1), axis=1)))
        place = _meeting(v, v1, u, w, r, dist, pts[k])
        out.append((k, place, u, w, v, v1))
        i = nxt
    return out


def _meeting(v, v1, u, w, r: float, dist: np.ndarray | None, mid: np.ndarray) -> np.ndarray:
    """Where the line in along ``u`` through ``v`` meets the line out along ``w`` through
    ``v1`` (a 折 cut across by the skeleton), when that is within two half-widths ``r`` of
    ``mid`` (the skeleton's point in the chamfer's middle); with ``dist``, the point nearest
    it on the way from ``mid`` where the ink is MEET_HOLD of ``r`` thick. ``mid`` when the lines
    do not meet; no farther than MEET_REACH of ``r`` from ``mid``."""
    cross = u[0] * w[1] - u[1] * w[0]
    if abs(cross) <= 0.2:
        return mid
    t = ((v1 - v)[0] * w[1] - (v1 - v)[1] * w[0]) / cross
    meet = v + t * u
    gap = float(np.linalg.norm(meet - mid, axis=-1))
    if gap > MEET_REACH * r:  # nearly parallel legs: not farther out than a thick shoulder
        meet = mid + (meet - mid) * MEET_REACH * r / gap
        gap = MEET_REACH * r
    if dist is None:
        return meet if gap <= 2.0 * r else mid
    h, wd = dist.shape
    for f in np.linspace(1.0, 0.0, max(int(gap), 1) + 1)[:-1]:  # the farthest out in the ink
        q = mid + f * (meet - mid)
        x, y = np.round(q).astype(int)
        if 0 <= x < wd and 0 <= y < h and dist[y, x] >= MEET_HOLD * r:
            return q
    return mid


def _corner_point(p, u, w, hold: float, dist: np.ndarray, heel: float = CORNER_HEEL):
    """From ``p``, the farthest point of the turn's outside - the ways between going straight
    on (``u``, into a hook's foot or a 折's shoulder; up to ``heel`` rad inside it, where a
    hook's heel hangs) and the outer bisector (away from both legs) - reached through ink at
    least ``hold`` thick (the distance to the paper)."""
    h, wd = dist.shape
    out = (u - w) / max(float(np.linalg.norm(u - w, axis=-1)), 1e-9)
    a0, a1 = exact.arctan2(float(u[1]), float(u[0])), exact.arctan2(float(out[1]), float(out[0]))
    a1 = a0 + (a1 - a0 + np.pi) % (2 * np.pi) - np.pi
    a0 -= heel * np.sign(a1 - a0)  # a hook's heel hangs a little inside the turn
    best, far = p, 0.0
    for ang in np.linspace(a0, a1, 11):
        d = np.array(exact.sin_cos(ang)[::-1])
        s = 0.0
        while True:
            x, y = np.round(p + (s + 1.0) * d).astype(int)
            if not (0 <= x < wd and 0 <= y < h) or dist[y, x] < hold:
                break
            s += 1.0
        if s > far:
            best, far = p + s * d, s
    return best


def _on_leg(pts, k: int, place, way, r: float, step: int) -> int:
    """The first point from ``k`` (forwards or backwards, ``step``) on the leg leaving
    ``place`` along ``way``: a half-width or more along it and within half of one of its
    line (past the skeleton's chamfer across the turn)."""
    j = k
    while 0 < j < len(pts) - 1:
        d = pts[j] - place
        if matmul(d, way) >= r and abs(d[0] * way[1] - d[1] * way[0]) <= 0.5 * r:
            return j
        j += step
    return j


def _aligned(pts, j: int, c, way, step: int, stop: int) -> int:
    """From ``j`` on (forwards or backwards, ``step``, not past ``stop``), the first point
    that the moved corner ``c`` reaches within CORNER_ALIGN of the leg's way: the line from a
    corner pushed out into a 折's shoulder goes on down the leg, not back across the turn."""
    while j != stop:
        d = pts[j] - c
        if matmul(d, way) >= exact.cos(CORNER_ALIGN) * max(float(np.linalg.norm(d, axis=-1)), 1e-9):
            return j
        j += step
    return j


def _inside(pts, j: int, c, dist: np.ndarray, hold: float, k: int) -> int:
    """From ``j`` towards ``k`` (the turn's point on the skeleton), the first point whose
    straight line into the corner ``c`` runs through ink at least ``hold`` thick (the distance
    to the paper) all the way: a leg's line is the chord of the whole leg, and where the leg
    bends on its way into the turn (国's top rising into its shoulder) the line from the far
    point it gives cut across the bend along the ink's edge, where the writer reads the
    stroke as no wider than a hair and lifts the brush off (the horizontal broken before the
    shoulder). ``k`` itself when no point's line does."""
    h, w = dist.shape
    step = 1 if k >= j else -1
    while j != k:
        d = float(np.linalg.norm(c - pts[j], axis=-1))
        t = np.linspace(0.0, 1.0, max(int(d), 1) + 1)[:, None]
        q = np.round(pts[j] + t * (c - pts[j])).astype(int)
        x, y = np.clip(q[:, 0], 0, w - 1), np.clip(q[:, 1], 0, h - 1)
        if float(dist[y, x].min()) >= hold:
            return j
        j += step
    return j


def into_corners(s: Stroke, dist: np.ndarray) -> Stroke:
    """The stroke's centre line taken into its sharp corners (a 折's shoulder, a hook's foot):
    the skeleton of a thick turn cuts across it, so the brush, following it, would round the
    corner off and miss the foot, which is often the character's lowest or outermost ink. At
    each sharp turn (``_turns``) the corner goes out from where the legs' lines meet, straight
    on or to the turn's outside (``_corner_point``): at the foot of a stroke that came down (a
    hook's: 竖钩, 横折钩) as far as the ink is still CORNER_HOLD of the legs' half-width thick;
    at a 折 that turns down (SHOULDER_DOWN) into its shoulder's bulge, as far as the ink is
    SHOULDER_HOLD of that thick (the brush pressed out there past both legs' edges: the
    character's outermost ink, left unwritten from the meeting point; pushed out to the
    shoulder's edge, the corner left a notch that opened 口's box); a turn up into a hook's tip
    stays where the legs meet. The line runs straight into the corner and out of it, from where
    that line stays inside the ink (``_inside``). (Beyond the
    paper's Sec. 9, which does not say how strokes are read off a picture: stroke data's
    medians go into their corners, and the writer presses into a corner before turning.)"""
    pts, rad = s.pts, s.radius
    turns = _turns(pts, rad, dist)
    if not turns:
        return s
    keep_pts, keep_rad, last = [], [], 0
    for k, place, u, w, v, v1 in turns:
        r_leg = float(np.median(rad[max(k - 10, 0) : k + 11]))
        if u[1] > FOOT_DOWN:  # the foot of a stroke that came down (竖钩, 横折钩, 弯钩)
            c = _corner_point(place, u, w, CORNER_HOLD * r_leg, dist)
        elif w[1] > SHOULDER_DOWN:  # a 折's shoulder: out from where the legs meet (no heel)
            c = _corner_point(place, u, w, SHOULDER_HOLD * r_leg, dist, heel=0.0)
        else:  # a turn up into a hook's tip (竖弯钩, 横斜钩): where the legs meet
            c = place
        i0, i1 = _on_leg(pts, k, v, -u, r_leg, -1), _on_leg(pts, k, v1, w, r_leg, 1)
        skip = int(np.ceil(CORNER_SKIP * r_leg / STEP_PX))  # at most this far down a leg
        i0 = _aligned(pts, i0, c, -u, -1, max(last, i0 - skip))
        i1 = _aligned(pts, i1, c, w, 1, min(len(pts) - 1, i1 + skip))
        cx, cy = np.clip(np.round(c).astype(int), 0, len(dist) - 1)
        hold = min(LINE_HOLD * r_leg, LINE_HOLD * float(dist[cy, cx]) / MEET_HOLD)
        i0, i1 = _inside(pts, i0, c, dist, hold, k), _inside(pts, i1, c, dist, hold, k)
        if i0 < last or i1 <= i0 + 1:
            continue
        keep_pts += [pts[last : i0 + 1], c[None]]
        keep_rad += [rad[last : i0 + 1], [r_leg]]
        last = i1
    if not keep_pts:
        return s
    line = np.vstack([*keep_pts, pts[last:]])
    radius = np.concatenate([*keep_rad, rad[last:]])
    seg = np.linalg.norm(np.diff(line, axis=0), axis=1)
    a = np.concatenate([[0.0], np.cumsum(seg)])
    si = np.linspace(0.0, a[-1], max(int(a[-1] / STEP_PX), 1) + 1)
    dense = np.stack([np.interp(si, a, line[:, 0]), np.interp(si, a, line[:, 1])], axis=1)
    return Stroke(dense, np.interp(si, a, radius), s.through, s.touches, s.joints)


def into_join(s: Stroke, dist: np.ndarray) -> Stroke:
    """A stroke that ends on another (its last point at a junction it touches: 永's right 撇
    on its 捺, a dot on the stroke it hangs from) carried on past the junction's centre along
    its way, JOIN_REACH of the ink's half-width there, and no farther than the ink is
    JOIN_HOLD of that thick: the writer lifts the brush to a point at a stroke's end, so a
    median that stops at the junction's centre leaves its tip short of the stroke it touches
    in the picture, and the ink in two pieces. (Its start is left alone: the brush lands
    pressed, round, and reaches.)"""
    end = s.pts[-1]
    if len(s.pts) < 3 or not any(np.linalg.norm(end - c, axis=-1) < 1.0 for c in s.joints.values()):
        return s
    h, w = dist.shape
    x, y = np.clip(np.round(end).astype(int), 0, (w - 1, h - 1))
    r = float(dist[y, x])
    k = max(int(np.ceil(r / STEP_PX)), 2)
    d = end - s.pts[max(len(s.pts) - 1 - k, 0)]
    d = d / max(float(np.linalg.norm(d, axis=-1)), 1e-9)
    add = []
    for t in np.arange(STEP_PX, JOIN_REACH * r + 1e-9, STEP_PX):
        q = end + t * d
        x, y = np.round(q).astype(int)
        if not (0 <= x < w and 0 <= y < h) or dist[y, x] < JOIN_HOLD * r:
            break
        add.append(q)
    if not add:
        return s
    pts = np.vstack([s.pts, add])
    radius = np.concatenate([s.radius, np.full(len(add), s.radius[-1])])
    return Stroke(pts, radius, s.through, s.touches, s.joints)


# -------------------------------------------------------------------- character data
def _to_data(pts: np.ndarray, n: int) -> np.ndarray:
    return np.stack([pts[:, 0] * EM / n, TOP - pts[:, 1] * EM / n], axis=1)


def _svg(polys: list, n: int) -> str:
    parts = []
    for p in polys:
        d = _to_data(p, n)
        parts.append("M " + " L ".join(f"{x:.1f} {y:.1f}" for x, y in d) + " Z")
    return " ".join(parts)


def outline_svg(region: np.ndarray, n: int) -> str:
    """A stroke's own ink as an SVG path in data units, within the point budget."""
    polys = trace_outline(region)
    eps = OUTLINE_EPS
    while True:
        simple = [q for q in (simplify(p, eps) for p in polys) if len(q) >= 3]
        if sum(len(q) for q in simple) <= OUTLINE_POINT_BUDGET or eps > 8:
            return _svg(simple, n)
        eps *= 1.6


def _straight_start(pts: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """The median's start straightened inside the blot where the brush landed: the skeleton of
    a round blot (the head of the scan's 永 撇) curls within the blot's half-width of the end,
    and the writer takes such a curl for a sharp turn (it lifts and lands again there: a false
    折 and a second blot). Where the heading within the blot differs from the stroke's heading
    beyond it by more than BLOT_CURL, the median runs straight on along the stroke's heading
    there instead. (The stroke's last end is left alone: a hook turns inside its foot.)"""
    p = pts.astype(np.float64).copy()
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    reach = float(radius[: max(len(radius) // 4, 1)].max())
    i = int(np.searchsorted(s, reach))
    j = int(np.searchsorted(s, s[min(i, len(s) - 1)] + reach))
    if i < 2 or j >= len(p) - 1 or s[-1] < 3.0 * reach:
        return p
    beyond, inside = p[i] - p[j], p[0] - p[i]
    cos = matmul(beyond, inside) / max(
        float(np.linalg.norm(beyond, axis=-1) * np.linalg.norm(inside, axis=-1)), 1e-9
    )
    if exact.arccos(float(np.clip(cos, -1.0, 1.0))) > BLOT_CURL:
        u = beyond / max(float(np.linalg.norm(beyond, axis=-1)), 1e-9)
        p[:i] = p[i] + u * (s[i] - s[:i])[:, None]
    return p


def _median(s: Stroke, n: int) -> list:
    """The stroke's centre line as a polyline within MEDIAN_EPS of it (the skeleton's jitter
    gone, its corners kept, its start straight inside its blot), in data units."""
    eps = MEDIAN_EPS * n / 512
    line = _straight_start(s.pts, s.radius)
    pts = simplify(line, eps, closed=False)
    while len(pts) > MEDIAN_POINT_BUDGET:
        eps *= 1.5
        pts = simplify(line, eps, closed=False)
    return [[round(float(x), 1), round(float(y), 1)] for x, y in _to_data(pts, n)]


def read_strokes(ink: Ink) -> tuple[list, list, dict]:
    """The strokes of a picture's ink in writing order, their own ink, and the character data
    for the writer."""
    n = ink.mask.shape[0]
    found = [orient(s) for s in find_strokes(ink.mask)]
    found = [s for s in found if len(s.pts) >= 2 and s.radius.max() > 0]
    if not found:
        raise PictureError("no strokes found in the picture's ink")
    if len(found) > MAX_STROKES:
        raise PictureError(
            f"the picture's ink makes {len(found)} strokes; at most {MAX_STROKES} (one character)"
        )
    strokes = [found[i] for i in writing_order(found, n, ink.mask)]
    dist = M.edt(ink.mask)
    strokes = [into_join(into_corners(s, dist), dist) for s in strokes]
    regions = stroke_regions(strokes, ink.mask)
    keep = [i for i, r in enumerate(regions) if r.sum() >= 4]
    if not keep:  # every stroke's own ink is a few pixels: nothing the writer could write
        raise PictureError("no strokes found in the picture's ink")
    strokes, regions = [strokes[i] for i in keep], [regions[i] for i in keep]
    char = {
        "strokes": [outline_svg(r, n) for r in regions],
        "medians": [_median(s, n) for s in strokes],
    }
    return strokes, regions, char
